// nerfstudio (and instant-ngp style) transforms.json.
#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>
#include <Eigen/Dense>

#include "ingest/capture/capture_detail.hpp"
#include "ingest/import/common.hpp"
#include "ingest/import/json_field.hpp"
#include "model/error.hpp"

namespace smql::ingest::capture_detail {

namespace {

using import::detail::Field;
using import::detail::JsonSource;

// Camera fields, at the top level or per frame (per frame wins).
struct CameraFields {
    std::optional<double> flX, flY, cx, cy, w, h, angleX, angleY;
    std::array<double, kDistortionNames.size()> distortion{};
    std::string model;
};

void readCameraFields(const Field& object, CameraFields& out) {
    auto number = [&](std::string_view key, std::optional<double>& into) {
        if (std::optional<Field> f = object.find(key)) into = f->number();
    };
    number("fl_x", out.flX);
    number("fl_y", out.flY);
    number("cx", out.cx);
    number("cy", out.cy);
    number("w", out.w);
    number("h", out.h);
    number("camera_angle_x", out.angleX);
    number("camera_angle_y", out.angleY);
    for (std::size_t i = 0; i < kDistortionNames.size(); ++i)
        if (std::optional<Field> f = object.find(kDistortionNames[i])) out.distortion[i] = f->number();
    if (std::optional<Field> f = object.find("camera_model")) out.model = f->string();
}

struct FrameEntry {
    std::string filePath;  // as written, for the order
    CaptureFrame frame;
    Intrinsics intrinsics;
};

// The image a path names, nullopt when there is no such file.
std::optional<fs::path> findImage(const fs::path& base, const Field& field) {
    std::string written = field.string();
    if (written.empty()) field.fail("empty path");
    fs::path path = fs::path(written).is_absolute() ? fs::path(written) : base / written;
    std::error_code ec;
    if (!fs::exists(path, ec) && !path.has_extension()) {
        // instant-ngp / Blender datasets leave out the extension ("./train/r_0").
        for (const char* ext : {".png", ".jpg", ".jpeg"}) {
            fs::path candidate = path;
            candidate += ext;
            if (fs::exists(candidate, ec)) return candidate.lexically_normal();
        }
    }
    if (!fs::exists(path, ec)) return std::nullopt;
    return path.lexically_normal();
}

fs::path resolveImage(const fs::path& base, const Field& field) {
    auto path = findImage(base, field);
    if (!path) field.fail(fmt::format("{}: no such file", (base / field.string()).lexically_normal().string()));
    return *path;
}

// `image` names the frame in errors.
Pose readTransform(const Field& field, std::string_view image) {
    std::size_t rows = field.size();
    if (rows != 3 && rows != 4) field.fail(fmt::format("expected a 4x4 (or 3x4) matrix, got {} rows", rows));
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    for (std::size_t r = 0; r < rows; ++r) {
        std::vector<double> row = field[r].numbers(4);
        for (int c = 0; c < 4; ++c) m(static_cast<int>(r), c) = row[c];
    }
    if (rows == 4 && (m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-6)
        field.fail("the last row of a camera-to-world matrix must be 0 0 0 1");
    Eigen::Matrix3d r = m.topLeftCorner<3, 3>();
    double error = (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    if (r.determinant() <= 0)
        field.fail(
            fmt::format("the camera pose of frame '{}' is mirrored (left-handed): its rotation has determinant "
                        "{:.3g}; smql takes right-handed poses only",
                        image, r.determinant()));
    if (error > 1e-2) field.fail("the rotation part is not a rotation (it is scaled or skewed)");
    Eigen::JacobiSVD<Eigen::Matrix3d> svd(r, Eigen::ComputeFullU | Eigen::ComputeFullV);
    r = svd.matrixU() * svd.matrixV().transpose();
    // OpenGL / Blender camera (x right, y up, looking along -z) to OpenCV
    // (x right, y down, looking along +z): flip the camera's y and z axes.
    r.col(1) *= -1;
    r.col(2) *= -1;
    Pose pose;
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) pose.rotation[row * 3 + col] = r(row, col);
    pose.translation = {m(0, 3), m(1, 3), m(2, 3)};
    // Field::fail names the file and the frame's JSON path.
    constexpr double limit = import::detail::kMaxCoordinate;
    for (double c : {m(0, 3), m(1, 3), m(2, 3)})
        if (std::abs(c) > limit)
            field.fail(
                fmt::format("the camera is at ({:g}, {:g}, {:g}), beyond {:g} m from the origin: positions must "
                            "lie within {:g} on every axis (a unit mix-up or a geo-referenced model?)",
                            m(0, 3), m(1, 3), m(2, 3), limit, limit));
    return pose;
}

// A frame's pinhole camera from its fields (or the top level's): the image size (read from the first
// image when not given), the focal lengths from fl_x/fl_y or the view angles, the principal point.
Intrinsics frameIntrinsics(Field& f, CameraFields cam, const fs::path& color, std::optional<cv::Size>& firstImageSize) {
    if (!cam.w || !cam.h) {
        if (!firstImageSize) firstImageSize = readColorImage(color.string()).size();
        if (!cam.w) cam.w = firstImageSize->width;
        if (!cam.h) cam.h = firstImageSize->height;
    }
    if (*cam.w < 1 || *cam.h < 1 || *cam.w != std::floor(*cam.w) || *cam.h != std::floor(*cam.h))
        f.fail(fmt::format("image size w x h must be positive integers, got {} x {}", *cam.w, *cam.h));
    double fx = 0, fy = 0;
    if (cam.flX)
        fx = *cam.flX;
    else if (cam.angleX)
        fx = 0.5 * *cam.w / std::tan(0.5 * *cam.angleX);
    else
        f.fail("no focal length: give fl_x (pixels) or camera_angle_x (radians), here or at the top level");
    if (cam.flY)
        fy = *cam.flY;
    else if (cam.angleY)
        fy = 0.5 * *cam.h / std::tan(0.5 * *cam.angleY);
    else
        fy = fx;
    if (!(fx > 0) || !(fy > 0) || !std::isfinite(fx) || !std::isfinite(fy))
        f.fail(
            fmt::format("focal lengths must be positive, got fl_x {} and fl_y {} (a negative focal length is a "
                        "mirrored camera, which smql refuses)",
                        fx, fy));
    // nerfstudio puts pixel centres at +0.5 (the image corner is 0); ours are at integers.
    double cx = cam.cx ? *cam.cx : *cam.w / 2, cy = cam.cy ? *cam.cy : *cam.h / 2;
    Intrinsics out{static_cast<int>(*cam.w), static_cast<int>(*cam.h), fx, fy, cx - 0.5, cy - 0.5};
    // A fisheye's k1-k4 are another model's: it is read as a pinhole (the note in readNerfstudio).
    if (lowerCase(cam.model).find("fisheye") == std::string::npos)
        std::copy(cam.distortion.begin(), cam.distortion.end(), out.distortion.begin());
    return out;
}

}  // namespace

Capture readNerfstudio(const fs::path& transformsFile, const CaptureOptions& options) {
    Capture capture;
    capture.layout = "nerfstudio";
    const std::string file = transformsFile.string();
    JsonSource source{file, kNerfstudioHint};
    import::detail::Json json = import::detail::parseJsonFile(source);
    Field root(json, source);
    const fs::path base = transformsFile.has_parent_path() ? transformsFile.parent_path() : fs::path(".");

    CameraFields top;
    readCameraFields(root, top);
    Field frames = root.at("frames");
    if (frames.size() == 0) frames.fail("no frames");

    double depthUnit = 0.001;  // metres per depth unit
    if (std::optional<Field> f = root.find("depth_unit_scale_factor")) {
        depthUnit = f->number();
        if (depthUnit <= 0) f->fail(fmt::format("expected a positive number of metres per unit, got {}", depthUnit));
    }

    std::vector<FrameEntry> entries;
    std::optional<cv::Size> firstImageSize;
    bool distorted = false, fisheye = false;
    std::size_t withDepth = 0;
    std::vector<std::string> absent;  // frames listed whose image is not in the folder: skipped
    ImageFileChecks images(kNerfstudioHint);
    for (std::size_t i = 0; i < frames.size(); ++i) {
        Field f = frames[i];
        FrameEntry entry;
        Field filePath = f.at("file_path");
        entry.filePath = filePath.string();
        std::optional<fs::path> found = findImage(base, filePath);
        if (!found) {
            absent.push_back(entry.filePath);
            continue;
        }
        const fs::path& color = *found;
        if (!images.check(color, "colour image")) continue;  // named with the others after the loop
        entry.frame.colorPath = color.string();
        entry.frame.pose = readTransform(f.at("transform_matrix"), entry.filePath);
        if (std::optional<Field> depth = f.find("depth_file_path")) {
            fs::path depthPath = resolveImage(base, *depth);
            images.check(depthPath, "depth image");
            entry.frame.depthPath = depthPath.string();
            ++withDepth;
        }

        CameraFields cam = top;
        readCameraFields(f, cam);
        std::string model = lowerCase(cam.model);
        if (model == "equirectangular") f.fail("equirectangular cameras are not supported (pinhole only)");
        if (model.find("fisheye") != std::string::npos) fisheye = true;
        entry.intrinsics = frameIntrinsics(f, cam, color, firstImageSize);
        distorted = distorted || entry.intrinsics.distorted();
        entries.push_back(std::move(entry));
    }
    images.refuseUnreadable();

    if (entries.empty())
        frames.fail(fmt::format("none of its {} frames' images is in the folder (the first: {})", frames.size(),
                                (base / absent.front()).lexically_normal().string()));
    if (!absent.empty())
        capture.notes.push_back(
            fmt::format("{}: {} of {} frames listed have no image in the folder and are skipped "
                        "(the first: {})",
                        file, absent.size(), frames.size(), absent.front()));
    std::stable_sort(entries.begin(), entries.end(),
                     [](const FrameEntry& a, const FrameEntry& b) { return naturalLess(a.filePath, b.filePath); });
    bool perFrame = false;
    for (std::size_t i = 0; i < entries.size(); ++i) {
        CaptureFrame frame = std::move(entries[i].frame);
        frame.index = static_cast<int>(i);
        frame.time = options.fps > 0 ? i / options.fps : static_cast<double>(i);
        if (i == 0) capture.intrinsics = entries[i].intrinsics;
        if (!hasOptionIntrinsics(options) && !(entries[i].intrinsics == capture.intrinsics)) {
            frame.intrinsics = entries[i].intrinsics;
            perFrame = true;
        }
        capture.frames.push_back(std::move(frame));
    }

    takeOptionIntrinsics(capture, options, file);

    if (perFrame) capture.notes.push_back(fmt::format("{}: the frames have different intrinsics", file));
    if (distorted && !hasOptionIntrinsics(options))
        capture.notes.push_back(
            fmt::format("{}: the cameras' lens distortion (k1, k2, p1, p2, k3) is undone as each frame is read", file));
    if (fisheye)
        capture.notes.push_back(
            fmt::format("{}: fisheye camera read as a pinhole camera: geometry near the image "
                        "edges will be off",
                        file));
    capture.metric = withDepth > 0;
    const auto firstWithDepth = std::find_if(capture.frames.begin(), capture.frames.end(),
                                             [](const CaptureFrame& f) { return !f.depthPath.empty(); });
    if (firstWithDepth != capture.frames.end())
        if (auto note = depthResolutionNote(readRawFrame(*firstWithDepth))) capture.notes.push_back(*note);
    if (withDepth > 0 && withDepth < capture.frames.size())
        capture.notes.push_back(fmt::format("{}: {} of {} frames have depth", file, withDepth, capture.frames.size()));
    if (withDepth == 0)
        capture.notes.push_back(fmt::format("{}: no depth_file_path: poses are taken as up to scale", file));
    capture.depthScale = options.depthScale ? *options.depthScale : 1.0 / depthUnit;
    return capture;
}

// transforms.json, named or in the folder.
extern const CaptureLayout kNerfstudioLayout{
    "nerfstudio", "a nerfstudio transforms.json", "transforms.json (nerfstudio)",
    [](const fs::path& target, std::vector<std::string>&) -> std::optional<fs::path> {
        if (isDirectory(target) && isFile(target / "transforms.json")) return target / "transforms.json";
        if (isFile(target) && lowerCase(target.filename().string()) == "transforms.json") return target;
        return std::nullopt;
    },
    readNerfstudio};

}  // namespace smql::ingest::capture_detail
