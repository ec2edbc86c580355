// Coloured 3D points with the frame each came from, and the two ways ingest
// makes them from RGB-D frames: back-projection and voxel down-sampling.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "ingest/capture/capture.hpp"
#include "model/types.hpp"

namespace smql::ingest {

// A grid cell's three integer coordinates as one key, 21 bits each, offset to be positive (+-2^20 cells:
// +-10 km at 1 cm cells), z lowest: a cell and the cells above and below it are consecutive keys.
inline std::uint64_t packCell(std::int64_t x, std::int64_t y, std::int64_t z) {
    constexpr std::int64_t kOffset = std::int64_t{1} << 20, kMask = (std::int64_t{1} << 21) - 1;
    return static_cast<std::uint64_t>((((x + kOffset) & kMask) << 42) | (((y + kOffset) & kMask) << 21) |
                                      ((z + kOffset) & kMask));
}
inline std::array<std::int64_t, 3> unpackCell(std::uint64_t key) {
    constexpr std::int64_t kOffset = std::int64_t{1} << 20;
    constexpr std::uint64_t kMask = (std::uint64_t{1} << 21) - 1;
    return {static_cast<std::int64_t>(key >> 42 & kMask) - kOffset,
            static_cast<std::int64_t>(key >> 21 & kMask) - kOffset, static_cast<std::int64_t>(key & kMask) - kOffset};
}

struct FrameImages;

struct PointCloud {
    std::vector<model::Vec3> points;
    std::vector<std::array<std::uint8_t, 3>> colors;  // RGB, one per point
    std::vector<std::uint32_t> frames;                // index of the frame each point was seen in

    std::size_t size() const { return points.size(); }
    bool empty() const { return points.empty(); }
    void reserve(std::size_t n);
    void push(const model::Vec3& point, std::array<std::uint8_t, 3> color, std::uint32_t frame);
};

// A frame's depth (and optionally colour) as plain row-major buffers, for
// callers outside ingest/ that have no OpenCV (tests, other readers).
struct DepthView {
    int width = 0, height = 0;
    const float* metres = nullptr;      // width * height, 0 or NaN = no reading
    const std::uint8_t* rgb = nullptr;  // width * height * 3, RGB; may be null (points come out grey)
    Intrinsics intrinsics;
};

// Readings farther than this (metres) are noise for room-scale sensors.
inline constexpr double kMaxDepthReading = 6.0;

// Depth pixels of one frame as world points, through the camera-to-world
// `pose`: every `stride`-th pixel in both directions; pixels without a reading
// (0, NaN) and readings beyond `maxDepth` metres are dropped. Every point
// carries `frame` and its pixel's colour. Frames without depth give nothing.
PointCloud backProject(const FrameImages& images, const Pose& pose, std::uint32_t frame, int stride = 2,
                       double maxDepth = kMaxDepthReading);
PointCloud backProject(const DepthView& depth, const Pose& pose, std::uint32_t frame, int stride = 2,
                       double maxDepth = kMaxDepthReading);

// One point per occupied voxel of edge `voxel`: the mean position and mean
// colour of the voxel's points, and the frame of the point nearest that mean
// (so a surface seen from several views keeps voxels from all of them).
PointCloud voxelDownsample(const PointCloud& cloud, double voxel);

// The points at `indices`, in that order.
PointCloud subset(const PointCloud& cloud, const std::vector<std::size_t>& indices);
void append(PointCloud& into, const PointCloud& from);

}  // namespace smql::ingest
