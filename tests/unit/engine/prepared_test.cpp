// Prepared statements: parsed once, run with bound values, which are data and never SMQL.
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>

#include "engine/parser/parser.hpp"
#include "engine_support.hpp"
#include "ingest/generate/room_generator.hpp"
#include "ingest/import/importers.hpp"

using namespace smql;
using namespace smql::testing;

namespace {

struct Room0 {
    TempDir dir;
    std::unique_ptr<Engine> engine = Engine::open(dir.path.string());
    Room0() { engine->importScene(import::readReplica(replicaRoom0(), "replica-room0")); }
};

std::vector<std::int64_t> ids(const ResultSet& rs) {
    std::vector<std::int64_t> out;
    for (const auto& row : rs.rows) out.push_back(std::get<std::int64_t>(row.at(0)));
    return out;
}

// An engine on `dir` that has answered nothing before, in scene `scene` ('*': all scenes): its answers
// are the truth a connection that kept things between statements is held to.
std::unique_ptr<Engine> freshEngine(const TempDir& dir, const std::string& scene) {
    auto fresh = Engine::open(dir.path.string());
    run(*fresh, "USE SCENE '" + scene + "'");
    return fresh;
}

Error errorOf(const std::function<void()>& call) {
    try {
        call();
    } catch (const Error& e) {
        return e;
    }
    FAIL("expected an error");
    return Error(ErrorKind::Usage, "");
}

}  // namespace

TEST_CASE("a prepared statement answers as the statement written out, without parsing again", "[prepared]") {
    Room0 room;
    PreparedStatement find = room.engine->prepare("FIND ? WHERE near(?, ?)");
    CHECK(find.parameterCount() == 3);

    const std::uint64_t parsedBefore = parser::statementsParsed();
    find.bind(1, std::string("cushion"));
    find.bind(2, std::string("sofa"));
    find.bind(3, Length{0.5});
    auto cushions = ids(find.execute());
    find.bind(1, std::string("book"));
    find.bind(2, std::string("table"));
    find.bind(3, std::int64_t{1});
    auto books = ids(find.execute());
    find.bind(3, 0.25);
    auto closeBooks = ids(find.execute());
    CHECK(parser::statementsParsed() == parsedBefore);

    CHECK_FALSE(cushions.empty());
    CHECK(cushions == ids(run(*room.engine, "FIND cushion WHERE near(sofa, 0.5 m)")));
    CHECK(books == ids(run(*room.engine, "FIND book WHERE near(table, 1 m)")));
    CHECK(closeBooks == ids(run(*room.engine, "FIND book WHERE near(table, 25 cm)")));
}

TEST_CASE("placeholders stand for sides, sub-query names, comparison values and LIMIT", "[prepared]") {
    Room0 room;
    PreparedStatement side = room.engine->prepare("FIND object WHERE near(?.left)");
    side.bind(1, std::string("WALL"));  // folded to lower case as a written name is
    CHECK(ids(side.execute()) == ids(run(*room.engine, "FIND object WHERE near(wall.left)")));

    // The sub-query is copied before values go in: the second run sees its own value.
    PreparedStatement sub = room.engine->prepare("FIND cushion WHERE on((FIND $1 LIMIT $2))");
    sub.bind(1, std::string("sofa"));
    sub.bind(2, std::int64_t{1});
    CHECK(ids(sub.execute()) == ids(run(*room.engine, "FIND cushion WHERE on((FIND sofa LIMIT 1))")));
    sub.bind(1, std::string("table"));
    CHECK(ids(sub.execute()) == ids(run(*room.engine, "FIND cushion WHERE on((FIND table LIMIT 1))")));

    PreparedStatement count = room.engine->prepare("COUNT object WHERE category = ? AND source_id > ?");
    count.bind(1, std::string("lamp"));
    count.bind(2, std::int64_t{0});
    CHECK(count.execute().rows == run(*room.engine, "COUNT object WHERE category = 'lamp' AND source_id > 0").rows);

    PreparedStatement explain = room.engine->prepare("EXPLAIN FIND ? LIMIT ?");
    explain.bind(1, std::string("lamp"));
    explain.bind(2, std::int64_t{2});
    CHECK(explain.execute().message == run(*room.engine, "EXPLAIN FIND lamp LIMIT 2").message);
}

TEST_CASE("a bound value with quotes is a name, never SMQL", "[prepared]") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    model::SceneData scene = generate::generateRoom({.seed = 3, .objectCount = 20, .name = "office"});
    model::Node* renamed = nullptr;
    for (auto& node : scene.nodes)
        if (node.kind == model::NodeKind::Object && !renamed) renamed = &node;
    REQUIRE(renamed);
    renamed->category = "o'brien's mug";
    engine->importScene(scene);

    PreparedStatement find = engine->prepare("FIND ?");
    find.bind(1, std::string("O'Brien's mug"));
    ResultSet found = find.execute();
    REQUIRE(found.rows.size() == 1);
    CHECK(found.rows[0][1] == Value(std::string("o'brien's-mug")));  // stored by its canonical name

    PreparedStatement count = engine->prepare("COUNT object WHERE category = $1");
    count.bind(1, std::string("o'brien's mug"));
    CHECK(count.execute().rows.at(0).at(0) == Value(std::int64_t{1}));

    // SMQL inside a value is part of an unknown name: a binding error, and the scene stays.
    for (const char* injected : {"it's", "mug' OR on(desk", "x; DROP SCENE office"}) {
        find.bind(1, std::string(injected));
        CHECK(errorOf([&] { find.execute(); }).kind() == ErrorKind::Binding);
    }
    CHECK(run(*engine, "SHOW SCENES").rows.size() == 1);
}

TEST_CASE("binding errors name the placeholder", "[prepared]") {
    Room0 room;
    PreparedStatement find = room.engine->prepare("FIND ? WHERE near(?, ?) LIMIT ?");
    CHECK(find.parameterCount() == 4);
    CHECK_THAT(errorOf([&] { find.bind(0, std::string("x")); }).message(), Catch::Contains("no placeholder 0"));
    CHECK_THAT(errorOf([&] { find.bind(5, std::string("x")); }).message(), Catch::Contains("has 4 (1 to 4)"));
    CHECK_THAT(errorOf([&] { find.bind(1, std::int64_t{3}); }).message(),
               Catch::Contains("? number 1 stands for a name, not an integer"));
    CHECK_THAT(errorOf([&] { find.bind(3, std::string("far")); }).message(),
               Catch::Contains("stands for a distance, not text"));
    CHECK_THAT(errorOf([&] { find.bind(4, 2.5); }).message(), Catch::Contains("LIMIT's whole number"));

    Error unbound = errorOf([&] { find.execute(); });
    CHECK(unbound.kind() == ErrorKind::Usage);
    CHECK_THAT(unbound.message(), Catch::Contains("placeholder ? number 1 has no value"));
    REQUIRE(unbound.where());
    CHECK(unbound.where()->column == 6);

    find.bind(1, std::string("cushion"));
    find.bind(2, std::string("sofa"));
    find.bind(3, -1.0);
    find.bind(4, std::int64_t{2});
    CHECK_THAT(errorOf([&] { find.execute(); }).message(), Catch::Contains("cannot be -1"));
    find.bind(3, std::monostate{});
    CHECK_THAT(errorOf([&] { find.execute(); }).message(), Catch::Contains("? number 3 is bound to NULL"));
    find.bind(3, 0.5);
    find.bind(4, std::int64_t{-1});
    CHECK_THAT(errorOf([&] { find.execute(); }).message(), Catch::Contains("cannot be negative"));
    find.bind(4, std::int64_t{1});
    CHECK(find.execute().rows.size() == 1);
    find.clearBindings();
    CHECK_THAT(errorOf([&] { find.execute(); }).message(), Catch::Contains("has no value"));

    // Run without values, a statement with placeholders stops at the first.
    CHECK_THAT(errorOf([&] { room.engine->execute("FIND lamp LIMIT $1"); }).message(),
               Catch::Contains("placeholder $1 has no value"));
    CHECK(errorOf([&] { room.engine->prepare("FIND ?; FIND ?"); }).kind() == ErrorKind::Usage);
}

TEST_CASE("a COUNT across all scenes prepared before another connection or process writes sees the new count",
          "[prepared]") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    engine->importScene(generate::generateRoom({.seed = 1, .objectCount = 60, .name = "first"}));
    run(*engine, "USE SCENE '*'");
    PreparedStatement count = engine->prepare("COUNT ?");
    PreparedStatement written = engine->prepare("COUNT book");

    // The truth, from an engine that has answered nothing before (it shares the database).
    auto counted = [&](const std::string& category) {
        return std::get<std::int64_t>(run(*freshEngine(dir, "*"), "COUNT " + category).rows.at(0).at(0));
    };
    auto answer = [](PreparedStatement& statement) {
        ResultSet rs = statement.execute();
        REQUIRE(rs.columns.size() == 1);
        CHECK(rs.columns[0].name == "count");
        CHECK(rs.message.empty());
        return std::get<std::int64_t>(rs.rows.at(0).at(0));
    };

    count.bind(1, std::string("Book"));
    const std::int64_t before = answer(count);
    REQUIRE(before > 0);
    CHECK(answer(count) == before);  // the second run answers as the first
    CHECK(answer(written) == before);
    CHECK(std::get<std::int64_t>(run(*engine, "COUNT book").rows.at(0).at(0)) == before);
    count.bind(1, std::string("book"));  // written as stored: read as bound, not folded
    CHECK(answer(count) == before);
    count.bind(1, std::string("Book"));
    PreparedStatement find = engine->prepare("FIND ? LIMIT 1000");
    find.bind(1, std::string("Book"));
    CHECK(static_cast<std::int64_t>(find.execute().rows.size()) == before);

    SECTION("another connection in this process") {
        auto other = Engine::open(dir.path.string());
        other->importScene(generate::generateRoom({.seed = 2, .objectCount = 60, .name = "second"}));
    }
    SECTION("another process") {
        const pid_t child = ::fork();
        REQUIRE(child >= 0);
        if (child == 0) {
            // No Catch2 and no destructors here: the child opens the database anew, writes and ends.
            try {
                auto other = Engine::open(dir.path.string());
                other->importScene(generate::generateRoom({.seed = 2, .objectCount = 60, .name = "second"}));
            } catch (...) {
                ::_exit(3);
            }
            ::_exit(0);
        }
        int status = 0;
        REQUIRE(::waitpid(child, &status, 0) == child);
        REQUIRE(WIFEXITED(status));
        REQUIRE(WEXITSTATUS(status) == 0);
    }
    const std::int64_t after = counted("book");
    CHECK(after > before);
    // FIND of a category across all scenes keeps its label keys and count with COUNT's: the other
    // connection's books are found too.
    CHECK(static_cast<std::int64_t>(find.execute().rows.size()) == after);
    CHECK(answer(count) == after);
    CHECK(answer(written) == after);
    CHECK(std::get<std::int64_t>(run(*engine, "COUNT book").rows.at(0).at(0)) == after);

    // Dropped, the scenes' books go with them: the count falls, and with no book left the answer
    // is the note of a thing no scene holds, as before any COUNT ran.
    run(*engine, "DROP SCENE 'second'");
    CHECK(answer(count) == before);
    CHECK(static_cast<std::int64_t>(find.execute().rows.size()) == before);
    run(*engine, "DROP SCENE 'first'");
    ResultSet none = count.execute();
    CHECK(none.rows.at(0).at(0) == Value(std::int64_t{0}));
    CHECK_THAT(none.message, Catch::Contains("no book in any scene"));
}

TEST_CASE("a FIND across all scenes answers from the label index as the binder's path does, and sees every write",
          "[prepared]") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    engine->importScene(generate::generateRoom({.seed = 1, .objectCount = 60, .name = "first"}));
    run(*engine, "USE SCENE '*'");
    // The truth, from an engine that has bound nothing before.
    auto truth = [&](const std::string& text) { return run(*freshEngine(dir, "*"), text); };
    auto requireSame = [](const ResultSet& got, const ResultSet& want) {
        REQUIRE(got.columns.size() == want.columns.size());
        for (std::size_t i = 0; i < want.columns.size(); ++i) {
            CHECK(got.columns[i].name == want.columns[i].name);
            CHECK(got.columns[i].type == want.columns[i].type);
        }
        REQUIRE(got.rows.size() == want.rows.size());
        for (std::size_t i = 0; i < want.rows.size(); ++i) CHECK(got.rows[i] == want.rows[i]);
        CHECK(got.message == want.message);
    };

    PreparedStatement find = engine->prepare("FIND ? LIMIT ?");
    find.bind(1, std::string("Book"));  // bound names are folded as the statement's text is
    find.bind(2, std::int64_t{1000});
    const ResultSet books = truth("FIND book LIMIT 1000");
    REQUIRE(books.rows.size() > 2);
    requireSame(find.execute(), books);  // bound: the label keys and count kept
    requireSame(find.execute(), books);  // answered from what was kept
    requireSame(run(*engine, "FIND book LIMIT 1000"), books);
    find.bind(2, std::int64_t{2});
    requireSame(find.execute(), truth("FIND book LIMIT 2"));
    find.bind(2, std::int64_t{0});
    CHECK(find.execute().rows.empty());

    // What the binder refuses is refused the same way once the category is kept.
    find.bind(2, std::int64_t{-1});
    CHECK_THAT(errorOf([&] { find.execute(); }).message(), Catch::Contains("cannot be negative"));
    find.bind(2, std::int64_t{1000});
    run(*engine, "SET max_rows = 2");
    const Error tooMany = errorOf([&] { find.execute(); });
    CHECK(tooMany.kind() == ErrorKind::Limit);
    CHECK_THAT(tooMany.message(), Catch::Contains("the answer has 3 rows; the limit is 2"));
    run(*engine, "SET max_rows = 100000");
    CHECK_THAT(errorOf([&] { run(*engine, "FIND book LIMIT 5 PATH"); }).message(),
               Catch::Contains("across all scenes, FIND takes no"));

    // Another connection's write commits a new transaction: the next FIND binds again and finds the
    // new books.
    Engine::open(dir.path.string())
        ->importScene(generate::generateRoom({.seed = 2, .objectCount = 60, .name = "second"}));
    const ResultSet more = truth("FIND book LIMIT 1000");
    REQUIRE(more.rows.size() > books.rows.size());
    requireSame(find.execute(), more);
    requireSame(find.execute(), more);
    run(*engine, "DROP SCENE 'second'");
    requireSame(find.execute(), books);
}

TEST_CASE(
    "a statement run again keeps its plan for its values, scene and commit, binds again when one changes, and "
    "answers by the settings of its run",
    "[prepared]") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    // More scenes than the engine keeps decoded (32), so plans also go with their scenes' snapshots.
    constexpr int kScenes = 36;
    for (int i = 0; i < kScenes; ++i)
        engine->importScene(generate::generateRoom(
            {.seed = static_cast<std::uint64_t>(i), .objectCount = 40, .name = fmt::format("room_{}", i)}));
    // The truth, in the same session state.
    auto truth = [&](const std::string& scene, const std::string& settings, const std::string& text) {
        auto fresh = freshEngine(dir, scene);
        if (!settings.empty()) run(*fresh, settings);
        return outcome(*fresh, text);
    };
    // As outcome() gives a text's answer.
    auto answer = [](PreparedStatement& statement) {
        try {
            const ResultSet rs = statement.execute();
            return formatCsv(rs) + "|" + rs.message + "\n";
        } catch (const Error& e) {
            return "error: " + e.message();
        }
    };
    PreparedStatement nearDoor = engine->prepare("FIND object WHERE near(?) RETURN id, category");
    PreparedStatement nearest = engine->prepare("FIND object NEAREST TO ? LIMIT ?");
    nearest.bind(2, std::int64_t{3});
    const std::string nearText = "FIND object WHERE near(door) RETURN id, category";

    for (int round = 0; round < 2; ++round)
        for (int i = 0; i < kScenes; i += 5) {
            const std::string scene = fmt::format("room_{}", i);
            run(*engine, "USE SCENE '" + scene + "'");
            nearDoor.bind(1, std::string("door"));
            CHECK(answer(nearDoor) == truth(scene, "", nearText));
            CHECK(outcome(*engine, nearText) == truth(scene, "", nearText));  // the text, run again
            nearest.bind(1, std::string("door"));
            CHECK(answer(nearest) == truth(scene, "", "FIND object NEAREST TO door LIMIT 3"));
            nearest.bind(1, std::string("window"));
            CHECK(answer(nearest) == truth(scene, "", "FIND object NEAREST TO window LIMIT 3"));
        }

    run(*engine, "USE SCENE 'room_5'");
    nearDoor.bind(1, std::string("door"));
    const std::string before = answer(nearDoor);
    // A setting the binder or the executor reads.
    run(*engine, "SET near = 3 m");
    const std::string wider = truth("room_5", "SET near = 3 m", nearText);
    CHECK(wider != before);
    CHECK(answer(nearDoor) == wider);
    CHECK(outcome(*engine, nearText) == wider);
    run(*engine, "SET max_rows = 1");
    CHECK_THAT(answer(nearDoor), Catch::StartsWith("error: the answer has") && Catch::Contains("the limit is 1"));
    run(*engine, "SET max_rows = 1000000");
    run(*engine, "SET near = 1 m");
    CHECK(answer(nearDoor) == before);
    run(*engine, "SET near = 3 m");

    // Another connection's commit: the scene is dropped and stored again with other things.
    {
        auto other = Engine::open(dir.path.string());
        run(*other, "DROP SCENE 'room_5'");
        other->importScene(generate::generateRoom({.seed = 99, .objectCount = 40, .name = "room_5"}));
    }
    const std::string after = truth("room_5", "SET near = 3 m", nearText);
    CHECK(after != wider);
    CHECK(answer(nearDoor) == after);
    CHECK(outcome(*engine, nearText) == after);
}
