// The planner's R-tree push-down must never change an answer: for every local
// predicate over a generated scene, the probed plan returns exactly what a
// full scan returns.
#include <catch2/catch.hpp>

#include <optional>

#include <fmt/format.h>

#include "engine/binder/binder.hpp"
#include "engine/exec/executor.hpp"
#include "engine/parser/parser.hpp"
#include "engine/planner/planner.hpp"
#include "engine_support.hpp"
#include "ingest/generate/room_generator.hpp"
#include "relations/hierarchy.hpp"
#include "storage/database.hpp"

using namespace smql;
using namespace smql::testing;

namespace {

struct PlannedScene {
    TempDir dir;
    std::unique_ptr<storage::Database> db = storage::Database::open(dir.path.string());
    // What the snapshot reads the nodes it has not decoded yet through (the engine names each
    // statement's transaction): one that sees the scene as it was loaded, for the test's life.
    std::optional<storage::ReadTransaction> reader;
    std::shared_ptr<const catalog::SceneSnapshot> snapshot;
    relations::Thresholds thresholds;

    PlannedScene() {
        auto scene = generate::generateRoom({.seed = 11, .objectCount = 400, .name = "big"});
        relations::assignParents(scene);
        auto write = db->beginWrite();
        write.importScene(scene);
        write.commit();
        reader.emplace(db->beginRead());
        snapshot = catalog::SceneSnapshot::load(*reader, *reader->sceneByName("big"));
    }

    catalog::Session session;

    // Bound and planned as the engine does it, in this scene.
    planner::Plan plan(const std::string& text) {
        auto statements = parser::parse(text);
        auto read = db->beginRead();
        binder::Binder b({read, session, [&] { return snapshot; }, [&](const std::string&) { return snapshot; }});
        return planner::plan(std::make_shared<const binder::BoundStatement>(b.bind(statements.front())));
    }

    // The plan with its FIND's access path replaced.
    static planner::Plan withAccess(planner::Plan plan, planner::Access access) {
        plan.find->access = access;
        return plan;
    }

    std::vector<catalog::Slot> run(const planner::Plan& plan, bool sorted = true) {
        auto read = db->beginRead();
        std::vector<catalog::Slot> out;
        for (const auto& hit : exec::Executor(read, session, plan).find(*plan.find)) out.push_back(hit.slot);
        if (sorted) std::sort(out.begin(), out.end());
        return out;
    }
};

}  // namespace

TEST_CASE("R-tree probes return exactly what a scan returns") {
    PlannedScene scene;
    const char* queries[] = {
        "FIND object WHERE on(desk)",
        "FIND object WHERE on(table) AND color = 'red'",
        "FIND object WHERE in(cabinet)",
        "FIND object WHERE above(bed)",
        "FIND object WHERE below(lamp)",
        "FIND object WHERE near(sofa)",
        "FIND object WHERE near(door, 2 m)",
        "FIND object WHERE attached(window)",
        "FIND chair WHERE near(table, 0.4 m)",
        "FIND node WHERE near(mug)",
        // HERE: a person standing at the viewpoint, or where VIEW FROM puts the viewer.
        "FIND object WHERE near(HERE)",
        "FIND object VIEW FROM #39 WHERE near(HERE, 2 m)",
        "FIND object WHERE above(HERE)",
    };
    int probed = 0;
    for (const char* q : queries) {
        INFO(q);
        auto plan = scene.plan(q);
        probed += plan.find->access == planner::Access::RTreeProbe;
        CHECK(scene.run(plan) == scene.run(PlannedScene::withAccess(plan, planner::Access::Scan)));
    }
    CHECK(probed >= 11);  // the predicates over few reference nodes are pushed down
    // Around HERE the probe finds things to compare: the viewer stands in the hall, not outside it.
    CHECK_FALSE(scene.run(scene.plan("FIND object WHERE near(HERE)")).empty());
    CHECK_FALSE(scene.run(scene.plan("FIND object VIEW FROM #39 WHERE near(HERE, 2 m)")).empty());
}

TEST_CASE("distance(x) < d probes the R-tree and returns what a scan returns") {
    PlannedScene scene;
    const char* queries[] = {
        "FIND object WHERE distance(sofa) < 1 m",
        "FIND object WHERE distance(door) <= 250 cm",
        "FIND object WHERE distance(desk) < 0 m",
        "FIND node WHERE distance(mug) < 3 m AND color = 'red'",
        "FIND object WHERE distance(bed) < 50 cm AND on(bed)",
        // HERE: around the line where the viewer stands, the scene's viewpoint or the one VIEW FROM sets.
        "FIND object WHERE distance(HERE) < 2 m",
        "FIND object VIEW FROM #39 WHERE distance(HERE) < 1.5 m",
    };
    for (const char* q : queries) {
        INFO(q);
        auto plan = scene.plan(q);
        CHECK(plan.find->access == planner::Access::RTreeProbe);
        CHECK(scene.run(plan) == scene.run(PlannedScene::withAccess(plan, planner::Access::Scan)));
    }
    for (const char* q :
         {"FIND object WHERE distance(HERE) < 2 m", "FIND object VIEW FROM #39 WHERE distance(HERE) < 1.5 m"}) {
        INFO(q);
        CHECK_FALSE(scene.run(scene.plan(q)).empty());
    }
    // A lower bound cannot be probed: everything far away qualifies.
    CHECK(scene.plan("FIND object WHERE distance(sofa) > 1 m").find->access == planner::Access::Scan);
}

TEST_CASE("ORDER BY an attribute with a LIMIT is a top k of the full order") {
    PlannedScene scene;
    for (const char* order : {"height DESC", "volume", "x", "color DESC", "z"}) {
        INFO(order);
        auto top = scene.plan(fmt::format("FIND object ORDER BY {} LIMIT 7", order));
        CHECK(top.find->topK);
        auto full = scene.plan(fmt::format("FIND object ORDER BY {}", order));
        CHECK_FALSE(full.find->topK);
        auto all = scene.run(full, false);
        all.resize(7);
        CHECK(scene.run(top, false) == all);
    }
}

TEST_CASE("the planner scans when the reference set is large and for view-relative predicates") {
    PlannedScene scene;
    CHECK(scene.plan("FIND mug WHERE near(object)").find->access == planner::Access::Scan);
    CHECK(scene.plan("FIND object WHERE left_of(door)").find->access == planner::Access::Scan);
    // The smallest reference set drives the probe.
    auto both = scene.plan("FIND object WHERE near(wall) AND on(door)");
    REQUIRE(both.find->access == planner::Access::RTreeProbe);
    CHECK(both.find->probeTerm().predicate == relations::Predicate::On);
}

TEST_CASE("NEAREST TO through the R-tree gives the scan's answer") {
    PlannedScene scene;
    int nearestFirst = 0;
    for (const char* q :
         {"FIND object NEAREST TO door LIMIT 5", "FIND object NEAREST TO ceiling LIMIT 3",
          "FIND chair ORDER BY distance(window) LIMIT 4", "FIND object WHERE color = 'red' NEAREST TO door LIMIT 2",
          "FIND node NEAREST TO door LIMIT 40", "FIND object NEAREST TO HERE LIMIT 6",
          "FIND chair VIEW FROM #39 ORDER BY distance(HERE) LIMIT 3"}) {
        INFO(q);
        auto plan = scene.plan(q);
        nearestFirst += plan.find->access == planner::Access::NearestFirst;
        auto fast = scene.run(plan, false);
        // The same order from a scan and a sort.
        auto slow = scene.run(PlannedScene::withAccess(plan, planner::Access::Scan), false);
        CHECK(fast.size() == std::min<std::size_t>(*plan.find->find->limit, slow.size()));
        CHECK(fast == slow);
    }
    CHECK(nearestFirst == 6);  // all but the one ordered by distance to several windows
}

// The nearest-first search stops at the first candidate whose bounds are farther than the k-th
// answer found: around many references and for several k, it must still give the scan's answer,
// ties ordered by id included.
TEST_CASE("NEAREST TO stops early with the scan's answer around any node and for any LIMIT") {
    PlannedScene scene;
    const auto& objects = scene.snapshot->shownOfKind(model::NodeKind::Object);
    std::vector<model::NodeId> references;
    for (std::size_t i = 0; i < objects.size(); i += 25) references.push_back(scene.snapshot->node(objects[i]).id);
    for (const char* anchor : {"door", "window", "floor"})
        for (catalog::Slot s : scene.snapshot->withCategory(anchor)) references.push_back(scene.snapshot->node(s).id);
    REQUIRE(references.size() > 15);
    for (model::NodeId reference : references) {
        for (int limit : {1, 2, 5, 17}) {
            for (const char* target : {"object", "node"}) {
                const std::string q = fmt::format("FIND {} NEAREST TO #{} LIMIT {}", target, reference, limit);
                INFO(q);
                auto plan = scene.plan(q);
                REQUIRE(plan.find->access == planner::Access::NearestFirst);
                CHECK(scene.run(plan, false) ==
                      scene.run(PlannedScene::withAccess(plan, planner::Access::Scan), false));
            }
        }
    }
}

TEST_CASE("sub-queries are planned, and run by the executor once") {
    PlannedScene scene;
    auto plan = scene.plan("FIND object WHERE near((FIND table LIMIT 1)) AND on((FIND desk))");
    std::size_t subqueries = 0;
    for (const auto& sub : plan.subqueries) subqueries += sub != nullptr;
    CHECK(subqueries == 2);
    // The same answer as the references named directly.
    auto direct = scene.plan("FIND object WHERE near(#" +
                             std::to_string(scene.snapshot->node(scene.snapshot->withCategory("table").front()).id) +
                             ") AND on(desk)");
    CHECK(scene.run(plan) == scene.run(direct));
}

TEST_CASE("LIMIT 0 answers no rows on every access path") {
    PlannedScene scene;
    for (const char* q : {"FIND object NEAREST TO door LIMIT 0", "FIND object LIMIT 0",
                          "FIND object WHERE near(door) LIMIT 0", "FIND object ORDER BY distance(door) DESC LIMIT 0"}) {
        INFO(q);
        CHECK(scene.run(scene.plan(q)).empty());
    }
}
