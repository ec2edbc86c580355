// Do the frames' depth images agree with each other through their poses? A point one frame saw
// must, seen from another frame that looks at it, be at the depth that frame reads, or behind
// something nearer; a frame that reads farther sees through it. Mirrored poses or images, poses in
// another convention and a wrong depth unit (with the cameras moving) all break this, whatever the
// focal lengths' signs say (docs/ingest.md, "Plausibility").
#pragma once

#include <cstddef>
#include <vector>

#include "ingest/capture/capture.hpp"
#include "ingest/geometry/point_cloud.hpp"

namespace smql::ingest {

// A frame's depth at a few thousand pixels (nearest samples), with its pose: small enough to keep
// one for every few frames of a long capture.
struct DepthSketch {
    Pose pose;
    Intrinsics intrinsics;  // of the sketch's pixels
    std::vector<float> metres;
};

DepthSketch sketchDepth(const DepthView& depth, const Pose& pose, int width = 64);

struct ViewAgreement {
    std::size_t pairs = 0;     // pairs of frames that see enough of each other
    std::size_t agree = 0;     // points of one seen at the depth the other reads
    std::size_t conflict = 0;  // points the other frame sees through
    // agree / (agree + conflict); 1 with nothing tested.
    double share() const;
    bool tested() const;  // enough pairs and points for the share to mean something
};

// Every pair of sketches whose views overlap, both ways.
ViewAgreement compareViews(const std::vector<DepthSketch>& sketches);

}  // namespace smql::ingest
