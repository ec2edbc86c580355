// The only door to PCL. Everything PCL does for ingest (RANSAC plane
// segmentation, kd-tree searches, Euclidean clustering) goes through these
// functions, which take and return our own types: PCL headers are heavy to
// compile and are included by exactly one translation unit (pcl_ops.cpp).
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "model/types.hpp"

namespace smql::ingest::pcl_ops {

// How a RANSAC plane must sit relative to `axis` (a unit vector).
enum class PlaneConstraint {
    NormalAlongAxis,   // horizontal planes when axis is up (PCL SACMODEL_PERPENDICULAR_PLANE)
    NormalAcrossAxis,  // vertical planes when axis is up (PCL SACMODEL_PARALLEL_PLANE)
};

struct PlaneSearch {
    model::Vec3 axis{0, 0, 1};
    PlaneConstraint constraint = PlaneConstraint::NormalAlongAxis;
    double epsAngle = 0.5;   // radians the plane may deviate from the constraint
    double distance = 0.03;  // inlier distance, in the cloud's units
    int maxIterations = 1000;
    bool optimise = true;  // least-squares refit on the inliers
};

struct PlaneFound {
    model::Vec3 normal;  // unit; normal . p + offset = 0
    double offset = 0;
    std::vector<std::size_t> inliers;  // indices into the points given
};

// RANSAC (fixed seed, so runs repeat) over points[indices]; nullopt when there
// are fewer than 3 points or no plane satisfies the constraint.
std::optional<PlaneFound> segmentPlane(const std::vector<model::Vec3>& points, const std::vector<std::size_t>& indices,
                                       const PlaneSearch& search);

// PCL EuclideanClusterExtraction (kd-tree) over points[indices]: clusters of
// points chained by gaps <= tolerance, sized within [minPoints, maxPoints],
// largest first, as indices into `points`.
std::vector<std::vector<std::size_t>> euclideanClusters(const std::vector<model::Vec3>& points,
                                                        const std::vector<std::size_t>& indices, double tolerance,
                                                        std::size_t minPoints, std::size_t maxPoints);

// The points with at least `minNeighbours` others within `radius` (kd-tree radius search), as
// indices into `points` in their order: a surface's points, without the specks floating apart from it.
std::vector<std::size_t> withNeighbours(const std::vector<model::Vec3>& points, double radius, int minNeighbours);

struct SurfaceNormal {
    model::Vec3 normal;    // unit, sign arbitrary; zero when undefined
    double curvature = 1;  // smallest eigenvalue / sum of eigenvalues (0 = perfectly flat)
};

// Local plane fit (PCA of the neighbours within `radius`, kd-tree search) at
// every point; points with fewer than `minNeighbours` neighbours get a zero normal.
std::vector<SurfaceNormal> estimateNormals(const std::vector<model::Vec3>& points, double radius, int minNeighbours);

}  // namespace smql::ingest::pcl_ops
