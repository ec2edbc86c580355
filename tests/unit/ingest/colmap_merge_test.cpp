// Models of one COLMAP mapper run that share images, merged by Debian's `colmap` (model_merger, then
// bundle_adjuster) into the largest: mergeSharingModels (ingest/geometry/colmap_runner.hpp).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "ingest/capture/capture_detail.hpp"
#include "ingest/geometry/colmap_runner.hpp"
#include "scratch_dir.hpp"

using namespace smql::ingest;
using smql::ingest::test::ScratchDir;
namespace fs = std::filesystem;

namespace {

constexpr double kFocal = 500, kWidth = 640, kHeight = 480;

// A walk of 12 cameras around a cloud of 300 points, every point seen by every camera.
struct Walk {
    std::vector<Eigen::Vector3d> points;
    std::vector<Eigen::Matrix3d> rotations;  // world to camera
    std::vector<Eigen::Vector3d> centres;

    Walk() {
        std::srand(20261130);
        auto uniform = [] { return 2.0 * std::rand() / RAND_MAX - 1; };
        for (int i = 0; i < 300; ++i) points.emplace_back(uniform(), uniform(), 1.0 + 0.5 * uniform());
        for (int c = 0; c < 12; ++c) {
            const double angle = 0.15 * c;
            centres.emplace_back(4 * std::cos(angle), 4 * std::sin(angle), 1.5);
            rotations.push_back(facingCloud(centres.back()));
        }
    }

    // A camera at `centre` looking at the cloud's middle, upright.
    static Eigen::Matrix3d facingCloud(const Eigen::Vector3d& centre) {
        const Eigen::Vector3d ahead = (Eigen::Vector3d(0, 0, 1) - centre).normalized();
        const Eigen::Vector3d right = ahead.cross(Eigen::Vector3d::UnitZ()).normalized();
        Eigen::Matrix3d r;
        r.row(0) = right;
        r.row(1) = ahead.cross(right);
        r.row(2) = ahead;
        return r;
    }
};

// Writes the walk's images `images` as a COLMAP text model whose frame is the world's under the similarity
// x -> scale * turn * x + shift. Every image lists the projections of all points in one order (its keypoints in
// the database); those of the model's points refer to them.
void writeModel(const fs::path& folder, const Walk& walk, const std::vector<int>& images, double scale,
                const Eigen::Matrix3d& turn, const Eigen::Vector3d& shift) {
    fs::create_directories(folder);
    std::ofstream(folder / "cameras.txt")
        << fmt::format("1 PINHOLE {} {} {} {} {} {}\n", kWidth, kHeight, kFocal, kFocal, kWidth / 2, kHeight / 2);
    std::ofstream out(folder / "images.txt");
    for (int image : images) {
        const Eigen::Matrix3d r = walk.rotations[image];
        const Eigen::Vector3d t = -r * walk.centres[image];
        // Seen in the model's frame: the same projection, the depths times `scale`.
        const Eigen::Matrix3d rotation = r * turn.transpose();
        const Eigen::Vector3d translation = scale * t - rotation * shift;
        const Eigen::Quaterniond q(rotation);
        out << fmt::format("{} {} {} {} {} {} {} {} 1 frame{:02}.png\n", image + 1, q.w(), q.x(), q.y(), q.z(),
                           translation.x(), translation.y(), translation.z(), image);
        for (std::size_t p = 0; p < walk.points.size(); ++p) {
            const Eigen::Vector3d seen = r * walk.points[p] + t;
            out << fmt::format("{} {} {} ", kFocal * seen.x() / seen.z() + kWidth / 2,
                               kFocal * seen.y() / seen.z() + kHeight / 2, p + 1);
        }
        out << "\n";
    }
    std::ofstream points(folder / "points3D.txt");
    for (std::size_t p = 0; p < walk.points.size(); ++p) {
        const Eigen::Vector3d x = scale * turn * walk.points[p] + shift;
        points << fmt::format("{} {} {} {} 128 128 128 0", p + 1, x.x(), x.y(), x.z());
        for (int image : images) points << fmt::format(" {} {}", image + 1, p);
        points << "\n";
    }
}

bool runColmapStep(const fs::path& log, const std::string& step, const std::string& arguments) {
    const std::string line =
        fmt::format("QT_QPA_PLATFORM=offscreen colmap {} {} >> '{}' 2>&1", step, arguments, log.string());
    return std::system(line.c_str()) == 0;
}

}  // namespace

TEST_CASE("COLMAP models that share three images are merged into the largest, in its frame") {
    ScratchDir dir;
    const Walk walk;
    const Eigen::Matrix3d none = Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d turned = Eigen::AngleAxisd(0.5, Eigen::Vector3d(0.2, 0.3, 1).normalized()).matrix();
    // The largest: images 0-6 in the world's frame. The second shares 4, 5 and 6 and adds 7-11, in a frame of its
    // own (scaled, turned, moved, as two models of one mapper run are). The third shares two images only.
    writeModel(dir.path / "0", walk, {0, 1, 2, 3, 4, 5, 6}, 1, none, Eigen::Vector3d::Zero());
    writeModel(dir.path / "1", walk, {4, 5, 6, 7, 8, 9, 10, 11}, 0.4, turned, Eigen::Vector3d(3, -1, 2));
    writeModel(dir.path / "2", walk, {0, 1}, 2, none, Eigen::Vector3d(1, 1, 1));
    std::vector<ColmapModel> models;
    for (const char* folder : {"0", "1", "2"})
        models.push_back({dir.path / folder, capture_detail::colmapImageNames(dir.path / folder)});
    REQUIRE(models[0].images.size() == 7);
    std::swap(models[0], models[1]);  // largest first: the 8 images
    std::vector<std::string> steps;
    const auto merged = mergeSharingModels(models, dir.path / "merged", [&](const auto& step, const auto& arguments) {
        steps.push_back(step);
        return runColmapStep(dir.path / "colmap.log", step, arguments);
    });
    REQUIRE(merged.has_value());
    CHECK(merged->joined == 1);
    CHECK(merged->images == 12);
    CHECK(steps == std::vector<std::string>{"model_merger", "bundle_adjuster"});
    CHECK(merged->folder == dir.path / "merged" / "adjusted");

    // Every camera of the merged model stands where the walk put it, in the largest model's frame.
    const cv::Mat blank(static_cast<int>(kHeight), static_cast<int>(kWidth), CV_8UC3, cv::Scalar(128, 128, 128));
    for (int image = 0; image < 12; ++image)
        cv::imwrite((dir.path / fmt::format("frame{:02}.png", image)).string(), blank);
    smql::ingest::CaptureOptions options;
    options.imageDirectory = dir.path.string();
    const Capture capture = capture_detail::readColmap(merged->folder, options);
    REQUIRE(capture.frames.size() == 12);
    for (const auto& frame : capture.frames) {
        const int image = std::stoi(fs::path(frame.colorPath).stem().string().substr(5));
        const Eigen::Vector3d expected = 0.4 * turned * walk.centres[image] + Eigen::Vector3d(3, -1, 2);
        const Eigen::Vector3d stored(frame.pose->translation.x, frame.pose->translation.y, frame.pose->translation.z);
        INFO(frame.colorPath);
        CHECK((stored - expected).norm() < 1e-3);
    }
}

TEST_CASE("COLMAP models whose shared images do not agree are not merged") {
    ScratchDir dir;
    const Walk walk;
    const Eigen::Matrix3d none = Eigen::Matrix3d::Identity();
    writeModel(dir.path / "0", walk, {0, 1, 2, 3, 4, 5, 6}, 1, none, Eigen::Vector3d::Zero());
    // Images 4, 5 and 6 again, placed elsewhere around the cloud in this model (a model of repeated things
    // elsewhere): no similarity takes their cameras onto the first model's.
    Walk elsewhere = walk;
    elsewhere.centres[4] = {-4, 0, 1.5};
    elsewhere.centres[5] = {0, 4, 0.5};
    elsewhere.centres[6] = {3, -2, 3};
    for (int c : {4, 5, 6}) elsewhere.rotations[c] = Walk::facingCloud(elsewhere.centres[c]);
    writeModel(dir.path / "1", elsewhere, {4, 5, 6, 7, 8}, 1, none, Eigen::Vector3d::Zero());
    std::vector<ColmapModel> models;
    for (const char* folder : {"0", "1"})
        models.push_back({dir.path / folder, capture_detail::colmapImageNames(dir.path / folder)});
    std::vector<std::string> steps;
    const auto merged = mergeSharingModels(models, dir.path / "merged", [&](const auto& step, const auto& arguments) {
        steps.push_back(step);
        return runColmapStep(dir.path / "colmap.log", step, arguments);
    });
    CHECK_FALSE(merged.has_value());
    CHECK(steps == std::vector<std::string>{"model_merger"});
}
