// The objects stage: every track with enough views becomes a node, an object
// with an upright box and attributes (colour, size, material, views, first and
// last seen), or a door or window as a thin plane in its wall; walls, floor
// and ceiling tracks are left to the geometry. The evidence crops become the
// nodes' blobs, and so does the normalised mean of the views' embeddings
// (blob `embedding`, model/embedding.hpp) when the detections carry them. Then the object source adds the objects it
// finds in the aligned structure (clusters).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ingest/capture/capture.hpp"
#include "ingest/geometry/walls.hpp"
#include "ingest/pipeline/object_finder.hpp"
#include "ingest/pipeline/pipeline.hpp"
#include "ingest/pipeline/stage_data.hpp"
#include "ingest/pipeline/stage_runner.hpp"
#include "model/types.hpp"

namespace smql::ingest {

// A hull carved without depth (ObjectTrack::carved), in the aligned frame, held to where its thing's
// surfaces were seen (`surface`, the sparse points it was carved around): along the mean direction the
// `cameras` that saw it looked in, at its top, and, for a thing `widestAtTop` (one that holds things
// and has no upright end, typical_sizes.hpp: a table, a desk), to the footprint its top shows. Where the
// floor was placed a table's height under a table top (`tableTop`, Alignment::tableTopHeight), such a thing
// whose hull and surfaces reach past that height has it for its top.
std::vector<model::Vec3> holdToSurface(const std::vector<model::Vec3>& hull, const std::vector<model::Vec3>& surface,
                                       const std::vector<model::Vec3>& cameras, bool widestAtTop,
                                       std::optional<double> tableTop = std::nullopt);

struct ObjectsStage {
    static constexpr std::string_view kName = "objects";
    const Capture& capture;
    const IngestOptions& options;
    std::vector<ObjectTrack> tracks;  // consumed: their views and crops move on
    const AlignedCapture& aligned;
    const std::vector<WallSegment>& walls;
    ObjectFinder& finder;
    model::SceneData& scene;

    std::size_t steps() const { return tracks.size(); }
    std::vector<TrackedNode> run(StageProgress& progress);
    std::string summary(const std::vector<TrackedNode>& nodes) const;
};

}  // namespace smql::ingest
