// Helpers shared by the capture readers and the frame loader: errors, file
// listing, text lines, numbers, poses, default intrinsics and image checks.
// Internal to ingest/capture.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>

#include "ingest/capture/capture.hpp"

namespace smql::ingest::capture_detail {

namespace fs = std::filesystem;

// Hints, one per layout, recalled in every error about that layout.
inline constexpr const char* kRgbdHint =
    "an rgbd capture is a folder with color/ and depth/ (images named by frame number: 1.png, 2.png... "
    "depth 16-bit PNG or PGM) and pose.txt (one line per frame: tx ty tz qx qy qz qw, camera-to-world); "
    "camera.json {width,height,fx,fy,cx,cy,depth_scale} is optional";
inline constexpr const char* kTumHint =
    "a TUM RGB-D capture holds rgb.txt and depth.txt ('timestamp file' per line) and groundtruth.txt "
    "('timestamp tx ty tz qx qy qz qw'); lines starting with '#' are comments";
inline constexpr const char* kNerfstudioHint =
    "transforms.json needs fl_x (or camera_angle_x), w, h and frames[] with file_path and a 4x4 "
    "transform_matrix (camera-to-world, OpenGL convention); depth_file_path is optional";
inline constexpr const char* kColmapHint =
    "a COLMAP sparse model is cameras.txt, images.txt, points3D.txt (or the .bin files) as written by "
    "`colmap mapper` / `colmap model_converter`; the images go in images/ beside the model or are named "
    "with the image-directory option";
inline constexpr const char* kImagesHint = "an image folder holds .jpg, .jpeg or .png files, read in natural order";
inline constexpr const char* kVideoHint = "any video OpenCV's videoio (FFmpeg) decodes: mp4, avi, mov, mkv...";

// smql::Error(Input) "<file>: <what>", or "<file>:<line>: <what>" with the line in where().
[[noreturn]] void fail(const std::string& file, std::string_view what, std::string_view hint = {});
[[noreturn]] void failAt(const std::string& file, int line, std::string_view what, std::string_view hint = {});

std::string lowerCase(std::string_view text);
std::string extensionOf(const fs::path& path);  // lower case, without the dot
bool isImageExtension(std::string_view ext);    // jpg, jpeg, png
bool isVideoExtension(std::string_view ext);

// "2.png" < "10.png": runs of digits compare as numbers.
bool naturalLess(std::string_view a, std::string_view b);

// Regular files directly in `dir`, hidden ones (".x") left out, in natural order of their names.
std::vector<fs::path> listFiles(const fs::path& dir);

// The stem as a frame number when it is all digits ("0007" -> 7).
std::optional<long long> frameNumber(const fs::path& file);

// The whole text file; errors name the file.
std::string readText(const fs::path& file, std::string_view hint);

// Lines that hold data: blank lines and '#' comments are skipped. `number` is 1-based.
struct TextLine {
    int number = 0;
    std::string_view text;
};
std::vector<TextLine> dataLines(std::string_view text);
// Every line, numbered, blank ones included (COLMAP's images.txt needs them).
std::vector<TextLine> allLines(std::string_view text);
std::vector<std::string_view> splitWhitespace(std::string_view text);

// A whole token as a number; std::nullopt when it is not one. NaN and infinity
// parse (so that the caller can say "not finite" rather than "not a number").
std::optional<double> parseNumber(std::string_view token);
// Every token as a finite number, or an error at file:line naming the token.
std::vector<double> parseNumbers(const std::string& file, int line, const std::vector<std::string_view>& tokens,
                                 std::string_view hint);

// Camera-to-world pose from a translation and a quaternion; the quaternion is
// normalised. Errors (non-finite, zero norm) at file:line.
Pose poseFromQuaternion(const std::string& file, int line, double tx, double ty, double tz, double qx, double qy,
                        double qz, double qw, std::string_view hint);
Pose inverse(const Pose& pose);

// Where a camera or point may be: within import::detail::kMaxCoordinate
// (10 km) of the origin on every axis, as imported scenes. A pose of 1e39 m
// becomes Inf in the single-precision clouds and aborts PCL; anything beyond
// a few km is a unit mix-up or a geo-referenced model, never a room.
// Throws an Input error at file:line naming `what` ("the camera of frame 3").
void checkPosition(const std::string& file, int line, std::string_view what, const model::Vec3& position,
                   std::string_view hint);

// Kinect default (fx = fy = 525 at 640 px wide, centred principal point).
Intrinsics kinectDefault(int width, int height);
// A guess for an unknown camera: fx = fy = 1.2 * width, centred principal point.
Intrinsics guessedIntrinsics(int width, int height);
// Scales intrinsics to an image of another size (same camera, resized image).
Intrinsics scaleIntrinsics(const Intrinsics& in, int width, int height);
// Options' intrinsics, checked, with width/height 0 meaning "the images' size".
Intrinsics userIntrinsics(const Intrinsics& given, int width, int height);
void checkDepthScale(double scale, const std::string& from);

// The camera the options give (--camera, else --fov) for images of width x
// height, or std::nullopt; optionName says which ("--camera"), optionOrigin
// how well it is known (camera_source.cpp).
std::optional<Intrinsics> optionIntrinsics(const CaptureOptions& options, int width, int height);
const char* optionName(const CaptureOptions& options);
IntrinsicsOrigin optionOrigin(const CaptureOptions& options);
inline bool hasOptionIntrinsics(const CaptureOptions& options) {
    return options.intrinsics.has_value() || options.horizontalFov.has_value();
}
// The options' camera in place of the one the capture's `file` gave, for its first frame's size;
// either must fit that size (fitIntrinsics below), to which each frame's is scaled as it is read.
void takeOptionIntrinsics(Capture& capture, const CaptureOptions& options, const std::string& file);

// What a photo's EXIF says about its camera (libexif; nothing for files without EXIF).
struct ExifCamera {
    std::optional<double> focal35mm;  // FocalLengthIn35mmFilm, millimetres
    int orientation = 1;              // 1 = as stored; others: OpenCV turns the image when it reads it
};
ExifCamera readExif(const fs::path& file);
// A pinhole camera with the 35 mm equivalent focal length's diagonal field of view, centred.
Intrinsics intrinsicsFrom35mm(double focal35mm, int width, int height);

// Throws smql::Error(Input) naming the frame when a pose is mirrored (its
// rotation's determinant is not positive) or a focal length is not positive.
void refuseMirroredCameras(const Capture& capture);

// A capture's image files, checked before anything is decoded by a cheap look at each file's bytes: each
// must exist, have a signature OpenCV recognises, and end where its format says it ends (cutShort). An image
// cut short decodes in part without an error (libjpeg fills the rest grey), so it would be taken as it is; and
// a capture copied or downloaded in part has many such, so one error names every one (refuseUnreadable).
// An image past kMaxImagePixels is refused at once, with its own hint.
class ImageFileChecks {
public:
    explicit ImageFileChecks(std::string_view hint) : hint_(hint) {}
    // `what` names the file's role ("colour image"). Whether it can be read.
    bool check(const fs::path& file, std::string_view what);
    // Throws smql::Error(Input) naming each file that cannot be read, and why, when any cannot.
    void refuseUnreadable() const;

private:
    std::string hint_;
    std::vector<std::pair<std::string, std::string>> unreadable_;  // the file, why
};

// Why a file with a PNG's, a JPEG's or a binary PGM's signature ends before its format says it ends: a PNG
// without its end chunk (IEND) in its last 4 KiB, a JPEG with no end-of-image marker after its first scan (a
// trailer after that marker, as a phone's motion photo has, is no damage), a PGM shorter than its header's
// pixels; nullopt otherwise (other formats are left to their decoders).
std::optional<std::string> cutShort(const fs::path& file);

// The most pixels an image may have (docs/ingest.md, "Bounds"): 100 megapixels, 300 MB decoded.
// Checked on the file's header before anything is decoded.
inline constexpr long long kMaxImagePixels = 100'000'000;
// OpenCV's bound on a decoded image's side (CV_IO_MAX_IMAGE_WIDTH and _HEIGHT): past it imdecode throws,
// so the decoders here leave such an image to it.
inline constexpr int kMaxDecodedSide = 1 << 20;
// Width and height as a PNG's, a JPEG's or a binary PGM's header states them; nullopt for other formats (OpenCV
// then decodes them under its own bound) and for headers it cannot read.
std::optional<std::pair<int, int>> storedImageSize(const fs::path& file);

// Decoded images; errors name the file.
cv::Mat readColorImage(const std::string& file);
cv::Mat readDepthImage(const std::string& file);  // CV_16U or CV_32F, one channel
cv::Mat readMaskImage(const std::string& file);   // CV_16U, one channel (8-bit masks are widened)

// Whether two images have one aspect ratio: the second's height within a pixel of the first's scaled to its width.
bool sameAspect(cv::Size a, cv::Size b);

// A frame's images as stored, decoded, with depth and mask sizes checked against the colour image (errors name the
// file and both sizes). A depth image of another size with the colour image's aspect ratio (sameAspect) is
// registered to the colour camera at another resolution (a phone's LiDAR depth of 256 x 192 beside colour of
// 1920 x 1440); loadFrame resizes it once, to the size it gives the colour, each pixel the nearest reading.
struct RawFrame {
    cv::Mat color;      // CV_8UC3
    cv::Mat depth;      // CV_16U or CV_32F, the colour image's aspect ratio; empty without depth
    cv::Mat instances;  // CV_16U, the colour image's size; empty without masks
};
RawFrame readRawFrame(const CaptureFrame& frame);
// The capture's note for depth read at another resolution than the colour (readRawFrame), from a frame with depth;
// nothing when the two have one size.
std::optional<std::string> depthResolutionNote(const RawFrame& frame);

// Intrinsics for an image of width x height: scaled when they were given for
// another size with the same aspect ratio, else an error naming the image.
Intrinsics fitIntrinsics(const Intrinsics& in, int width, int height, const std::string& imageFile,
                         std::string_view source);

// camera.json of rgbd (and TUM) captures: {width,height,fx,fy,cx,cy,depth_scale}.
struct CameraJson {
    Intrinsics intrinsics;
    std::optional<double> depthScale;
};
CameraJson readCameraJson(const fs::path& file, std::string_view hint);

// A JSON file the capture names (labels, detections): its path, once it parses.
std::string checkedJson(const fs::path& file, std::string_view hint);

// Keeps the first time of every 1/fps step: a time is taken when it reaches the
// next target minus `tolerance`. fps <= 0 keeps every time.
class Sampler {
public:
    Sampler(double fps, double tolerance) : step_(fps > 0 ? 1.0 / fps : 0), tolerance_(tolerance) {}
    bool take(double time);

private:
    double step_;
    double tolerance_;
    std::optional<double> next_;
};

// A capture layout: how a path (a folder or a file) is recognised as one, and its reader. The
// layouts are one table (capture_layouts.cpp); readCapture tries them in its order, and its hint
// and its error for a path no layout recognises are made from the rows.
struct CaptureLayout {
    std::string_view name;      // "rgbd"
    std::string_view reads;     // what the hint says it reads: "an rgbd folder (color/ depth/ pose.txt)"
    std::string_view looksFor;  // what the error says was looked for: "color/ and depth/ folders (rgbd)"
    // The path the reader takes when `target` is one of its captures (the folder, transforms.json,
    // the model's folder), else nothing; what it chose on the way goes to `notes`.
    std::optional<fs::path> (*recognise)(const fs::path& target, std::vector<std::string>& notes);
    Capture (*read)(const fs::path& path, const CaptureOptions& options);
};
// Every layout, in the order they are tried.
const std::vector<const CaptureLayout*>& captureLayouts();
// "smql reads: an rgbd folder (...), ..., or a video file": the hint of a capture smql cannot read.
const std::string& layoutsHint();

bool isDirectory(const fs::path& path);
bool isFile(const fs::path& path);

// One reader per layout. `dir` is the folder (or file) the layout was found in.
Capture readRgbd(const fs::path& dir, const CaptureOptions& options);
Capture readTum(const fs::path& dir, const CaptureOptions& options);
Capture readNerfstudio(const fs::path& transformsFile, const CaptureOptions& options);
Capture readColmap(const fs::path& modelDir, const CaptureOptions& options);
Capture readImageFolder(const fs::path& dir, const CaptureOptions& options);
Capture readVideo(const fs::path& file, const CaptureOptions& options);

// The COLMAP model files in `dir` ("bin" or "txt"), or std::nullopt.
std::optional<std::string> colmapModelFormat(const fs::path& dir);

}  // namespace smql::ingest::capture_detail
