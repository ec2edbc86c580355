// WHERE conditions: precedence, predicates, comparisons and literals.
#include <catch2/catch.hpp>

#include "engine/parser/parser.hpp"

using namespace smql;
namespace parser = smql::parser;

namespace {

ast::Expr whereOf(std::string_view condition) {
    std::vector<ast::Statement> statements = parser::parse("FIND x WHERE " + std::string(condition));
    REQUIRE(statements.size() == 1);
    const auto& find = std::get<ast::FindStmt>(statements.front().body);
    REQUIRE(find.where);
    return *find.where;
}

}  // namespace

TEST_CASE("AND binds tighter than OR", "[parser][expr]") {
    ast::Expr e = whereOf("on(a) OR on(b) AND on(c)");
    REQUIRE(e.kind == ast::Expr::Kind::Or);
    REQUIRE(e.children.size() == 2);
    CHECK(e.children[0].kind == ast::Expr::Kind::Predicate);
    CHECK(e.children[0].args.at(0).name == "a");
    REQUIRE(e.children[1].kind == ast::Expr::Kind::And);
    CHECK(e.children[1].children.at(0).args.at(0).name == "b");
    CHECK(e.children[1].children.at(1).args.at(0).name == "c");
}

TEST_CASE("NOT binds tighter than AND", "[parser][expr]") {
    ast::Expr e = whereOf("NOT on(a) AND on(b)");
    REQUIRE(e.kind == ast::Expr::Kind::And);
    REQUIRE(e.children.at(0).kind == ast::Expr::Kind::Not);
    REQUIRE(e.children.at(0).children.size() == 1);
    CHECK(e.children.at(0).children[0].args.at(0).name == "a");
    CHECK(e.children.at(1).kind == ast::Expr::Kind::Predicate);

    ast::Expr twice = whereOf("NOT NOT on(a)");
    REQUIRE(twice.kind == ast::Expr::Kind::Not);
    CHECK(twice.children.at(0).kind == ast::Expr::Kind::Not);
}

TEST_CASE("parentheses override precedence", "[parser][expr]") {
    ast::Expr e = whereOf("(on(a) OR on(b)) AND on(c)");
    REQUIRE(e.kind == ast::Expr::Kind::And);
    CHECK(e.children.at(0).kind == ast::Expr::Kind::Or);
    CHECK(e.children.at(1).kind == ast::Expr::Kind::Predicate);

    ast::Expr negated = whereOf("NOT (on(a) OR on(b))");
    REQUIRE(negated.kind == ast::Expr::Kind::Not);
    CHECK(negated.children.at(0).kind == ast::Expr::Kind::Or);
}

TEST_CASE("chains of one operator are one node", "[parser][expr]") {
    ast::Expr e = whereOf("on(a) AND on(b) AND on(c)");
    REQUIRE(e.kind == ast::Expr::Kind::And);
    CHECK(e.children.size() == 3);
    CHECK(whereOf("on(a) or on(b) or on(c) or on(d)").children.size() == 4);
    CHECK(e.where.column == 14);
    CHECK(e.where.length == 25);
}

TEST_CASE("predicate calls", "[parser][expr]") {
    ast::Expr on = whereOf("On(Desk)");
    CHECK(on.kind == ast::Expr::Kind::Predicate);
    CHECK(on.predicate == "on");
    REQUIRE(on.args.size() == 1);
    CHECK(on.args[0].name == "desk");
    CHECK_FALSE(on.threshold);

    ast::Expr near = whereOf("near(window, 1.5 m)");
    CHECK(near.args.size() == 1);
    REQUIRE(near.threshold);
    CHECK(near.threshold->metres == 1.5);

    ast::Expr between = whereOf("between(lamp, sofa)");
    CHECK(between.predicate == "between");
    REQUIRE(between.args.size() == 2);
    CHECK(between.args[1].name == "sofa");
    CHECK_FALSE(between.threshold);

    ast::Expr three = whereOf("between(lamp, 'indoor plant', #4, 20 cm)");
    CHECK(three.args.size() == 3);
    CHECK(three.args[1].name == "indoor plant");
    CHECK(three.args[2].kind == ast::Ref::Kind::NodeId);
    CHECK(three.threshold->metres == Approx(0.2));

    // Aliases and unknown predicates pass through as written: the binder decides.
    CHECK(whereOf("inside(box)").predicate == "inside");
    CHECK(whereOf("under(table)").predicate == "under");
    CHECK(whereOf("left_of(sofa)").predicate == "left_of");
    CHECK(whereOf("frobnicate(sofa)").predicate == "frobnicate");
    CHECK(whereOf("near(wall.left)").args.at(0).kind == ast::Ref::Kind::Side);
}

TEST_CASE("comparison operators", "[parser][expr]") {
    using Op = ast::CompareOp;
    const std::vector<std::pair<const char*, Op>> cases = {
        {"=", Op::Eq}, {"!=", Op::Ne}, {"<>", Op::Ne},     {"<", Op::Lt},      {"<=", Op::Le},
        {">", Op::Gt}, {">=", Op::Ge}, {"LIKE", Op::Like}, {"like", Op::Like},
    };
    for (const auto& [text, op] : cases) {
        INFO(text);
        ast::Expr e = whereOf(std::string("material ") + text + " 'wood'");
        CHECK(e.kind == ast::Expr::Kind::Compare);
        CHECK(e.attribute == "material");
        CHECK(e.op == op);
    }
}

TEST_CASE("comparison literals", "[parser][expr]") {
    CHECK(std::get<std::string>(whereOf("color = 'red'").literal) == "red");
    CHECK(std::get<std::string>(whereOf("color = \"Dark Red\"").literal) == "Dark Red");
    CHECK(std::get<std::string>(whereOf("text LIKE '%mug%'").literal) == "%mug%");
    CHECK(std::get<std::string>(whereOf("text = 'it''s'").literal) == "it's");
    CHECK(std::get<std::int64_t>(whereOf("source_id = 93").literal) == 93);
    CHECK(std::get<std::int64_t>(whereOf("id = -4").literal) == -4);
    CHECK(std::get<double>(whereOf("confidence >= 0.5").literal) == 0.5);
    CHECK(std::get<double>(whereOf("confidence >= .5").literal) == 0.5);
    CHECK(std::get<double>(whereOf("z > -0.25").literal) == -0.25);
    // A length in a comparison becomes metres.
    CHECK(std::get<double>(whereOf("height > 1 m").literal) == 1.0);
    CHECK(std::get<double>(whereOf("height > 30 cm").literal) == std::get<double>(whereOf("height > 0.3 m").literal));
    CHECK(std::get<double>(whereOf("height > 30cm").literal) == Approx(0.3));
    CHECK(std::get<double>(whereOf("z > -5 mm").literal) == Approx(-0.005));
}

TEST_CASE("a comparison and a predicate mix", "[parser][expr]") {
    ast::Expr e = whereOf("color = 'red' AND near(window, 1.5 m)");
    REQUIRE(e.kind == ast::Expr::Kind::And);
    CHECK(e.children[0].kind == ast::Expr::Kind::Compare);
    CHECK(e.children[1].kind == ast::Expr::Kind::Predicate);
    CHECK(e.children[1].where.column == 32);
}
