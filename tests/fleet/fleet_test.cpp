// The fleet store against a real PostgreSQL + PostGIS: the schema and its migrations, push and
// pull (byte for byte the scene JSON export), idempotence, devices pushing at once, a read-only role.
#include <catch2/catch.hpp>

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>

#include <fmt/format.h>

#include "fleet/fleet.hpp"
#include "fleet/pg/connection.hpp"
#include "fleet/schema.hpp"
#include "fleet/store.hpp"
#include "fleet_support.hpp"
#include "model/error.hpp"
#include "storage/database.hpp"

using namespace smql;
using namespace smql::testing;

namespace {

std::string messageOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.message() + "\nhint: " + e.hint();
    }
    FAIL("no error");
    return {};
}

// A pull of `scene` (the newest version unless `version`; of any device unless `device`).
fleet::PullRequest request(const std::string& scene, std::uint64_t version = 0, const std::string& device = "") {
    fleet::PullRequest out;
    out.scene = scene;
    out.version = version;
    out.device = device;
    return out;
}

}  // namespace

TEST_CASE("fleet init creates the versioned schema, and a second init does nothing") {
    const std::string url = freshStore("fleet_init");
    auto first = fleet::init(url);
    CHECK(first.before == 0);
    CHECK(first.after == fleet::latestSchemaVersion());
    auto second = fleet::init(url);
    CHECK(second.before == fleet::latestSchemaVersion());
    CHECK(second.after == fleet::latestSchemaVersion());
    fleet::pg::Connection c(url, "the store");
    CHECK(c.exec("SELECT count(*) FROM smql.schema_version", "").integer(0, 0) == fleet::latestSchemaVersion());
    // The GiST index the queries probe with is there.
    CHECK(c.exec("SELECT count(*) FROM pg_indexes WHERE indexname = 'nodes_by_scene_footprint' AND indexdef LIKE "
                 "'%USING gist (scene, footprint)%'",
                 "")
              .integer(0, 0) == 1);
}

TEST_CASE("two inits at once make one schema") {
    const std::string url = freshStore("fleet_init_race");
    std::vector<std::thread> threads;
    std::atomic<int> failures = 0;
    for (int i = 0; i < 4; ++i)
        threads.emplace_back([&] {
            try {
                fleet::init(url);
            } catch (const Error&) {
                ++failures;
            }
        });
    for (auto& t : threads) t.join();
    CHECK(failures == 0);
    fleet::pg::Connection c(url, "the store");
    CHECK(c.exec("SELECT count(*) FROM smql.schema_version", "").integer(0, 0) == fleet::latestSchemaVersion());
}

TEST_CASE("a bad URL, a server that is down, a store without a schema or of a newer one are refused clearly") {
    TempDir dir;
    auto database = storage::Database::open(dir.sub("db"));

    CHECK_THAT(messageOf([&] { fleet::init("mysql://somewhere/fleet"); }), Catch::Contains("is not a fleet store URL"));
    CHECK_THAT(messageOf([&] { fleet::init("postgresql://host/db?colour=blue"); }),
               Catch::Contains("is not a fleet store URL") && Catch::Contains("colour"));
    // A password in a URL never reaches a message.
    // libpq's own reason quotes a malformed URL whole: masked as well.
    const std::string secret = messageOf([&] { fleet::init("postgresql://robot:hunter2@host/db?colour=blue"); }) +
                               messageOf([&] { fleet::init("postgresql://robot@host/db?password=hunter2&colour=1"); }) +
                               messageOf([&] { fleet::init("postgresql://robot:hunter2@[::1:5432/fleet"); });
    CHECK_THAT(secret, !Catch::Contains("hunter2") && Catch::Contains("robot:***@host"));
    CHECK_THAT(messageOf([&] { fleet::init("postgresql://postgres@/fleet?host=" + dir.path.string()); }),
               Catch::Contains("cannot connect to the fleet store database fleet") &&
                   Catch::Contains("check that the server runs"));

    const std::string url = freshStore("fleet_versions");
    CHECK_THAT(messageOf([&] { fleet::push(*database, url); }),
               Catch::Contains("has no smql schema") && Catch::Contains("smql fleet init URL"));
    fleet::init(url);
    cluster().execute("fleet_versions", "INSERT INTO smql.schema_version(version) VALUES (99)");
    CHECK_THAT(messageOf([&] { fleet::init(url); }),
               Catch::Contains("has schema version 99; this smql knows versions up to 1"));
    CHECK_THAT(messageOf([&] { fleet::push(*database, url); }), Catch::Contains("has schema version 99"));
}

TEST_CASE("a store whose server has PostGIS but a role that may not create it says what to do") {
    cluster().execute("postgres", "CREATE DATABASE fleet_no_postgis");
    cluster().execute("postgres", "CREATE ROLE builder LOGIN");
    cluster().execute("fleet_no_postgis",
                      "GRANT ALL ON DATABASE fleet_no_postgis TO builder; "
                      "GRANT ALL ON SCHEMA public TO builder");
    CHECK_THAT(messageOf([&] { fleet::init(cluster().url("fleet_no_postgis", "builder")); }),
               Catch::Contains("extension") && Catch::Contains("CREATE EXTENSION postgis"));
}

TEST_CASE("push sends every scene version, pull brings each back byte for byte, a second push sends nothing") {
    const std::string url = freshStore("fleet_round_trip");
    fleet::init(url);
    TempDir dir;
    auto engine = Engine::open(dir.sub("device"));
    buildRooms(*engine);
    auto database = storage::Database::open(dir.sub("device"));

    auto first = fleet::push(*database, url);
    CHECK(first.sent == kRoomVersions);
    CHECK(first.present == 0);
    CHECK(first.nodes > 150);
    CHECK(storedVersions(url, first.device) == static_cast<long long>(kRoomVersions));
    CHECK(inconsistencies(url) == 0);
    CHECK(database->beginRead().setting(fleet::kDeviceSetting) == first.device);

    auto again = fleet::push(*database, url);
    CHECK(again.device == first.device);
    CHECK(again.sent == 0);
    CHECK(again.present == kRoomVersions);
    CHECK(storedVersions(url) == static_cast<long long>(kRoomVersions));

    auto pulledDatabase = storage::Database::open(dir.sub("pulled"));
    for (const char* scene : {"replica-room0", "scene0251_00", "scene0277_02", "41069025", "den"}) {
        auto pulled = fleet::pull(url, request(scene), *pulledDatabase);
        CHECK(pulled.device == first.device);
    }
    auto pulledEngine = Engine::open(dir.sub("pulled"));
    for (const char* scene : {"replica-room0", "scene0251_00", "scene0277_02", "41069025", "den"}) {
        INFO(scene);
        const std::string original = exportedJson(*engine, scene);
        CHECK(original.size() > 1000);
        CHECK(exportedJson(*pulledEngine, scene) == original);
    }
    // The embeddings and the evidence went through the float4[] and bytea columns and came back.
    CHECK(exportedJson(*engine, "den").find("evidence-1.jpg") != std::string::npos);
    CHECK(exportedJson(*engine, "den").find("\"embedding\"") != std::string::npos);

    // A superseded version comes back as it was stored, with the changes of the update after it.
    auto local = fleet::readVersions(*database, "den");
    REQUIRE(local.size() == 2);
    auto old = fleet::fetch(url, request("den", 1));
    CHECK(old.version.version == 1);
    CHECK(old.version.supersededAt == local[0].supersededAt);
    CHECK(old.version.changes == local[0].changes);
    CHECK(!old.version.changes.empty());
    CHECK(old.version.data.nodes == local[0].data.nodes);
    CHECK(old.version.data.relations == local[0].data.relations);
    CHECK(old.version.data.info == local[0].data.info);

    CHECK_THAT(messageOf([&] { fleet::fetch(url, request("den", 3)); }),
               Catch::Contains("versions 1 to 2 of scene 'den', not 3"));
    CHECK_THAT(messageOf([&] { fleet::fetch(url, request("attic")); }), Catch::Contains("has no scene named 'attic'"));
    CHECK_THAT(messageOf([&] { fleet::pull(url, request("den"), *pulledDatabase); }),
               Catch::Contains("already exists") || Catch::Contains("exists"));
}

TEST_CASE("two devices push at once; their scenes of the same name stay apart") {
    const std::string url = freshStore("fleet_two_devices");
    fleet::init(url);
    TempDir dir;
    for (const char* name : {"a", "b"}) {
        auto engine = Engine::open(dir.sub(name));
        buildRooms(*engine);
    }
    auto a = storage::Database::open(dir.sub("a"));
    auto b = storage::Database::open(dir.sub("b"));
    fleet::PushReport reportA, reportB;
    std::thread pushA([&] { reportA = fleet::push(*a, url); });
    std::thread pushB([&] { reportB = fleet::push(*b, url); });
    pushA.join();
    pushB.join();
    CHECK(reportA.device != reportB.device);
    CHECK(reportA.sent == kRoomVersions);
    CHECK(reportB.sent == kRoomVersions);
    CHECK(storedVersions(url) == 2 * static_cast<long long>(kRoomVersions));
    CHECK(inconsistencies(url) == 0);

    CHECK_THAT(messageOf([&] { fleet::fetch(url, request("den")); }),
               Catch::Contains("2 devices hold a scene named 'den'") && Catch::Contains(reportA.device) &&
                   Catch::Contains("--device"));
    auto pulled = fleet::fetch(url, request("den", 0, reportB.device.substr(0, 8)));
    CHECK(pulled.device == reportB.device);
}

TEST_CASE("one device's pushes at once store each version once") {
    const std::string url = freshStore("fleet_same_device");
    fleet::init(url);
    TempDir dir;
    {
        auto engine = Engine::open(dir.sub("device"));
        buildRooms(*engine);
    }
    auto database = storage::Database::open(dir.sub("device"));
    fleet::deviceId(*database);  // made before the threads, as two processes would find it made
    std::vector<fleet::PushReport> reports(3);
    std::vector<std::thread> threads;
    for (auto& report : reports) threads.emplace_back([&] { report = fleet::push(*database, url); });
    for (auto& t : threads) t.join();
    std::size_t sent = 0;
    for (const auto& r : reports) {
        sent += r.sent;
        CHECK(r.sent + r.present == kRoomVersions);
    }
    CHECK(sent == kRoomVersions);
    CHECK(storedVersions(url) == static_cast<long long>(kRoomVersions));
    CHECK(inconsistencies(url) == 0);
}

TEST_CASE("a read-only role can pull but not push") {
    const std::string url = freshStore("fleet_read_only");
    fleet::init(url);
    cluster().execute("fleet_read_only",
                      "CREATE ROLE reader LOGIN; GRANT USAGE ON SCHEMA smql TO reader; "
                      "GRANT SELECT ON ALL TABLES IN SCHEMA smql TO reader");
    TempDir dir;
    {
        auto engine = Engine::open(dir.sub("device"));
        buildRooms(*engine);
    }
    auto database = storage::Database::open(dir.sub("device"));
    fleet::push(*database, url);

    TempDir other;
    {
        auto engine = Engine::open(other.sub("device"));
        buildRooms(*engine);
    }
    auto otherDatabase = storage::Database::open(other.sub("device"));
    const std::string readerUrl = cluster().url("fleet_read_only", "reader");
    CHECK_THAT(messageOf([&] { fleet::push(*otherDatabase, readerUrl); }),
               Catch::Contains("the role reader may not push") && Catch::Contains("read-only role"));
    CHECK(storedVersions(url) == static_cast<long long>(kRoomVersions));

    // The server refuses too, whatever the client checks: a write as the reader fails.
    fleet::Store store(readerUrl);
    fleet::SceneVersionData version = fleet::readVersions(*otherDatabase, "den").back();
    CHECK_THROWS_WITH(store.put("some-device", version), Catch::Contains("permission denied"));

    auto pulled = fleet::fetch(readerUrl, request("replica-room0"));
    CHECK(pulled.version.data.nodes.size() > 50);
}

TEST_CASE("the smql command: fleet init, push, pull, statements on the store, exit statuses, messages") {
    const char* smqlProgram = std::getenv("SMQL_PROGRAM");
    REQUIRE(smqlProgram != nullptr);
    const std::string url = freshStore("fleet_shell");
    TempDir dir;
    auto shell = [&](const std::string& arguments) {
        const std::string command = fmt::format("{} {} > {} 2>&1", smqlProgram, arguments, dir.sub("output.txt"));
        int status = std::system(command.c_str());
        std::ifstream in(dir.sub("output.txt"));
        std::stringstream text;
        text << in.rdbuf();
        return std::make_pair(WEXITSTATUS(status), text.str());
    };
    const std::string replica = std::string(SMQL_SHARED_DATA) + "/replica-room0/info_semantic.json";
    REQUIRE(shell(fmt::format("import replica {} --db {}", replica, dir.sub("device"))).first == 0);

    auto init = shell(fmt::format("fleet init '{}'", url));
    CHECK(init.first == 0);
    CHECK_THAT(init.second, Catch::Contains("created the fleet store's schema: version 1"));
    CHECK_THAT(shell(fmt::format("fleet init '{}'", url)).second, Catch::Contains("nothing to do"));

    auto push = shell(fmt::format("push {} '{}'", dir.sub("device"), url));
    CHECK(push.first == 0);
    CHECK_THAT(push.second, Catch::Contains("pushed 1 scene version (") && Catch::Contains("0 were there already"));
    CHECK_THAT(shell(fmt::format("push {} '{}'", dir.sub("device"), url)).second,
               Catch::Contains("pushed 0 scene versions") && Catch::Contains("1 was there already"));

    auto pull = shell(fmt::format("pull '{}' --scene replica-room0 {}", url, dir.sub("copy")));
    CHECK(pull.first == 0);
    CHECK_THAT(pull.second, Catch::Contains("pulled version 1 of scene 'replica-room0'"));
    auto original = shell(fmt::format("export json --db {} --scene replica-room0", dir.sub("device")));
    auto pulled = shell(fmt::format("export json --db {} --scene replica-room0", dir.sub("copy")));
    CHECK(original.second.size() > 1000);
    CHECK(pulled.second == original.second);

    // Statements on the store, as the shell runs them, answer as the local database does.
    const std::string count = "USE SCENE 'replica-room0'; COUNT chair";
    auto onStore = shell(fmt::format("'{}' -c \"{}\" --csv", url, count));
    CHECK(onStore.first == 0);
    CHECK(onStore.second == shell(fmt::format("{} -c \"{}\" --csv", dir.sub("device"), count)).second);
    auto found = shell(fmt::format("'{}' \"USE SCENE 'replica-room0'; FIND chair WHERE near(table)\" --csv", url));
    CHECK(found.first == 0);
    CHECK_THAT(found.second, Catch::StartsWith("id,category,source_id,box\n") && Catch::Contains(",chair,"));
    auto unsupported = shell(fmt::format("'{}' -c \"USE SCENE 'replica-room0'; FIND chair SIMILAR TO 'a seat'\"", url));
    CHECK(unsupported.first == 1);
    CHECK_THAT(unsupported.second, Catch::Contains("does not run") && Catch::Contains("yet"));
    auto noScene = shell(fmt::format("'{}' -c 'COUNT chair'", url));
    CHECK(noScene.first == 1);
    CHECK_THAT(noScene.second, Catch::Contains("USE SCENE"));

    auto down =
        shell(fmt::format("push {} 'postgresql://postgres@/fleet?host={}'", dir.sub("device"), dir.path.string()));
    CHECK(down.first == 1);
    CHECK_THAT(down.second, Catch::Contains("cannot connect to the fleet store"));
    auto badUrl = shell(fmt::format("pull 'mysql://x' --scene a {}", dir.sub("copy")));
    CHECK(badUrl.first == 1);
    CHECK_THAT(badUrl.second, Catch::Contains("is not a fleet store URL"));
}
