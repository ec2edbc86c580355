#include "ingest/pipeline/align_stage.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "model/category.hpp"
#include "model/geometry.hpp"

namespace smql::ingest {

namespace {

// The frame pass's named things: each track's surface points, else its views' points.
std::vector<NamedThing> trackedThings(const std::vector<ObjectTrack>& tracks) {
    std::vector<NamedThing> things;
    for (const auto& track : tracks) {
        if (track.kind != model::NodeKind::Object) continue;
        NamedThing thing{track.category, track.surface};
        if (thing.points.empty())
            for (const auto& v : track.views) thing.points.insert(thing.points.end(), v.points.begin(), v.points.end());
        things.push_back(std::move(thing));
    }
    return things;
}

}  // namespace

std::vector<NamedThing> thingsAsStored(const model::SceneData& scene, const std::vector<TrackedNode>& tracked,
                                       const Alignment& alignment) {
    std::vector<NamedThing> things;
    for (const auto& t : tracked) {
        auto node = std::find_if(scene.nodes.begin(), scene.nodes.end(), [&](const auto& n) { return n.id == t.node; });
        if (!t.fused || node == scene.nodes.end() || node->kind != model::NodeKind::Object) continue;
        NamedThing thing{node->category, {}};
        if (node->category == model::kUnnamedCategory) {
            auto detected = std::find_if(node->attributes.begin(), node->attributes.end(),
                                         [](const auto& a) { return a.name == "detected_as"; });
            if (detected == node->attributes.end()) continue;
            thing = NamedThing{detected->value, {}, /*measures=*/false};
        }
        const model::Box& box = node->box;
        const model::BoxFrame frame(box);
        for (int i = -1; i <= 1; ++i)
            for (int j = -1; j <= 1; ++j)
                for (int k = -1; k <= 1; ++k) {
                    const model::Vec2 at = frame.world({i * box.size.x / 2, j * box.size.y / 2});
                    thing.points.push_back(alignment.unapply({at.x, at.y, box.center.z + k * box.size.z / 2}));
                }
        things.push_back(std::move(thing));
    }
    return things;
}

AlignedCapture AlignStage::run(StageProgress& progress) {
    AlignOptions align;
    align.metric = capture.metric;
    align.scale = options.scale;
    if (options.cameraHeight) {
        align.cameraHeight = *options.cameraHeight;
        align.cameraHeightGiven = true;
    }
    align.evidencePoints = frames.measuredPoints;
    align.thingsOnDepth = storedThings != nullptr;
    std::vector<Pose> poses;
    for (const auto& c : frames.cameras) poses.push_back(c.pose);
    // Named things tell the floor from a table top (what stands on it), and those of a typical height
    // are one of the scale's priors when there is a scale to find.
    const std::vector<NamedThing> tracked = storedThings ? std::vector<NamedThing>{} : trackedThings(frames.tracks);
    const std::vector<NamedThing>& things = storedThings ? *storedThings : tracked;
    AlignedCapture out;
    out.alignment = alignCapture(frames.structure, poses, align, things, frames.lines);
    for (const auto& n : out.alignment.notes) progress.note(n);
    out.cloud = transformed(frames.structure, out.alignment);
    for (const auto& c : frames.cameras) out.cameraCentres.push_back(out.alignment.apply(c.pose.translation));
    out.onLiftedThings = storedThings != nullptr;
    return out;
}

std::string AlignStage::summary(const AlignedCapture& aligned) const {
    const Alignment& a = aligned.alignment;
    return fmt::format("floor {}, heading {:.1f} deg, scale {:.3f}", a.floorFound ? "found" : "not found",
                       a.heading / model::kDegree, a.scale);
}

}  // namespace smql::ingest
