// The thing one view shows: among the points a detection owns in its frame
// (its mask, else its box), those on the thing itself. Once the room is
// aligned, the floor, the ceiling and the walls are known planes: their points,
// and whatever was seen beyond a wall, are taken out; what remains falls apart
// into clusters, of which the largest is the thing (docs/ingest.md, "Objects
// from detections").
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "ingest/geometry/alignment.hpp"
#include "ingest/geometry/point_cloud.hpp"
#include "ingest/geometry/walls.hpp"

namespace smql::ingest {

// What the aligned frame knows of the room's own surfaces (z up, floor at z = 0, metres).
struct RoomSurfaces {
    bool floorFound = true;
    std::optional<double> ceilingHeight;
    const std::vector<WallSegment>* walls = nullptr;
    // A floor not found but placed a table's height under a table top: that top's height (Alignment::tableTopHeight).
    std::optional<double> tableTopHeight;
};

// What an aligned capture knows of its room's surfaces, with its walls.
RoomSurfaces roomSurfaces(const Alignment& alignment, const std::vector<WallSegment>* walls);

struct ViewSegmentOptions {
    double floorMargin = 0.03;    // points this close above the floor, or below it, are floor
    double ceilingMargin = 0.05;  // ... this close below the ceiling, or above it, ceiling
    double wallMargin = 0.05;     // ... in front of a wall's plane, or behind it, within its extent, wall
    double wallReach = 0.2;       // a wall's extent, widened by this along it and in height
    double tolerance = 0.05;      // points chained by gaps of at most this are one cluster ...
    double pitchGaps = 8;         // ... and neighbours on the region's grid by gaps of this many grid steps (a
                                  // bed's top seen at a grazing angle lies in rows far apart)
    std::size_t minPoints = 12;   // the thing needs this many points (after thinning)
    double surfaceBin = 0.02;     // a thing that stands on a table: its region's heights in bins of this ...
    double surfaceShare = 0.15;   // ... and the fullest bin, with this share of the points, is the table's top
};

// A view's region: its points in the aligned frame with their colours, each with its place on the
// image grid it was sampled on, and that grid's step at the thing's depth.
struct ViewRegion {
    PointCloud points;
    std::vector<std::array<int, 2>> grid;  // (column, row), one per point
    double pitch = 0;                      // m
};

// The points of `region` that lie on the thing: empty when too few are left. Points chain into one
// cluster when they lie within `tolerance` of each other, or are neighbours on the grid within
// `pitchGaps` steps. A thing that stands on tables and desks (`onSurface`: a mug, a laptop, a book)
// shares its region with the top it stands on, which is taken out with what lies below it.
PointCloud thingInView(const ViewRegion& region, const RoomSurfaces& room, bool onSurface,
                       const ViewSegmentOptions& options = {});

// Whether a point is on the room's floor, ceiling or a wall, or beyond them.
bool onRoomSurface(const model::Vec3& p, const RoomSurfaces& room, const ViewSegmentOptions& options = {});

}  // namespace smql::ingest
