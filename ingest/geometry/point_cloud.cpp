#include "ingest/geometry/point_cloud.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <unordered_map>

#include <opencv2/imgproc.hpp>

#include "ingest/capture/frame_loader.hpp"

namespace smql::ingest {

void PointCloud::reserve(std::size_t n) {
    points.reserve(n);
    colors.reserve(n);
    frames.reserve(n);
}

void PointCloud::push(const model::Vec3& point, std::array<std::uint8_t, 3> color, std::uint32_t frame) {
    points.push_back(point);
    colors.push_back(color);
    frames.push_back(frame);
}

PointCloud backProject(const DepthView& depth, const Pose& pose, std::uint32_t frame, int stride, double maxDepth) {
    PointCloud cloud;
    if (!depth.metres || depth.width <= 0 || depth.height <= 0) return cloud;
    assert(stride >= 1);
    const Intrinsics& k = depth.intrinsics;
    assert(k.fx > 0 && k.fy > 0);
    const auto& r = pose.rotation;
    const auto& t = pose.translation;
    cloud.reserve(static_cast<std::size_t>(depth.height / stride + 1) *
                  static_cast<std::size_t>(depth.width / stride + 1));
    for (int v = 0; v < depth.height; v += stride) {
        for (int u = 0; u < depth.width; u += stride) {
            const std::size_t pixel = static_cast<std::size_t>(v) * depth.width + u;
            double z = depth.metres[pixel];
            if (!(z > 0) || z > maxDepth) continue;  // also drops NaN
            double x = (u - k.cx) * z / k.fx;
            double y = (v - k.cy) * z / k.fy;
            model::Vec3 world{r[0] * x + r[1] * y + r[2] * z + t.x, r[3] * x + r[4] * y + r[5] * z + t.y,
                              r[6] * x + r[7] * y + r[8] * z + t.z};
            std::array<std::uint8_t, 3> rgb{128, 128, 128};
            if (depth.rgb) rgb = {depth.rgb[3 * pixel], depth.rgb[3 * pixel + 1], depth.rgb[3 * pixel + 2]};
            cloud.push(world, rgb, frame);
        }
    }
    return cloud;
}

PointCloud backProject(const FrameImages& images, const Pose& pose, std::uint32_t frame, int stride, double maxDepth) {
    if (images.depth.empty()) return {};
    assert(images.depth.type() == CV_32F);
    cv::Mat depth = images.depth.isContinuous() ? images.depth : images.depth.clone();
    cv::Mat rgb;
    if (!images.color.empty() && images.color.size() == images.depth.size()) {
        assert(images.color.type() == CV_8UC3);
        cv::cvtColor(images.color, rgb, cv::COLOR_BGR2RGB);  // a new, continuous matrix
    }
    DepthView view;
    view.width = depth.cols;
    view.height = depth.rows;
    view.metres = depth.ptr<float>(0);
    view.rgb = rgb.empty() ? nullptr : rgb.ptr<std::uint8_t>(0);
    view.intrinsics = images.intrinsics;
    return backProject(view, pose, frame, stride, maxDepth);
}

PointCloud voxelDownsample(const PointCloud& cloud, double voxel) {
    assert(voxel > 0);
    struct Cell {
        double x = 0, y = 0, z = 0;
        double r = 0, g = 0, b = 0;
        std::size_t count = 0;
        std::size_t nearest = 0;
        double nearestDistance = std::numeric_limits<double>::max();
    };
    auto key = [voxel](const model::Vec3& p) {
        auto cell = [voxel](double c) { return static_cast<std::int64_t>(std::floor(c / voxel)); };
        return packCell(cell(p.x), cell(p.y), cell(p.z));
    };
    std::unordered_map<std::uint64_t, std::size_t> slot;
    std::vector<Cell> cells;
    std::vector<std::size_t> cellOf(cloud.size());
    slot.reserve(cloud.size() / 4 + 16);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        const auto& p = cloud.points[i];
        auto [it, inserted] = slot.try_emplace(key(p), cells.size());
        if (inserted) cells.emplace_back();
        Cell& c = cells[it->second];
        cellOf[i] = it->second;
        c.x += p.x, c.y += p.y, c.z += p.z;
        c.r += cloud.colors[i][0], c.g += cloud.colors[i][1], c.b += cloud.colors[i][2];
        ++c.count;
    }
    for (auto& c : cells) {
        c.x /= c.count, c.y /= c.count, c.z /= c.count;
        c.r /= c.count, c.g /= c.count, c.b /= c.count;
    }
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        Cell& c = cells[cellOf[i]];
        const auto& p = cloud.points[i];
        double d = (p.x - c.x) * (p.x - c.x) + (p.y - c.y) * (p.y - c.y) + (p.z - c.z) * (p.z - c.z);
        if (d < c.nearestDistance) c.nearestDistance = d, c.nearest = i;
    }
    PointCloud out;
    out.reserve(cells.size());
    auto channel = [](double v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 255.0))); };
    for (const auto& c : cells)
        out.push({c.x, c.y, c.z}, {channel(c.r), channel(c.g), channel(c.b)}, cloud.frames[c.nearest]);
    return out;
}

PointCloud subset(const PointCloud& cloud, const std::vector<std::size_t>& indices) {
    PointCloud out;
    out.reserve(indices.size());
    for (auto i : indices) out.push(cloud.points[i], cloud.colors[i], cloud.frames[i]);
    return out;
}

void append(PointCloud& into, const PointCloud& from) {
    into.points.insert(into.points.end(), from.points.begin(), from.points.end());
    into.colors.insert(into.colors.end(), from.colors.begin(), from.colors.end());
    into.frames.insert(into.frames.end(), from.frames.begin(), from.frames.end());
}

}  // namespace smql::ingest
