// The frames stage: one pass over the frames. Each posed frame feeds the
// structure cloud (back-projected depth, down-sampled as it grows so memory
// stays flat) and the object source; frames without a pose are skipped with a
// note. Cancellation is checked before every frame.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "ingest/capture/capture.hpp"
#include "ingest/pipeline/object_finder.hpp"
#include "ingest/pipeline/pipeline.hpp"
#include "ingest/pipeline/stage_data.hpp"
#include "ingest/pipeline/stage_runner.hpp"

namespace smql::ingest {

struct FramesStage {
    static constexpr std::string_view kName = "frames";
    const Capture& capture;
    const IngestOptions& options;
    ObjectFinder& finder;

    std::size_t steps() const { return capture.frames.size(); }
    FramePass run(StageProgress& progress);
    std::string summary(const FramePass& pass) const;
};

}  // namespace smql::ingest
