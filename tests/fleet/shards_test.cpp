// A store sharded by scene over three PostgreSQL clusters (the run's own and two more started
// here): a push through the coordinator spreads the scene versions over the shards, each version
// whole on one of them; fleet queries see every scene's rows; a one-scene query reads one shard.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <iostream>
#include <memory>

#include <fmt/format.h>

#include "fleet/fleet.hpp"
#include "fleet/pg/connection.hpp"
#include "fleet/query.hpp"
#include "fleet/shards.hpp"
#include "fleet/store.hpp"
#include "fleet_support.hpp"
#include "storage/database.hpp"

using namespace smql;
using namespace smql::testing;

namespace {

std::unique_ptr<fleet::pg::LocalCluster> anotherCluster() {
    std::string whyNot, settings = "-c fsync=off";
#ifdef SMQL_PG_MODULE_DIR
    settings += " -c dynamic_library_path=" SMQL_PG_MODULE_DIR;
#endif
    auto cluster = fleet::pg::LocalCluster::start({.settings = settings, .prefix = "smql-fleet-shard"}, whyNot);
    INFO(whyNot);
    REQUIRE(cluster);
    return cluster;
}

// How many foreign scans the plan of `sql` on the coordinator has: the shards it reads.
int shardsRead(const std::string& url, const std::string& sql) {
    fleet::pg::Connection c(url, "the coordinator");
    fleet::pg::Result plan = c.exec("EXPLAIN " + sql, "explaining");
    int scans = 0;
    for (int i = 0; i < plan.rows(); ++i) scans += plan.text(i, 0).find("Foreign Scan") != std::string_view::npos;
    return scans;
}

}  // namespace

TEST_CASE("three shards: a push spreads the scenes over them, fleet queries see every scene") {
    auto second = anotherCluster();
    auto third = anotherCluster();
    std::vector<std::string> shards;
    for (fleet::pg::LocalCluster* c : {&cluster(), second.get(), third.get()}) {
        c->createDatabase("fleet_shard");
        shards.push_back(c->url("fleet_shard"));
    }
    const std::string url = freshStore("fleet_coordinator");
    auto made = fleet::initSharded(url, shards);
    CHECK(made.before == 0);
    CHECK(made.after == 1);
    CHECK(fleet::initSharded(url, shards).before == 1);  // a second init changes nothing
    const char* smqlProgram = std::getenv("SMQL_PROGRAM");
    REQUIRE(smqlProgram != nullptr);
    std::string command = fmt::format("{} fleet init '{}'", smqlProgram, url);
    for (const std::string& shard : shards) command += fmt::format(" --shard '{}'", shard);
    CHECK(std::system((command + " > /dev/null").c_str()) == 0);

    TempDir dir;
    {
        auto layouts = Engine::open(dir.sub("layouts"));
        buildRealLayouts(*layouts);
        auto rooms = Engine::open(dir.sub("rooms"));
        buildRooms(*rooms);
    }
    auto layouts = storage::Database::open(dir.sub("layouts"));
    auto rooms = storage::Database::open(dir.sub("rooms"));
    const auto pushedLayouts = fleet::push(*layouts, url);
    const auto pushedRooms = fleet::push(*rooms, url);
    const auto total = static_cast<long long>(pushedLayouts.sent) + static_cast<long long>(pushedRooms.sent);
    CHECK(total == 238 + static_cast<long long>(kRoomVersions));
    CHECK(fleet::push(*rooms, url).sent == 0);

    // Every shard holds some versions, whole; together all of them, each once.
    long long onShards = 0;
    for (const std::string& shard : shards) {
        const long long here = storedVersions(shard);
        std::cout << "shard: " << here << " scene versions\n";
        CHECK(here > total / 6);
        CHECK(inconsistencies(shard) == 0);
        onShards += here;
    }
    CHECK(onShards == total);
    CHECK(storedVersions(url) == total);
    CHECK(inconsistencies(url) == 0);

    // A scene back through the coordinator, byte for byte; a statement on it as in the engine.
    auto pulledDatabase = storage::Database::open(dir.sub("pulled"));
    fleet::pull(url, {.scene = "den", .device = "", .version = 0}, *pulledDatabase);
    {
        auto original = Engine::open(dir.sub("rooms"));
        auto pulled = Engine::open(dir.sub("pulled"));
        CHECK(exportedJson(*pulled, "den") == exportedJson(*original, "den"));
#ifdef SMQL_PG_MODULE_DIR
        REQUIRE(made.predicates);
        fleet::Store store(url);
        const auto replica = store.versionsNamed("replica-room0", "").back();
        original->execute("USE SCENE 'replica-room0'");
        const auto local = original->execute("COUNT chair WHERE near(table)").back();
        CHECK(fleet::runQuery(store, replica, "COUNT chair WHERE near(table)").count ==
              std::get<std::int64_t>(local.rows.at(0).at(0)));
        // A session's one-scene statements run on the shard that holds the scene, as on one server;
        // across every scene, through the coordinator.
        fleet::StoreSession session(url, "");
        std::vector<ResultSet> answers;
        const auto keep = [&](ResultSet&& rs) { answers.push_back(std::move(rs)); };
        session.execute("USE SCENE 'replica-room0'; COUNT chair WHERE near(table); USE SCENE '*'; COUNT chair", keep);
        CHECK(answers.at(1).rows.at(0).at(0) == local.rows.at(0).at(0));
        CHECK(std::get<std::int64_t>(answers.at(3).rows.at(0).at(0)) ==
              fleet::Store(url)
                  .connection()
                  .exec("SELECT count(*) FROM smql.nodes n JOIN (SELECT DISTINCT ON (device, "
                        "name) id FROM smql.scenes ORDER BY device, name, version DESC) s "
                        "ON s.id = n.scene WHERE n.category = 'chair'",
                        "counting chairs")
                  .integer(0, 0));
#endif
    }

    // Pushes through the coordinator killed at random moments: each version whole on its shard or absent.
    CHECK(killPushes(*layouts, url, killCount(20) / 2).cutShort > 0);

    // One scene's rows are read from one shard; the fleet's from all three.
    const auto den = fleet::Store(url).versionsNamed("den", "").back();
    CHECK(shardsRead(url, fmt::format("SELECT count(*) FROM smql.nodes WHERE scene = {}", den.key)) == 1);
    CHECK(shardsRead(url, "SELECT count(*) FROM smql.nodes WHERE category = 'chair'") == 3);
}
