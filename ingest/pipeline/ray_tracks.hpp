// Detections that too few sparse points fall on, placed by their boxes alone
// (docs/ingest.md, "Detections without depth"): the ray through a box's centre
// passes near the thing's centre, so the views of one thing have rays that
// meet there, and that point falls near the centre of each of its boxes.
#pragma once

#include <string>
#include <vector>

#include "ingest/capture/observations.hpp"

namespace smql::ingest {

// One view of a detection not yet in a placed track.
struct UnplacedView {
    Observation view;  // bounds: the detection's box at the working resolution
    std::string category;
    EvidenceCrop evidence;  // empty when a track's evidence came from another view
};

// First, each view joins the placed track of its category whose hull centre
// falls near the centre of its box, when that track has no view in its frame.
// Then the rest are grouped by their boxes' rays, greedily, the group with the
// most frames first: a candidate centre is where two views' rays (of one
// category, in different frames, at least kMinRayAngle degrees apart) come
// closest, and its group is the views, one per frame, whose box centre it falls
// near (within kCentreShare of the box's width and height). A group of at least
// `minViews` frames (and 2) is carved around its centre from its views'
// outlines or boxes (carveRegion: each must hold a voxel); views whose box the
// hull does not fill (hullFillsBox) leave the group, which is carved again
// without them, and the group becomes a new track in `placed`. Last, two
// carved tracks of one category that never share a frame, one's centre inside
// the other's hull bounds, become one. `cameras` has every frame's
// camera (MaskView). Returns how many views joined a track or became one.
inline constexpr double kMinRayAngle = 3;    // degrees
inline constexpr double kCentreShare = 0.3;  // of the box's width and height, from its centre
std::size_t placeByRays(std::vector<UnplacedView> unplaced, const std::vector<MaskView>& cameras,
                        std::vector<ObjectTrack>& placed, int minViews = 2);

}  // namespace smql::ingest
