// The cache of statement shapes (binder/shape_cache.hpp): a text that differs from one run before
// only in its literals skips the parser, and the answer, or the error, is never another.
#include <algorithm>
#include <functional>
#include <sstream>

#include <fmt/format.h>
#include <catch2/catch.hpp>

#include "engine/format.hpp"
#include "engine/parser/normalise.hpp"
#include "engine/parser/parser.hpp"
#include "engine_support.hpp"
#include "ingest/import/registry.hpp"
#include "query_suites.hpp"

using namespace smql;
using namespace smql::testing;
namespace fs = std::filesystem;

namespace {

// An engine over its own database, with the shape cache on or off.
struct Database {
    TempDir dir;
    std::unique_ptr<Engine> engine = Engine::open(dir.path.string());
    explicit Database(bool shapes) {
        if (!shapes) engine->execute("SET shape_cache = 0");
    }
};

// An outcome less the two lines where the engines differ by design: EXPLAIN's word that the
// statement came from a shape, and SHOW SETTINGS' row of the cache's size.
std::string withoutCacheLines(const std::string& outcome) {
    std::istringstream lines(outcome);
    std::string out;
    for (std::string line; std::getline(lines, line);)
        if (line.rfind("\"Parse skipped: a cached statement shape", 0) != 0 && line.rfind("shape_cache,", 0) != 0)
            out += line + "\n";
    return out;
}

// Another text of the same shape: every literal changed, so a cache that kept a literal's old
// value would answer for the wrong one. Built from the shape's placeholder text.
std::string siblingOf(const parser::StatementShape& shape) {
    std::istringstream tokens{std::string(shape.placeholderText())};
    std::string out;
    for (std::string token; tokens >> token;) {
        if (token.size() > 1 && token[0] == '$') {
            const parser::ShapeLiteral& literal = shape.literals.at(std::stoul(token.substr(1)) - 1);
            switch (literal.kind) {
                case parser::ShapeLiteral::Kind::Text:
                    token = literal.text == "chair" ? "'table'" : "'chair'";
                    break;
                case parser::ShapeLiteral::Kind::Integer:
                    token = std::to_string(literal.integer + 1);
                    break;
                case parser::ShapeLiteral::Kind::NodeId:
                    token = "#" + std::to_string(literal.integer + 1);
                    break;
                case parser::ShapeLiteral::Kind::Real:
                    token = fmt::format("{:.3f}", literal.number + 0.5);
                    break;
                case parser::ShapeLiteral::Kind::Length:
                    token = fmt::format("{:.3f} m", literal.number + 0.25);
                    break;
            }
        }
        out += token + " ";
    }
    return out;
}

}  // namespace

TEST_CASE("a text with new literals is answered from its shape, without the parser", "[shapes]") {
    Database cached(true), plain(false);
    for (Database* db : {&cached, &plain})
        db->engine->importScene(import::read("replica", replicaRoom0(), "replica-room0"));
    const std::string first = "FIND object WHERE near('sofa', 0.5 m) AND on(#20)";
    const std::string second = "find object where near(\"table\", 120 cm) and on(#21) -- another";
    CHECK(outcome(*cached.engine, first) == outcome(*plain.engine, first));

    const std::uint64_t parsedBefore = parser::statementsParsed();
    const std::uint64_t hitsBefore = cached.engine->shapeCacheStats().hits;
    const std::string answer = outcome(*cached.engine, second);
    CHECK(parser::statementsParsed() == parsedBefore);
    CHECK(cached.engine->shapeCacheStats().hits == hitsBefore + 1);
    CHECK(answer == outcome(*plain.engine, second));
    CHECK(plain.engine->shapeCacheStats().hits == 0);

    // RELATE's node ids are literals too.
    CHECK(outcome(*cached.engine, "RELATE #20 TO #21") == outcome(*plain.engine, "RELATE #20 TO #21"));
    CHECK(outcome(*cached.engine, "RELATE #22 TO #23") == outcome(*plain.engine, "RELATE #22 TO #23"));
    CHECK(cached.engine->shapeCacheStats().hits == hitsBefore + 2);
}

TEST_CASE("EXPLAIN says when the statement came from a cached shape", "[shapes]") {
    Database db(true);
    db.engine->importScene(import::read("replica", replicaRoom0(), "replica-room0"));
    auto plan = [&](const std::string& text) { return formatCsv(run(*db.engine, text)); };
    const std::string note = "Parse skipped: a cached statement shape";
    CHECK(plan("EXPLAIN FIND object WHERE near('sofa', 1 m)").find(note) == std::string::npos);
    const std::string shaped = plan("EXPLAIN FIND object WHERE near('table', 2 m)");
    CHECK(shaped.find(note) != std::string::npos);
    CHECK(shaped.find("2 m") != std::string::npos);  // the plan of this text's literals
}

TEST_CASE("a text that fails fails as the parser and binder say, located in its own text", "[shapes]") {
    Database cached(true), plain(false);
    for (Database* db : {&cached, &plain})
        db->engine->importScene(import::read("replica", replicaRoom0(), "replica-room0"));
    outcome(*cached.engine, "FIND 'cushion' WHERE near('sofa', 1 m)");
    for (const std::string text : {
             "FIND 'cushion' WHERE near('sofaa', 1 m)",     // unknown category, with a did-you-mean
             "FIND    'cushion' WHERE near('', 1 m)",       // an empty quoted name is a syntax error
             "FIND 'cushion' WHERE near('pianos', 10 mm)",  // a category no node has: a note, no error
         }) {
        INFO(text);
        CHECK(outcome(*cached.engine, text) == outcome(*plain.engine, text));
    }
    CHECK(outcome(*cached.engine, "FIND 'cushion' WHERE near('sofaa', 1 m)").find("line 1") != std::string::npos);
}

TEST_CASE("the cache holds at most shape_cache shapes, the least recently used leaving first", "[shapes]") {
    Database db(true);
    db.engine->importScene(import::read("replica", replicaRoom0(), "replica-room0"));
    run(*db.engine, "SET shape_cache = 2");
    run(*db.engine, "COUNT 'sofa'");
    run(*db.engine, "FIND 'sofa' LIMIT 1");
    run(*db.engine, "COUNT 'table'");  // used again: the FIND is now the least recent
    run(*db.engine, "RELATE #20 TO #21");
    binder::ShapeCacheStats stats = db.engine->shapeCacheStats();
    CHECK(stats.size == 2);
    CHECK(stats.evicted == 1);
    CHECK(stats.hits == 1);
    run(*db.engine, "COUNT 'chair'");
    CHECK(db.engine->shapeCacheStats().hits == 2);
    run(*db.engine, "FIND 'chair' LIMIT 2");  // evicted: parsed again
    CHECK(db.engine->shapeCacheStats().hits == 2);

    run(*db.engine, "SET shape_cache = 0");
    CHECK(db.engine->shapeCacheStats().size == 0);
    run(*db.engine, "COUNT 'cushion'");
    CHECK(db.engine->shapeCacheStats().hits == 2);
    CHECK_THROWS_AS(run(*db.engine, "SET shape_cache = -1"), Error);
}

// Every query suite, run on two engines: one without the cache, and one where each statement's
// shape was learned first from another text of that shape (every literal changed). The answers
// and errors must be the same, text for text.
TEST_CASE("every query suite answers the same with the shape cache on and off", "[shapes][suites]") {
    const std::vector<fs::path> suites = querySuites();
    REQUIRE(suites.size() >= 6);
    std::uint64_t hits = 0;
    std::size_t compared = 0;
    for (const fs::path& suite : suites) {
        Database cached(true), plain(false);
        for (const SuiteBlock& block : readSuite(suite)) {
            if (!block.load.empty()) {
                for (Database* db : {&cached, &plain}) loadSuiteData(*db->engine, block.load, suite.parent_path());
                continue;
            }
            if (std::optional<parser::StatementShape> shape = parser::statementShape(block.text)) {
                const std::string sibling = siblingOf(*shape);
                REQUIRE(parser::statementShape(sibling)->key == shape->key);
                outcome(*cached.engine, sibling);
            }
            INFO(suite.filename().string() << ": " << block.text);
            CHECK(withoutCacheLines(outcome(*cached.engine, block.text)) ==
                  withoutCacheLines(outcome(*plain.engine, block.text)));
            ++compared;
        }
        hits += cached.engine->shapeCacheStats().hits;
        CHECK(plain.engine->shapeCacheStats().hits == 0);
    }
    CHECK(compared > 150);
    CHECK(hits > 50);  // the suites did run through the cache
}
