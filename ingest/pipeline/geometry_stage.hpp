// Where the capture's geometry comes from (docs/ingest.md, "--geometry"): the
// poses and depth the capture carries, or COLMAP's poses and sparse points
// from its colour frames (the `colmap` stage). Decides, runs COLMAP when
// needed, and checks that the frames then have what the later stages need.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "ingest/capture/capture.hpp"
#include "ingest/geometry/dense_stereo.hpp"
#include "ingest/pipeline/pipeline.hpp"
#include "ingest/pipeline/stage_data.hpp"
#include "ingest/pipeline/stage_runner.hpp"

namespace smql::ingest {

// Whether the poses come from COLMAP. Throws smql::Error(Input) when the given
// poses were asked for and some frame has none.
bool usesColmap(const Capture& capture, GeometrySource geometry);

struct ColmapStage {
    static constexpr std::string_view kName = "colmap";
    const Capture& input;
    const ColmapOptions& options;

    // The frames: each COLMAP command's bar counts them as its log does (ColmapWatch::progress).
    std::size_t steps() const { return input.frames.size(); }
    Reconstruction run(StageProgress& progress);
    std::string summary(const Reconstruction& reconstruction) const;
};

// Whether the capture gets dense points (dense_stereo.hpp): photos without depth, some placed, with
// sparse points to give each frame its depth range; not when --dense off.
bool needsDensePoints(const Capture& capture, const IngestOptions& options);

// Dense points from pairs of placed frames: the capture's densePoints, beside its sparse points.
struct DenseStage {
    static constexpr std::string_view kName = "dense";
    const Capture& input;
    const DenseOptions& options;

    std::size_t steps() const { return input.frames.size(); }
    Reconstruction run(StageProgress& progress);
    std::string summary(const Reconstruction& reconstruction) const;
};

// Throws smql::Error(Input) unless some frame has a pose and the frames have
// depth or the capture has 3D points.
void requirePosesAndStructure(const Capture& capture);

// Every frame has a depth image (else the structure is the capture's sparse points).
bool framesHaveDepth(const Capture& capture);
// Every frame has a camera pose (else COLMAP finds them).
bool framesHavePoses(const Capture& capture);
// What places things in 3D: depth images, or the capture's 3D points.
bool hasStructure(const Capture& capture);

}  // namespace smql::ingest
