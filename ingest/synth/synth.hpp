// `smql synth`: synthetic RGB-D captures of procedural rooms, with ground truth.
// A room from generate::generateRoom, an egocentric walk through it (walk.hpp),
// every frame rendered by our rasterizer (render.hpp), written in the
// rgbd-dining layout plus masks, labels and truth (docs/ingest.md,
// "Synthetic captures"). Same options -> byte-identical files.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "ingest/capture/capture.hpp"
#include "model/types.hpp"

namespace smql::synth {

struct SynthOptions {
    std::uint64_t seed = 1;
    int frames = 60;
    int objects = 24;    // objects in the generator's sense (furniture, chairs, small things)
    bool force = false;  // write into a non-empty folder, replacing an earlier capture's files
    // The same room and walk after someone tidied up: a few small things moved to other furniture,
    // a few taken away, a few new ones put down (changes.json lists them).
    bool changes = false;
    // Only what a plain camera gives: the colour frames as a photo folder (images/, with camera.json
    // and the perfect detector's detections.json), no depth, masks or poses; the truth, and the true
    // poses for check-ingest, stay beside it.
    bool rgbOnly = false;
};

// An instance counts as seen in a frame when at least this many of its pixels are visible.
inline constexpr int kMinVisiblePixels = 200;
// Depth beyond this is written as 0 (no reading); colour and masks still show it.
inline constexpr double kMaxDepth = 10.0;

// A ground-truth relation label, as in relations.json (ReplicaSSG's shape and predicate ids).
struct LabelledRelation {
    model::NodeId subject = model::kNoNode;
    model::NodeId object = model::kNoNode;
    int predicateId = 0;  // 30 on, 21 in, 28 near
    std::string predicate;
};

// The ground truth of a synthetic capture, before any rendering.
struct SynthScene {
    model::SceneData truth;  // parents assigned, name "synth-<seed>"
    std::vector<LabelledRelation> relations;
    std::vector<ingest::Pose> poses;  // frame N is poses[N - 1]
    // With SynthOptions::changes: what differs from the capture without it. Ids are truth ids:
    // `before` of the room without changes, `after` of this one (a moved thing keeps its id).
    std::vector<model::ObjectChange> changes;
};

SynthScene makeSynthScene(const SynthOptions& options);

struct SynthResult {
    SynthScene scene;
    ingest::Intrinsics intrinsics;
    std::map<model::NodeId, int> framesSeen;  // every node with geometry -> frames with >= kMinVisiblePixels
    double frameSeconds = 0;                  // rendering and writing the frames (two threads)
    double totalSeconds = 0;                  // everything
};

// Writes the capture into `directory` (created if missing). Throws
// smql::Error(Usage) when it exists and is not empty, unless options.force.
SynthResult writeSynth(const std::string& directory, const SynthOptions& options);

// 640x480, fx = fy = 525, cx = 319.5, cy = 239.5.
ingest::Intrinsics synthIntrinsics();

// A PNG as plain numbers, for tests and tools that do not use OpenCV: 8-bit
// colour images as R, G, B (channels = 3), 16-bit images as they are (channels = 1).
struct Image {
    int width = 0, height = 0, channels = 0;
    std::vector<std::uint16_t> data;  // row-major, channels interleaved
    std::uint16_t at(int u, int v, int channel = 0) const {
        return data[(static_cast<std::size_t>(v) * width + u) * channels + channel];
    }
};
// Throws smql::Error(Input) naming the file when it cannot be read.
Image readImage(const std::string& path);

}  // namespace smql::synth
