// The planner's R-tree push-down must never change an answer: for every local
// predicate over a generated scene, the probed plan returns exactly what a
// full scan returns.
#include <catch2/catch.hpp>

#include "engine/binder/binder.hpp"
#include "engine/exec/executor.hpp"
#include "engine/parser/parser.hpp"
#include "engine/planner/planner.hpp"
#include "engine/relations/hierarchy.hpp"
#include "engine_support.hpp"
#include "ingest/generate/room_generator.hpp"
#include "storage/database.hpp"

using namespace smql;
using namespace smql::testing;

namespace {

struct PlannedScene {
    TempDir dir;
    std::unique_ptr<storage::Database> db = storage::Database::open(dir.path.string());
    std::shared_ptr<const exec::SceneSnapshot> snapshot;
    relations::Thresholds thresholds;

    PlannedScene() {
        auto scene = generate::generateRoom({.seed = 11, .objectCount = 400, .name = "big"});
        relations::assignParents(scene);
        auto write = db->beginWrite();
        write.importScene(scene);
        write.commit();
        auto read = db->beginRead();
        snapshot = exec::SceneSnapshot::load(read, *read.sceneByName("big"));
    }

    binder::BoundFind bind(const std::string& text) const {
        auto statements = parser::parse(text);
        binder::Binder b({*snapshot, thresholds, nullptr, nullptr});
        return b.bindFind(std::get<ast::FindStmt>(statements.front().body));
    }

    std::vector<exec::Slot> run(const planner::FindPlan& plan) const {
        std::vector<exec::Slot> out;
        for (const auto& hit : exec::Executor(*snapshot, thresholds).find(plan)) out.push_back(hit.slot);
        std::sort(out.begin(), out.end());
        return out;
    }
};

}  // namespace

TEST_CASE("R-tree probes return exactly what a scan returns") {
    PlannedScene scene;
    const char* queries[] = {
        "FIND object WHERE on(desk)",          "FIND object WHERE on(table) AND color = 'red'",
        "FIND object WHERE in(cabinet)",       "FIND object WHERE above(bed)",
        "FIND object WHERE below(lamp)",       "FIND object WHERE near(sofa)",
        "FIND object WHERE near(door, 2 m)",   "FIND object WHERE attached(window)",
        "FIND chair WHERE near(table, 0.4 m)", "FIND node WHERE near(mug)",
    };
    int probed = 0;
    for (const char* q : queries) {
        INFO(q);
        auto bound = scene.bind(q);
        auto plan = planner::planFind(bound, *scene.snapshot, scene.thresholds);
        probed += plan.probe.has_value();
        auto scan = plan;
        scan.probe.reset();
        auto viaProbe = scene.run(plan);
        CHECK(viaProbe == scene.run(scan));
    }
    CHECK(probed >= 8);  // the predicates over few reference nodes are pushed down
}

TEST_CASE("the planner scans when the reference set is large and for view-relative predicates") {
    PlannedScene scene;
    auto wide = scene.bind("FIND mug WHERE near(object)");
    CHECK_FALSE(planner::planFind(wide, *scene.snapshot, scene.thresholds).probe);
    auto lateral = scene.bind("FIND object WHERE left_of(door)");
    CHECK_FALSE(planner::planFind(lateral, *scene.snapshot, scene.thresholds).probe);
    // The smallest reference set drives the probe.
    auto both = scene.bind("FIND object WHERE near(wall) AND on(door)");
    auto plan = planner::planFind(both, *scene.snapshot, scene.thresholds);
    REQUIRE(plan.probe);
    CHECK(plan.probe->description.rfind("on(door", 0) == 0);
}

TEST_CASE("NEAREST TO through the R-tree gives the scan's answer") {
    PlannedScene scene;
    for (const char* q : {"FIND object NEAREST TO door LIMIT 5", "FIND object NEAREST TO ceiling LIMIT 3",
                          "FIND chair ORDER BY distance(window) LIMIT 4", "FIND object WHERE color = 'red' NEAREST TO door LIMIT 2",
                          "FIND node NEAREST TO door LIMIT 40"}) {
        INFO(q);
        auto bound = scene.bind(q);
        auto plan = planner::planFind(bound, *scene.snapshot, scene.thresholds);
        std::vector<exec::Slot> fast;
        for (const auto& hit : exec::Executor(*scene.snapshot, scene.thresholds).find(plan)) fast.push_back(hit.slot);
        // The same order without a limit (a full scan and sort), cut afterwards.
        auto unlimited = bound;
        unlimited.limit.reset();
        auto all = planner::planFind(unlimited, *scene.snapshot, scene.thresholds);
        std::vector<exec::Slot> slow;
        for (const auto& hit : exec::Executor(*scene.snapshot, scene.thresholds).find(all)) slow.push_back(hit.slot);
        slow.resize(std::min(slow.size(), fast.size()));
        CHECK(fast.size() == std::min<std::size_t>(*bound.limit, fast.size()));
        CHECK(fast == slow);
    }
}
