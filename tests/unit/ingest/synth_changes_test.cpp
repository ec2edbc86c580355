// `smql synth --changes` and the memory over time: the room of a seed, then the same room after
// a few small things moved, went and appeared. Stored and then updated with the exact layouts,
// the memory's change report must be the ground truth, change for change.
#include <algorithm>
#include <cmath>

#include <catch2/catch.hpp>

#include "engine/engine.hpp"
#include "ingest/synth/synth.hpp"
#include "ingest/synth/walk.hpp"
#include "model/geometry.hpp"
#include "scratch_dir.hpp"

using namespace smql;

namespace {

bool sameCentre(const model::Box& a, const model::Box& b) {
    return std::hypot(a.center.x - b.center.x, a.center.y - b.center.y, a.center.z - b.center.z) < 1e-9;
}

}  // namespace

TEST_CASE("--changes keeps the room and the walk, and lists what it changed", "[synth][changes]") {
    auto before = synth::makeSynthScene({.seed = 4, .frames = 8});
    auto after = synth::makeSynthScene({.seed = 4, .frames = 8, .changes = true});
    CHECK(before.changes.empty());
    REQUIRE(after.poses.size() == before.poses.size());
    for (std::size_t i = 0; i < after.poses.size(); ++i)
        CHECK(synth::poseLine(after.poses[i]) == synth::poseLine(before.poses[i]));
    CHECK(after.truth.info.captureTime > before.truth.info.captureTime);
    std::size_t moved = 0, added = 0, missing = 0;
    for (const auto& c : after.changes) {
        moved += c.kind == model::ChangeKind::Moved;
        added += c.kind == model::ChangeKind::Added;
        missing += c.kind == model::ChangeKind::Missing;
    }
    CHECK(moved == 2);
    CHECK(added == 2);
    CHECK(missing == 2);
    // Local ids stay 1..n, as an smql scene file needs.
    for (std::size_t i = 0; i < after.truth.nodes.size(); ++i) CHECK(after.truth.nodes[i].id == i + 1);
}

TEST_CASE("an update by the changed room reports exactly the changes synth made", "[synth][changes]") {
    for (std::uint64_t seed : {1, 2, 3, 5, 8, 11, 13}) {
        CAPTURE(seed);
        ingest::test::ScratchDir dir;
        auto before = synth::makeSynthScene({.seed = seed, .frames = 1});
        auto after = synth::makeSynthScene({.seed = seed, .frames = 1, .changes = true});
        auto engine = Engine::open(dir.path.string());
        const model::NodeId first = engine->importScene(before.truth);
        auto report = engine->updateScene(before.truth.info.name, after.truth);
        const model::NodeId second = engine->readScene(before.truth.info.name).info.id;

        REQUIRE(report.changes.size() == after.changes.size());
        for (const auto& truth : after.changes) {
            // Database ids: a scene's block starts with its scene node, then local ids in order.
            auto found = std::find_if(report.changes.begin(), report.changes.end(), [&](const model::ObjectChange& c) {
                return c.kind == truth.kind && c.category == truth.category &&
                       c.before == (truth.before ? first + truth.before : model::kNoNode) &&
                       c.after == (truth.after ? second + truth.after : model::kNoNode);
            });
            REQUIRE(found != report.changes.end());
            if (truth.kind != model::ChangeKind::Added) CHECK(sameCentre(found->from, truth.from));
            if (truth.kind != model::ChangeKind::Missing) CHECK(sameCentre(found->to, truth.to));
        }
        CHECK(report.unseen == 0);
    }
}
