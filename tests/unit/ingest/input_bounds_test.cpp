// Captures whose numbers are finite but absurd: cameras and points far beyond
// any room (1e39 m became Inf in the single-precision clouds and aborted PCL),
// and depth images without a single reading.
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "capture_support.hpp"
#include "ingest/capture/capture.hpp"
#include "ingest/pipeline/pipeline.hpp"
#include "ingest/pipeline/progress.hpp"

using namespace smql;
using namespace smql::ingest;
using namespace smql::ingest::test;

namespace {

std::string colmapBinaryImage(double tx) {
    std::string bin;
    put<std::uint64_t>(bin, 1);  // one image
    put<std::uint32_t>(bin, 7);  // id
    for (double q : {1.0, 0.0, 0.0, 0.0}) put<double>(bin, q);
    for (double t : {tx, 0.0, 0.0}) put<double>(bin, t);
    put<std::uint32_t>(bin, 1);  // camera
    bin += std::string("a.png") + '\0';
    put<std::uint64_t>(bin, 0);  // no 2D points
    return bin;
}

std::string colmapBinaryCamera() {
    std::string bin;
    put<std::uint64_t>(bin, 1);
    put<std::int32_t>(bin, 1);  // id
    put<std::int32_t>(bin, 1);  // PINHOLE
    put<std::uint64_t>(bin, 40);
    put<std::uint64_t>(bin, 30);
    for (double p : {50.0, 50.0, 20.0, 15.0}) put<double>(bin, p);
    return bin;
}

}  // namespace

TEST_CASE("capture bounds: camera positions beyond 10 km are refused with the frame and line",
          "[capture][errors][bounds]") {
    TempDir dir;

    SECTION("pose.txt") {
        writeRgbd(dir, 3);
        dir.write("pose.txt", "# poses\n0 0 0 0 0 0 1\n1e39 0 0 0 0 0 1\n0 0 0 0 0 0 1\n");
        requireError([&] { readCapture(dir.path()); },
                     {dir.path("pose.txt") + ":3:", "the camera of frame 2", "(1e+39, 0, 0)", "10000 m"}, 3);
        dir.write("pose.txt", "0 0 0 0 0 0 1\n0 0 0 0 0 0 1\n0 -2e6 0 0 0 0 1\n");
        requireError([&] { readCapture(dir.path()); }, {dir.path("pose.txt") + ":3:", "the camera of frame 3"}, 3);
        dir.write("pose.txt", "0 0 0 0 0 0 1\n0 0 0 0 0 0 1\n0 0 9999.5 0 0 0 1\n");  // within the limit
        CHECK(readCapture(dir.path()).frames.size() == 3);
    }
    SECTION("TUM groundtruth.txt") {
        writeColor(dir, "rgb/a.png", 32, 24);
        writeDepth(dir, "depth/a.png", 32, 24);
        dir.write("rgb.txt", "1.0 rgb/a.png\n");
        dir.write("depth.txt", "1.0 depth/a.png\n");
        dir.write("groundtruth.txt", "1.0 0 0 0 0 0 0 1\n1.5 0 0 1e30 0 0 0 1\n");
        requireError([&] { readCapture(dir.path()); },
                     {dir.path("groundtruth.txt") + ":2:", "the camera at time 1.5", "1e+30"}, 2);
    }
    SECTION("COLMAP text: images and points") {
        dir.write("sparse/0/cameras.txt", "1 PINHOLE 40 30 50 50 20 15\n");
        dir.write("sparse/0/images.txt", "1 1 0 0 0 0 0 0 1 a.png\n\n2 1 0 0 0 0 0 -3e7 1 b.png\n\n");
        dir.write("sparse/0/points3D.txt", "");
        writeColor(dir, "images/a.png", 40, 30);
        writeColor(dir, "images/b.png", 40, 30);
        requireError([&] { readCapture(dir.path()); },
                     {dir.path("sparse/0/images.txt") + ":3:", "the camera of image 2 ('b.png')", "3e+07"}, 3);
        dir.write("sparse/0/images.txt", "1 1 0 0 0 0 0 0 1 a.png\n\n");
        dir.write("sparse/0/points3D.txt", "1 0 0 0 255 0 0 0.5\n2 1e39 0 0 255 0 0 0.5\n");
        requireError([&] { readCapture(dir.path()); }, {dir.path("sparse/0/points3D.txt") + ":2:", "point 2"}, 2);
    }
    SECTION("COLMAP binary") {
        dir.write("sparse/0/cameras.bin", colmapBinaryCamera());
        dir.write("sparse/0/images.bin", colmapBinaryImage(1e39));
        writeColor(dir, "images/a.png", 40, 30);
        requireError([&] { readCapture(dir.path()); },
                     {dir.path("sparse/0/images.bin"), "image 7 ('a.png')", "the camera is at (-1e+39,"});
        dir.write("sparse/0/images.bin", colmapBinaryImage(12.0));
        CHECK(readCapture(dir.path()).frames.size() == 1);
    }
    SECTION("transforms.json") {
        writeColor(dir, "images/0.png", 40, 30);
        dir.write("transforms.json",
                  R"({"fl_x": 50, "w": 40, "h": 30, "frames": [{"file_path": "images/0.png", "transform_matrix": )"
                  R"([[1,0,0,0],[0,1,0,1e39],[0,0,1,0],[0,0,0,1]]}]})");
        requireError([&] { readCapture(dir.path()); },
                     {dir.path("transforms.json"), "frames[0].transform_matrix", "(0, 1e+39, 0)", "10000 m"});
    }
}

TEST_CASE("ingest: depth images without a single reading are an error, not an empty scene",
          "[pipeline][errors][bounds]") {
    TempDir dir;
    writeRgbd(dir, 2);
    for (const char* name : {"depth/1.png", "depth/2.png"})
        REQUIRE(cv::imwrite(dir.path(name), cv::Mat(48, 64, CV_16U, cv::Scalar(0))));
    SilentProgress silent;
    IngestOptions options;
    options.sceneName = "empty";
    requireError([&] { ingestCapture(readCapture(dir.path()), options, silent); },
                 {dir.path(), "no depth reading in any frame", "farther than 6 m"});
}
