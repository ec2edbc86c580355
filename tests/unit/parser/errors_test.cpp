// Syntax errors: message, location and hint; isIncomplete for the shell.
#include <catch2/catch.hpp>

#include <unistd.h>
#include <cstdio>

#include "parser_test_support.hpp"

using namespace smql;
namespace parser = smql::parser;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

Error errorOf(std::string_view text) { return parser::testing::syntaxErrorOf(text); }

SourceLocation whereOf(const Error& error) {
    REQUIRE(error.where());
    return *error.where();
}

}  // namespace

TEST_CASE("a misspelt clause keyword after the target", "[parser][errors]") {
    Error error = errorOf("FIND cushion WHER on(sofa)");
    CHECK(error.message() == "unexpected 'WHER'");
    CHECK(whereOf(error).line == 1);
    CHECK(whereOf(error).column == 14);
    CHECK(whereOf(error).length == 4);
    CHECK_THAT(error.hint(), StartsWith("did you mean WHERE?"));
    CHECK_THAT(error.hint(),
               Contains("VIEW FROM, WHERE, NEAREST TO, SIMILAR TO, ORDER BY, LIMIT, PATH, RETURN, AS OF or ';'"));
}

TEST_CASE("a misspelt keyword after a condition", "[parser][errors]") {
    Error error = errorOf("FIND mug WHERE on(desk) ODER BY distance(door)");
    CHECK(error.message() == "unexpected 'ODER'");
    CHECK(whereOf(error).column == 25);
    CHECK_THAT(error.hint(), StartsWith("did you mean ORDER?"));
    CHECK_THAT(error.hint(), Contains("AND, OR,"));
}

TEST_CASE("a misspelt statement keyword", "[parser][errors]") {
    Error error = errorOf("FIMD sofa");
    CHECK(error.message() == "'FIMD' does not start a statement");
    CHECK(whereOf(error).column == 1);
    CHECK(error.hint() == "did you mean FIND?");
    CHECK(errorOf("DESCIRBE #4").hint() == "did you mean DESCRIBE?");
    CHECK_THAT(errorOf("SELECT * FROM mug").hint(), StartsWith("a statement starts with"));

    Error unknown = errorOf("HELLO world");
    CHECK(unknown.hint() ==
          "a statement starts with FIND, COUNT, RELATE, DESCRIBE, SHOW, USE, SET, ASK, CHECK, DROP, RENAME, GUIDE or "
          "EXPLAIN");

    // A question typed in English as it is: the hint writes the ASK that takes it, quotes doubled.
    CHECK(errorOf("where is the bed?").hint() == "to ask in English, write ASK 'where is the bed?'");
    CHECK(errorOf("how many chairs are there?").hint() == "to ask in English, write ASK 'how many chairs are there?'");
    CHECK(errorOf("what's on the desk?").hint() == "to ask in English, write ASK 'what''s on the desk?'");
}

TEST_CASE("an error on line 2 of a script", "[parser][errors][locations]") {
    Error error = errorOf("SHOW SCENES;\nFIND mug WHERE colr 'red';\nSHOW TREE");
    CHECK(whereOf(error).line == 2);
    CHECK(whereOf(error).column == 21);
    CHECK(error.message() == "unexpected 'red'");
    CHECK_THAT(error.hint(), Contains("a comparison (=, !=, <, <=, >, >=, LIKE)"));
    std::string rendered = error.render("SHOW SCENES;\nFIND mug WHERE colr 'red';\nSHOW TREE");
    CHECK_THAT(rendered, Contains("line 2, column 21"));
    CHECK_THAT(rendered, Contains("\n  FIND mug WHERE colr 'red';\n                      ^^^^^"));
}

TEST_CASE("the first error in the text wins", "[parser][errors]") {
    Error error = errorOf("FIND a LIMIT 2.5; FIND b WHER c");
    CHECK_THAT(error.message(), Contains("LIMIT needs a whole number"));
    CHECK(whereOf(error).column == 14);
}

TEST_CASE("an unterminated string", "[parser][errors]") {
    Error error = errorOf("FIND mug WHERE color = 'red");
    CHECK(error.message() == "unterminated string");
    CHECK(whereOf(error).column == 24);
    CHECK(whereOf(error).length == 1);
    CHECK_THAT(error.hint(), Contains("close it with '"));
    CHECK(errorOf("FIND \"indoor plant").message() == "unterminated string");
    // A string may span lines, so a missing quote swallows the rest.
    CHECK(errorOf("FIND 'a;\nFIND b;").message() == "unterminated string");
}

TEST_CASE("unbalanced parentheses", "[parser][errors]") {
    Error open = errorOf("FIND x WHERE (on(desk) AND near(door)");
    CHECK(open.message() == "'(' is never closed");
    CHECK(whereOf(open).column == 14);
    CHECK(open.hint() == "add ')' at the end");
    CHECK(errorOf("FIND x WHERE near(door;").hint() == "add ')' before the ';'");

    Error extra = errorOf("FIND x WHERE on(desk))");
    CHECK(extra.message() == "')' has no matching '('");
    CHECK(whereOf(extra).column == 22);
}

TEST_CASE("missing numbers and unknown units", "[parser][errors]") {
    Error missing = errorOf("FIND x WHERE near(window, cm)");
    CHECK(missing.message() == "missing number before 'cm'");
    CHECK(whereOf(missing).column == 27);
    CHECK_THAT(missing.hint(), Contains("near(window, 1.5 m)"));

    Error unit = errorOf("FIND x WHERE near(window, 1.5 km)");
    CHECK(unit.message() == "'km' is not a unit");
    CHECK(whereOf(unit).column == 31);
    CHECK(unit.hint() == "the units are m, cm and mm, as in 30 cm");

    // A misspelt keyword after a number reads as a unit: say which keyword.
    Error keyword = errorOf("FIND x WHERE size > 3 LIMT 4");
    CHECK(keyword.message() == "'LIMT' is not a unit");
    CHECK(whereOf(keyword).column == 23);
    CHECK_THAT(keyword.hint(), Contains("did you mean LIMIT?"));

    Error noNumber = errorOf("FIND x WHERE height >");
    CHECK(noNumber.message() == "unexpected end of input after '>'");
    CHECK(noNumber.hint() == "expected a quoted string or a number");
}

TEST_CASE("LIMIT needs a whole number of 0 or more", "[parser][errors]") {
    Error fraction = errorOf("FIND x LIMIT 2.5");
    CHECK(fraction.message() == "LIMIT needs a whole number, not 2.5");
    CHECK(whereOf(fraction).column == 14);

    Error negative = errorOf("FIND x LIMIT -3");
    CHECK(negative.message() == "LIMIT cannot be negative");
    CHECK(whereOf(negative).column == 14);
    CHECK(whereOf(negative).length == 2);

    Error word = errorOf("FIND x LIMIT ten");
    CHECK(word.message() == "unexpected 'ten'");
    CHECK(word.hint() == "expected a number");

    CHECK_THAT(errorOf("FIND x LIMIT 99999999999999999999").message(), Contains("too large"));
}

TEST_CASE("empty input", "[parser][errors]") {
    for (const char* text : {"", "   \n\t", "-- only a comment\n", ";;"}) {
        INFO(text);
        Error error = errorOf(text);
        CHECK_THAT(error.message(), StartsWith("empty input"));
        CHECK_THAT(error.hint(), Contains("FIND"));
    }
}

TEST_CASE("a statement that ends too early", "[parser][errors]") {
    Error end = errorOf("FIND mug WHERE");
    CHECK(end.message() == "unexpected end of input after 'WHERE'");
    CHECK(whereOf(end).column == 15);
    CHECK(end.hint() == "expected a condition such as on(desk) or color = 'red'");

    Error semicolon = errorOf("FIND mug WHERE ; SHOW SCENES");
    CHECK(semicolon.message() == "unexpected ';' after 'WHERE'");
    CHECK(whereOf(semicolon).column == 16);

    Error target = errorOf("DESCRIBE");
    CHECK_THAT(target.hint(), Contains("a reference"));
}

TEST_CASE("text values need quotes", "[parser][errors]") {
    Error error = errorOf("FIND mug WHERE color = red");
    CHECK(error.message() == "unexpected 'red'");
    CHECK(whereOf(error).column == 24);
    CHECK(error.hint() == "text goes in quotes: 'red'");
}

TEST_CASE("an apostrophe that ends quoted text says how to write it", "[parser][errors]") {
    Error error = errorOf("ASK 'what's on the table?'");
    CHECK(error.message() == "unexpected 's'");
    CHECK(whereOf(error).column == 11);
    CHECK(error.hint() ==
          "a quote inside quoted text is written twice ('what''s ...'), or the text goes in double quotes "
          "(\"what's ...\")");
    // A word after quoted text and a space is another mistake, with its own hint.
    CHECK_THAT(errorOf("FIND mug WHERE color = 'red' blue").hint(), !Contains("written twice"));
}

TEST_CASE("clauses out of order or repeated", "[parser][errors]") {
    Error order = errorOf("FIND x LIMIT 3 WHERE on(y)");
    CHECK(order.message() == "WHERE must come before LIMIT");
    CHECK(whereOf(order).column == 16);

    Error twice = errorOf("FIND x WHERE on(y) WHERE near(z)");
    CHECK(twice.message() == "WHERE given twice");
    CHECK(twice.hint() == "combine the conditions with AND");

    CHECK(errorOf("FIND x PATH LIMIT 2 PATH").message() == "PATH given twice");
    CHECK(errorOf("COUNT x WHERE on(y) VIEW FROM door").message() == "VIEW FROM must come before WHERE");

    Error count = errorOf("COUNT chair LIMIT 3");
    CHECK(count.message() == "unexpected 'LIMIT'");
    CHECK_THAT(count.hint(), Contains("VIEW FROM, WHERE, AS OF or ';'"));
}

TEST_CASE("bad references", "[parser][errors]") {
    Error side = errorOf("FIND x WHERE near(wall.top)");
    CHECK(side.message() == "unknown side 'top'");
    CHECK(whereOf(side).column == 24);
    CHECK_THAT(side.hint(), Contains("left, right, front or back"));

    Error hash = errorOf("DESCRIBE # 42");
    CHECK(hash.message() == "'#' must be followed by a node id");
    CHECK(whereOf(hash).column == 10);

    CHECK_THAT(errorOf("DESCRIBE #99999999999999999999").message(), Contains("too large"));
    CHECK(errorOf("FIND ''").message() == "a quoted name cannot be empty");
    CHECK(errorOf("DESCRIBE src #93").message() == "unexpected '#93'");
}

TEST_CASE("stray characters and missing separators", "[parser][errors]") {
    Error stray = errorOf("FIND mug @ desk");
    CHECK(stray.message() == "unexpected character '@'");
    CHECK(whereOf(stray).column == 10);

    Error joined = errorOf("FIND mug FIND cup");
    CHECK(joined.message() == "unexpected 'FIND'");
    CHECK(joined.hint() == "end the statement before FIND with ';'");

    Error show = errorOf("SHOW TABLES");
    CHECK(show.hint() == "expected SCENES, TREE, SETTINGS, CATEGORIES, ATTRIBUTES, CHANGES or GRAPH");

    // ORDER BY takes distance(x) or an attribute name; which names are attributes the binder decides.
    Error order = errorOf("FIND mug ORDER BY");
    CHECK(order.hint() == "expected a name");

    Error nested = errorOf("EXPLAIN EXPLAIN FIND x");
    CHECK(nested.message() == "'EXPLAIN' does not start a statement");

    Error utf8 = errorOf("FIND \xff\xfe");
    CHECK_THAT(utf8.message(), Contains("UTF-8"));
}

TEST_CASE("parsing never prints and never throws anything but smql::Error", "[parser][errors]") {
    // Capture stderr: ANTLR's console listeners must be gone.
    std::fflush(stderr);
    int saved = dup(fileno(stderr));
    std::FILE* capture = std::tmpfile();
    REQUIRE(capture);
    dup2(fileno(capture), fileno(stderr));

    const std::string query =
        "FIND mug VIEW FROM door FACING 'indoor plant' WHERE color = 'red' AND NOT near(wall.left, 1.5 m) "
        "OR on((FIND desk WHERE id >= #3)) NEAREST TO src#9 LIMIT 3 PATH; SET on.min_overlap = 30 cm";
    std::size_t failures = 0;
    auto attempt = [&](const std::string& text) {
        try {
            parser::parse(text);
        } catch (const Error&) {
            ++failures;
        }
    };
    // Every prefix and every single-character deletion.
    for (std::size_t n = 0; n <= query.size(); ++n) attempt(query.substr(0, n));
    for (std::size_t i = 0; i < query.size(); ++i) attempt(query.substr(0, i) + query.substr(i + 1));

    std::fflush(stderr);
    dup2(saved, fileno(stderr));
    close(saved);
    CHECK(std::ftell(capture) == 0);
    std::fclose(capture);
    CHECK(failures > 0);
}

TEST_CASE("isIncomplete tells the shell to keep reading", "[parser][incomplete]") {
    CHECK(parser::isIncomplete("FIND mug"));
    CHECK(parser::isIncomplete("FIND mug WHERE"));
    CHECK(parser::isIncomplete("SHOW SCENES;\nFIND mug"));
    CHECK(parser::isIncomplete("FIND mug WHERE on(desk;"));       // open parenthesis
    CHECK(parser::isIncomplete("FIND mug WHERE color = 'red;"));  // open quote
    CHECK(parser::isIncomplete("FIND \"indoor\nplant"));          // open double quote
    CHECK(parser::isIncomplete("FIND mug -- a comment;"));        // the ';' is inside the comment

    CHECK_FALSE(parser::isIncomplete("FIND mug;"));
    CHECK_FALSE(parser::isIncomplete("FIND mug;  -- done\n"));
    CHECK_FALSE(parser::isIncomplete("FIND mug WHERE text = 'a;b';"));
    CHECK_FALSE(parser::isIncomplete("FIND mug WHERE on(desk));"));  // an error, but complete: parse() reports it
    CHECK_FALSE(parser::isIncomplete(""));
    CHECK_FALSE(parser::isIncomplete("   "));
    CHECK_FALSE(parser::isIncomplete("-- only a comment"));
}

TEST_CASE("a byte that is not UTF-8 is named by its position", "[parser][errors][utf8]") {
    // A Latin-1 é (0xE9) inside a string: the runtime's decoder would swallow
    // the closing quote and report an unterminated string.
    Error error = errorOf("FIND mug;\nFIND 'caf\xE9' WHERE on(desk)");
    CHECK_THAT(error.message(), StartsWith("the text is not valid UTF-8: byte 20 (0xE9)"));
    CHECK(whereOf(error).line == 2);
    CHECK(whereOf(error).column == 10);
    CHECK_THAT(error.hint(), Contains("UTF-8"));
    // Columns count characters: the 2-byte é before the bad byte is one column.
    CHECK(whereOf(errorOf("FIND 'é\xFF'")).column == 8);
    CHECK_THAT(errorOf("FIND \xC0\xAF").message(), Contains("byte 6 (0xC0)"));        // an overlong '/'
    CHECK_THAT(errorOf("FIND '\xED\xA0\x80'").message(), Contains("byte 7 (0xED)"));  // a surrogate
    CHECK_THAT(errorOf("FIND '\xE2\x82'").message(), Contains("byte 7 (0xE2)"));      // cut short
    CHECK_NOTHROW(parser::parse("FIND 'café' WHERE label = '日本'"));
}

TEST_CASE("nesting is bounded before the recursive parser runs", "[parser][errors][limits]") {
    auto parens = [](std::size_t n) {
        return "FIND mug WHERE " + std::string(n, '(') + "on(desk)" + std::string(n, ')');
    };
    // The deepest statement allowed parses (on(desk) itself is one more level).
    CHECK_NOTHROW(parser::parse(parens(parser::kMaxNestingDepth - 1)));

    // 6,000 parentheses (a 12 KB statement) overflowed the stack.
    Error deep = errorOf(parens(6000));
    CHECK_THAT(deep.message(), Contains("nests more than 100 levels deep"));
    CHECK(whereOf(deep).column == static_cast<int>(16 + parser::kMaxNestingDepth));  // the 101st parenthesis
    CHECK_THAT(deep.hint(), Contains("fewer levels"));

    std::string subqueries = "FIND mug WHERE near(";
    for (int i = 0; i < 3000; ++i) subqueries += "(FIND ";
    subqueries += "door" + std::string(3000, ')') + ")";
    CHECK_THAT(errorOf(subqueries).message(), Contains("nests more than 100 levels deep"));

    std::string nots = "FIND mug WHERE ";
    for (int i = 0; i < 20000; ++i) nots += "NOT ";
    CHECK_THAT(errorOf(nots + "on(desk)").message(), Contains("nests more than 100 levels deep"));

    // NOTs and parentheses add up; closed parentheses give their levels back.
    std::string mixed = "FIND mug WHERE ";
    for (int i = 0; i < 60; ++i) mixed += "NOT (";
    mixed += "on(desk)" + std::string(60, ')');
    CHECK_THAT(errorOf(mixed).message(), Contains("nests more than 100 levels deep"));
    std::string wide = "FIND mug WHERE on(desk)";
    for (int i = 0; i < 500; ++i) wide += " OR (" + std::string(50, '(') + "on(desk)" + std::string(50, ')') + ")";
    CHECK_NOTHROW(parser::parse(wide));
}

TEST_CASE("statement length is bounded", "[parser][errors][limits]") {
    std::string name(parser::kMaxStatementLength - 5, 'x');
    CHECK_NOTHROW(parser::parse("FIND " + name));  // exactly the limit
    Error error = errorOf("SHOW SCENES;\nFIND " + name + "x");
    CHECK(error.message() == "the statement is 100001 characters long; the limit is 100000");
    CHECK(whereOf(error).line == 2);
    CHECK(whereOf(error).column == 1);
    CHECK(error.hint() == "split it into shorter statements");
}

TEST_CASE("a quoted text is bounded: what is compared per row costs at most kMaxTextValue bytes",
          "[parser][errors][limits]") {
    const std::string longest(parser::kMaxTextValue, 'a');
    CHECK_NOTHROW(parser::parse("FIND mug WHERE color = '" + longest + "'"));
    Error error = errorOf("FIND mug WHERE color = '" + longest + "a'");
    CHECK(error.message() == "a quoted text of 4097 bytes: names, values and questions are at most 4096");
    CHECK(whereOf(error).column == 24);
}

TEST_CASE("distances that are not finite or are negative", "[parser][errors]") {
    Error nan = errorOf("FIND chair WHERE near(door, NaN m)");
    CHECK(nan.message() == "'NaN' is not a number");
    CHECK(whereOf(nan).column == 29);
    CHECK(whereOf(nan).length == 3);
    CHECK_THAT(nan.hint(), Contains("finite numbers"));
    CHECK(errorOf("FIND chair WHERE near(door, inf m)").message() == "'inf' is not a number");
    CHECK(errorOf("FIND chair WHERE height > Infinity m").message() == "'Infinity' is not a number");
    CHECK(errorOf("FIND chair WHERE height < -inf").message() == "'inf' is not a number");
    CHECK(errorOf("SET near = NaN m").message() == "'NaN' is not a number");

    Error negative = errorOf("FIND chair WHERE near(door, -1 m)");
    CHECK(negative.message() == "a distance cannot be negative");
    CHECK(whereOf(negative).column == 29);
    CHECK(whereOf(negative).length == 4);
    CHECK_THAT(negative.hint(), Contains("0 or more"));
    CHECK(errorOf("FIND chair WHERE near(door, -20)").message() == "a distance cannot be negative");
    // A name that merely starts like one is still a name.
    CHECK_THAT(errorOf("FIND chair WHERE near(door, nano m)").message(), Contains("unexpected 'm'"));
}
