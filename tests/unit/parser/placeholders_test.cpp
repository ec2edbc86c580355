// Placeholders: where they may stand, how they are numbered, and the errors of mixing them.
#include <catch2/catch.hpp>

#include "parser_test_support.hpp"

using namespace smql;
namespace parser = smql::parser;
using smql::parser::testing::parseOne;

namespace {

std::string syntaxError(std::string_view text) { return parser::testing::syntaxErrorOf(text).message(); }

}  // namespace

TEST_CASE("? placeholders are numbered in the order they are written", "[parser][parameters]") {
    ast::Statement statement = parseOne("FIND ? WHERE near(?, ?) AND color = ? LIMIT ?");
    CHECK(statement.parameterCount == 5);
    const auto& find = std::get<ast::FindStmt>(statement.body);
    CHECK(find.target.kind == ast::Ref::Kind::Param);
    CHECK(find.target.placeholder.index == 1);
    CHECK_FALSE(find.target.placeholder.numbered);
    REQUIRE(find.where);
    const ast::Expr& near = find.where->children.at(0);
    REQUIRE(near.args.size() == 2);  // the distance is an argument until a number is bound to it
    CHECK(near.args[0].placeholder.index == 2);
    CHECK(near.args[1].placeholder.index == 3);
    const ast::Expr& color = find.where->children.at(1);
    REQUIRE(color.literalParam);
    CHECK(color.literalParam->index == 4);
    REQUIRE(find.limitParam);
    CHECK(find.limitParam->index == 5);
    CHECK_FALSE(find.limit);
    CHECK(find.limitParam->name() == "? number 5");
    CHECK(find.limitParam->where.column == 45);
}

TEST_CASE("GUIDE numbers its placeholders in text order, though its target is read first", "[parser][parameters]") {
    auto guide = std::get<ast::GuideStmt>(parseOne("GUIDE FROM ? TO ?").body);
    CHECK(guide.from->placeholder.index == 1);
    CHECK(guide.to.placeholder.index == 2);
}

TEST_CASE("$n placeholders carry their number and may repeat", "[parser][parameters]") {
    ast::Statement statement = parseOne("RELATE $2 TO (FIND $1 WHERE on($2))");
    CHECK(statement.parameterCount == 2);
    const auto& relate = std::get<ast::RelateStmt>(statement.body);
    CHECK(relate.subject.placeholder.index == 2);
    CHECK(relate.subject.placeholder.numbered);
    CHECK(relate.subject.placeholder.name() == "$2");
    CHECK(relate.object.subquery->target.placeholder.index == 1);
}

TEST_CASE("a placeholder with a side keeps the side", "[parser][parameters]") {
    auto find = std::get<ast::FindStmt>(parseOne("FIND object WHERE near(?.left)").body);
    const ast::Ref& arg = find.where->args.at(0);
    CHECK(arg.kind == ast::Ref::Kind::Param);
    CHECK(arg.side == "left");
}

TEST_CASE("statements without placeholders have none", "[parser][parameters]") {
    CHECK(parseOne("FIND mug WHERE name = '?' LIMIT 3").parameterCount == 0);
}

TEST_CASE("placeholder errors", "[parser][parameters]") {
    CHECK_THAT(syntaxError("FIND ? WHERE near($1)"), Catch::Contains("cannot mix ? and $1"));
    CHECK_THAT(syntaxError("FIND $0"), Catch::Contains("$0 is out of range"));
    CHECK_THAT(syntaxError("FIND $1000"), Catch::Contains("out of range"));
    // Not a value position: keywords and operators stay SMQL.
    syntaxError("FIND mug WHERE ? = 'red'");
    syntaxError("FIND mug WHERE ?(sofa)");
    syntaxError("USE SCENE ?");
}
