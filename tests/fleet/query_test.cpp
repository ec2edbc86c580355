// Statements run by the store's server against the engine on the same data: every COUNT of a
// category and FIND of a category with one predicate on another, over real rooms, must give the
// same answer both ways (the server's predicates are the engine's code, in smql_pg.so).
#include <catch2/catch.hpp>

#include <algorithm>
#include <iostream>
#include <map>
#include <set>

#include <fmt/format.h>

#include "fleet/fleet.hpp"
#include "fleet/query.hpp"
#include "fleet_support.hpp"
#include "model/error.hpp"
#include "relations/predicates.hpp"
#include "storage/database.hpp"

using namespace smql;
using namespace smql::testing;

namespace {

// The engine's answer in local ids (the scene's nodes numbered 1..n in id order, as pushed).
struct LocalAnswers {
    Engine& engine;
    std::map<std::int64_t, std::int64_t> localOf;

    LocalAnswers(Engine& e, const std::string& scene) : engine(e) {
        const model::SceneData data = engine.readScene(scene);
        for (std::size_t i = 0; i < data.nodes.size(); ++i)
            localOf.emplace(static_cast<std::int64_t>(data.nodes[i].id), static_cast<std::int64_t>(i) + 1);
        engine.execute(fmt::format("USE SCENE '{}'", scene));
    }
    std::vector<std::int64_t> find(const std::string& statement) {
        std::vector<std::int64_t> out = ordered(statement);
        std::sort(out.begin(), out.end());
        return out;
    }
    std::vector<std::int64_t> ordered(const std::string& statement) {
        std::vector<std::int64_t> out;
        const std::vector<ResultSet> results = engine.execute(statement);
        for (const auto& row : results.back().rows) out.push_back(localOf.at(std::get<std::int64_t>(row[0])));
        return out;
    }
    std::int64_t count(const std::string& statement) {
        const std::vector<ResultSet> results = engine.execute(statement);
        return std::get<std::int64_t>(results.back().rows.at(0).at(0));
    }
};

// The scene's categories a statement can name as written (lower case, no quote), most frequent first.
std::vector<std::string> namedCategories(Engine& engine, const std::string& scene) {
    std::map<std::string, int> counts;
    for (const auto& n : engine.readScene(scene).nodes) {
        bool plain = !n.category.empty() && n.category.find('\'') == std::string::npos &&
                     std::none_of(n.category.begin(), n.category.end(), [](char c) { return std::isupper(c); });
        if (plain && n.kind != model::NodeKind::Description && n.kind != model::NodeKind::Frame) ++counts[n.category];
    }
    std::vector<std::pair<int, std::string>> ranked;
    for (const auto& [name, count] : counts) ranked.emplace_back(-count, name);
    std::sort(ranked.begin(), ranked.end());
    std::vector<std::string> out;
    for (const auto& r : ranked) out.push_back(r.second);
    return out;
}

}  // namespace

TEST_CASE("COUNT and FIND with one predicate answer on the store as in the engine") {
#ifndef SMQL_PG_MODULE_DIR
    WARN("skipped: smql_pg.so was not built (no PostgreSQL server headers: postgresql-server-dev-15)");
    return;
#endif
    const std::string url = freshStore("fleet_queries");
    auto report = fleet::init(url);
    INFO(report.predicatesMissing);
    REQUIRE(report.predicates);
    TempDir dir;
    auto engine = Engine::open(dir.sub("device"));
    buildRooms(*engine);
    {
        auto database = storage::Database::open(dir.sub("device"));
        fleet::push(*database, url);
    }
    fleet::Store store(url);
    std::size_t statements = 0, nonEmpty = 0;
    for (const char* scene : {"replica-room0", "scene0251_00", "scene0277_02", "41069025"}) {
        const fleet::StoredVersion stored = store.versionsNamed(scene, "").back();
        LocalAnswers local(*engine, scene);
        const std::vector<std::string> categories = namedCategories(*engine, scene);
        for (const std::string& c : categories) {
            const std::string statement = fmt::format("COUNT '{}'", c);
            INFO(scene << ": " << statement);
            CHECK(fleet::runQuery(store, stored, statement).count == local.count(statement));
            ++statements;
        }
        const std::size_t few = std::min<std::size_t>(categories.size(), 5);
        for (const auto& spec : relations::predicates()) {
            if (spec.arity != 1) continue;
            for (std::size_t i = 0; i < few; ++i)
                for (std::size_t j = 0; j < few; ++j) {
                    const std::string statement =
                        fmt::format("FIND '{}' WHERE {}('{}')", categories[i], spec.name(), categories[j]);
                    INFO(scene << ": " << statement);
                    const auto expected = local.find(statement);
                    CHECK(fleet::runQuery(store, stored, statement).ids == expected);
                    nonEmpty += !expected.empty();
                    ++statements;
                }
        }
        // The nearest first, in order, ties in id order as the engine breaks them.
        for (std::size_t i = 0; i < few; ++i)
            for (const int k : {1, 3, 12}) {
                for (const std::string& statement :
                     {fmt::format("FIND object NEAREST TO '{}' LIMIT {}", categories[i], k),
                      fmt::format("FIND '{}' ORDER BY distance('{}') LIMIT {}", categories[(i + 1) % few],
                                  categories[i], k)}) {
                    INFO(scene << ": " << statement);
                    CHECK(fleet::runQuery(store, stored, statement).ids == local.ordered(statement));
                    ++statements;
                }
            }
        // A distance written in the statement reaches the server's near.
        const std::string written = fmt::format("FIND '{}' WHERE near('{}', 2.5 m)", categories[0], categories[1]);
        INFO(written);
        CHECK(fleet::runQuery(store, stored, written).ids == local.find(written));
        const std::string counted = fmt::format("COUNT '{}' WHERE near('{}')", categories[0], categories[1]);
        CHECK(fleet::runQuery(store, stored, counted).count == local.count(counted));
        statements += 2;
    }
    std::cout << statements << " statements answered alike on the store and in the engine (" << nonEmpty
              << " FINDs with a non-empty answer)\n";
    CHECK(nonEmpty > 50);  // the comparison is not between empty answers only

    CHECK_THROWS_WITH(
        fleet::runQuery(store, store.versionsNamed("replica-room0", "").back(), "FIND chair SIMILAR TO 'a seat'"),
        Catch::Contains("does not run FIND with SIMILAR TO"));
    CHECK_THROWS_WITH(
        fleet::runQuery(store, store.versionsNamed("replica-room0", "").back(), "FIND chair NEAREST TO HERE LIMIT 1"),
        Catch::Contains("does not run HERE"));

    // AS OF in a session: the version the store held then, as the engine reads its history.
    fleet::StoreSession session(url, "");
    engine->execute("USE SCENE 'den'");
    session.execute("USE SCENE 'den'", [](ResultSet&&) {});
    for (const char* when : {"2026-11-20T12:00:00Z", "2026-11-22T00:00:00Z"}) {
        const std::string statement = fmt::format("FIND object AS OF '{}'", when);
        std::vector<ResultSet> onStore;
        session.execute(statement, [&](ResultSet&& rs) { onStore.push_back(std::move(rs)); });
        const ResultSet inEngine = engine->execute(statement).back();
        INFO(statement);
        CHECK(onStore.back().rows.size() == inEngine.rows.size());
    }
    CHECK_THROWS_WITH(session.execute("COUNT object AS OF '2020-01-01'", [](ResultSet&&) {}),
                      Catch::Contains("the store holds nothing of it"));
}
