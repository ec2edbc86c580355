// Class-agnostic objects from an aligned cloud: Euclidean clusters and the
// upright boxes around them.
#pragma once

#include <cstddef>
#include <vector>

#include "ingest/geometry/point_cloud.hpp"
#include "model/types.hpp"

namespace smql::ingest {

// PCL EuclideanClusterExtraction (kd-tree): points chained by gaps of at most
// `tolerance` metres form a cluster; clusters outside [minPoints, maxPoints]
// are dropped. Index lists into `cloud` (sorted), largest cluster first.
// Remove floor, ceiling and walls first (nonStructuralPoints in walls.hpp)
// and pass the rest as `indices`; the overload without indices clusters all points.
std::vector<std::vector<std::size_t>> euclideanClusters(const PointCloud& cloud,
                                                        const std::vector<std::size_t>& indices, double tolerance,
                                                        std::size_t minPoints, std::size_t maxPoints);
std::vector<std::vector<std::size_t>> euclideanClusters(const PointCloud& cloud, double tolerance,
                                                        std::size_t minPoints, std::size_t maxPoints);

// Points joined into chains (union-find with path halving): a view's points that lie near one another, or
// near on the view's grid, are one thing (view_segment.hpp).
struct UnionFind {
    std::vector<std::size_t> parent;
    explicit UnionFind(std::size_t n);
    std::size_t find(std::size_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    }
    void unite(std::size_t a, std::size_t b) { parent[find(a)] = find(b); }
};

// Unites every two points nearer than `tolerance`, as PCL's Euclidean clustering chains them (its k-d tree's
// test: the squared distance in single precision, summed x, y, z, below the squared tolerance in single
// precision). Found through a grid of cells a tolerance wide, where a point's neighbours lie in the 27 cells
// around its own: for the few thousand points of a view about five times faster than building and searching
// the tree.
void uniteNear(const std::vector<model::Vec3>& points, double tolerance, UnionFind& chains);
// The chains uniteNear makes: PCL's clusters without size bounds, each in index order, ordered by their first
// point.
std::vector<std::vector<std::size_t>> nearChains(const std::vector<model::Vec3>& points, double tolerance);

// An upright box around points (docs/ingest.md): height from the robust range
// of z, yaw and footprint from the minimum-area rectangle of the xy points
// after outliers are trimmed. The box's x axis runs along the longer side of
// the footprint; yaw is in (-pi/2, pi/2]. Fewer than 3 points give a box of
// size 0 at their mean.
model::Box uprightBox(const std::vector<model::Vec3>& points);
model::Box uprightBox(const PointCloud& cloud, const std::vector<std::size_t>& indices);

// The upright box along the walls (the aligned frame's axes, which the walls were turned to) when
// its quantile footprint is at most `slack` times the smallest one's, else uprightBox: furniture
// stands square to the walls, and a few points of a neighbour or of noise turn the minimum-area
// rectangle of a fridge between cabinets 22 degrees off them.
model::Box wallAlignedBox(const std::vector<model::Vec3>& points, double slack);

}  // namespace smql::ingest
