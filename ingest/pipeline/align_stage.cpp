#include "ingest/pipeline/align_stage.hpp"

#include <cmath>

#include <fmt/format.h>

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

AlignedCapture AlignStage::run(StageProgress& progress) {
    AlignOptions align;
    align.metric = capture.metric;
    align.scale = options.scale;
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
