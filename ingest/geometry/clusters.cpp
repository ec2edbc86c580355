#include "ingest/geometry/clusters.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <opencv2/imgproc.hpp>

#include "ingest/geometry/pcl_ops.hpp"
#include "ingest/geometry/robust.hpp"

namespace smql::ingest {

namespace {

constexpr double kDegree = std::numbers::pi / 180;

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
    return (detail::quantile(u, 0.98) - detail::quantile(u, 0.02)) *
           (detail::quantile(v, 0.98) - detail::quantile(v, 0.02));
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

model::Box uprightBox(const std::vector<model::Vec3>& points) {
    model::Box box;
    if (points.size() < 3) {
        for (const auto& p : points) {
            box.center.x += p.x / static_cast<double>(points.size());
            box.center.y += p.y / static_cast<double>(points.size());
            box.center.z += p.z / static_cast<double>(points.size());
        }
        return box;
    }
    std::vector<double> z;
    z.reserve(points.size());
    for (const auto& p : points) z.push_back(p.z);
    auto [z0, z1] = detail::robustRange(z);

    std::vector<cv::Point2d> xy;
    xy.reserve(points.size());
    for (const auto& p : points)
        if (p.z >= z0 && p.z <= z1) xy.emplace_back(p.x, p.y);

    // Coarse yaw of the bulk (1 degree steps over 90), then trim outliers in that frame.
    std::vector<cv::Point2d> sample;
    const std::size_t stride = std::max<std::size_t>(1, xy.size() / 2000);
    for (std::size_t i = 0; i < xy.size(); i += stride) sample.push_back(xy[i]);
    double coarse = 0, bestArea = std::numeric_limits<double>::max();
    for (int step = 0; step < 90; ++step) {
        double area = bulkArea(sample, step * kDegree);
        if (area < bestArea) bestArea = area, coarse = step * kDegree;
    }
    double c = std::cos(coarse), s = std::sin(coarse);
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
    box.center = {rect.center.x + origin.x, rect.center.y + origin.y, (z0 + z1) / 2};
    box.size = {width, height, z1 - z0};
    box.yaw = yaw;
    return box;
}

model::Box uprightBox(const PointCloud& cloud, const std::vector<std::size_t>& indices) {
    std::vector<model::Vec3> points;
    points.reserve(indices.size());
    for (auto i : indices) points.push_back(cloud.points[i]);
    return uprightBox(points);
}

}  // namespace smql::ingest
