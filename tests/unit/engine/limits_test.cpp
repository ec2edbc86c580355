// Limits a session sets on what one statement may build, and interrupting a running statement.
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <thread>

#include "engine_support.hpp"
#include "ingest/generate/room_generator.hpp"

using namespace smql;
using namespace smql::testing;

namespace {

struct GeneratedRoom {
    TempDir dir;
    std::unique_ptr<Engine> engine = Engine::open(dir.path.string());
    GeneratedRoom() { engine->importScene(generate::generateRoom({.seed = 5, .objectCount = 400, .name = "big"})); }
    ResultSet q(const std::string& s) { return run(*engine, s); }
};

ErrorKind kindOf(const std::function<void()>& statement) {
    try {
        statement();
    } catch (const Error& e) {
        return e.kind();
    }
    FAIL("expected an error");
    return ErrorKind::Usage;
}

}  // namespace

// A typed RELATE relates two single nodes; a question's RELATE (ASK) relates every pair of its
// names, and max_pairs bounds that.
TEST_CASE("max_pairs bounds a question's RELATE before any pair is compared") {
    GeneratedRoom room;
    auto objects = std::get<std::int64_t>(room.q("COUNT object").rows[0][0]);
    REQUIRE(objects * objects > 100'000);  // over the default
    const char* everyPair = "ASK 'where are the objects relative to the objects?'";
    CHECK(kindOf([&] { room.q(everyPair); }) == ErrorKind::Limit);
    CHECK_THROWS_WITH(room.q(everyPair), Catch::Contains("pairs; the limit is 100000"));
    CHECK_THROWS_WITH(room.q("RELATE object TO object"), Catch::Contains("object is ambiguous"));
    room.q("SET max_pairs = 4");
    const char* walls = "ASK 'where is the wall relative to the wall?'";
    CHECK(kindOf([&] { room.q(walls); }) == ErrorKind::Limit);  // 4 walls: 16 pairs
    room.q("SET max_pairs = 16");
    CHECK_NOTHROW(room.q(walls));
}

TEST_CASE("max_rows bounds a result; LIMIT keeps under it") {
    GeneratedRoom room;
    room.q("SET max_rows = 10");
    CHECK(kindOf([&] { room.q("FIND object"); }) == ErrorKind::Limit);
    CHECK(room.q("FIND object LIMIT 10").rows.size() == 10);
    // COUNT returns one row however many it counts.
    CHECK(std::get<std::int64_t>(room.q("COUNT object").rows[0][0]) > 10);
    bool listed = false;
    for (const auto& row : room.q("SHOW SETTINGS").rows)
        if (std::get<std::string>(row[0]) == "max_rows") listed = std::get<double>(row[1]) == 10;
    CHECK(listed);
    CHECK(kindOf([&] { room.q("SET max_rows = 0"); }) == ErrorKind::Binding);
    CHECK(kindOf([&] { room.q("SET max_rows = 2.5"); }) == ErrorKind::Binding);
    CHECK(kindOf([&] { room.q("SET max_rows = 3 m"); }) == ErrorKind::Binding);
}

TEST_CASE("interrupt stops a running statement and leaves the engine usable") {
    GeneratedRoom room;
    room.q("SET max_pairs = 1000000");
    // About 160,000 pairs several times over; and few candidates with many pairs each (between).
    for (const char* statement : {"ASK 'where are the objects relative to the objects?'; ASK 'where are the objects "
                                  "relative to the objects?'",
                                  "COUNT object WHERE between(object, object)"}) {
        INFO(statement);
        std::atomic<bool> done{false};
        std::optional<ErrorKind> outcome;
        std::thread worker([&] {
            try {
                room.q(statement);
            } catch (const Error& e) {
                outcome = e.kind();
            }
            done = true;
        });
        // An interrupt before the statement starts is dropped, as in SQLite: keep sending until it ends.
        while (!done) {
            room.engine->interrupt();
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        worker.join();
        REQUIRE(outcome);
        CHECK(*outcome == ErrorKind::Interrupted);
        CHECK(room.q("FIND object LIMIT 3").rows.size() == 3);
    }
}
