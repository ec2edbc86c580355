// Objects of category `object` from the aligned structure cloud (objects_from_clusters.cpp): what the
// fallback source finds, and what the detectors' sources add for the large things no model names.
#pragma once

#include <cstddef>
#include <vector>

#include "ingest/geometry/walls.hpp"
#include "ingest/pipeline/object_fusion.hpp"
#include "ingest/pipeline/stage_data.hpp"
#include "model/types.hpp"

namespace smql::ingest {

struct ClusterObjects {
    double gap = 0.08;           // m: points this close chain into one cluster
    std::size_t minPoints = 30;  // of the structure cloud's 5 cm voxels
    double minLonger = 0.05;     // m: the box's longer footprint side at least ...
    double minShorter = 0.03;    // ... its shorter ...
    double minHeight = 0.03;     // ... and its height
    double maxLonger = 1e9;      // m: longer than this, a cluster is part of the room (a wall not found as one)
    std::size_t minFrames = 1;   // frames whose points it holds
    bool outsideKnown = false;   // leave out the points in (or next to) the scene's objects' boxes
    double knownMargin = 0.1;    // m
};

struct ClusterCounts {
    std::size_t added = 0;     // nodes added
    std::size_t cabinets = 0;  // of them, the cabinets a basin is set in
};

// Adds a node for each cluster of the aligned structure's points that are not floor, ceiling or
// wall (nor, with outsideKnown, in an object the scene holds) and whose box and views pass the
// options, as an `object`; a cluster right under a basin (typical_sizes.hpp: Role::Basin; a sink), most
// of it under the basin's footprint, is the cabinet the basin is set in (a vanity: object_fusion.hpp,
// cabinetOf), named so, its footprint reaching under the basin's (reachUnder).
ClusterCounts addClusterObjects(const AlignedCapture& aligned, const std::vector<WallSegment>& walls,
                                model::SceneData& scene, const ClusterObjects& options);

// The basin of the scene the cluster's box is the cabinet of (cabinetOf), or null.
const model::Node* basinOver(const model::Box& cluster, const model::SceneData& scene,
                             const FusionOptions& options = {});

}  // namespace smql::ingest
