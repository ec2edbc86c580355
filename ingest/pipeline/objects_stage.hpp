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

// The column a thing stands on (`top`, its box, aligned): under its footprint, the room's own points (`roomPoints`,
// indices into the aligned `cloud` without its walls' points: nonStructuralPoints in walls.hpp; those in the `others`
// things' boxes left out) rising from the floor to it in one column
// narrower than half the thing (or than `narrowest`, where that is wider), at most heights. Returns the column's
// points (indices into `cloud`), none when they make no column. A sink's pedestal (its box as fusion left it: its bowl,
// fitBasin in object_fusion.hpp) passes; a vanity's front is as wide as the basin, and a sink hung on a wall has
// nothing under it but its drain, which ends in the wall above the floor.
std::vector<std::size_t> pedestalUnder(const model::Box& top, const PointCloud& cloud,
                                       const std::vector<std::size_t>& roomPoints,
                                       const std::vector<model::Box>& others, double narrowest = 0);

// A track's place once the room is aligned: its colour samples and its box.
struct PlacedTrack {
    std::size_t track;  // in ObjectsStage::tracks
    cv::Mat colors;
    model::Box box;
    bool againstWall = false;  // a thing with a front turned to face away from the wall it stands against
    bool pushedIn = false;     // a chair seen by its back alone, pushed in square to its table
    model::Vec3 seenFrom{};    // the mean centre of the cameras that saw it
};

// A stand no model named, under a thing it holds up (standOnPedestals): its box and its points (indices into the
// aligned cloud).
struct Stand {
    model::Box box;
    std::vector<std::size_t> points;
};

// What stands on a pedestal (pedestalUnder), with depth and a floor found. A sink whose views gave its bowl alone is
// one thing with its pedestal: its box reaches down to the floor (`sinks` counts them), and its footprint is all its
// fused points', square to the walls (wallAlignedBox), as no counter lies around its bowl: ScanNet's apartment from
// every second frame fitted its 0.67 x 0.45 m basin's bowl 0.46 x 0.22 m, turned 45 degrees from its wall. A thing of a
// kind that is not always on the floor (a floor's kind, a chair or a bed, holds its own legs) that is held up by a
// column no model named stands on it: the column is a stand (a pedestal table, a towel stand), returned to be stored as
// a table from the floor up to the thing, as wide as the thing. ScanNet's bathroom's towels on a tripod stand were a
// "toy" 0.49 m over the floor with nothing stored under it; ScanNet labels the stand a table.
struct Pedestals {
    std::size_t sinks = 0;
    std::vector<Stand> stands;
};
Pedestals standOnPedestals(std::vector<PlacedTrack>& placed, const std::vector<ObjectTrack>& tracks,
                           const PointCloud& cloud, const std::vector<WallSegment>& walls);

// Two things of one kind, the smaller mostly inside the larger (plausibility.hpp: storedTwice), are one thing stored
// twice, where both are hulls carved without depth or both chairs pushed in at a table. A hull's views went to two
// tracks that share frames, so they were not joined as one thing split in two (ray_tracks.hpp: mergeSplitTracks);
// ScanNet's apartment as 100 photos stored a toilet, a book and a sofa twice each, the plausibility check warning of
// each. A chair's back was seen in two pieces, which overlap once both are pushed in: the dining frames' two 0.97 m
// tall slabs 0.18 m apart. So is a thing stored unnamed mostly inside a sink that reaches the floor (standOnPedestals):
// what holds the sink, seen apart, its name doubted under the bowl (object_fusion.hpp: sinkOverTable; ScanNet's
// apartment from every second frame from the second and every third, its pedestal a 0.79 x 0.31 x 0.38 m and a
// 0.54 x 0.36 x 0.28 m "table"). The smaller's views join the larger's; the larger's box stays, or for chairs takes in
// the smaller's footprint (two pieces of one back). Returns how many were merged.
std::size_t mergeStoredTwice(std::vector<PlacedTrack>& placed, std::vector<ObjectTrack>& tracks);

// Chairs seated as people leave them. A chair within 0.5 m of a table or a desk faces it; one whose box holds its
// back alone (shallower than any chair of its width, at most half as deep as wide) is pushed in, square to the table's
// nearest side, as deep as the shallowest chairs of its width towards it (the dining frames' four at the table,
// 0.11-0.19 m deep slabs). One whose back alone was seen at no table was seen from behind, and faces away from the
// cameras that saw it (PlacedTrack::seenFrom), as deep as the shallowest chairs of its width ahead of its back. Chairs
// against a wall are left as they were turned. How many were pushed in, and how many turned from the cameras.
std::pair<std::size_t, std::size_t> seatChairs(std::vector<PlacedTrack>& placed,
                                               const std::vector<ObjectTrack>& tracks);

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
