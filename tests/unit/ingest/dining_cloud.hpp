// The real RGB-D frames in ../shared/data/rgbd-dining as one cloud with their cameras, for the tests that hold
// geometry to a real room.
#pragma once

#include <catch2/catch.hpp>

#include <fstream>
#include <string>
#include <vector>

#include "ingest/capture/capture.hpp"
#include "ingest/geometry/point_cloud.hpp"

namespace smql::ingest::test {

// A binary 16-bit PGM (P5, maxval > 255, big-endian samples) as metres.
inline std::vector<float> readDepthPgm(const std::string& path, int& width, int& height, double unitsPerMetre) {
    std::ifstream in(path, std::ios::binary);
    REQUIRE(in);
    std::string magic;
    int maxval = 0;
    in >> magic >> width >> height >> maxval;
    REQUIRE(magic == "P5");
    REQUIRE(maxval > 255);
    in.get();  // the single whitespace before the samples
    std::vector<unsigned char> bytes(static_cast<std::size_t>(width) * height * 2);
    in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    REQUIRE(in.gcount() == static_cast<std::streamsize>(bytes.size()));
    std::vector<float> metres(static_cast<std::size_t>(width) * height);
    for (std::size_t i = 0; i < metres.size(); ++i)
        metres[i] = static_cast<float>(((bytes[2 * i] << 8) | bytes[2 * i + 1]) / unitsPerMetre);
    return metres;
}

// rgbd-dining: 5 frames, poses `tx ty tz qx qy qz qw` camera-to-world, depth in millimetres.
struct Dining {
    PointCloud cloud;
    std::vector<Pose> cameras;
};

inline Dining loadDining(int stride, double voxel) {
    const std::string root = std::string(SMQL_SHARED_DATA) + "/rgbd-dining";
    Dining dining;
    std::ifstream poses(root + "/pose.txt");
    REQUIRE(poses);
    Intrinsics k;
    k.width = 640, k.height = 480, k.fx = 518.0, k.fy = 519.0, k.cx = 325.5, k.cy = 253.5;
    PointCloud all;
    for (int n = 1; n <= 5; ++n) {
        double tx, ty, tz, qx, qy, qz, qw;
        REQUIRE(poses >> tx >> ty >> tz >> qx >> qy >> qz >> qw);
        Pose pose;
        pose.rotation = {1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw),     2 * (qx * qz + qy * qw),
                         2 * (qx * qy + qz * qw),     1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw),
                         2 * (qx * qz - qy * qw),     2 * (qy * qz + qx * qw),     1 - 2 * (qx * qx + qy * qy)};
        pose.translation = {tx, ty, tz};
        dining.cameras.push_back(pose);
        DepthView view;
        auto metres = readDepthPgm(root + "/depth/" + std::to_string(n) + ".pgm", view.width, view.height, 1000.0);
        view.metres = metres.data();
        view.intrinsics = k;
        append(all, backProject(view, pose, static_cast<std::uint32_t>(n - 1), stride));
    }
    dining.cloud = voxelDownsample(all, voxel);
    return dining;
}

}  // namespace smql::ingest::test
