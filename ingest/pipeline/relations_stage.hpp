// The relations stage: parents by the tree rule (docs/relations.md); `on` and
// `in` between objects, evaluated once in the aligned frame; left/right per
// view, stored against frame nodes (the cameras that saw objects) and
// consolidated where enough views agree; then the two-layer descriptions
// (descriptions.hpp), which are reported as part of this stage.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "ingest/capture/capture.hpp"
#include "ingest/pipeline/pipeline.hpp"
#include "ingest/pipeline/stage_data.hpp"
#include "ingest/pipeline/stage_runner.hpp"
#include "model/types.hpp"

namespace smql::ingest {

struct RelationsStage {
    static constexpr std::string_view kName = "relations";
    const Capture& capture;
    const IngestOptions& options;
    const FramePass& frames;
    const AlignedCapture& aligned;
    const std::vector<TrackedNode>& tracked;
    model::SceneData& scene;

    std::size_t steps() const { return 1; }
    void run(StageProgress& progress);
    std::string summary() const;
};

}  // namespace smql::ingest
