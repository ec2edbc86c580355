#include "ingest/pipeline/request.hpp"

#include <charconv>
#include <filesystem>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "ingest/pipeline/object_finder.hpp"
#include "model/error.hpp"
#include "model/names.hpp"

namespace smql::ingest {

namespace fs = std::filesystem;

namespace {

// The highest --camera-height taken (m): above a person's reach on a pole, and far below a height in centimetres.
constexpr double kHighestCamera = 5;

[[noreturn]] void badValue(std::string_view name, const std::string& value, const std::string& takes) {
    throw Error(ErrorKind::Usage, fmt::format("{} {}: not a valid value", optionFlag(name), value), std::nullopt,
                fmt::format("{} takes {}", optionFlag(name), takes));
}

double number(std::string_view name, const std::string& value, bool zeroAllowed) {
    double out = 0;
    auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), out);
    if (ec != std::errc() || end != value.data() + value.size() || !(out > 0 || (zeroAllowed && out == 0)))
        badValue(name, value, zeroAllowed ? "a number, 0 or more" : "a number above 0");
    return out;
}

std::string existingFile(std::string_view name, const std::string& value) {
    std::error_code ec;
    if (!fs::is_regular_file(value, ec))
        throw Error(ErrorKind::Usage, fmt::format("{} {}: no such file", optionFlag(name), value));
    return value;
}

std::string oneOf(std::string_view name, const std::string& value, const std::vector<std::string>& names) {
    for (const auto& n : names)
        if (n == value) return value;
    std::string hint = fmt::format("{} takes {}", optionFlag(name), model::joinAlternatives(names));
    if (auto close = model::nearestNames(value, names, 1); !close.empty())
        hint = fmt::format("did you mean {}? {}", close.front(), hint);
    throw Error(ErrorKind::Usage, fmt::format("{} {}: not a known value", optionFlag(name), value), std::nullopt, hint);
}

// The words of the options that choose among a few ways, each with the way it names: the option's
// check, its help and the request's mapping to IngestOptions all read them here.
template <class Way>
using Words = std::vector<std::pair<std::string, Way>>;
const Words<GeometrySource> kGeometryWords = {
    {"given", GeometrySource::Given}, {"colmap", GeometrySource::Colmap}, {"auto", GeometrySource::Auto}};
const Words<DenseUse> kDenseWords = {
    {"auto", DenseUse::Auto}, {"room", DenseUse::Room}, {"on", DenseUse::All}, {"off", DenseUse::Off}};

template <class Way>
std::vector<std::string> wordsOf(const Words<Way>& words) {
    std::vector<std::string> out;
    for (const auto& word : words) out.push_back(word.first);
    return out;
}

// An option's value as --help shows it: given|colmap|auto.
std::string wordList(const std::vector<std::string>& words) { return fmt::format("{}", fmt::join(words, "|")); }

// The way a word that oneOf accepted names.
template <class Way>
Way wayOf(const Words<Way>& words, const std::string& word) {
    for (const auto& [w, way] : words)
        if (w == word) return way;
    throw std::logic_error("an option's word not among its words: " + word);
}

// The table's rows. Help texts are functions because some are made from other tables (objects).
const std::vector<IngestOption> kIngestOptions = {
    {"scene", "TEXT", [] { return std::string("scene name (default: the capture's folder name)"); },
     [](IngestRequest& r, const std::string& v) { r.scene = v; }},
    {"geometry", wordList(wordsOf(kGeometryWords)),
     [] {
         return std::string(
             "given (the capture's poses), colmap (structure from motion on the colour frames) or auto (default: "
             "colmap when some frame has no pose, or without depth: then with the given poses)");
     },
     [](IngestRequest& r, const std::string& v) { r.geometry = oneOf("geometry", v, wordsOf(kGeometryWords)); }},
    {"objects", wordList(objectSourceNames()), objectSourcesHelp,
     [](IngestRequest& r, const std::string& v) { r.objects = oneOf("objects", v, objectSourceNames()); }},
    {"detector", "FILE",
     [] {
         return std::string(
             "NanoDet ONNX model for --objects detect (default: the one scripts/detector/setup.sh "
             "installs)");
     },
     [](IngestRequest& r, const std::string& v) { r.detector = existingFile("detector", v); }},
    {"classes", "FILE",
     [] { return std::string("the detector's class names, one a line (default: coco.names beside the model)"); },
     [](IngestRequest& r, const std::string& v) { r.classes = existingFile("classes", v); }},
    {"video_frames", "FOLDER",
     [] {
         return std::string(
             "a video's decoded frames go to this folder and stay there (default: a new folder under /tmp, named in "
             "a note)");
     },
     [](IngestRequest& r, const std::string& v) { r.videoFrames = v; }},
    {"fps", "NUMBER",
     [] {
         return std::string("frames per second kept from videos and TUM sequences (default 1; 0 keeps every frame)");
     },
     [](IngestRequest& r, const std::string& v) { r.fps = number("fps", v, true); }},
    {"camera", "FX,FY,CX,CY[,K1,K2,P1,P2,K3]",
     [] {
         return std::string(
             "the camera in pixels of the images as stored, and its lens's distortion in OpenCV's order when known "
             "(default: the capture's camera.json or calibration, else the photos' EXIF focal length, else a stated "
             "guess); COLMAP keeps it fixed");
     },
     [](IngestRequest& r, const std::string& v) {
         parseCameraOption(v);  // checked now, not after the capture is read
         r.camera = v;
     }},
    {"fov", "DEGREES",
     [] {
         return std::string("the horizontal field of view, when only that is known (COLMAP refines the focal length)");
     },
     [](IngestRequest& r, const std::string& v) { r.fov = checkFieldOfView(number("fov", v, false)); }},
    {"max_size", "PIXELS",
     [] {
         return std::string(
             "COLMAP sees the frames scaled down to this many pixels on the long side (default 1024, 0 = as "
             "stored); poses and intrinsics come back in the frames' own pixels");
     },
     [](IngestRequest& r, const std::string& v) {
         double size = number("max_size", v, true);
         if (size != static_cast<int>(size)) badValue("max_size", v, "a whole number of pixels");
         r.maxSize = static_cast<int>(size);
     }},
    {"vocab_tree", "FILE",
     [] {
         return std::string(
             "a COLMAP vocabulary tree (vocab_tree_*.bin) for loop detection in sequential matching (Debian ships "
             "none; without it, loops are closed by matching 30 frames spread through the capture all against "
             "all)");
     },
     [](IngestRequest& r, const std::string& v) { r.vocabularyTree = existingFile("vocab_tree", v); }},
    {"colmap_dir", "FOLDER",
     [] {
         return std::string(
             "COLMAP works in this folder and leaves it (default: a new folder under /tmp, removed after a "
             "success); a later ingest of the same frames reads the finished run back instead of running COLMAP "
             "again");
     },
     [](IngestRequest& r, const std::string& v) { r.colmapDir = v; }},
    {"dense", wordList(wordsOf(kDenseWords)),
     [] {
         return std::string(
             "photos without depth: dense points from pairs of placed frames, beside COLMAP's sparse ones; auto "
             "(the default): the floor, walls and scale are found among them, and the things are lifted on their "
             "depth where the points cover most of what the detectors saw; room: the floor, walls and scale only; "
             "on: the things always; off: COLMAP's points alone (docs/ingest.md, \"Dense points from placed "
             "photos\")");
     },
     [](IngestRequest& r, const std::string& v) { r.dense = oneOf("dense", v, wordsOf(kDenseWords)); }},
    {"scale", "NUMBER", [] { return std::string("metres per capture unit, overriding the estimate"); },
     [](IngestRequest& r, const std::string& v) { r.scale = number("scale", v, false); }},
    {"camera_height", "METRES",
     [] {
         return fmt::format(
             "photos without depth: the cameras' median height above the floor, when known (a robot's mounted "
             "camera, a tripod; at most {:g}); the scale then stands on it, the things' heights checking it, where "
             "a person's 1.50 m is assumed otherwise",
             kHighestCamera);
     },
     [](IngestRequest& r, const std::string& v) {
         // Metres, as every length of the memory: 150 is a height in centimetres.
         const double height = number("camera_height", v, false);
         if (height > kHighestCamera)
             badValue("camera_height", v, fmt::format("metres above the floor, at most {:g}", kHighestCamera));
         r.cameraHeight = height;
     }},
    {"depth_scale", "NUMBER",
     [] {
         return std::string(
             "units of the depth images per metre (1000 for millimetres, 5000 for TUM's), overriding the "
             "capture's camera.json and the layout's default");
     },
     [](IngestRequest& r, const std::string& v) { r.depthScale = number("depth_scale", v, false); }},
    {"update", "SCENE",
     [] {
         return std::string(
             "make the capture the next version of this stored scene of the same place (docs/history.md) instead "
             "of adding a new scene");
     },
     [](IngestRequest& r, const std::string& v) { r.update = v; }},
    {"force", "",
     [] {
         return std::string(
             "store the memory even when it does not look like a room (cameras, ceiling or things of implausible "
             "size: a wrong depth unit or scale, docs/ingest.md \"Plausibility\"); it is refused otherwise");
     },
     [](IngestRequest& r, const std::string& v) {
         if (v != "true" && v != "false" && v != "1" && v != "0") badValue("force", v, "true or false");
         r.force = v == "true" || v == "1";
     }},
};

}  // namespace

const std::vector<IngestOption>& ingestOptions() { return kIngestOptions; }

std::string optionFlag(std::string_view name) {
    std::string flag = "--" + std::string(name);
    for (char& c : flag)
        if (c == '_') c = '-';
    return flag;
}

void setIngestOption(IngestRequest& request, std::string_view name, const std::string& value) {
    std::vector<std::string> names;
    for (const auto& option : kIngestOptions) {
        if (option.name == name) return option.set(request, value);
        names.emplace_back(option.name);
    }
    std::string hint = "the options are " + model::joinAlternatives(names);
    if (auto close = model::nearestNames(name, names, 1); !close.empty())
        hint = fmt::format("did you mean {}? {}", close.front(), hint);
    throw Error(ErrorKind::Usage, fmt::format("unknown ingest option '{}'", name), std::nullopt, hint);
}

std::string sceneNameOf(const IngestRequest& request) {
    if (!request.scene.empty()) return request.scene;
    fs::path capture = fs::absolute(request.capture).lexically_normal();
    std::string name = capture.filename().string();
    return name.empty() ? capture.parent_path().filename().string() : name;
}

IngestRun runIngest(const IngestRequest& request, ProgressSink& progress, const std::function<bool()>& cancelled) {
    if (!request.camera.empty() && request.fov)
        throw Error(ErrorKind::Usage, "--camera and --fov both say what the camera is", std::nullopt,
                    "give one: --camera when the focal length is known, --fov when only the field of view is");
    if (request.scale && request.cameraHeight)
        throw Error(ErrorKind::Usage, "--scale and --camera-height both say what the scale is", std::nullopt,
                    "give one: --camera-height when the cameras' height above the floor is known, --scale when the "
                    "metres per capture unit are");
    CaptureOptions captureOptions;
    captureOptions.fps = request.fps;
    if (!request.camera.empty()) captureOptions.intrinsics = parseCameraOption(request.camera);
    captureOptions.horizontalFov = request.fov;
    captureOptions.depthScale = request.depthScale;
    captureOptions.workDirectory = request.videoFrames;
    IngestRun run;
    Capture capture = readCapture(request.capture, captureOptions);
    run.frames = capture.frames.size();
    progress.captureRead(run.frames);

    IngestOptions options;
    options.sceneName = sceneNameOf(request);
    options.geometry = wayOf(kGeometryWords, request.geometry);
    options.objects = request.objects;
    options.detectorModel = request.detector;
    options.detectorClasses = request.classes;
    options.scale = request.scale;
    options.cameraHeight = request.cameraHeight;
    options.force = request.force;
    options.colmap.maxImageSize = request.maxSize;
    options.colmap.vocabularyTree = request.vocabularyTree;
    options.colmap.workDirectory = request.colmapDir;
    options.dense = wayOf(kDenseWords, request.dense);
    run.result = ingestCapture(capture, options, progress, cancelled);
    return run;
}

}  // namespace smql::ingest
