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
    std::size_t added = 0;         // nodes added
    std::size_t cabinets = 0;      // of them, the cabinets a basin is set in
    std::size_t wallCabinets = 0;  // ... and the cabinets hung on a wall (hungOnWall)
};

// Adds a node for each cluster of the aligned structure's points that are not floor, ceiling or
// wall (nor, with outsideKnown, in an object the scene holds) and whose box and views pass the
// options, as an `object`; a cluster right under a basin (typical_sizes.hpp: Role::Basin; a sink), most
// of it under the basin's footprint, is the cabinet the basin is set in (a vanity: object_fusion.hpp,
// cabinetOf), named so, its footprint reaching under the basin's (reachUnder); one hung on a wall
// (hungOnWall) is a wall cabinet, named so too.
ClusterCounts addClusterObjects(const AlignedCapture& aligned, const std::vector<WallSegment>& walls,
                                model::SceneData& scene, const ClusterObjects& options, const Capture& capture);

// Whether a cluster's box hangs on a wall: its bottom kWallCabinetBottom or more above the floor (z = 0), its
// footprint within kAgainstWall of a wall's (model::horizontalGap to WallSegment::box). A box of a thing no model named
// hung so, at least ClusterObjects' least size (0.5 x 0.3 x 0.3 m), is a wall cabinet: of the things of ScanNet's 18
// labelled classes that size whose bottom is 1.2 m or more above their room's floor (its scans' boxes in
// mmdetection3d's scannet_infos_train.pkl and _val.pkl, 1,513 scans), 215 of 274 are cabinets, 37 windows (an
// opening's frame, which the walls stage keeps), 11 curtains, 4 bookshelves; beside a wall a ceiling's lamp or fan
// does not hang.
inline constexpr double kWallCabinetBottom = 1.2;  // m
bool hungOnWall(const model::Box& box, const std::vector<WallSegment>& walls);

// A thing no model named, stored from the points of the aligned `cloud` that make it (`indices`): as `category` with
// `box`, the colour its points show, its size and how many points it holds, at half confidence (nothing named it),
// and, where the capture's frames have depth, the first and last of its frames its points were seen in (first_seen,
// last_seen, as the named things have them: what "which did I see first?" orders by). The clusters here and the
// stands under things (objects_stage.hpp: standOnPedestals) are stored so.
model::Node& addUnnamedThing(model::SceneData& scene, std::string category, const model::Box& box,
                             const PointCloud& cloud, const std::vector<std::size_t>& indices, const Capture& capture);

// The basin of the scene the cluster's box is the cabinet of (cabinetOf), or null.
const model::Node* basinOver(const model::Box& cluster, const model::SceneData& scene,
                             const FusionOptions& options = {});

}  // namespace smql::ingest
