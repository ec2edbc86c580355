// Where a capture's camera comes from (--camera, --fov, camera.json, EXIF, the
// stated guess) and the refusal of mirrored cameras and poses.
#include <array>
#include <cmath>
#include <string>

#include "capture_support.hpp"
#include "exif_jpeg.hpp"
#include "ingest/capture/capture.hpp"
#include "ingest/capture/capture_detail.hpp"
#include "ingest/capture/frame_loader.hpp"

using namespace smql;
using namespace smql::ingest;
using namespace smql::ingest::test;

TEST_CASE("--camera and --fov are parsed and checked", "[capture][camera]") {
    Intrinsics k = parseCameraOption("1450, 1440.5,959.5,539.5");
    CHECK(k.fx == 1450);
    CHECK(k.fy == 1440.5);
    CHECK(k.cx == 959.5);
    CHECK(k.cy == 539.5);
    CHECK(k.width == 0);  // the images' size
    CHECK_FALSE(k.distorted());
    // The lens's distortion after the pinhole, in OpenCV's order (TUM's Freiburg 1), as many terms as known.
    k = parseCameraOption("517.3,516.5,318.6,255.3,0.2624,-0.9531,-0.0054,0.0026,1.1633");
    CHECK(k.distortion == std::array<double, 8>{0.2624, -0.9531, -0.0054, 0.0026, 1.1633, 0, 0, 0});
    CHECK(parseCameraOption("517.3,516.5,318.6,255.3,0.2624").distortion[0] == 0.2624);

    requireError([] { parseCameraOption("1450,1450,959.5"); }, {"--camera takes 4 numbers", "got 3"}, std::nullopt,
                 ErrorKind::Usage);
    requireError([] { parseCameraOption("1,1,1,1,0,0,0,0,0,0"); }, {"--camera", "up to 5", "k1,k2,p1,p2,k3", "got 10"},
                 std::nullopt, ErrorKind::Usage);
    requireError([] { parseCameraOption("1450,wide,959.5,539.5"); }, {"--camera", "value 2 'wide' is not a number"},
                 std::nullopt, ErrorKind::Usage);
    requireError([] { parseCameraOption("-1450,1450,959.5,539.5"); }, {"--camera", "mirrored", "-1450"}, std::nullopt,
                 ErrorKind::Usage);
    requireError([] { parseCameraOption(""); }, {"--camera", "not a number"}, std::nullopt, ErrorKind::Usage);

    CHECK(checkFieldOfView(66) == 66);
    requireError([] { checkFieldOfView(0); }, {"--fov", "between 0 and 180", "got 0"}, std::nullopt, ErrorKind::Usage);
    requireError([] { checkFieldOfView(200); }, {"--fov", "got 200"}, std::nullopt, ErrorKind::Usage);
}

TEST_CASE("a photo folder's camera: options, camera.json, EXIF, else a stated guess", "[capture][camera]") {
    TempDir dir;
    writeColor(dir, "photos/a.png", 80, 60, 1);
    writeColor(dir, "photos/b.png", 80, 60, 2);
    const std::string photos = dir.path("photos");

    SECTION("nothing known: the guess, and a note saying so") {
        Capture capture = readCapture(photos);
        CHECK(capture.intrinsicsOrigin == IntrinsicsOrigin::Guessed);
        CHECK(capture.intrinsics.fx == Approx(1.2 * 80));
        CHECK(hasNote(capture, "the camera is unknown"));
        CHECK(hasNote(capture, "guessed"));
    }
    SECTION("--camera, kept as given") {
        CaptureOptions options;
        options.intrinsics = parseCameraOption("70,71,39.5,29.5");
        Capture capture = readCapture(photos, options);
        CHECK(capture.intrinsicsOrigin == IntrinsicsOrigin::Measured);
        CHECK(capture.intrinsics == Intrinsics{80, 60, 70, 71, 39.5, 29.5});
        CHECK(hasNote(capture, "camera from --camera"));
    }
    SECTION("--camera with the lens's distortion: kept with the camera, the frames read undistorted") {
        CaptureOptions options;
        options.intrinsics = parseCameraOption("70,71,39.5,29.5,0.1,-0.05");
        Capture capture = readCapture(photos, options);
        CHECK(capture.intrinsics == Intrinsics{80, 60, 70, 71, 39.5, 29.5, {0.1, -0.05, 0, 0, 0, 0, 0, 0}});
        CHECK_FALSE(loadFrame(capture, capture.frames[0], 80).intrinsics.distorted());
    }
    SECTION("--fov: the focal length from the width") {
        CaptureOptions options;
        options.horizontalFov = 90;
        Capture capture = readCapture(photos, options);
        CHECK(capture.intrinsicsOrigin == IntrinsicsOrigin::Approximate);
        CHECK(capture.intrinsics.fx == Approx(40));  // half the width at 45 degrees
        CHECK(capture.intrinsics.fy == Approx(40));
        CHECK(capture.intrinsics.cx == Approx(39.5));
        CHECK(hasNote(capture, "camera from --fov"));
    }
    SECTION("--camera and --fov together are refused") {
        CaptureOptions options;
        options.intrinsics = parseCameraOption("70,70,39.5,29.5");
        options.horizontalFov = 90;
        requireError([&] { readCapture(photos, options); }, {"--camera", "--fov", "not both"}, std::nullopt,
                     ErrorKind::Usage);
    }
    SECTION("camera.json in the folder, scaled to the photos") {
        dir.write("photos/camera.json",
                  R"({"width": 160, "height": 120, "fx": 140, "fy": 140, "cx": 79.5, "cy": 59.5})");
        Capture capture = readCapture(photos);
        CHECK(capture.intrinsicsOrigin == IntrinsicsOrigin::Measured);
        CHECK(capture.intrinsics.width == 80);
        CHECK(capture.intrinsics.fx == Approx(70));
        CHECK(capture.intrinsics.cx == Approx(39.5));
        CHECK(hasNote(capture, dir.path("photos/camera.json")));
    }
    SECTION("a camera.json with a negative focal length is refused as mirrored") {
        dir.write("photos/camera.json", R"({"width": 80, "height": 60, "fx": -70, "fy": 70, "cx": 39.5, "cy": 29.5})");
        requireError([&] { readCapture(photos); }, {dir.path("photos/camera.json"), "fx", "mirrored"});
    }
}

TEST_CASE("photos' EXIF focal length (35 mm equivalent) gives their camera", "[capture][camera][exif]") {
    TempDir dir;
    writeExifJpeg(dir, "photos/a.jpg", colorImage(120, 80), {.focal35mm = 24});
    writeExifJpeg(dir, "photos/b.jpg", colorImage(120, 80), {.focal35mm = 24});
    REQUIRE(capture_detail::readExif(dir.path("photos/a.jpg")).focal35mm == 24);

    Capture capture = readCapture(dir.path("photos"));
    CHECK(capture.intrinsicsOrigin == IntrinsicsOrigin::Approximate);
    // 3:2 photos: the 35 mm frame's 36 mm width maps onto the 120 px width.
    CHECK(capture.intrinsics.fx == Approx(24.0 / 36.0 * 120));
    CHECK(hasNote(capture, "EXIF focal length (24 mm equivalent"));

    SECTION("one photo without EXIF: the guess for all, and how many had it") {
        writeColor(dir, "photos/c.jpg", 120, 80);
        Capture mixed = readCapture(dir.path("photos"));
        CHECK(mixed.intrinsicsOrigin == IntrinsicsOrigin::Guessed);
        CHECK(hasNote(mixed, "2 of 3 photos give an EXIF focal length"));
    }
}

TEST_CASE("photos stored on their side (EXIF orientation 6) are read upright", "[capture][camera][exif]") {
    TempDir dir;
    // Stored 64 x 48 (landscape), seen 48 x 64: the square of the top-left corner turns to the top right.
    auto writePhotos = [&](const ExifTags& tags) {
        for (const char* name : {"photos/a.jpg", "photos/b.jpg"}) writeExifJpeg(dir, name, markedImage(64, 48), tags);
        REQUIRE(capture_detail::readExif(dir.path("photos/a.jpg")).orientation == 6);
    };

    SECTION("frames and the guessed camera have the turned size") {
        writePhotos({.orientation = 6});
        Capture capture = readCapture(dir.path("photos"));
        CHECK(capture.intrinsicsOrigin == IntrinsicsOrigin::Guessed);
        CHECK(capture.intrinsics.width == 48);
        CHECK(capture.intrinsics.height == 64);
        CHECK(capture.intrinsics.fx == Approx(1.2 * 48));
        CHECK(capture.intrinsics.cx == Approx(23.5));
        CHECK(capture.intrinsics.cy == Approx(31.5));
        CHECK(hasNote(capture, "1.2 x width = 57.6"));
        for (const CaptureFrame& frame : capture.frames) {
            cv::Mat color = capture_detail::readRawFrame(frame).color;
            CHECK(color.cols == 48);
            CHECK(color.rows == 64);
            CHECK(brightCorner(color) == "top-right");
        }
    }
    SECTION("an EXIF focal length gives the camera at the turned size") {
        writePhotos({.focal35mm = 24, .orientation = 6});
        Capture capture = readCapture(dir.path("photos"));
        CHECK(capture.intrinsicsOrigin == IntrinsicsOrigin::Approximate);
        CHECK(capture.intrinsics.width == 48);
        CHECK(capture.intrinsics.height == 64);
        // The 35 mm frame's diagonal maps onto the photo's: 80 pixels whichever way it is turned.
        CHECK(capture.intrinsics.fx == Approx(24 * 80 / std::hypot(36.0, 24.0)));
        CHECK(capture.intrinsics.cx == Approx(23.5));
        CHECK(hasNote(capture, "for 48x64"));
    }
}

TEST_CASE("mirrored poses and cameras are refused, naming the frame", "[capture][camera][mirrored]") {
    TempDir dir;
    writeColor(dir, "images/0.png", 40, 30);
    writeColor(dir, "images/1.png", 40, 30);
    const std::string identity = R"([[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]])";
    const std::string mirrored = R"([[-1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]])";

    SECTION("a determinant -1 rotation in transforms.json") {
        dir.write("transforms.json", R"({"fl_x": 50, "w": 40, "h": 30, "frames": [)"
                                     R"({"file_path": "images/0.png", "transform_matrix": )" +
                                         identity + R"(}, {"file_path": "images/1.png", "transform_matrix": )" +
                                         mirrored + "}]}");
        requireError([&] { readCapture(dir.path()); },
                     {dir.path("transforms.json"), "frames[1]", "images/1.png", "mirrored", "determinant -1"});
    }
    SECTION("a negative focal length in transforms.json") {
        dir.write("transforms.json", R"({"fl_x": -50, "w": 40, "h": 30, "frames": [)"
                                     R"({"file_path": "images/0.png", "transform_matrix": )" +
                                         identity + "}]}");
        requireError([&] { readCapture(dir.path()); }, {dir.path("transforms.json"), "frames[0]", "mirrored"});
    }
    SECTION("a negative focal length in a COLMAP model") {
        dir.write("sparse/0/cameras.txt", "1 PINHOLE 40 30 -50 50 20 15\n");
        dir.write("sparse/0/images.txt", "1 1 0 0 0 0 0 0 1 0.png\n\n");
        requireError([&] { readCapture(dir.path()); }, {dir.path("sparse/0/cameras.txt") + ":1", "mirrored"});
    }
    SECTION("any reader's capture: a determinant -1 rotation names the frame") {
        Capture capture;
        capture.path = "walk";
        capture.intrinsics = Intrinsics{40, 30, 50, 50, 19.5, 14.5};
        capture.frames.resize(2);
        capture.frames[1].index = 1;
        capture.frames[1].colorPath = "images/1.png";
        capture.frames[0].pose = Pose{};
        capture.frames[1].pose = Pose{{1, 0, 0, 0, -1, 0, 0, 0, 1}, {}};
        requireError([&] { capture_detail::refuseMirroredCameras(capture); },
                     {"frame 1 (images/1.png)", "mirrored (left-handed)", "determinant -1"});
        capture.frames[1].pose = Pose{};
        capture.frames[1].intrinsics = Intrinsics{40, 30, 50, -50, 19.5, 14.5};
        requireError([&] { capture_detail::refuseMirroredCameras(capture); }, {"frame 1 (images/1.png)", "mirrored"});
    }
}
