// Doors and windows as openings in wall planes, where no label or detection
// gives them (docs/ingest.md, "Openings"): depth seen through a wall, the wall
// itself missing there.
#pragma once

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "ingest/geometry/point_cloud.hpp"
#include "ingest/geometry/walls.hpp"
#include "model/types.hpp"

namespace smql::ingest {

struct WallOpening {
    std::size_t wall = 0;           // index into the walls searched
    std::string category;           // "door" (from the floor up) or "window"
    double along0 = 0, along1 = 0;  // extent along the wall's direction()
    double z0 = 0, z1 = 0;          // extent in height
    std::size_t through = 0;        // points seen through it

    // A thin upright box in the wall's plane (GeometryKind::Plane in the model).
    model::Box box(const WallSegment& wall) const;
};

struct OpeningOptions {
    double cell = 0.1;                  // the wall is cut into square cells of this side (metres)
    double behindDistance = 0.3;        // a point this far behind the wall was seen through it
    int minThrough = 2;                 // a cell is open when this many rays pass through it ...
    double surfaceShare = 0.5;          // ... and the wall's own points there are at most this share of them
    double minFill = 0.5;               // an opening's open cells fill this share of its rectangle
    double doorSill = 0.2;              // an opening starting this near the floor is a door; so is one above wall
    double hiddenShare = 0.2;           // ... of which at most this share of cells shows (furniture stands in front)
    double doorHeight = 1.8;            // a door's top is at least this high (m) ...
    double doorWidth[2] = {0.6, 2.6};   // ... and it is this wide
    double windowSill[2] = {0.3, 1.5};  // a window's lower edge
    double windowSize = 0.4;            // its least width and height
};

// Openings in `walls` of an aligned cloud whose points carry the frame they were
// seen from (depth, back-projected), `cameras` those frames' camera centres in
// the aligned frame. A point behind a wall was seen through it where the ray
// from its camera crosses the wall's plane; the cells of the wall crossed by
// such rays, with few of the wall's own points, group into rectangles, and a
// rectangle of a door's or a window's shape and place becomes one.
std::vector<WallOpening> findOpenings(const PointCloud& aligned,
                                      const std::unordered_map<std::uint32_t, model::Vec3>& cameras,
                                      const std::vector<WallSegment>& walls, const OpeningOptions& options = {});

}  // namespace smql::ingest
