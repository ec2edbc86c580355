// Wall planes of an aligned cloud (z up, floor at z = 0, metres).
#pragma once

#include <algorithm>
#include <cstddef>
#include <optional>
#include <vector>

#include "ingest/geometry/point_cloud.hpp"
#include "model/types.hpp"

namespace smql::ingest {

struct WallSegment {
    model::Vec3 normal;             // horizontal unit vector pointing into the room
    double offset = 0;              // normal . p + offset = 0
    double along0 = 0, along1 = 0;  // extent along direction()
    double z0 = 0, z1 = 0;          // extent in height
    double thickness = 0.02;        // spread of the inliers across the plane
    std::size_t inliers = 0;
    std::size_t frames = 0;  // views that saw it
    double confidence = 0;   // 0..1, from support (inliers and views)

    // The wall's own horizontal axis: the normal turned +90 degrees about +z.
    model::Vec3 direction() const { return {-normal.y, normal.x, 0}; }
    double signedDistance(const model::Vec3& p) const { return normal.x * p.x + normal.y * p.y + offset; }
    double length() const { return along1 - along0; }
    // How far from the plane, either side, a point is on the wall's surface: half the thickness, but
    // at most kSurfaceBand. A thick segment is parallel planes merged (walls of rooms in a row, set a
    // few centimetres apart), and what stands against it, a vanity or a cabinet, begins within
    // centimetres of it: its front and top farther out are the thing's (ScanNet's apartment: a wall
    // 0.34 m thick took a vanity's points, and its sink was stored as the basin alone).
    static constexpr double kSurfaceBand = 0.1;
    double surfaceBand() const { return std::min(thickness / 2, kSurfaceBand); }
    // A thin upright box (GeometryKind::Plane in the model): x along the wall, y its thickness, z its height.
    model::Box box() const;
};

// What stands against a wall: a box square to it (its axes within kSquareToWall degrees of the wall's), its centre in
// front of the wall's extent, the face of its side towards the wall within `within` metres of the wall's plane
// (either way: a box fitted to points may reach a little into a thick wall). Of several, the nearest; with
// `longSide`, only a wall its longer side runs along (a desk's, a sofa's). Null for none.
inline constexpr double kSquareToWall = 15.0;  // degrees
inline constexpr double kAgainstWall = 0.2;    // m: a side this close to a wall's plane stands against it
const WallSegment* wallAgainst(const model::Box& box, const std::vector<WallSegment>& walls,
                               double within = kAgainstWall, bool longSide = false);

struct WallOptions {
    double minPointHeight = 0.1;    // only points above this (metres over the floor) take part
    double distance = 0.04;         // RANSAC inlier distance
    double verticalTolerance = 10;  // degrees a plane's normal may tilt from horizontal
    int maxPlanes = 15;             // RANSAC rounds (accepted or not)
    std::size_t minInliers = 200;   // points a wall needs (tuned for 5 cm voxels)
    std::size_t minFrames = 2;      // views that saw it (capped at the number of views in the cloud)
    double frameShare = 0.02;       // a view "saw" a wall when it holds this share of its inliers (and >= 3)
    double minHeight = 1.0;         // height extent a wall needs
    double minLength = 0.5;         // length a wall needs
    double maxGap = 1.0;            // inliers farther apart than this along the plane form separate segments
    double behindDistance = 0.3;    // a point this far behind a wall was seen through it (depth noise is less)
    double maxBehindShare = 0.2;    // walls bound the room: of the points over a segment, at most this share behind it
    double layerDistance = 1.0;     // an overlapping segment up to this far in front of a wall is furniture ...
    double layerAngle = 20;         // ... when it turns from the wall by at most this many degrees
    double coverageCell = 0.25;     // the extent is cut into cells of this side ...
    double minCoverage = 0.4;       // ... and a wall's inliers fill at least this share of them
    double maxBehindOfSurface = 0.3;  // ... and at most this many per inlier of the segment itself
    double mergeAngle = 10;           // degrees: near-duplicate planes ...
    double mergeOffset = 0.1;         // ... with offsets this close (and touching extents) are merged
};

// Vertical planes by iterated RANSAC (docs/ingest.md), strongest first.
// `cameras` are the camera positions in the aligned frame (may be empty):
// walls face the cameras, which stand inside the room.
std::vector<WallSegment> findWalls(const PointCloud& aligned, const std::vector<model::Vec3>& cameras,
                                   const WallOptions& options = {});

// Indices of the points that are neither floor (z < floorMargin), ceiling (z
// > ceilingHeight - ceilingMargin, when known) nor within wallMargin (or half
// the wall's thickness, if more) of a wall segment: what object clustering
// starts from.
struct StructureOptions {
    double floorMargin = 0.05;
    double wallMargin = 0.1;
    double ceilingMargin = 0.1;
    std::optional<double> ceilingHeight;
};
std::vector<std::size_t> nonStructuralPoints(const PointCloud& aligned, const std::vector<WallSegment>& walls,
                                             const StructureOptions& options = {});

}  // namespace smql::ingest
