// The anchors stage: the floor (the aligned cloud's extent at z = 0, without
// outliers: strays do not stretch it), the
// ceiling when the alignment found one, and walls from vertical planes, added
// to the scene. Doors and windows come later, from the object source and the
// openings stage.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "ingest/geometry/walls.hpp"
#include "ingest/pipeline/stage_data.hpp"
#include "ingest/pipeline/stage_runner.hpp"
#include "model/types.hpp"

namespace smql::ingest {

struct AnchorsStage {
    static constexpr std::string_view kName = "anchors";
    const AlignedCapture& aligned;
    model::SceneData& scene;

    std::size_t steps() const { return 1; }
    std::vector<WallSegment> run(StageProgress& progress);
    std::string summary(const std::vector<WallSegment>& walls) const;
};

}  // namespace smql::ingest
