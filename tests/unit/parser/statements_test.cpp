// Every statement form, references, literals and source locations.
#include <catch2/catch.hpp>

#include "parser_test_support.hpp"

using namespace smql;
namespace parser = smql::parser;
using smql::parser::testing::parseOne;

namespace {

template <typename Body>
Body bodyOf(std::string_view text) {
    ast::Statement statement = parseOne(text);
    REQUIRE(std::holds_alternative<Body>(statement.body));
    return std::get<Body>(statement.body);
}

ast::Ref targetOf(std::string_view text) { return bodyOf<ast::FindStmt>(text).target; }

}  // namespace

TEST_CASE("FIND with every clause", "[parser][find]") {
    auto find = bodyOf<ast::FindStmt>(
        "FIND mug VIEW FROM door FACING window WHERE color = 'red' ORDER BY distance(sofa) DESC LIMIT 3 PATH");
    CHECK(find.target.kind == ast::Ref::Kind::Name);
    CHECK(find.target.name == "mug");
    REQUIRE(find.view);
    CHECK(find.view->from.name == "door");
    REQUIRE(find.view->facing);
    CHECK(find.view->facing->name == "window");
    REQUIRE(find.where);
    CHECK(find.where->kind == ast::Expr::Kind::Compare);
    REQUIRE(find.orderBy);
    CHECK(find.orderBy->distanceTo->name == "sofa");
    CHECK(find.orderBy->descending);
    CHECK(find.limit == 3);
    CHECK(find.path);
    CHECK_FALSE(find.nearestTo);
}

TEST_CASE("FIND with only a target leaves every clause empty", "[parser][find]") {
    auto find = bodyOf<ast::FindStmt>("FIND object");
    CHECK(find.target.name == "object");
    CHECK_FALSE(find.view);
    CHECK_FALSE(find.where);
    CHECK_FALSE(find.nearestTo);
    CHECK_FALSE(find.orderBy);
    CHECK_FALSE(find.limit);
    CHECK_FALSE(find.path);
}

TEST_CASE("FIND NEAREST TO and ORDER BY ascending", "[parser][find]") {
    // Both at once parse; the binder rejects the pair.
    auto both = bodyOf<ast::FindStmt>("FIND x NEAREST TO door ORDER BY distance(door)");
    CHECK(both.nearestTo);
    CHECK(both.orderBy);

    auto nearest = bodyOf<ast::FindStmt>("FIND object NEAREST TO door LIMIT 5");
    REQUIRE(nearest.nearestTo);
    CHECK(nearest.nearestTo->name == "door");
    CHECK(nearest.limit == 5);

    auto ordered = bodyOf<ast::FindStmt>("FIND mug ORDER BY distance(door) ASC");
    REQUIRE(ordered.orderBy);
    CHECK_FALSE(ordered.orderBy->descending);
    CHECK_FALSE(bodyOf<ast::FindStmt>("FIND mug ORDER BY distance(door)").orderBy->descending);
}

TEST_CASE("PATH may stand anywhere after the target", "[parser][find]") {
    for (const char* text : {"FIND mug PATH WHERE on(desk) LIMIT 2", "FIND mug WHERE on(desk) PATH LIMIT 2",
                             "FIND mug WHERE on(desk) LIMIT 2 PATH"}) {
        INFO(text);
        auto find = bodyOf<ast::FindStmt>(text);
        CHECK(find.path);
        CHECK(find.where);
        CHECK(find.limit == 2);
    }
}

TEST_CASE("LIMIT 0 is allowed", "[parser][find]") { CHECK(bodyOf<ast::FindStmt>("FIND mug LIMIT 0").limit == 0); }

TEST_CASE("COUNT with a view and a condition", "[parser][count]") {
    auto count = bodyOf<ast::CountStmt>("COUNT chair VIEW FROM door WHERE near(table)");
    CHECK(count.target.name == "chair");
    REQUIRE(count.view);
    CHECK(count.view->from.name == "door");
    CHECK_FALSE(count.view->facing);
    REQUIRE(count.where);
    CHECK(count.where->predicate == "near");
    CHECK_FALSE(bodyOf<ast::CountStmt>("COUNT chair").where);
}

TEST_CASE("RELATE two references, with and without a view", "[parser][relate]") {
    auto relate = bodyOf<ast::RelateStmt>("RELATE lamp TO window");
    CHECK(relate.subject.name == "lamp");
    CHECK(relate.object.name == "window");
    CHECK_FALSE(relate.view);

    auto viewed = bodyOf<ast::RelateStmt>("RELATE lamp TO #7 VIEW FROM door FACING window");
    CHECK(viewed.object.kind == ast::Ref::Kind::NodeId);
    REQUIRE(viewed.view);
    CHECK(viewed.view->facing->name == "window");
}

TEST_CASE("DESCRIBE a node", "[parser][describe]") {
    auto describe = bodyOf<ast::DescribeStmt>("DESCRIBE #42");
    CHECK(describe.target.kind == ast::Ref::Kind::NodeId);
    CHECK(describe.target.number == 42);
}

TEST_CASE("SHOW SCENES, TREE and SETTINGS", "[parser][show]") {
    CHECK(bodyOf<ast::ShowStmt>("SHOW SCENES").what == ast::ShowStmt::What::Scenes);
    CHECK(bodyOf<ast::ShowStmt>("SHOW SETTINGS").what == ast::ShowStmt::What::Settings);
    auto tree = bodyOf<ast::ShowStmt>("SHOW TREE");
    CHECK(tree.what == ast::ShowStmt::What::Tree);
    CHECK_FALSE(tree.root);
    auto subtree = bodyOf<ast::ShowStmt>("SHOW TREE #12");
    REQUIRE(subtree.root);
    CHECK(subtree.root->number == 12);
}

TEST_CASE("USE SCENE: bare names are lower-cased, quoted names kept", "[parser][use]") {
    auto bare = bodyOf<ast::UseStmt>("USE SCENE Room0");
    CHECK(bare.scene == "room0");
    CHECK(bodyOf<ast::UseStmt>("USE SCENE 'Kitchen 2024'").scene == "Kitchen 2024");
    CHECK(bodyOf<ast::UseStmt>("use scene scene").scene == "scene");
    CHECK(bodyOf<ast::UseStmt>("USE SCENE *").scene == "*");
    CHECK(bare.where.line == 1);
    CHECK(bare.where.column == 1);
    CHECK(bare.where.length == 15);
}

TEST_CASE("SET values: distances, numbers, strings, words", "[parser][set]") {
    auto distance = bodyOf<ast::SetStmt>("SET near = 0.8 m");
    CHECK(distance.name == "near");
    REQUIRE(std::holds_alternative<ast::Distance>(distance.value));
    CHECK(std::get<ast::Distance>(distance.value).metres == Approx(0.8));
    CHECK(std::get<ast::Distance>(distance.value).where.column == 12);
    CHECK(std::get<ast::Distance>(distance.value).where.length == 5);

    auto centimetres = bodyOf<ast::SetStmt>("SET near = 30 cm");
    CHECK(std::get<ast::Distance>(centimetres.value).metres == Approx(0.3));

    auto dotted = bodyOf<ast::SetStmt>("SET On.Min_Overlap = 0.4");
    CHECK(dotted.name == "on.min_overlap");
    REQUIRE(std::holds_alternative<double>(dotted.value));
    CHECK(std::get<double>(dotted.value) == Approx(0.4));

    auto whole = bodyOf<ast::SetStmt>("SET limit = 10");
    CHECK(whole.name == "limit");
    CHECK(std::get<double>(whole.value) == 10.0);
    CHECK(std::get<double>(bodyOf<ast::SetStmt>("SET offset = -2").value) == -2.0);

    auto quoted = bodyOf<ast::SetStmt>("SET format = 'JSON'");
    CHECK(std::get<std::string>(quoted.value) == "JSON");
    auto word = bodyOf<ast::SetStmt>("SET format = Table");
    CHECK(std::get<std::string>(word.value) == "table");

    // Ranges are the setting's business, not the parser's.
    auto negative = bodyOf<ast::SetStmt>("SET near = -30 cm");
    CHECK(std::get<ast::Distance>(negative.value).metres == Approx(-0.3));
}

TEST_CASE("EXPLAIN wraps a statement with its own text", "[parser][explain]") {
    ast::Statement statement = parseOne("EXPLAIN FIND mug WHERE on(desk)");
    CHECK(statement.text == "EXPLAIN FIND mug WHERE on(desk)");
    REQUIRE(std::holds_alternative<ast::ExplainStmt>(statement.body));
    const ast::Statement& inner = *std::get<ast::ExplainStmt>(statement.body).inner;
    CHECK(inner.text == "FIND mug WHERE on(desk)");
    CHECK(inner.where.column == 9);
    REQUIRE(std::holds_alternative<ast::FindStmt>(inner.body));
    CHECK(std::get<ast::FindStmt>(inner.body).target.name == "mug");
}

TEST_CASE("units convert to metres", "[parser][units]") {
    auto thresholdOf = [](std::string_view text) {
        auto find = bodyOf<ast::FindStmt>(text);
        REQUIRE(find.where);
        REQUIRE(find.where->threshold);
        return find.where->threshold->metres;
    };
    CHECK(thresholdOf("FIND x WHERE near(a, 30 cm)") == thresholdOf("FIND x WHERE near(a, 0.3 m)"));
    CHECK(thresholdOf("FIND x WHERE near(a, 30cm)") == Approx(0.3));
    CHECK(thresholdOf("FIND x WHERE near(a, 5 mm)") == Approx(0.005));
    CHECK(thresholdOf("FIND x WHERE near(a, 1500 MM)") == Approx(1.5));
    CHECK(thresholdOf("FIND x WHERE near(a, 2 M)") == 2.0);
    CHECK(thresholdOf("FIND x WHERE near(a, .5)") == 0.5);  // no unit: metres
    CHECK(thresholdOf("FIND x WHERE near(a, 1.)") == 1.0);
}

TEST_CASE("reference kinds", "[parser][refs]") {
    ast::Ref name = targetOf("FIND Sofa");
    CHECK(name.kind == ast::Ref::Kind::Name);
    CHECK(name.name == "sofa");

    ast::Ref quoted = targetOf("FIND 'Indoor Plant'");
    CHECK(quoted.kind == ast::Ref::Kind::Name);
    CHECK(quoted.name == "indoor plant");
    CHECK(targetOf("FIND \"it's\"").name == "it's");
    CHECK(targetOf("FIND 'it''s'").name == "it's");

    ast::Ref side = targetOf("FIND wall.Left");
    CHECK(side.kind == ast::Ref::Kind::Side);
    CHECK(side.name == "wall");
    CHECK(side.side == "left");
    for (const char* s : {"right", "front", "back"}) CHECK(targetOf(std::string("FIND wall.") + s).side == s);

    ast::Ref node = targetOf("FIND #42");
    CHECK(node.kind == ast::Ref::Kind::NodeId);
    CHECK(node.number == 42);

    ast::Ref source = targetOf("FIND SRC#93");
    CHECK(source.kind == ast::Ref::Kind::SourceId);
    CHECK(source.number == 93);

    ast::Ref sub = targetOf("FIND (FIND mug WHERE on(desk))");
    CHECK(sub.kind == ast::Ref::Kind::SubQuery);
    REQUIRE(sub.subquery);
    CHECK(sub.subquery->target.name == "mug");
    CHECK(sub.subquery->where);
}

TEST_CASE("hyphenated names", "[parser][refs]") {
    CHECK(targetOf("FIND plant-stand").name == "plant-stand");
    CHECK(targetOf("FIND Wall-Plug").name == "wall-plug");
    auto find = bodyOf<ast::FindStmt>("FIND indoor-plant WHERE on(plant-stand-2)");
    CHECK(find.target.name == "indoor-plant");
    CHECK(find.where->args.at(0).name == "plant-stand-2");
    // A double hyphen starts a comment, even straight after a name.
    CHECK(targetOf("FIND lamp--the tall one").name == "lamp");
}

TEST_CASE("kind words and keywords are names where a name is expected", "[parser][refs]") {
    CHECK(targetOf("FIND object").name == "object");
    CHECK(targetOf("FIND scene").name == "scene");
    CHECK(targetOf("FIND tree PATH").name == "tree");
    auto find = bodyOf<ast::FindStmt>("FIND path WHERE near(view) PATH");
    CHECK(find.target.name == "path");
    CHECK(find.where->args.at(0).name == "view");
    CHECK(find.path);
}

TEST_CASE("sub-queries nest", "[parser][refs]") {
    auto find = bodyOf<ast::FindStmt>("FIND mug WHERE on((FIND desk WHERE near((FIND window WHERE on(wall.left)))))");
    const ast::Ref& desk = find.where->args.at(0);
    REQUIRE(desk.kind == ast::Ref::Kind::SubQuery);
    CHECK(desk.subquery->target.name == "desk");
    const ast::Ref& window = desk.subquery->where->args.at(0);
    REQUIRE(window.kind == ast::Ref::Kind::SubQuery);
    CHECK(window.subquery->target.name == "window");
    const ast::Ref& wall = window.subquery->where->args.at(0);
    CHECK(wall.kind == ast::Ref::Kind::Side);
    CHECK(wall.side == "left");
}

TEST_CASE("keywords are case-insensitive", "[parser][case]") {
    auto find = bodyOf<ast::FindStmt>(
        "find Mug where Color = 'Red' and NEAR(Window, 1 M) order by DISTANCE(door) desc limit 2 path");
    CHECK(find.target.name == "mug");
    REQUIRE(find.where);
    CHECK(find.where->kind == ast::Expr::Kind::And);
    CHECK(find.where->children.at(0).attribute == "color");
    CHECK(std::get<std::string>(find.where->children.at(0).literal) == "Red");  // values keep their case
    CHECK(find.where->children.at(1).predicate == "near");
    CHECK(find.where->children.at(1).args.at(0).name == "window");
    CHECK(find.orderBy->descending);
    CHECK(find.limit == 2);
    CHECK(find.path);
    CHECK(std::holds_alternative<ast::ShowStmt>(parseOne("sHoW sCeNeS").body));
}

TEST_CASE("statements are separated by semicolons, the last one optional", "[parser][script]") {
    auto statements = parser::parse("SHOW SCENES; USE SCENE 'room0'; SHOW TREE;");
    REQUIRE(statements.size() == 3);
    CHECK(std::holds_alternative<ast::ShowStmt>(statements[0].body));
    CHECK(std::holds_alternative<ast::UseStmt>(statements[1].body));
    CHECK(std::holds_alternative<ast::ShowStmt>(statements[2].body));

    CHECK(parser::parse("FIND a; FIND b").size() == 2);
    CHECK(parser::parse(";; FIND a;; ;").size() == 1);  // empty statements are skipped
}

TEST_CASE("comments are ignored", "[parser][script]") {
    auto statements = parser::parse(
        "-- the lamps\n"
        "RELATE lamp TO window;   -- \"lamp is left of window\"\n"
        "DESCRIBE #42 -- node by id\n"
        ";\n"
        "-- the end");
    REQUIRE(statements.size() == 2);
    CHECK(statements[0].text == "RELATE lamp TO window");
    CHECK(statements[1].text == "DESCRIBE #42");
    CHECK(parser::parse("FIND mug -- WHERE on(desk)\n").size() == 1);
    CHECK_FALSE(bodyOf<ast::FindStmt>("FIND mug -- WHERE on(desk)\n").where);
}

TEST_CASE("statement text and locations", "[parser][locations]") {
    auto statements = parser::parse("SHOW SCENES;\n  FIND mug\n    WHERE on(desk)  ;");
    REQUIRE(statements.size() == 2);
    const ast::Statement& find = statements[1];
    CHECK(find.text == "FIND mug\n    WHERE on(desk)");
    CHECK(find.where.line == 2);
    CHECK(find.where.column == 3);

    const auto& body = std::get<ast::FindStmt>(find.body);
    CHECK(body.target.where.line == 2);
    CHECK(body.target.where.column == 8);
    CHECK(body.target.where.length == 3);
    REQUIRE(body.where);
    CHECK(body.where->where.line == 3);
    CHECK(body.where->where.column == 11);
    CHECK(body.where->where.length == 8);  // on(desk)
    CHECK(body.where->args.at(0).where.column == 14);
}

TEST_CASE("locations of views, orderings, distances and settings", "[parser][locations]") {
    auto find = bodyOf<ast::FindStmt>("FIND mug VIEW FROM door FACING window ORDER BY distance(sofa) DESC");
    CHECK(find.view->where.column == 10);
    CHECK(find.view->where.length == 28);  // VIEW FROM door FACING window
    CHECK(find.view->facing->where.column == 32);
    CHECK(find.orderBy->where.column == 39);
    CHECK(find.orderBy->where.length == 28);  // ORDER BY distance(sofa) DESC
    CHECK(find.orderBy->distanceTo->where.column == 57);

    auto near = bodyOf<ast::FindStmt>("FIND x WHERE near(window, 1.5 m)").where;
    CHECK(near->threshold->where.column == 27);
    CHECK(near->threshold->where.length == 5);

    auto set = bodyOf<ast::SetStmt>("SET near = 0.8 m");
    CHECK(set.where.column == 1);
    CHECK(set.where.length == 16);

    ast::Ref sub = targetOf("FIND (FIND mug)");
    CHECK(sub.where.column == 6);
    CHECK(sub.where.length == 10);
}

TEST_CASE("keywords() lists the upper-case keywords", "[parser][keywords]") {
    const auto& words = parser::keywords();
    for (const char* word :
         {"FIND",   "COUNT", "RELATE",  "DESCRIBE", "SHOW",  "USE", "SET", "EXPLAIN", "VIEW",  "FROM",
          "FACING", "WHERE", "NEAREST", "TO",       "ORDER", "BY",  "ASC", "DESC",    "LIMIT", "PATH",
          "SCENES", "SCENE", "TREE",    "SETTINGS", "AND",   "OR",  "NOT", "LIKE",    "GUIDE", "HERE",
          "GRAPH",  "DROP",  "RENAME",  "CHANGES",  "SINCE", "AS",  "OF"})
        CHECK(std::find(words.begin(), words.end(), word) != words.end());
    CHECK(std::find(words.begin(), words.end(), "IDENT") == words.end());
    CHECK(std::find(words.begin(), words.end(), "STRING") == words.end());
}

TEST_CASE("ASK takes the question as a string, case and quotes kept", "[parser][ask]") {
    auto ask = bodyOf<ast::AskStmt>("ask 'Where''s the Red mug?'");
    CHECK(ask.question == "Where's the Red mug?");
    CHECK(ask.where.column == 5);
    CHECK(bodyOf<ast::AskStmt>("ASK \"is there a sofa?\"").question == "is there a sofa?");
    // ASK is also a name, like the other statement words.
    CHECK(targetOf("FIND ask").name == "ask");
    CHECK_THROWS_AS(parser::parse("ASK where is the mug"), Error);
    CHECK_THROWS_AS(parser::parse("ASK"), Error);
}

TEST_CASE("name#id is a node id with the category to check", "[parser][refs]") {
    auto ref = targetOf("FIND Sofa#50");
    CHECK(ref.kind == ast::Ref::Kind::NodeId);
    CHECK(ref.number == 50);
    CHECK(ref.name == "sofa");
    CHECK(targetOf("FIND plant-stand#7").name == "plant-stand");
    // `#50` alone names no category; src#50 stays a source id.
    CHECK(targetOf("FIND #50").name.empty());
    CHECK(targetOf("FIND src#50").kind == ast::Ref::Kind::SourceId);
    auto relate = bodyOf<ast::RelateStmt>("RELATE lamp#13 TO window#9");
    CHECK(relate.subject.number == 13);
    CHECK(relate.object.name == "window");
}

TEST_CASE("CHECK: a predicate between references, with a distance and a view", "[parser][check]") {
    auto check = bodyOf<ast::CheckStmt>("CHECK lamp LEFT_OF window#9");
    CHECK(check.subject.name == "lamp");
    CHECK(check.predicate == "left_of");
    REQUIRE(check.args.size() == 1);
    CHECK(check.args[0].number == 9);
    CHECK_FALSE(check.threshold);
    CHECK_FALSE(check.view);

    auto near = bodyOf<ast::CheckStmt>("CHECK mug near window 30 cm VIEW FROM door");
    REQUIRE(near.threshold);
    CHECK(near.threshold->metres == Approx(0.3));
    REQUIRE(near.view);
    CHECK(near.view->from.name == "door");

    auto between = bodyOf<ast::CheckStmt>("CHECK lamp between sofa AND (FIND desk LIMIT 1)");
    REQUIRE(between.args.size() == 2);
    CHECK(between.args[1].kind == ast::Ref::Kind::SubQuery);
}

TEST_CASE("SHOW CATEGORIES and SHOW ATTRIBUTES", "[parser][show]") {
    CHECK(bodyOf<ast::ShowStmt>("show categories").what == ast::ShowStmt::What::Categories);
    CHECK(bodyOf<ast::ShowStmt>("SHOW ATTRIBUTES").what == ast::ShowStmt::What::Attributes);
    // The new keywords are still names.
    CHECK(targetOf("FIND check").name == "check");
    CHECK(targetOf("FIND categories").name == "categories");
}

TEST_CASE("ORDER BY an attribute, RETURN columns", "[parser][find]") {
    auto find = bodyOf<ast::FindStmt>("FIND lamp ORDER BY Height DESC LIMIT 1 RETURN id, Color, center");
    REQUIRE(find.orderBy);
    CHECK_FALSE(find.orderBy->distanceTo);
    CHECK(find.orderBy->attribute == "height");
    CHECK(find.orderBy->descending);
    CHECK(find.columns == std::vector<std::string>{"id", "color", "center"});
    // RETURN may stand anywhere after the target, once.
    CHECK(bodyOf<ast::FindStmt>("FIND mug RETURN id WHERE color = 'red'").columns.size() == 1);
    CHECK_THROWS_WITH(parser::parse("FIND mug RETURN id RETURN color"), Catch::Contains("RETURN given twice"));
}

TEST_CASE("comparisons of distance(x), units remembered, BETWEEN as two bounds", "[parser][expr]") {
    auto find = bodyOf<ast::FindStmt>("FIND object WHERE distance(sofa) < 2 m");
    REQUIRE(find.where);
    CHECK(find.where->kind == ast::Expr::Kind::Compare);
    REQUIRE(find.where->distanceTo);
    CHECK(find.where->distanceTo->name == "sofa");
    CHECK(find.where->literalHasUnit);
    CHECK(std::get<double>(find.where->literal) == 2.0);
    CHECK_FALSE(bodyOf<ast::FindStmt>("FIND object WHERE height > 2").where->literalHasUnit);

    auto band = bodyOf<ast::FindStmt>("FIND object WHERE height BETWEEN 50 cm AND 1 m AND on(desk)");
    REQUIRE(band.where);
    REQUIRE(band.where->kind == ast::Expr::Kind::And);
    REQUIRE(band.where->children.size() == 2);  // (height BETWEEN ...) AND on(desk)
    const ast::Expr& bounds = band.where->children[0];
    REQUIRE(bounds.kind == ast::Expr::Kind::And);
    CHECK(bounds.children[0].op == ast::CompareOp::Ge);
    CHECK(std::get<double>(bounds.children[0].literal) == Approx(0.5));
    CHECK(bounds.children[1].op == ast::CompareOp::Le);
    CHECK(std::get<double>(bounds.children[1].literal) == 1.0);
    // between(...) is still the predicate.
    CHECK(bodyOf<ast::FindStmt>("FIND lamp WHERE between(sofa, desk)").where->predicate == "between");
}
