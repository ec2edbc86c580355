// The capture readers: every layout the ingest reads, and loadFrame.
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <sstream>

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "capture_support.hpp"
#include "ingest/capture/capture.hpp"
#include "ingest/capture/frame_loader.hpp"

using namespace smql;
using namespace smql::ingest;
using namespace smql::ingest::test;

namespace {

std::array<double, 9> rotationOf(double qx, double qy, double qz, double qw) {
    double n = std::sqrt(qx * qx + qy * qy + qz * qz + qw * qw);
    qx /= n, qy /= n, qz /= n, qw /= n;
    return {1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw),     2 * (qx * qz + qy * qw),
            2 * (qx * qy + qz * qw),     1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw),
            2 * (qx * qz - qy * qw),     2 * (qy * qz + qx * qw),     1 - 2 * (qx * qx + qy * qy)};
}

// rotation * v
model::Vec3 rotate(const Pose& pose, model::Vec3 v) {
    const auto& r = pose.rotation;
    return {r[0] * v.x + r[1] * v.y + r[2] * v.z, r[3] * v.x + r[4] * v.y + r[5] * v.z,
            r[6] * v.x + r[7] * v.y + r[8] * v.z};
}

void checkVec(model::Vec3 actual, model::Vec3 expected, double margin = 1e-9) {
    CHECK(actual.x == Approx(expected.x).margin(margin));
    CHECK(actual.y == Approx(expected.y).margin(margin));
    CHECK(actual.z == Approx(expected.z).margin(margin));
}

void checkRotation(const Pose& pose, const std::array<double, 9>& expected, double margin = 1e-9) {
    for (int i = 0; i < 9; ++i) CHECK(pose.rotation[i] == Approx(expected[i]).margin(margin));
}

}  // namespace

// ---------------------------------------------------------------------------
// rgbd

TEST_CASE("rgbd-dining reads with no options", "[capture][rgbd]") {
    Capture capture = readCapture(diningPath());
    CHECK(capture.path == diningPath());
    CHECK(readCapture(diningPath() + "/").frames.size() == 5);
    CHECK(capture.layout == "rgbd");
    CHECK(capture.metric);
    CHECK(capture.depthScale == 1000);
    REQUIRE(capture.frames.size() == 5);
    CHECK(capture.labelsPath.empty());
    CHECK(capture.detectionsPath.empty());
    CHECK(capture.points.empty());

    // Kinect default intrinsics, and a note saying so.
    CHECK(capture.intrinsics == Intrinsics{640, 480, 525, 525, 319.5, 239.5});
    CHECK(hasNote(capture, "default intrinsics"));

    std::ifstream poses(diningPath() + "/pose.txt");
    for (int i = 0; i < 5; ++i) {
        const CaptureFrame& frame = capture.frames[i];
        INFO("frame " << i);
        CHECK(frame.index == i);
        CHECK(frame.time == Approx(i));
        CHECK(frame.colorPath == diningPath() + "/color/" + std::to_string(i + 1) + ".png");
        CHECK(frame.depthPath == diningPath() + "/depth/" + std::to_string(i + 1) + ".pgm");
        CHECK(frame.instancePath.empty());
        CHECK_FALSE(frame.intrinsics);
        double tx, ty, tz, qx, qy, qz, qw;
        REQUIRE(poses >> tx >> ty >> tz >> qx >> qy >> qz >> qw);
        REQUIRE(frame.pose);
        checkVec(frame.pose->translation, {tx, ty, tz}, 0);
        checkRotation(*frame.pose, rotationOf(qx, qy, qz, qw));
    }
}

TEST_CASE("rgbd-dining: loadFrame gives colour and depth in metres", "[capture][rgbd][load]") {
    Capture capture = readCapture(diningPath());
    const CaptureFrame& frame = capture.frames[2];
    cv::Mat raw = cv::imread(frame.depthPath, cv::IMREAD_UNCHANGED);
    REQUIRE(raw.type() == CV_16U);

    FrameImages images = loadFrame(capture, frame, 640);
    CHECK(images.color.type() == CV_8UC3);
    CHECK(images.color.cols == 640);
    CHECK(images.color.rows == 480);
    REQUIRE(images.depth.type() == CV_32F);
    CHECK(images.depth.size() == images.color.size());
    CHECK(images.instances.empty());
    CHECK(images.intrinsics == capture.intrinsics);

    int checked = 0;
    for (cv::Point p : {cv::Point(320, 240), cv::Point(100, 400), cv::Point(600, 50), cv::Point(17, 33)}) {
        std::uint16_t value = raw.at<std::uint16_t>(p);
        CHECK(images.depth.at<float>(p) == Approx(value / 1000.0).epsilon(1e-6));
        if (value > 0) ++checked;
    }
    CHECK(checked > 0);
    CHECK(cv::countNonZero(images.depth) == cv::countNonZero(raw));

    SECTION("scaled to a working width of 320") {
        FrameImages small = loadFrame(capture, frame, 320);
        CHECK(small.color.cols == 320);
        CHECK(small.color.rows == 240);
        CHECK(small.depth.size() == small.color.size());
        CHECK(small.intrinsics == Intrinsics{320, 240, 262.5, 262.5, 159.5, 119.5});
        // Nearest neighbour: every depth value is one of the raw values, not a blend.
        for (cv::Point p : {cv::Point(160, 120), cv::Point(50, 200), cv::Point(300, 25)}) {
            float d = small.depth.at<float>(p);
            bool found = false;
            for (int dy = 0; dy <= 1 && !found; ++dy)
                for (int dx = 0; dx <= 1 && !found; ++dx)
                    found = std::abs(raw.at<std::uint16_t>(2 * p.y + dy, 2 * p.x + dx) / 1000.0 - d) < 1e-6;
            CHECK(found);
        }
    }
    SECTION("a working width of 0 or above the image's keeps the size") {
        CHECK(loadFrame(capture, frame, 0).color.cols == 640);
        CHECK(loadFrame(capture, frame, 1000).color.cols == 640);
    }
}

TEST_CASE("rgbd-dining with its depth at a quarter of the pixels, as a phone's LiDAR gives it, registered",
          "[capture][rgbd][load]") {
    // The five real frames, their depth subsampled to 320 x 240 beside the 640 x 480 colour (an iPhone's LiDAR
    // depth is 256 x 192 beside colour of 1920 x 1440: the same aspect ratio, registered to the colour camera).
    TempDir dir;
    const Capture full = readCapture(diningPath());
    std::string poses;
    for (const CaptureFrame& frame : full.frames) {
        const std::string name = std::to_string(frame.index + 1);
        fs::create_directories(dir.root() / "color");
        fs::copy_file(frame.colorPath, dir.path("color/" + name + ".png"));
        cv::Mat depth = cv::imread(frame.depthPath, cv::IMREAD_UNCHANGED), small;
        cv::resize(depth, small, {320, 240}, 0, 0, cv::INTER_NEAREST);
        fs::create_directories(dir.root() / "depth");
        REQUIRE(cv::imwrite(dir.path("depth/" + name + ".png"), small));
    }
    fs::copy_file(diningPath() + "/pose.txt", dir.path("pose.txt"));
    const Capture capture = readCapture(dir.path());
    CHECK(hasNote(capture, "320x240 images beside 640x480 colour"));
    CHECK(capture.intrinsics == full.intrinsics);

    // Each colour pixel takes the reading of the depth pixel it lies in.
    const FrameImages images = loadFrame(capture, capture.frames[2], 640);
    const cv::Mat small = cv::imread(dir.path("depth/3.png"), cv::IMREAD_UNCHANGED);
    REQUIRE(images.depth.size() == images.color.size());
    for (cv::Point p : {cv::Point(320, 240), cv::Point(101, 401), cv::Point(600, 50), cv::Point(17, 33)})
        CHECK(images.depth.at<float>(p) == Approx(small.at<std::uint16_t>(p.y / 2, p.x / 2) / 1000.0).epsilon(1e-6));

    // Another aspect ratio is no registered depth: an error naming both images.
    writeDepth(dir, "depth/1.png", 320, 200);
    requireError([&] { readCapture(dir.path()); }, {dir.path("depth/1.png"), "320x200", "another aspect ratio"});
}

TEST_CASE("rgbd: camera.json, options, instance masks, labels and detections", "[capture][rgbd]") {
    TempDir dir;
    writeRgbd(dir, 3);
    dir.mkdir("instance");
    for (int i = 1; i <= 3; ++i) {
        cv::Mat mask(48, 64, CV_16U, cv::Scalar(0));
        mask(cv::Rect(10, 10, 20, 20)).setTo(7);
        REQUIRE(cv::imwrite(dir.path("instance/" + std::to_string(i) + ".png"), mask));
    }
    dir.write("labels.json", R"({"7": "chair"})");
    dir.write("detections.json", "[]");
    dir.write("camera.json",
              R"({"width": 64, "height": 48, "fx": 60, "fy": 61, "cx": 31, "cy": 23, "depth_scale": 500})");

    Capture capture = readCapture(dir.path());
    CHECK(capture.layout == "rgbd");
    CHECK(capture.intrinsics == Intrinsics{64, 48, 60, 61, 31, 23});
    CHECK(capture.depthScale == 500);
    CHECK_FALSE(hasNote(capture, "default intrinsics"));
    CHECK(capture.labelsPath == dir.path("labels.json"));
    CHECK(capture.detectionsPath == dir.path("detections.json"));
    REQUIRE(capture.frames.size() == 3);
    CHECK(capture.frames[1].instancePath == dir.path("instance/2.png"));
    checkVec(capture.frames[2].pose->translation, {0.3, 0, 0});

    FrameImages images = loadFrame(capture, capture.frames[0], 32);
    CHECK(images.color.cols == 32);
    CHECK(images.color.rows == 24);
    REQUIRE(images.instances.type() == CV_16U);
    CHECK(images.instances.size() == images.color.size());
    CHECK(images.instances.at<std::uint16_t>(10, 10) == 7);
    CHECK(images.instances.at<std::uint16_t>(2, 2) == 0);
    // depth value 1000 + x at x = 2 * 5 (nearest), scale 500.
    CHECK(images.depth.at<float>(3, 5) == Approx((1000 + 10) / 500.0));
    CHECK(images.intrinsics.fx == Approx(30));
    CHECK(images.intrinsics.fy == Approx(30.5));
    CHECK(images.intrinsics.cx == Approx(15.25));

    SECTION("options override camera.json") {
        CaptureOptions options;
        options.depthScale = 2000;
        options.intrinsics = Intrinsics{0, 0, 70, 70, 32, 24};
        options.fps = 10;
        Capture over = readCapture(dir.path(), options);
        CHECK(over.depthScale == 2000);
        CHECK(over.intrinsics == Intrinsics{64, 48, 70, 70, 32, 24});
        CHECK(over.frames[2].time == Approx(0.2));
    }
}

TEST_CASE("rgbd: camera.json's lens distortion is undone as frames are read", "[capture][rgbd][load]") {
    // TUM's Freiburg 1 colour calibration, distortion and all, on 640 x 480 frames. A point of the scene at
    // normalised coordinates (0.42, 0.3) lands where the lens bends it: the frame on disk shows a bright
    // 3 x 3 spot there, and a depth reading of 2 m under it.
    constexpr double fx = 517.3, fy = 516.5, cx = 318.6, cy = 255.3;
    constexpr std::array<double, 5> k{0.2624, -0.9531, -0.0054, 0.0026, 1.1633};
    const double x = 0.42, y = 0.3, r2 = x * x + y * y;
    const double radial = 1 + k[0] * r2 + k[1] * r2 * r2 + k[4] * r2 * r2 * r2;
    const double xd = x * radial + 2 * k[2] * x * y + k[3] * (r2 + 2 * x * x);
    const double yd = y * radial + k[2] * (r2 + 2 * y * y) + 2 * k[3] * x * y;
    const cv::Point bent(static_cast<int>(std::lround(fx * xd + cx)), static_cast<int>(std::lround(fy * yd + cy)));
    const cv::Point2d pinhole(fx * x + cx, fy * y + cy);
    REQUIRE(cv::norm(cv::Point2d(bent) - pinhole) > 5);  // the lens moves it by several pixels

    TempDir dir;
    dir.mkdir("color");
    dir.mkdir("depth");
    cv::Mat color(480, 640, CV_8UC3, cv::Scalar::all(0)), depth(480, 640, CV_16U, cv::Scalar(0));
    color(cv::Rect(bent.x - 1, bent.y - 1, 3, 3)).setTo(cv::Scalar::all(255));
    depth(cv::Rect(bent.x - 1, bent.y - 1, 3, 3)).setTo(10000);
    REQUIRE(cv::imwrite(dir.path("color/1.png"), color));
    REQUIRE(cv::imwrite(dir.path("depth/1.png"), depth));
    dir.write("pose.txt", "0 0 0 0 0 0 1\n");
    dir.write("camera.json", R"({"width": 640, "height": 480, "fx": 517.3, "fy": 516.5, "cx": 318.6, "cy": 255.3,
                                 "k1": 0.2624, "k2": -0.9531, "p1": -0.0054, "p2": 0.0026, "k3": 1.1633,
                                 "depth_scale": 5000})");
    Capture capture = readCapture(dir.path());
    CHECK(capture.intrinsics.distorted());
    CHECK(capture.intrinsics.distortion[4] == 1.1633);

    // Read, the frame is the pinhole image of the same intrinsics: the spot where the point projects without
    // the lens, within a pixel, and its depth under it.
    FrameImages images = loadFrame(capture, capture.frames[0], 640);
    CHECK_FALSE(images.intrinsics.distorted());
    CHECK(images.intrinsics.fx == fx);
    cv::Mat gray;
    cv::cvtColor(images.color, gray, cv::COLOR_BGR2GRAY);
    const cv::Moments spot = cv::moments(gray, false);
    REQUIRE(spot.m00 > 0);
    CHECK(cv::norm(cv::Point2d(spot.m10 / spot.m00, spot.m01 / spot.m00) - pinhole) < 1.0);
    CHECK(images.depth.at<float>(static_cast<int>(std::lround(pinhole.y)), static_cast<int>(std::lround(pinhole.x))) ==
          Approx(2.0));
    CHECK(cv::countNonZero(images.depth) <= 16);  // nearest pixels: no reading smeared between them

    // Scaled down to the working width, the same spot: the distortion is of normalised coordinates.
    FrameImages half = loadFrame(capture, capture.frames[0], 320);
    cv::cvtColor(half.color, gray, cv::COLOR_BGR2GRAY);
    const cv::Moments small = cv::moments(gray, false);
    REQUIRE(small.m00 > 0);
    CHECK(cv::norm(cv::Point2d(small.m10 / small.m00, small.m01 / small.m00) -
                   cv::Point2d(half.intrinsics.fx * x + half.intrinsics.cx,
                               half.intrinsics.fy * y + half.intrinsics.cy)) < 1.0);
}

TEST_CASE("rgbd: frames in numeric order, leading zeros and other extensions", "[capture][rgbd]") {
    TempDir dir;
    for (int i : {1, 2, 10}) {
        std::string name = (i == 10 ? "0010" : std::to_string(i));
        writeColor(dir, "color/" + name + ".jpg", 32, 24, i);
        writeDepth(dir, "depth/" + std::to_string(i) + ".png", 32, 24);
    }
    dir.write("pose.txt", "# tx ty tz qx qy qz qw\n1 0 0 0 0 0 1\n\n2 0 0 0 0 0 1\n10 0 0 0 0 0 2\n");
    Capture capture = readCapture(dir.path());
    REQUIRE(capture.frames.size() == 3);
    CHECK(fs::path(capture.frames[0].colorPath).filename() == "1.jpg");
    CHECK(fs::path(capture.frames[1].colorPath).filename() == "2.jpg");
    CHECK(fs::path(capture.frames[2].colorPath).filename() == "0010.jpg");
    CHECK(fs::path(capture.frames[2].depthPath).filename() == "10.png");
    CHECK(capture.frames[2].pose->translation.x == 10);
    checkRotation(*capture.frames[2].pose, {1, 0, 0, 0, 1, 0, 0, 0, 1});  // normalised quaternion
    CHECK(capture.intrinsics.fx == Approx(525.0 * 32 / 640));
}

// ---------------------------------------------------------------------------
// TUM

TEST_CASE("tum: association, ground truth and sampling", "[capture][tum]") {
    TempDir dir;
    writeColor(dir, "rgb/a.png", 64, 48);
    writeDepth(dir, "depth/a.png", 64, 48, 5000);
    std::ostringstream rgb, depth, gt;
    rgb << "# color images\n# file: 'x.bag'\n# timestamp filename\n";
    depth << "# depth maps\n";
    gt << "# ground truth trajectory\n# timestamp tx ty tz qx qy qz qw\n";
    char line[200];
    for (int k = 0; k < 70; ++k) {
        double t = 100 + k / 30.0;
        std::snprintf(line, sizeof line, "%.6f rgb/a.png\n", t);
        rgb << line;
        if (k != 5) {
            std::snprintf(line, sizeof line, "%.6f depth/a.png\n", t + 0.01);
            depth << line;
        }
    }
    for (int k = 0; k < 150; ++k) {  // 100 Hz until t = 101.5, x = time - 100
        double t = 100.005 + k * 0.01;
        std::snprintf(line, sizeof line, "%.4f %.4f 0 1 0 0 0 1\n", t, t - 100);
        gt << line;
    }
    dir.write("rgb.txt", rgb.str());
    dir.write("depth.txt", depth.str());
    dir.write("groundtruth.txt", gt.str());

    Capture capture = readCapture(dir.path());  // fps 1
    CHECK(capture.layout == "tum");
    CHECK(capture.metric);
    CHECK(capture.depthScale == 5000);
    CHECK(capture.intrinsics == Intrinsics{64, 48, 52.5, 52.5, 31.5, 23.5});
    CHECK(hasNote(capture, "default intrinsics"));
    CHECK(hasNote(capture, "1 of 70 rgb frames have no depth"));
    REQUIRE(capture.frames.size() == 3);
    CHECK(capture.frames[0].time == Approx(0).margin(1e-9));
    CHECK(capture.frames[1].time == Approx(1).margin(1e-5));
    CHECK(capture.frames[2].time == Approx(2).margin(1e-5));
    CHECK(capture.frames[1].colorPath == dir.path("rgb/a.png"));
    CHECK(capture.frames[1].depthPath == dir.path("depth/a.png"));
    // t = 100: nearest sample 100.005; t = 101: interpolated between 100.995 and 101.005.
    REQUIRE(capture.frames[0].pose);
    checkVec(capture.frames[0].pose->translation, {0.005, 0, 1}, 1e-9);
    REQUIRE(capture.frames[1].pose);
    checkVec(capture.frames[1].pose->translation, {1.0, 0, 1}, 1e-5);
    checkRotation(*capture.frames[1].pose, {1, 0, 0, 0, 1, 0, 0, 0, 1});
    CHECK_FALSE(capture.frames[2].pose);  // ground truth ends at 101.5
    CHECK(hasNote(capture, "1 of 3 frames have no ground-truth pose"));
    // The frames the sampling leaves out are said, with the option that keeps them.
    CHECK(hasNote(capture, "3 of 69 frames kept, 1 a second (--fps; --fps 0 keeps every frame)"));

    FrameImages images = loadFrame(capture, capture.frames[1], 640);
    CHECK(images.depth.at<float>(5, 0) == Approx(1.0));
    CHECK(images.depth.at<float>(5, 50) == Approx(5050 / 5000.0));

    SECTION("fps 0 keeps every associated frame") {
        CaptureOptions options;
        options.fps = 0;
        Capture all = readCapture(dir.path(), options);
        CHECK(all.frames.size() == 69);
        CHECK_FALSE(hasNote(all, "frames kept"));
    }
    SECTION("fps 10") {
        CaptureOptions options;
        options.fps = 10;
        Capture dense = readCapture(dir.path(), options);
        CHECK(dense.frames.size() == 24);
        CHECK(dense.frames[1].time == Approx(0.1).margin(0.034));
    }
}

// ---------------------------------------------------------------------------
// nerfstudio

TEST_CASE("nerfstudio: OpenGL poses become OpenCV poses", "[capture][nerfstudio]") {
    TempDir dir;
    writeColor(dir, "images/frame_2.png", 40, 30);
    writeColor(dir, "images/frame_10.png", 40, 30);
    dir.write("transforms.json", R"({
      "camera_model": "OPENCV", "fl_x": 50, "fl_y": 52, "cx": 20, "cy": 15, "w": 40, "h": 30,
      "k1": 0.01, "k2": 0, "p1": 0, "p2": 0,
      "frames": [
        {"file_path": "images/frame_10.png",
         "transform_matrix": [[0, 0, 1, 1], [0, 1, 0, 2], [-1, 0, 0, 3], [0, 0, 0, 1]]},
        {"file_path": "images/frame_2.png",
         "transform_matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}
      ]})");
    Capture capture = readCapture(dir.path());
    CHECK(capture.layout == "nerfstudio");
    CHECK_FALSE(capture.metric);
    // OPENCV's k1 k2 p1 p2 are the first of OpenCV's coefficients, undone as frames are read.
    CHECK(capture.intrinsics == Intrinsics{40, 30, 50, 52, 19.5, 14.5, {0.01, 0, 0, 0, 0, 0, 0, 0}});
    CHECK(hasNote(capture, "distortion (k1, k2, p1, p2, k3) is undone"));
    REQUIRE(capture.frames.size() == 2);
    CHECK(fs::path(capture.frames[0].colorPath).filename() == "frame_2.png");  // natural order
    CHECK(fs::path(capture.frames[1].colorPath).filename() == "frame_10.png");
    CHECK(capture.frames[0].depthPath.empty());

    // Identity in OpenGL: a camera at the origin looking down -z, y up.
    const Pose& identity = *capture.frames[0].pose;
    checkVec(rotate(identity, {0, 0, 1}), {0, 0, -1});  // our viewing direction (+z camera) -> world -z
    checkVec(rotate(identity, {0, 1, 0}), {0, -1, 0});  // our y (down in the image) -> world -y
    checkVec(rotate(identity, {1, 0, 0}), {1, 0, 0});
    checkVec(identity.translation, {0, 0, 0});

    // The second camera: OpenGL -z (its viewing direction) is minus the third column, (-1, 0, 0).
    const Pose& turned = *capture.frames[1].pose;
    checkVec(turned.translation, {1, 2, 3});
    checkVec(rotate(turned, {0, 0, 1}), {-1, 0, 0});
    checkVec(rotate(turned, {0, 1, 0}), {0, -1, 0});

    // Just the reading of the matrix, independently: our R = M * diag(1, -1, -1).
    checkRotation(turned, {0, 0, -1, 0, -1, 0, -1, 0, 0});
}

TEST_CASE("nerfstudio: depth makes it metric, per-frame intrinsics, camera_angle_x", "[capture][nerfstudio]") {
    TempDir dir;
    writeColor(dir, "rgb/0.png", 40, 30);
    writeColor(dir, "rgb/1.png", 40, 30);
    writeDepth(dir, "depth/0.png", 40, 30, 100);
    writeDepth(dir, "depth/1.png", 40, 30, 100);
    dir.write("data/transforms.json", R"({
      "camera_angle_x": 1.5707963267948966, "depth_unit_scale_factor": 0.01,
      "frames": [
        {"file_path": "../rgb/0", "depth_file_path": "../depth/0.png",
         "transform_matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]},
        {"file_path": "../rgb/1.png", "depth_file_path": "../depth/1.png", "fl_x": 30, "fl_y": 30,
         "transform_matrix": [[1, 0, 0, 5], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}
      ]})");
    Capture capture = readCapture(dir.path("data/transforms.json"));
    CHECK(capture.layout == "nerfstudio");
    CHECK(capture.metric);
    CHECK(capture.depthScale == Approx(100));
    REQUIRE(capture.frames.size() == 2);
    CHECK(fs::path(capture.frames[0].colorPath) == fs::path(dir.path("rgb/0.png")));  // extension found
    // w, h from the image; fx from camera_angle_x (90 degrees: fx = w / 2).
    CHECK(capture.intrinsics.width == 40);
    CHECK(capture.intrinsics.fx == Approx(20));
    CHECK(capture.intrinsics.cx == Approx(19.5));
    CHECK_FALSE(capture.frames[0].intrinsics);
    REQUIRE(capture.frames[1].intrinsics);
    CHECK(capture.frames[1].intrinsics->fx == 30);
    CHECK(loadFrame(capture, capture.frames[1], 640).intrinsics.fx == 30);
    FrameImages images = loadFrame(capture, capture.frames[0], 640);
    CHECK(images.depth.at<float>(0, 3) == Approx(1.03));
    CHECK_FALSE(hasNote(capture, "registered to the colour camera"));

    // Depth at half the colour's resolution (as nerfstudio's record3d data gives it): read at the colour's size.
    writeDepth(dir, "depth/0.png", 20, 15, 100);
    const Capture half = readCapture(dir.path("data/transforms.json"));
    CHECK(hasNote(half, "20x15 images beside 40x30 colour"));
    const FrameImages halfImages = loadFrame(half, half.frames[0], 640);
    REQUIRE(halfImages.depth.size() == cv::Size(40, 30));
    CHECK(halfImages.depth.at<float>(0, 3) == Approx(1.01));  // the reading of depth pixel 1, which holds 100 + 1
}

// ---------------------------------------------------------------------------
// COLMAP

namespace {

struct ColmapData {
    struct Camera {
        int id;
        std::string model;
        int modelId;
        int width, height;
        std::vector<double> params;
    };
    struct Image {
        int id;
        std::array<double, 4> q;  // w x y z
        std::array<double, 3> t;
        int camera;
        std::string name;
    };
    struct Point {
        std::uint64_t id;
        std::array<double, 3> xyz;
        std::array<int, 3> rgb;
    };
    std::vector<Camera> cameras{{1, "PINHOLE", 1, 40, 30, {50, 52, 20, 15}},
                                {2, "SIMPLE_RADIAL", 2, 40, 30, {45, 20, 15, 0.1}}};
    std::vector<Image> images{{1, {std::sqrt(0.5), 0, 0, std::sqrt(0.5)}, {1, 2, 3}, 1, "b.png"},
                              {2, {1, 0, 0, 0}, {0, 0, -5}, 2, "a.png"}};
    std::vector<Point> points{{1, {0.5, -1, 2}, {255, 0, 10}}, {7, {3, 4, 5}, {1, 2, 3}}};
};

void writeColmapText(const TempDir& dir, const std::string& model, const ColmapData& data) {
    std::ostringstream cameras, images, points;
    cameras << "# Camera list with one line of data per camera:\n#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n";
    for (const auto& c : data.cameras) {
        cameras << c.id << ' ' << c.model << ' ' << c.width << ' ' << c.height;
        for (double p : c.params) cameras << ' ' << p;
        cameras << '\n';
    }
    images.precision(17);
    images << "# Image list with two lines of data per image:\n";
    for (const auto& i : data.images) {
        images << i.id << ' ' << i.q[0] << ' ' << i.q[1] << ' ' << i.q[2] << ' ' << i.q[3] << ' ' << i.t[0] << ' '
               << i.t[1] << ' ' << i.t[2] << ' ' << i.camera << ' ' << i.name << '\n';
        images << (i.id == 1 ? "10.5 12.25 1 3.0 4.0 -1\n" : "\n");
    }
    points << "# 3D point list\n";
    for (const auto& p : data.points)
        points << p.id << ' ' << p.xyz[0] << ' ' << p.xyz[1] << ' ' << p.xyz[2] << ' ' << p.rgb[0] << ' ' << p.rgb[1]
               << ' ' << p.rgb[2] << " 0.5 1 0 2 0\n";
    dir.write(model + "/cameras.txt", cameras.str());
    dir.write(model + "/images.txt", images.str());
    dir.write(model + "/points3D.txt", points.str());
}

void writeColmapBinary(const TempDir& dir, const std::string& model, const ColmapData& data) {
    std::string cameras, images, points;
    put<std::uint64_t>(cameras, data.cameras.size());
    for (const auto& c : data.cameras) {
        put<std::int32_t>(cameras, c.id);
        put<std::int32_t>(cameras, c.modelId);
        put<std::uint64_t>(cameras, c.width);
        put<std::uint64_t>(cameras, c.height);
        for (double p : c.params) put<double>(cameras, p);
    }
    put<std::uint64_t>(images, data.images.size());
    for (const auto& i : data.images) {
        put<std::uint32_t>(images, i.id);
        for (double v : i.q) put<double>(images, v);
        for (double v : i.t) put<double>(images, v);
        put<std::uint32_t>(images, i.camera);
        images += i.name;
        images += '\0';
        std::uint64_t n = i.id == 1 ? 2 : 0;
        put<std::uint64_t>(images, n);
        for (std::uint64_t k = 0; k < n; ++k) {
            put<double>(images, 1.5);
            put<double>(images, 2.5);
            put<std::int64_t>(images, k == 0 ? 1 : -1);
        }
    }
    put<std::uint64_t>(points, data.points.size());
    for (const auto& p : data.points) {
        put<std::uint64_t>(points, p.id);
        for (double v : p.xyz) put<double>(points, v);
        for (int c : p.rgb) put<std::uint8_t>(points, static_cast<std::uint8_t>(c));
        put<double>(points, 0.5);
        put<std::uint64_t>(points, 2);
        for (int k = 0; k < 2; ++k) {
            put<std::int32_t>(points, k + 1);
            put<std::int32_t>(points, 0);
        }
    }
    dir.write(model + "/cameras.bin", cameras);
    dir.write(model + "/images.bin", images);
    dir.write(model + "/points3D.bin", points);
}

void checkColmapCapture(const Capture& capture) {
    CHECK(capture.layout == "colmap");
    CHECK_FALSE(capture.metric);
    REQUIRE(capture.frames.size() == 2);
    // Image-name order: a.png (camera 2) first.
    CHECK(fs::path(capture.frames[0].colorPath).filename() == "a.png");
    CHECK(fs::path(capture.frames[1].colorPath).filename() == "b.png");
    CHECK(capture.frames[0].index == 0);
    CHECK(capture.frames[1].index == 1);
    CHECK(capture.frames[0].depthPath.empty());

    // Intrinsics: camera 2 for the capture, camera 1 on frame b; principal point moved by -0.5.
    // SIMPLE_RADIAL's k is OpenCV's k1.
    CHECK(capture.intrinsics == Intrinsics{40, 30, 45, 45, 19.5, 14.5, {0.1, 0, 0, 0, 0, 0, 0, 0}});
    CHECK_FALSE(capture.frames[0].intrinsics);
    REQUIRE(capture.frames[1].intrinsics);
    CHECK(*capture.frames[1].intrinsics == Intrinsics{40, 30, 50, 52, 19.5, 14.5});
    CHECK(hasNote(capture, "lens distortion is undone as each frame is read"));

    // a.png: world-to-camera identity, t = (0, 0, -5) -> camera at (0, 0, 5).
    checkRotation(*capture.frames[0].pose, {1, 0, 0, 0, 1, 0, 0, 0, 1});
    checkVec(capture.frames[0].pose->translation, {0, 0, 5});
    // b.png: world-to-camera 90 degrees about z, t = (1, 2, 3): camera-to-world is the transpose,
    // the centre -R^T t = (-2, 1, -3).
    checkRotation(*capture.frames[1].pose, {0, 1, 0, -1, 0, 0, 0, 0, 1});
    checkVec(capture.frames[1].pose->translation, {-2, 1, -3});

    REQUIRE(capture.points.size() == 2);
    checkVec(capture.points[0].position, {0.5, -1, 2});
    CHECK(capture.points[0].color == std::array<std::uint8_t, 3>{255, 0, 10});
    checkVec(capture.points[1].position, {3, 4, 5});
    CHECK(capture.points[1].color == std::array<std::uint8_t, 3>{1, 2, 3});
}

}  // namespace

TEST_CASE("colmap: text and binary models give the same capture", "[capture][colmap]") {
    ColmapData data;
    TempDir text, binary;
    for (const TempDir* dir : {&text, &binary}) {
        writeColor(*dir, "images/a.png", 40, 30, 1);
        writeColor(*dir, "images/b.png", 40, 30, 2);
    }
    writeColmapText(text, "sparse/0", data);
    writeColmapBinary(binary, "sparse/0", data);

    SECTION("text, named by the project folder") { checkColmapCapture(readCapture(text.path())); }
    SECTION("binary, named by the project folder") { checkColmapCapture(readCapture(binary.path())); }
    SECTION("text, named by the model folder") { checkColmapCapture(readCapture(text.path("sparse/0"))); }
    SECTION("binary, named by the model folder with a trailing slash") {
        checkColmapCapture(readCapture(binary.path("sparse/0/")));
    }
    SECTION("binary, named by a model file") { checkColmapCapture(readCapture(binary.path("sparse/0/images.bin"))); }
    SECTION("images found beside the model folder, or named by the option") {
        TempDir other;
        writeColmapText(other, "model", data);
        writeColor(other, "images/a.png", 40, 30, 1);
        writeColor(other, "images/b.png", 40, 30, 2);
        checkColmapCapture(readCapture(other.path("model")));
        CaptureOptions options;
        options.imageDirectory = text.path("images");
        checkColmapCapture(readCapture(binary.path("sparse/0"), options));
    }
    SECTION("images smaller than the model's cameras: intrinsics scale") {
        writeColor(text, "images/a.png", 20, 15, 1);
        Capture capture = readCapture(text.path());
        FrameImages images = loadFrame(capture, capture.frames[0], 640);
        CHECK(images.color.cols == 20);
        CHECK(images.intrinsics.fx == Approx(22.5));
        CHECK(images.intrinsics.cx == Approx(9.5));
    }
}

// ---------------------------------------------------------------------------
// image folders and videos

TEST_CASE("images: natural order, guessed intrinsics", "[capture][images]") {
    TempDir dir;
    writeColor(dir, "10.png", 50, 40, 10);
    writeColor(dir, "2.png", 50, 40, 2);
    writeColor(dir, "1.jpg", 50, 40, 1);
    dir.write("notes.txt", "not an image");
    CaptureOptions options;
    options.fps = 0.5;  // does not drop images
    Capture capture = readCapture(dir.path(), options);
    CHECK(capture.layout == "images");
    CHECK_FALSE(capture.metric);
    REQUIRE(capture.frames.size() == 3);
    CHECK(fs::path(capture.frames[0].colorPath).filename() == "1.jpg");
    CHECK(fs::path(capture.frames[1].colorPath).filename() == "2.png");
    CHECK(fs::path(capture.frames[2].colorPath).filename() == "10.png");
    CHECK(capture.frames[2].index == 2);
    CHECK_FALSE(capture.frames[0].pose);
    CHECK(capture.frames[0].depthPath.empty());
    CHECK(capture.intrinsics == Intrinsics{50, 40, 60, 60, 24.5, 19.5});
    CHECK(hasNote(capture, "guessed"));

    SECTION("a portrait photo among landscape ones gets its own guess") {
        writeColor(dir, "11.png", 40, 50, 3);
        Capture mixed = readCapture(dir.path());
        FrameImages images = loadFrame(mixed, mixed.frames[3], 640);
        CHECK(images.intrinsics == Intrinsics{40, 50, 48, 48, 19.5, 24.5});
    }
}

TEST_CASE("video: sampled at fps into PNGs", "[capture][video]") {
    TempDir dir;
    std::string path = dir.path("walk.avi");
    {
        cv::VideoWriter writer(path, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10, cv::Size(64, 48));
        REQUIRE(writer.isOpened());
        for (int i = 0; i < 30; ++i) writer.write(cv::Mat(48, 64, CV_8UC3, cv::Scalar(i * 8, i * 8, i * 8)));
    }
    CaptureOptions options;
    options.workDirectory = dir.path("work");
    Capture capture = readCapture(path, options);
    CHECK(capture.path == path);
    CHECK(capture.layout == "video");
    CHECK_FALSE(capture.metric);
    REQUIRE(capture.frames.size() == 3);
    for (int i = 0; i < 3; ++i) {
        INFO("frame " << i);
        CHECK(capture.frames[i].time == Approx(i));
        CHECK(fs::path(capture.frames[i].colorPath).parent_path() == fs::path(dir.path("work")));
        cv::Mat image = cv::imread(capture.frames[i].colorPath);
        REQUIRE(image.cols == 64);
        CHECK(cv::mean(image)[0] == Approx(i * 80).margin(6));  // frame 10 * i
    }
    CHECK(capture.intrinsics == Intrinsics{64, 48, 76.8, 76.8, 31.5, 23.5});

    SECTION("a temporary folder when none is given, scaled to the working width") {
        CaptureOptions small;
        small.fps = 2;
        small.workingWidth = 32;
        Capture temp = readCapture(path, small);
        REQUIRE(temp.frames.size() == 6);
        CHECK(temp.frames[1].time == Approx(0.5));
        fs::path folder = fs::path(temp.frames[0].colorPath).parent_path();
        CHECK(folder.string().rfind(fs::temp_directory_path().string(), 0) == 0);
        CHECK(hasNote(temp, folder.string()));
        CHECK(cv::imread(temp.frames[0].colorPath).cols == 32);
        CHECK(temp.intrinsics.width == 32);
        fs::remove_all(folder);
    }
}
