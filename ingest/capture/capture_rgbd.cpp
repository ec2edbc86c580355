// RGB-D captures: our rgbd folder (color/ depth/ pose.txt) and the TUM RGB-D
// benchmark layout (rgb.txt depth.txt groundtruth.txt).
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "ingest/capture/capture_detail.hpp"
#include "ingest/import/json_field.hpp"
#include "model/error.hpp"

namespace smql::ingest::capture_detail {

namespace {

using import::detail::Field;
using import::detail::JsonSource;

double frameTime(int index, double fps) { return fps > 0 ? index / fps : index; }

bool pathExists(const fs::path& path) {
    std::error_code ec;
    return fs::exists(path, ec);
}

// The camera of an RGB-D capture: the intrinsics option, else camera.json, else the Kinect default
// (with the note `defaultNote` words), fitted to the first frame's size; and the depth scale: the
// option, else camera.json's, else `defaultDepthScale`.
void chooseCamera(Capture& capture, const CaptureOptions& options, const fs::path& cameraFile, std::string_view hint,
                  double defaultDepthScale,
                  const std::function<std::string(const Intrinsics&, int width, int height)>& defaultNote) {
    std::optional<CameraJson> camera;
    if (pathExists(cameraFile)) camera = readCameraJson(cameraFile, hint);
    RawFrame first = readRawFrame(capture.frames.front());
    const int width = first.color.cols, height = first.color.rows;
    if (auto note = depthResolutionNote(first)) capture.notes.push_back(*note);
    if (std::optional<Intrinsics> given = optionIntrinsics(options, width, height)) {
        capture.intrinsics = *given;
        capture.intrinsicsOrigin = optionOrigin(options);
    } else if (camera) {
        capture.intrinsics = camera->intrinsics;
    } else {
        capture.intrinsics = kinectDefault(width, height);
        capture.intrinsicsOrigin = IntrinsicsOrigin::Guessed;
        capture.notes.push_back(defaultNote(capture.intrinsics, width, height));
    }
    capture.intrinsics = fitIntrinsics(capture.intrinsics, width, height, capture.frames.front().colorPath,
                                       hasOptionIntrinsics(options) ? optionName(options) : cameraFile.string());
    capture.depthScale = options.depthScale             ? *options.depthScale
                         : camera && camera->depthScale ? *camera->depthScale
                                                        : defaultDepthScale;
}

// Images named by frame number in `dir`, in numeric order.
std::vector<std::pair<long long, fs::path>> numberedImages(const fs::path& dir, std::string_view what,
                                                           std::vector<std::string>& notes) {
    std::vector<std::pair<long long, fs::path>> out;
    std::vector<std::string> ignored;
    for (const fs::path& file : listFiles(dir)) {
        if (std::optional<long long> number = frameNumber(file))
            out.emplace_back(*number, file);
        else
            ignored.push_back(file.filename().string());
    }
    std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t i = 1; i < out.size(); ++i)
        if (out[i].first == out[i - 1].first)
            fail(out[i].second.string(),
                 fmt::format("two {}s for frame {}: {} and {}", what, out[i].first,
                             out[i - 1].second.filename().string(), out[i].second.filename().string()),
                 kRgbdHint);
    if (!ignored.empty())
        notes.push_back(fmt::format("{}: ignored {} file(s) not named by a frame number ({}{})", dir.string(),
                                    ignored.size(), ignored.front(), ignored.size() > 1 ? ", ..." : ""));
    return out;
}

std::vector<Pose> readPoseFile(const fs::path& file) {
    std::string text = readText(file, kRgbdHint);
    std::vector<Pose> poses;
    for (const TextLine& line : dataLines(text)) {
        std::vector<std::string_view> tokens = splitWhitespace(line.text);
        if (tokens.size() != 7)
            failAt(file.string(), line.number,
                   fmt::format("expected 7 numbers (tx ty tz qx qy qz qw), got {}", tokens.size()), kRgbdHint);
        std::vector<double> v = parseNumbers(file.string(), line.number, tokens, kRgbdHint);
        poses.push_back(
            poseFromQuaternion(file.string(), line.number, v[0], v[1], v[2], v[3], v[4], v[5], v[6], kRgbdHint));
        checkPosition(file.string(), line.number,
                      fmt::format("the camera of frame {} (in frame-number order)", poses.size()),
                      poses.back().translation, kRgbdHint);
    }
    return poses;
}

// Which pose line is which frame's. Line i holds the pose of the i-th frame in frame-number order,
// counting every frame the capture has an image of (colour or depth): a colour image deleted from
// the middle of a capture leaves its depth image, so the poses after it stay with their frames
// (that frame is skipped, with a note). When the numbers have a gap that no image fills and the
// file has a line for every number from the first to the last, line i is frame first + i. Any
// other count cannot be matched and is an error, never a shift.
std::map<long long, Pose> posesByFrame(const std::vector<Pose>& poses,
                                       const std::vector<std::pair<long long, fs::path>>& colors,
                                       const std::map<long long, fs::path>& depths, const fs::path& poseFile,
                                       std::vector<std::string>& notes) {
    std::set<long long> roster;
    for (const auto& [number, path] : colors) roster.insert(number);
    for (const auto& [number, path] : depths) roster.insert(number);
    const long long first = *roster.begin(), last = *roster.rbegin();
    const auto span = static_cast<std::size_t>(last - first + 1);
    std::map<long long, Pose> out;
    if (poses.size() >= roster.size() && (roster.size() == span || poses.size() < span)) {
        std::size_t line = 0;
        for (long long number : roster) out[number] = poses[line++];
        if (poses.size() > roster.size())
            notes.push_back(fmt::format("{} has {} pose lines for {} frames: the extra lines are ignored",
                                        poseFile.string(), poses.size(), roster.size()));
    } else if (poses.size() >= span) {
        for (long long number : roster) out[number] = poses[static_cast<std::size_t>(number - first)];
        notes.push_back(fmt::format("{}: frames {} to {} have gaps; pose line i is frame {} + i", poseFile.string(),
                                    first, last, first));
    } else {
        fail(poseFile.string(),
             fmt::format("{} pose line(s) for {} frames: line i holds the pose of the i-th frame in frame-number order",
                         poses.size(), roster.size()),
             kRgbdHint);
    }
    return out;
}

}  // namespace

std::string checkedJson(const fs::path& file, std::string_view hint) {
    import::detail::parseJsonFile(JsonSource{file.string(), std::string(hint)});
    return file.string();
}

CameraJson readCameraJson(const fs::path& file, std::string_view hint) {
    JsonSource source{file.string(), std::string(hint)};
    import::detail::Json json = import::detail::parseJsonFile(source);
    Field root(json, source);
    root.allowOnly({"width", "height", "fx", "fy", "cx", "cy", "k1", "k2", "p1", "p2", "k3", "depth_scale"});
    CameraJson out;
    auto positiveInt = [&](std::string_view key) {
        Field f = root.at(key);
        std::int64_t v = f.integer();
        if (v <= 0 || v > 100000) f.fail(fmt::format("expected a positive number of pixels, got {}", v));
        return static_cast<int>(v);
    };
    auto positive = [&](const Field& f) {
        double v = f.number();
        if (v <= 0) f.fail(fmt::format("expected a positive number, got {}", v));
        return v;
    };
    auto focal = [&](const Field& f) {
        double v = f.number();
        if (v <= 0)
            f.fail(
                fmt::format("the focal length must be > 0, got {} (a negative focal length is a mirrored camera, "
                            "which smql refuses)",
                            v));
        return v;
    };
    out.intrinsics.width = positiveInt("width");
    out.intrinsics.height = positiveInt("height");
    out.intrinsics.fx = focal(root.at("fx"));
    out.intrinsics.fy = focal(root.at("fy"));
    out.intrinsics.cx = root.at("cx").number();
    out.intrinsics.cy = root.at("cy").number();
    // The lens's distortion, OpenCV's coefficients by OpenCV's names (TUM's Freiburg 1 and 2 calibrations).
    for (std::size_t i = 0; i < kDistortionNames.size(); ++i)
        if (std::optional<Field> k = root.find(kDistortionNames[i])) out.intrinsics.distortion[i] = k->number();
    if (std::optional<Field> scale = root.find("depth_scale")) out.depthScale = positive(*scale);
    return out;
}

Capture readRgbd(const fs::path& dir, const CaptureOptions& options) {
    Capture capture;
    capture.layout = "rgbd";
    capture.metric = true;
    const fs::path colorDir = dir / "color", depthDir = dir / "depth", instanceDir = dir / "instance";
    const fs::path poseFile = dir / "pose.txt", cameraFile = dir / "camera.json";

    auto colors = numberedImages(colorDir, "colour image", capture.notes);
    if (colors.empty())
        fail(colorDir.string(), "no frames: expected images named by frame number (1.png, 2.png...)", kRgbdHint);
    auto depthList = numberedImages(depthDir, "depth image", capture.notes);
    std::map<long long, fs::path> depths(depthList.begin(), depthList.end());
    std::map<long long, fs::path> masks;
    bool hasMasks = fs::is_directory(instanceDir);
    if (hasMasks) {
        auto maskList = numberedImages(instanceDir, "instance mask", capture.notes);
        masks.insert(maskList.begin(), maskList.end());
    }

    if (!pathExists(poseFile))
        fail(poseFile.string(), "missing: an rgbd capture needs one camera pose per frame", kRgbdHint);
    std::vector<Pose> poses = readPoseFile(poseFile);
    const std::map<long long, Pose> poseOf = posesByFrame(poses, colors, depths, poseFile, capture.notes);

    ImageFileChecks images(kRgbdHint);
    for (std::size_t i = 0; i < colors.size(); ++i) {
        const auto& [number, colorPath] = colors[i];
        auto depth = depths.find(number);
        if (depth == depths.end())
            fail(depthDir.string(), fmt::format("no depth image for frame {} ({})", number, colorPath.string()),
                 kRgbdHint);
        images.check(colorPath, "colour image");
        images.check(depth->second, "depth image");
        CaptureFrame frame;
        frame.index = static_cast<int>(i);
        frame.time = frameTime(frame.index, options.fps);
        frame.colorPath = colorPath.string();
        frame.depthPath = depth->second.string();
        if (hasMasks) {
            auto mask = masks.find(number);
            if (mask == masks.end())
                fail(instanceDir.string(),
                     fmt::format("no instance mask for frame {} ({}): with instance/, every frame needs one", number,
                                 colorPath.string()),
                     kRgbdHint);
            images.check(mask->second, "instance mask");
            frame.instancePath = mask->second.string();
        }
        frame.pose = poseOf.at(number);
        capture.frames.push_back(std::move(frame));
    }
    images.refuseUnreadable();
    std::vector<long long> colourless;
    for (const auto& depth : depths)
        if (std::none_of(colors.begin(), colors.end(), [&](const auto& c) { return c.first == depth.first; }))
            colourless.push_back(depth.first);
    if (!colourless.empty())
        capture.notes.push_back(fmt::format(
            "{}: {} depth image(s) without a colour image (frame {}{}): those frames "
            "are skipped, and their poses with them",
            depthDir.string(), colourless.size(), colourless.front(), colourless.size() > 1 ? ", ..." : ""));

    if (hasMasks) {
        if (pathExists(dir / "labels.json"))
            capture.labelsPath = checkedJson(dir / "labels.json", "labels.json maps instance ids to categories");
        else
            capture.notes.push_back(
                fmt::format("{} has instance masks but no labels.json: the masks have no categories", dir.string()));
    }
    if (pathExists(dir / "detections.json"))
        capture.detectionsPath =
            checkedJson(dir / "detections.json", "detections.json holds COCO-results style detections");

    chooseCamera(capture, options, cameraFile, kRgbdHint, 1000.0, [&](const Intrinsics& k, int width, int height) {
        return fmt::format(
            "no camera.json in {}: using the default intrinsics of a Kinect (fx = fy = {:g}, cx = {:g}, cy = {:g} for "
            "{}x{}); add camera.json or give the intrinsics for exact geometry",
            dir.string(), k.fx, k.cx, k.cy, width, height);
    });
    return capture;
}

// ---------------------------------------------------------------------------
// TUM RGB-D

namespace {

constexpr double kTumMaxDt = 0.02;  // seconds, for depth association and ground truth

struct Stamped {
    double time = 0;
    std::string file;
};

std::vector<Stamped> readStampedList(const fs::path& file) {
    std::string text = readText(file, kTumHint);
    std::vector<Stamped> out;
    for (const TextLine& line : dataLines(text)) {
        std::vector<std::string_view> tokens = splitWhitespace(line.text);
        if (tokens.size() != 2)
            failAt(file.string(), line.number, fmt::format("expected 'timestamp file', got {} values", tokens.size()),
                   kTumHint);
        double time = parseNumbers(file.string(), line.number, {tokens[0]}, kTumHint)[0];
        out.push_back(Stamped{time, std::string(tokens[1])});
    }
    std::stable_sort(out.begin(), out.end(), [](const Stamped& a, const Stamped& b) { return a.time < b.time; });
    return out;
}

struct PoseSample {
    double time = 0;
    Eigen::Vector3d position;
    Eigen::Quaterniond rotation;
};

std::vector<PoseSample> readGroundTruth(const fs::path& file) {
    std::string text = readText(file, kTumHint);
    std::vector<PoseSample> out;
    for (const TextLine& line : dataLines(text)) {
        std::vector<std::string_view> tokens = splitWhitespace(line.text);
        if (tokens.size() != 8)
            failAt(file.string(), line.number,
                   fmt::format("expected 8 numbers (timestamp tx ty tz qx qy qz qw), got {}", tokens.size()), kTumHint);
        std::vector<double> v = parseNumbers(file.string(), line.number, tokens, kTumHint);
        poseFromQuaternion(file.string(), line.number, v[1], v[2], v[3], v[4], v[5], v[6], v[7], kTumHint);  // checks
        checkPosition(file.string(), line.number, fmt::format("the camera at time {}", tokens[0]), {v[1], v[2], v[3]},
                      kTumHint);
        Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
        q.normalize();
        out.push_back(PoseSample{v[0], Eigen::Vector3d(v[1], v[2], v[3]), q});
    }
    std::stable_sort(out.begin(), out.end(), [](const PoseSample& a, const PoseSample& b) { return a.time < b.time; });
    return out;
}

Pose toPose(const Eigen::Vector3d& position, const Eigen::Quaterniond& rotation) {
    Eigen::Matrix3d r = rotation.toRotationMatrix();
    Pose pose;
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) pose.rotation[row * 3 + col] = r(row, col);
    pose.translation = {position.x(), position.y(), position.z()};
    return pose;
}

// Interpolated between the samples around `time` when both are within
// kTumMaxDt, else the nearest sample within kTumMaxDt, else none.
std::optional<Pose> poseAt(const std::vector<PoseSample>& samples, double time) {
    auto after = std::lower_bound(samples.begin(), samples.end(), time,
                                  [](const PoseSample& s, double t) { return s.time < t; });
    if (after != samples.end() && after->time == time) return toPose(after->position, after->rotation);
    if (after != samples.end() && after != samples.begin()) {
        const PoseSample& before = *(after - 1);
        if (time - before.time <= kTumMaxDt && after->time - time <= kTumMaxDt) {
            double a = (time - before.time) / (after->time - before.time);
            return toPose((1 - a) * before.position + a * after->position, before.rotation.slerp(a, after->rotation));
        }
    }
    const PoseSample* nearest = nullptr;
    if (after != samples.end()) nearest = &*after;
    if (after != samples.begin() && (!nearest || time - (after - 1)->time < nearest->time - time))
        nearest = &*(after - 1);
    if (nearest && std::abs(nearest->time - time) <= kTumMaxDt) return toPose(nearest->position, nearest->rotation);
    return std::nullopt;
}

}  // namespace

Capture readTum(const fs::path& dir, const CaptureOptions& options) {
    Capture capture;
    capture.layout = "tum";
    capture.metric = true;
    const fs::path rgbFile = dir / "rgb.txt", depthFile = dir / "depth.txt", gtFile = dir / "groundtruth.txt";
    const fs::path cameraFile = dir / "camera.json";

    std::vector<Stamped> rgb = readStampedList(rgbFile);
    if (rgb.empty()) fail(rgbFile.string(), "no frames listed", kTumHint);
    if (!pathExists(depthFile))
        fail(depthFile.string(), "missing: a TUM capture needs depth.txt beside rgb.txt", kTumHint);
    std::vector<Stamped> depth = readStampedList(depthFile);
    std::vector<PoseSample> groundTruth;
    if (pathExists(gtFile))
        groundTruth = readGroundTruth(gtFile);
    else
        capture.notes.push_back(fmt::format("{} not found: the frames have no poses", gtFile.string()));

    // Each rgb frame with the nearest depth image within kTumMaxDt; the others are dropped.
    std::vector<std::pair<const Stamped*, const Stamped*>> pairs;
    for (const Stamped& colour : rgb) {
        auto after = std::lower_bound(depth.begin(), depth.end(), colour.time,
                                      [](const Stamped& s, double t) { return s.time < t; });
        const Stamped* best = nullptr;
        if (after != depth.end()) best = &*after;
        if (after != depth.begin() && (!best || colour.time - (after - 1)->time < best->time - colour.time))
            best = &*(after - 1);
        if (best && std::abs(best->time - colour.time) <= kTumMaxDt) pairs.emplace_back(&colour, best);
    }
    if (pairs.empty())
        fail(rgbFile.string(),
             fmt::format("no rgb frame has a depth image within {} s in {}", kTumMaxDt, depthFile.string()), kTumHint);
    if (pairs.size() < rgb.size())
        capture.notes.push_back(fmt::format("{} of {} rgb frames have no depth image within {} s and are skipped",
                                            rgb.size() - pairs.size(), rgb.size(), kTumMaxDt));

    Sampler sampler(options.fps, 1e-3);
    double start = pairs.front().first->time;
    int withoutPose = 0;
    ImageFileChecks images(kTumHint);
    for (const auto& [colour, depthImage] : pairs) {
        if (!sampler.take(colour->time)) continue;
        CaptureFrame frame;
        frame.index = static_cast<int>(capture.frames.size());
        frame.time = colour->time - start;
        fs::path colorPath = dir / colour->file, depthPath = dir / depthImage->file;
        images.check(colorPath, "colour image");
        images.check(depthPath, "depth image");
        frame.colorPath = colorPath.string();
        frame.depthPath = depthPath.string();
        if (!groundTruth.empty()) frame.pose = poseAt(groundTruth, colour->time);
        if (!frame.pose) ++withoutPose;
        capture.frames.push_back(std::move(frame));
    }
    images.refuseUnreadable();
    if (capture.frames.size() < pairs.size())
        capture.notes.push_back(fmt::format("{} of {} frames kept, {:g} a second (--fps; --fps 0 keeps every frame)",
                                            capture.frames.size(), pairs.size(), options.fps));
    if (withoutPose > 0 && !groundTruth.empty())
        capture.notes.push_back(fmt::format("{} of {} frames have no ground-truth pose within {} s in {}", withoutPose,
                                            capture.frames.size(), kTumMaxDt, gtFile.string()));

    chooseCamera(capture, options, cameraFile, kTumHint, 5000.0, [](const Intrinsics& k, int width, int height) {
        return fmt::format(
            "TUM capture without camera.json: using the default intrinsics fx = fy = {:g}, cx = {:g}, cy = {:g} "
            "(the TUM ROS default for {}x{}); give the intrinsics of the sequence's camera (freiburg1/2/3) for exact "
            "geometry",
            k.fx, k.cx, k.cy, width, height);
    });
    return capture;
}

extern const CaptureLayout kRgbdLayout{
    "rgbd", "an rgbd folder (color/ depth/ pose.txt)", "color/ and depth/ folders (rgbd)",
    [](const fs::path& target, std::vector<std::string>&) -> std::optional<fs::path> {
        if (isDirectory(target / "color") && isDirectory(target / "depth")) return target;
        return std::nullopt;
    },
    readRgbd};

extern const CaptureLayout kTumLayout{"tum", "a TUM RGB-D folder (rgb.txt depth.txt groundtruth.txt)",
                                      "rgb.txt (TUM RGB-D)",
                                      [](const fs::path& target, std::vector<std::string>&) -> std::optional<fs::path> {
                                          if (isFile(target / "rgb.txt")) return target;
                                          return std::nullopt;
                                      },
                                      readTum};

}  // namespace smql::ingest::capture_detail

namespace smql::ingest {

std::vector<Pose> posesInFrameOrder(const std::string& poseFile, const std::string& colorDir,
                                    const std::string& depthDir) {
    using namespace capture_detail;
    std::vector<std::string> notes;
    const auto colors = numberedImages(colorDir, "colour image", notes);
    std::map<long long, fs::path> depths;
    if (isDirectory(depthDir))
        for (auto& [number, path] : numberedImages(depthDir, "depth image", notes)) depths.emplace(number, path);
    std::vector<Pose> out;
    if (colors.empty()) return out;
    const std::map<long long, Pose> poseOf = posesByFrame(readPoseFile(poseFile), colors, depths, poseFile, notes);
    for (const auto& [number, path] : colors) out.push_back(poseOf.at(number));
    return out;
}

}  // namespace smql::ingest
