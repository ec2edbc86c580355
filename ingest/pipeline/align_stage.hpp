// The align stage: floor, heading and scale of the structure cloud (docs/ingest.md,
// "Geometry and metric alignment"), and the cloud and cameras in the aligned frame.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "ingest/capture/capture.hpp"
#include "ingest/geometry/scale_priors.hpp"
#include "ingest/pipeline/pipeline.hpp"
#include "ingest/pipeline/stage_data.hpp"
#include "ingest/pipeline/stage_runner.hpp"

namespace smql::ingest {

struct AlignStage {
    static constexpr std::string_view kName = "align";
    const Capture& capture;
    const IngestOptions& options;
    const FramePass& frames;
    // The named things measured instead of the frame pass's tracks: those the objects stage stored, when it
    // lifted them on the dense points and the alignment is measured again on them (pipeline.cpp).
    const std::vector<NamedThing>* storedThings = nullptr;

    std::size_t steps() const { return 1; }
    AlignedCapture run(StageProgress& progress);
    std::string summary(const AlignedCapture& aligned) const;
};

// The things the objects stage fused in the aligned frame and stored under a name, in the capture's frame and
// units, for the alignment measured again on them (pipeline.cpp): each box as the 27 points of its corners, the middles
// of its edges and faces, and its centre, so that what weighs a surface and what measures a height (floor_evidence.hpp,
// scale_priors.hpp) read the box's bottom and top. A name that did not fit its box or its place is stored as "object"
// with detected_as: that thing measures nothing, and comes under the detector's name to doubt another room's names
// beside it.
std::vector<NamedThing> thingsAsStored(const model::SceneData& scene, const std::vector<TrackedNode>& tracked,
                                       const Alignment& alignment);

}  // namespace smql::ingest
