// Metric alignment: turns a capture's world frame into smql's frame, where
// the floor is z = 0, +z is up, the room's dominant walls run along x and y,
// and units are metres (docs/ingest.md, "Geometry and metric alignment").
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "ingest/capture/capture.hpp"
#include "ingest/geometry/point_cloud.hpp"
#include "ingest/geometry/scale_priors.hpp"
#include "ingest/geometry/vertical_lines.hpp"
#include "model/types.hpp"

namespace smql::ingest {

// normal . p + offset = 0, unit normal.
struct Plane {
    model::Vec3 normal{0, 0, 1};
    double offset = 0;
    std::size_t inliers = 0;
    double signedDistance(const model::Vec3& p) const;
};

// Every length here is in metres; for scale-free captures alignCapture first
// converts them to the cloud's units with a rough unit estimate (docs/ingest.md).
struct AlignOptions {
    bool metric = true;                  // Capture::metric: poses and points already in metres
    std::optional<double> scale;         // metres per cloud unit, overriding the estimate (and 1 for metric)
    double cameraHeight = 1.5;           // assumed median camera height above the floor (scale-free captures)
    bool cameraHeightGiven = false;      // ... or measured (--camera-height): then it leads the scale
    double ceilingHeight = 2.6;          // assumed floor-to-ceiling height (scale-free, ceiling found)
    std::optional<model::Vec3> upPrior;  // used only when there are no cameras (default +z)
    // The cloud's leading points that weigh a surface (floor_evidence.hpp): the capture's own (depth
    // readings, COLMAP's features); the dense points after them find planes only, since a glossy
    // floor's reflection matches between photos as points below it.
    std::size_t evidencePoints = std::numeric_limits<std::size_t>::max();
    // The named things were fused on depth (photos' things lifted on the dense points, as stored): their
    // tops are where their surfaces were seen, so one short of its kind was seen in part, and where no two
    // agree they are set aside (scaleFromHeights: seenWhole). Hulls carved from sparse points reach past
    // their things as often as short of them: all count, and they lead only where two agree, as lifted
    // things do (TUM's office photos: their hulls' heights 1.15x the true scale, the same things lifted
    // 0.97-1.01x, the cameras' height 0.94x).
    bool thingsOnDepth = false;

    double planeDistance = 0.03;       // RANSAC inlier distance for floor and ceiling
    double horizontalTolerance = 30;   // degrees a floor candidate may tilt from the up prior ...
    double steepTolerance = 65;        // ... or this many, when the cameras look down at it from above ...
    double lookDownPitch = 15;         // ... pitched at least this many degrees towards it (the median)
    int maxHorizontalPlanes = 6;       // horizontal planes extracted before choosing the floor
    double minPlaneShare = 0.02;       // a horizontal plane needs this share of all points ...
    std::size_t minPlanePoints = 100;  // ... and at least this many
    double sameLevel = 0.1;            // planes whose inliers' median heights differ less are one surface ...
    double sameLevelAngle = 5;         // ... when their normals are within this many degrees
    double largePlaneShare = 0.25;     // "large": this share of the biggest candidate below the cameras
    double cameraClearance = 0.2;      // the floor lies this far below every camera, the ceiling above
    double ceilingParallel = 5;        // degrees between the ceiling's and the floor's normals

    double normalRadius = 0.1;             // neighbourhood of the surface normals used for the heading
    double verticalSurfaceTolerance = 15;  // degrees a normal may tilt from horizontal and still vote
    double maxCurvature = 0.05;            // flatness a neighbourhood needs to vote
    std::size_t minHeadingVotes = 50;      // fewer voting normals: heading 0
    LineOptions lines;                     // finding up among the photos' vertical edges
    // A floor (or table top) of photos without depth that holds less than this share of the points is
    // seen little, at the photos' edges, and leans: their vertical edges level the room instead.
    double levellingShare = 0.2;
};

struct Alignment {
    model::Transform transform = model::kIdentity;  // capture -> aligned: p' = scale * R * p + t
    double scale = 1;                               // metres per capture unit
    model::Vec3 up{0, 0, 1};                        // floor normal in the capture frame
    double floorHeight = 0;                         // floor's height along `up`, capture frame and units
    double heading = 0;                             // radians turned about +z after levelling
    bool floorFound = false;
    // Why no floor was found (a table top, and what stands on it; or no horizontal surface below the
    // cameras), and where the floor was placed instead. Both empty when the floor was found.
    std::string floorNotSeen;
    std::string floorPlaced;
    // When the floor was placed under a table top: that top's height above it (aligned frame, metres). The
    // table whose top it is stands on that floor by the placement's own reading (object_fusion.hpp:
    // reachDownToFloor).
    std::optional<double> tableTopHeight;
    // Photos without depth: why the plane taken for the floor cannot be told from a table top (nothing
    // that stands on floors rises from it, and no ceiling or thing's height checks the scale the
    // cameras' height gives), or why it is not level (found on a second look and still leaning from the
    // photos' vertical edges). Empty when something confirms it, or when the scale is known.
    std::string floorUnconfirmed;
    std::size_t floorInliers = 0;
    // Degrees between the photos' vertical edges and the normal of the floor (or table top) that levels the
    // room, when measured; the plausibility checks call a reconstruction bent when they stand far apart.
    std::optional<double> edgesFromFloor;
    std::optional<double> ceilingHeight;  // aligned frame (metres above the floor), when found
    double scaleSpread = 0;               // how far the scale priors disagree ((largest - smallest) / scale)
    double scaleSplit = 0;                // the factor between two priors that leave no majority (ScaleChoice)
    std::size_t scalePriors = 0;          // the priors the scale was estimated from (0: given, or metric)
    // The things whose heights were noted and not counted, no two of them agreeing (ScaleEstimate::heldTogether);
    // empty when none were set aside.
    std::string scaleThingsApart;
    // Where no heights prior was measured, the things of a typical height it left out and those it took, too few
    // (heightsLeftOut); empty lists otherwise.
    HeightsLeftOut scaleThingsLeftOut;
    std::vector<std::string> notes;  // how each choice was made, for SHOW SCENES and logs

    model::Vec3 apply(const model::Vec3& p) const;
    model::Vec3 unapply(const model::Vec3& q) const;  // the inverse: aligned -> capture
    std::array<double, 9> rotation() const;           // R, row-major, without the scale
};

// Floor, heading and scale of a capture's world-frame cloud; `cameras` are
// the capture's camera-to-world poses (may be empty); `things`, named objects
// the capture shows, give the typical-heights prior of the scale
// (scale_priors.hpp); `lines`, the straight edges of photos without depth,
// are measured against a scale-free capture's floor, level the room where
// the floor is seen little, and give up where no level surface is seen at
// all (vertical_lines.hpp).
Alignment alignCapture(const PointCloud& world, const std::vector<Pose>& cameras, const AlignOptions& options = {},
                       const std::vector<NamedThing>& things = {}, const LinePlanes& lines = {});

PointCloud transformed(const PointCloud& cloud, const Alignment& alignment);
Pose transformed(const Pose& pose, const Alignment& alignment);

}  // namespace smql::ingest
