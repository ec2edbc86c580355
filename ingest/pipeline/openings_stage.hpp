// The openings stage: doors and windows found as openings in the walls
// (ingest/geometry/openings.hpp) where the object source gave none, added as
// anchors. It needs depth: a point seen through a wall must know the camera
// that saw it, which sparse points from COLMAP do not.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ingest/geometry/openings.hpp"
#include "ingest/geometry/walls.hpp"
#include "ingest/pipeline/stage_data.hpp"
#include "ingest/pipeline/stage_runner.hpp"
#include "model/types.hpp"

namespace smql::ingest {

struct OpeningsStage {
    static constexpr std::string_view kName = "openings";
    const AlignedCapture& aligned;
    const std::vector<std::pair<std::size_t, model::Vec3>>& cameraCentres;  // frame, centre in the aligned frame
    const std::vector<WallSegment>& walls;
    bool depth;  // the cloud's points came from depth frames, each with its frame
    model::SceneData& scene;

    std::size_t steps() const { return 1; }
    std::vector<WallOpening> run(StageProgress& progress);
    std::string summary(const std::vector<WallOpening>& added) const;
};

}  // namespace smql::ingest
