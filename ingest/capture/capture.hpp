// A capture as the ingest pipeline sees it, whatever layout it came in:
// frames (colour, optional depth and instance masks), camera intrinsics and,
// when known, camera poses. Readers in this folder fill it; they check every
// file they name exists and is readable, so later stages can trust it.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "model/types.hpp"

namespace smql::ingest {

// A camera in pixels: a pinhole, and the lens's distortion when it has one. Pixel centres sit at
// integer coordinates (the OpenCV convention: the top-left pixel's centre is (0, 0)).
// Capture::intrinsics describe the images as stored (width x height); loadFrame returns the images
// undistorted and scaled to the working resolution, with a pinhole's intrinsics.
struct Intrinsics {
    int width = 0, height = 0;
    double fx = 0, fy = 0, cx = 0, cy = 0;
    // OpenCV's coefficients in OpenCV's order (k1, k2, p1, p2, k3, k4, k5, k6: radial, tangential, then the
    // rational model's denominator), of normalised image coordinates, so the same at any image size. All zero:
    // no distortion. camera.json, COLMAP's cameras (SIMPLE_RADIAL, RADIAL, OPENCV, FULL_OPENCV) and
    // transforms.json fill them.
    std::array<double, 8> distortion{};
    bool distorted() const;
    friend bool operator==(const Intrinsics&, const Intrinsics&) = default;
};

// The names camera.json, transforms.json and --camera give the distortion's first coefficients, in OpenCV's order.
inline constexpr std::array<std::string_view, 5> kDistortionNames{"k1", "k2", "p1", "p2", "k3"};

// Camera-to-world: a world point is rotation * p_camera + translation. The
// camera looks along +z with x to the right and y down (the OpenCV convention).
struct Pose {
    std::array<double, 9> rotation = {1, 0, 0, 0, 1, 0, 0, 0, 1};  // row-major
    model::Vec3 translation;
};

struct CaptureFrame {
    int index = 0;             // position in the capture, from 0
    double time = 0;           // seconds from the start (index / fps when the layout has no times)
    std::string colorPath;     // an image OpenCV reads
    std::string depthPath;     // 16-bit depth image (PNG or PGM), empty without depth
    std::string instancePath;  // 16-bit instance mask (0 = none), empty without masks
    std::optional<Pose> pose;
    // This frame's own camera when it differs from Capture::intrinsics (COLMAP
    // models with several cameras, nerfstudio per-frame intrinsics).
    std::optional<Intrinsics> intrinsics;
};

// Where a capture's intrinsics came from. COLMAP keeps measured intrinsics
// fixed, refines approximate ones, and estimates guessed ones itself.
enum class IntrinsicsOrigin {
    Measured,     // --camera, camera.json, the layout's own calibration (COLMAP, nerfstudio)
    Approximate,  // --fov, EXIF focal length (35 mm equivalent)
    Guessed,      // nothing known: fx = fy = 1.2 x width (images, videos) or a Kinect's (RGB-D)
};

struct SparsePoint {
    model::Vec3 position;
    std::array<std::uint8_t, 3> color{};
};

struct Capture {
    std::string path;    // what the user named
    std::string layout;  // rgbd | tum | nerfstudio | colmap | images | video | synth
    Intrinsics intrinsics;
    IntrinsicsOrigin intrinsicsOrigin = IntrinsicsOrigin::Measured;
    double depthScale = 1000;  // depth image units per metre
    bool metric = true;        // poses and points in metres (sensors) or up to scale (SfM)
    std::vector<CaptureFrame> frames;
    std::vector<SparsePoint> points;  // reconstructed 3D points, when the layout has them
    // Points of the dense stage (dense_stereo.hpp) for photos without depth, one a voxel `denseSpacing`
    // wide: the structure (floor, walls, the scale's priors) and, once the room is aligned, each frame's
    // depth for its detections (objects_from_detections.cpp).
    std::vector<SparsePoint> densePoints;
    double denseSpacing = 0;     // capture units
    std::string labelsPath;      // instance id -> category (+ attributes), JSON, with masks
    std::string detectionsPath;  // COCO-results style detections, JSON
    // What the reader assumed or ignored (default intrinsics, ignored lens
    // distortion, where decoded video frames went...), one sentence each, for
    // the user: the pipeline prints them.
    std::vector<std::string> notes;
};

struct CaptureOptions {
    double fps = 1.0;        // sampling of videos and TUM sequences (0 = every frame); image folders keep every image
    int workingWidth = 640;  // frames wider than this are scaled down (docs/ingest.md)
    std::optional<double> depthScale;
    std::optional<Intrinsics> intrinsics;  // --camera (width, height 0: the images' size)
    std::optional<double> horizontalFov;   // --fov, degrees: fx = fy from the image width, centred principal point
    std::string workDirectory;             // where decoded video frames go (a temp folder by default)
    std::string imageDirectory;            // COLMAP: the images the model was made from (found beside it by default)
};

// `--camera fx,fy,cx,cy` in pixels of the images as stored. Throws
// smql::Error(Usage) naming the bad value (mirrored cameras, a negative focal
// length, are refused).
Intrinsics parseCameraOption(std::string_view text);
// `--fov DEG`: the horizontal field of view, checked (0 < DEG < 180).
double checkFieldOfView(double degrees);

// Recognises the layout of `path` (a folder or a file) and reads it. Throws
// smql::Error(ErrorKind::Input) naming the file and what is wrong. Layouts and
// the detection order: docs/formats.md, "Captures (smql ingest)". A mirrored
// (left-handed) camera, a pose whose rotation has determinant -1 or a negative
// focal length, is refused naming the frame.
Capture readCapture(const std::string& path, const CaptureOptions& options = {});

// The camera of each frame of a folder of images named by frame number (`colorDir`, with
// `depthDir` beside it when there is one) from `poseFile`, in frame order: pose.txt's lines
// matched to frame numbers as the rgbd layout matches them, gaps included. `smql check-ingest`
// pairs stored frames with their true cameras by it.
std::vector<Pose> posesInFrameOrder(const std::string& poseFile, const std::string& colorDir,
                                    const std::string& depthDir);

}  // namespace smql::ingest
