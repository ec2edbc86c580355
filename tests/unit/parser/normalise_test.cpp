// Statement shapes: the scan that takes a text's literals out (parser/normalise.hpp), and the
// shape's placeholder text as the parser reads it.
#include <catch2/catch.hpp>

#include "engine/parser/normalise.hpp"
#include "parser_test_support.hpp"

using namespace smql;
using namespace smql::parser;
using Kind = ShapeLiteral::Kind;

namespace {

StatementShape shapeOf(std::string_view text) {
    std::optional<StatementShape> shape = statementShape(text);
    REQUIRE(shape.has_value());
    return *shape;
}

}  // namespace

TEST_CASE("a shape is the text's tokens with literals as $k, then the literals' kinds", "[shapes]") {
    StatementShape shape = shapeOf("FIND object WHERE on('Table') AND near(window, 1.5 m) LIMIT 5");
    CHECK(shape.key == "find object where on ( $1 ) and near ( window , $2 ) limit $3\nsli");
    CHECK(shape.placeholderText() == "find object where on ( $1 ) and near ( window , $2 ) limit $3");
    REQUIRE(shape.literals.size() == 3);
    CHECK(shape.literals[0].kind == Kind::Text);
    CHECK(shape.literals[0].text == "Table");
    CHECK(shape.literals[1].kind == Kind::Length);
    CHECK(shape.literals[1].number == 1.5);
    CHECK(shape.literals[2].kind == Kind::Integer);
    CHECK(shape.literals[2].integer == 5);
}

TEST_CASE("texts that differ in literals, case, spacing and comments share a shape; others do not", "[shapes]") {
    const std::string key = shapeOf("RELATE #12 TO #40").key;
    CHECK(key == "relate $1 to $2\nnn");
    CHECK(shapeOf("relate   #7 to\n#9 -- a comment").key == key);
    CHECK(shapeOf("RELATE #1 TO #2;").key == key);
    CHECK(shapeOf("RELATE #1 TO sofa#2").key != key);  // a labelled id is kept as written
    CHECK(shapeOf("RELATE #1 TO sofa#2").key == "relate $1 to sofa#2\nn");
    CHECK(shapeOf("COUNT mug WHERE near(sofa, 1 m)").key != shapeOf("COUNT mug WHERE near(sofa, 1)").key);
    CHECK(shapeOf("COUNT mug WHERE near(sofa, 1)").key != shapeOf("COUNT mug WHERE near(sofa, 1.0)").key);
    CHECK(shapeOf("FIND mug LIMIT 3").key != shapeOf("FIND 'mug' LIMIT 3").key);
}

TEST_CASE("strings: both quotes, doubled quotes, lines, UTF-8 kept as written", "[shapes]") {
    StatementShape shape = shapeOf("FIND 'it''s' WHERE color = \"say \"\"hi\"\"\" AND near('a\nb', 2 cm)");
    REQUIRE(shape.literals.size() == 4);
    CHECK(shape.literals[0].text == "it's");
    CHECK(shape.literals[1].text == "say \"hi\"");
    CHECK(shape.literals[2].text == "a\nb");
    CHECK(shape.literals[3].kind == Kind::Length);
    CHECK(shape.literals[3].number == 2.0 / 100.0);  // as the parser divides: 2 cm is exactly 0.02 m
    CHECK(shapeOf("FIND 'café'").literals.at(0).text == "café");
    CHECK(shapeOf("FIND '-- not a comment'").literals.at(0).text == "-- not a comment");
}

TEST_CASE("numbers: whole, real, with units in any case, and what is not a unit", "[shapes]") {
    CHECK(shapeOf("FIND x WHERE height > .5").literals.at(0).kind == Kind::Real);
    CHECK(shapeOf("FIND x WHERE height > 2.").literals.at(0).number == 2.0);
    CHECK(shapeOf("FIND x WHERE height > 300 MM").literals.at(0).number == 0.3);
    CHECK(shapeOf("FIND x WHERE height > 80cm").literals.at(0).kind == Kind::Length);
    // `m#5` is a labelled id, not the unit m; `mug` is a name.
    StatementShape labelled = shapeOf("FIND x WHERE near(y, 2 m#5)");
    CHECK(labelled.literals.at(0).kind == Kind::Integer);
    CHECK(labelled.key == "find x where near ( y , $1 m#5 )\ni");
    CHECK(shapeOf("FIND x LIMIT 2 mug").key == "find x limit $1 mug\ni");
    // Hyphens inside a word; two of them begin a comment.
    CHECK(shapeOf("FIND plant-stand").key == "find plant-stand\n");
    CHECK(shapeOf("FIND plant--stand").key == "find plant\n");
}

TEST_CASE("EXPLAIN's statement and the statement's own text are found", "[shapes]") {
    const std::string text = "  EXPLAIN  FIND mug WHERE on(#4) ; -- done";
    StatementShape shape = shapeOf(text);
    CHECK(text.substr(shape.begin, shape.end - shape.begin) == "EXPLAIN  FIND mug WHERE on(#4)");
    CHECK(text.substr(shape.afterExplain, shape.end - shape.afterExplain) == "FIND mug WHERE on(#4)");
}

TEST_CASE("texts without a shape go to the parser", "[shapes]") {
    for (const char* text : {
             "",                                   // nothing
             "-- only a comment",                  //
             "USE SCENE 'room'",                   // changes the session
             "SET near = 1 m",                     //
             "ASK 'where is the mug?'",            //
             "SHOW SCENES",                        //
             "EXPLAIN SET near = 1 m",             //
             "FIND ? WHERE near(?, 1 m)",          // placeholders of its own
             "FIND $1",                            //
             "FIND mug; FIND cup",                 // two statements
             "FIND 'unterminated",                 //
             "FIND mug WHERE size ~ 3",            // a character SMQL does not know
             "FIND #",                             //
             "FIND x LIMIT 99999999999999999999",  // a number the parser refuses
             "FIND \xC3",                          // not UTF-8
             "FIND caf\xC3\xA9",                   // a letter outside ASCII outside quotes
         }) {
        INFO(text);
        CHECK_FALSE(statementShape(text).has_value());
    }
    CHECK_FALSE(statementShape("FIND '" + std::string(kMaxTextValue + 1, 'a') + "'").has_value());
    CHECK(statementShape("FIND '" + std::string(kMaxTextValue, 'a') + "'").has_value());
}

TEST_CASE("a shape's placeholder text parses, node ids standing for node ids", "[shapes]") {
    ast::Statement relate = parseShape(shapeOf("RELATE #12 TO 'Sofa'"));
    CHECK(relate.parameterCount == 2);
    const auto& body = std::get<ast::RelateStmt>(relate.body);
    CHECK(body.subject.kind == ast::Ref::Kind::Param);
    CHECK(body.subject.placeholder.nodeId);
    CHECK_FALSE(body.object.placeholder.nodeId);
    CHECK_THROWS_AS(parseShape(shapeOf("CHECK mug near window 1 m")), Error);  // no placeholder for CHECK's distance
}

TEST_CASE("sameStatement ignores places and text, and nothing else", "[shapes]") {
    using testing::parseOne;
    CHECK(sameStatement(parseOne("FIND mug WHERE near(sofa, 1 m)"), parseOne("find  MUG where near(sofa,100 cm)")));
    CHECK_FALSE(sameStatement(parseOne("FIND mug WHERE near(sofa, 1 m)"), parseOne("FIND mug WHERE near(sofa, 2 m)")));
    CHECK_FALSE(sameStatement(parseOne("FIND mug LIMIT 2"), parseOne("FIND mug LIMIT 3")));
    CHECK_FALSE(sameStatement(parseOne("RELATE #1 TO #2"), parseOne("RELATE #1 TO cup#2")));
    CHECK_FALSE(sameStatement(parseOne("FIND mug WHERE color = 'Red'"), parseOne("FIND mug WHERE color = 'red'")));
    CHECK_FALSE(sameStatement(parseOne("EXPLAIN COUNT mug"), parseOne("COUNT mug")));
    CHECK_FALSE(sameStatement(parseOne("SHOW SCENES"), parseOne("SHOW SCENES")));  // no shape holds SHOW
}
