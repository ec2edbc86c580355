#include "ingest/geometry/clusters.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <numeric>
#include <tuple>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "ingest/geometry/pcl_ops.hpp"
#include "ingest/geometry/robust.hpp"
#include "model/geometry.hpp"

namespace smql::ingest {

namespace {

using model::kDegree;

// Area of the 2-98% quantile rectangle of the points in a frame turned by `yaw`:
// an outlier-proof stand-in for the minimum-area rectangle, used to find the
// bulk before the exact rectangle is taken.
double bulkArea(const std::vector<cv::Point2d>& xy, double yaw) {
    double c = std::cos(yaw), s = std::sin(yaw);
    std::vector<double> u, v;
    u.reserve(xy.size());
    v.reserve(xy.size());
    for (const auto& p : xy) {
        u.push_back(c * p.x + s * p.y);
        v.push_back(-s * p.x + c * p.y);
    }
    return detail::quantileSpread(std::move(u), 0.02, 0.98) * detail::quantileSpread(std::move(v), 0.02, 0.98);
}

}  // namespace

std::vector<std::vector<std::size_t>> euclideanClusters(const PointCloud& cloud,
                                                        const std::vector<std::size_t>& indices, double tolerance,
                                                        std::size_t minPoints, std::size_t maxPoints) {
    return pcl_ops::euclideanClusters(cloud.points, indices, tolerance, minPoints, maxPoints);
}

std::vector<std::vector<std::size_t>> euclideanClusters(const PointCloud& cloud, double tolerance,
                                                        std::size_t minPoints, std::size_t maxPoints) {
    std::vector<std::size_t> all(cloud.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
    return euclideanClusters(cloud, all, tolerance, minPoints, maxPoints);
}

UnionFind::UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }

void uniteNear(const std::vector<model::Vec3>& points, double tolerance, UnionFind& chains) {
    const float limit = static_cast<float>(tolerance * tolerance);
    // A shade wider than the tolerance, so the single-precision test never reaches past the next cell.
    const double cell = tolerance * (1 + 1e-6);
    auto cellOf = [&](const model::Vec3& p) {
        return std::array<std::int64_t, 3>{static_cast<std::int64_t>(std::floor(static_cast<float>(p.x) / cell)),
                                           static_cast<std::int64_t>(std::floor(static_cast<float>(p.y) / cell)),
                                           static_cast<std::int64_t>(std::floor(static_cast<float>(p.z) / cell))};
    };
    // packCell keeps a cell and the cells above and below it one run of keys.
    std::vector<std::pair<std::uint64_t, std::uint32_t>> byCell(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        const auto c = cellOf(points[i]);
        byCell[i] = {packCell(c[0], c[1], c[2]), static_cast<std::uint32_t>(i)};
    }
    std::sort(byCell.begin(), byCell.end());
    for (std::size_t at = 0; at < byCell.size(); ++at) {
        const std::size_t i = byCell[at].second;
        const auto c = cellOf(points[i]);
        const float x = static_cast<float>(points[i].x), y = static_cast<float>(points[i].y),
                    z = static_cast<float>(points[i].z);
        for (std::int64_t dx = -1; dx <= 1; ++dx)
            for (std::int64_t dy = -1; dy <= 1; ++dy) {
                const std::uint64_t last = packCell(c[0] + dx, c[1] + dy, c[2] + 1);
                // Each pair once: from the earlier of the two in key order.
                auto from = std::lower_bound(byCell.begin() + static_cast<std::ptrdiff_t>(at) + 1, byCell.end(),
                                             std::pair{packCell(c[0] + dx, c[1] + dy, c[2] - 1), std::uint32_t{0}});
                for (auto other = from; other != byCell.end() && other->first <= last; ++other) {
                    const std::size_t j = other->second;
                    const float ex = x - static_cast<float>(points[j].x), ey = y - static_cast<float>(points[j].y),
                                ez = z - static_cast<float>(points[j].z);
                    float squared = ex * ex;
                    squared += ey * ey;
                    squared += ez * ez;
                    if (squared < limit) chains.unite(i, j);
                }
            }
    }
}

std::vector<std::vector<std::size_t>> nearChains(const std::vector<model::Vec3>& points, double tolerance) {
    UnionFind united(points.size());
    uniteNear(points, tolerance, united);
    std::vector<std::vector<std::size_t>> chains;
    std::vector<std::size_t> chainOf(points.size(), points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        std::size_t& chain = chainOf[united.find(i)];
        if (chain == points.size()) {
            chain = chains.size();
            chains.emplace_back();
        }
        chains[chain].push_back(i);
    }
    return chains;
}

namespace {

// The points an upright box is fitted to: the robust range of their heights, the xy of the points
// within it, and the yaw (1 degree steps over 90) whose quantile rectangle is the smallest.
struct Bulk {
    double z0 = 0, z1 = 0;
    std::vector<cv::Point2d> xy;
    double yaw = 0, area = std::numeric_limits<double>::max();
};

Bulk bulkOf(const std::vector<model::Vec3>& points) {
    Bulk bulk;
    std::vector<double> z;
    z.reserve(points.size());
    for (const auto& p : points) z.push_back(p.z);
    std::tie(bulk.z0, bulk.z1) = detail::robustRange(z);
    bulk.xy.reserve(points.size());
    for (const auto& p : points)
        if (p.z >= bulk.z0 && p.z <= bulk.z1) bulk.xy.emplace_back(p.x, p.y);
    std::vector<cv::Point2d> sample;
    const std::size_t stride = std::max<std::size_t>(1, bulk.xy.size() / 2000);
    for (std::size_t i = 0; i < bulk.xy.size(); i += stride) sample.push_back(bulk.xy[i]);
    for (int step = 0; step < 90; ++step) {
        double area = bulkArea(sample, step * kDegree);
        if (area < bulk.area) bulk.area = area, bulk.yaw = step * kDegree;
    }
    return bulk;
}

model::Box centroidBox(const std::vector<model::Vec3>& points) {
    model::Box box;
    for (const auto& p : points) {
        box.center.x += p.x / static_cast<double>(points.size());
        box.center.y += p.y / static_cast<double>(points.size());
        box.center.z += p.z / static_cast<double>(points.size());
    }
    return box;
}

}  // namespace

model::Box uprightBox(const std::vector<model::Vec3>& points) {
    if (points.size() < 3) return centroidBox(points);
    const Bulk bulk = bulkOf(points);
    const auto& xy = bulk.xy;
    model::Box box;
    double c = std::cos(bulk.yaw), s = std::sin(bulk.yaw);
    std::vector<double> u, v;
    for (const auto& p : xy) {
        u.push_back(c * p.x + s * p.y);
        v.push_back(-s * p.x + c * p.y);
    }
    auto [u0, u1] = detail::robustRange(u);
    auto [v0, v1] = detail::robustRange(v);
    std::vector<cv::Point2f> kept;
    kept.reserve(xy.size());
    // Relative to the first point so float precision does not suffer far from the origin.
    const cv::Point2d origin = xy.front();
    for (std::size_t i = 0; i < xy.size(); ++i)
        if (u[i] >= u0 && u[i] <= u1 && v[i] >= v0 && v[i] <= v1)
            kept.emplace_back(static_cast<float>(xy[i].x - origin.x), static_cast<float>(xy[i].y - origin.y));

    // Exact minimum-area rectangle of the kept points.
    cv::RotatedRect rect = cv::minAreaRect(kept);
    double width = rect.size.width, height = rect.size.height;
    double yaw = rect.angle * kDegree;  // the rectangle's width runs along this angle
    if (height > width) {
        std::swap(width, height);
        yaw += std::numbers::pi / 2;
    }
    while (yaw > std::numbers::pi / 2) yaw -= std::numbers::pi;
    while (yaw <= -std::numbers::pi / 2) yaw += std::numbers::pi;
    box.center = {rect.center.x + origin.x, rect.center.y + origin.y, (bulk.z0 + bulk.z1) / 2};
    box.size = {width, height, bulk.z1 - bulk.z0};
    box.yaw = yaw;
    return box;
}

model::Box wallAlignedBox(const std::vector<model::Vec3>& points, double slack) {
    if (points.size() < 3) return centroidBox(points);
    const Bulk bulk = bulkOf(points);
    if (bulkArea(bulk.xy, 0) > slack * bulk.area) return uprightBox(points);
    std::vector<double> x, y;
    for (const auto& p : bulk.xy) x.push_back(p.x), y.push_back(p.y);
    auto [x0, x1] = detail::robustRange(x);
    auto [y0, y1] = detail::robustRange(y);
    model::Box box;
    box.center = {(x0 + x1) / 2, (y0 + y1) / 2, (bulk.z0 + bulk.z1) / 2};
    const bool alongX = x1 - x0 >= y1 - y0;
    box.size = {alongX ? x1 - x0 : y1 - y0, alongX ? y1 - y0 : x1 - x0, bulk.z1 - bulk.z0};
    box.yaw = alongX ? 0 : std::numbers::pi / 2;
    return box;
}

model::Box uprightBox(const PointCloud& cloud, const std::vector<std::size_t>& indices) {
    std::vector<model::Vec3> points;
    points.reserve(indices.size());
    for (auto i : indices) points.push_back(cloud.points[i]);
    return uprightBox(points);
}

}  // namespace smql::ingest
