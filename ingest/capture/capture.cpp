// readCapture: recognises the layout of a folder or file and hands it to its
// reader. The detection order is documented in docs/formats.md.
#include "ingest/capture/capture.hpp"

#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "ingest/capture/capture_detail.hpp"
#include "model/error.hpp"

namespace smql::ingest {

using namespace capture_detail;

namespace {

constexpr const char* kLayoutsHint =
    "smql reads: an rgbd folder (color/ depth/ pose.txt), a TUM RGB-D folder (rgb.txt depth.txt "
    "groundtruth.txt), a nerfstudio transforms.json, a COLMAP sparse model (cameras/images/points3D .txt or "
    ".bin, also in sparse/0/), a folder of .jpg/.png images, or a video file";

bool isDirectory(const fs::path& path) {
    std::error_code ec;
    return fs::is_directory(path, ec);
}

bool isFile(const fs::path& path) {
    std::error_code ec;
    return fs::is_regular_file(path, ec);
}

// The COLMAP model in `dir`, `dir/sparse/0` or `dir/sparse`.
std::optional<fs::path> findColmapModel(const fs::path& dir, std::vector<std::string>& notes) {
    if (colmapModelFormat(dir)) return dir;
    fs::path sparse = dir / "sparse";
    if (colmapModelFormat(sparse / "0")) {
        std::vector<std::string> others;
        std::error_code ec;
        for (fs::directory_iterator it(sparse, ec), end; !ec && it != end; it.increment(ec)) {
            std::string name = it->path().filename().string();
            if (name != "0" && frameNumber(it->path()) && colmapModelFormat(it->path())) others.push_back(name);
        }
        if (!others.empty())
            notes.push_back(fmt::format("{} holds several COLMAP models; reading sparse/0 (the others: {})",
                                        sparse.string(), fmt::join(others, ", ")));
        return sparse / "0";
    }
    if (colmapModelFormat(sparse)) return sparse;
    return std::nullopt;
}

Capture readFolder(const fs::path& dir, const CaptureOptions& options) {
    std::vector<fs::path> entries;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        std::string name = it->path().filename().string();
        if (!name.empty() && name[0] != '.') entries.push_back(it->path());
    }
    if (ec) fail(dir.string(), "cannot list the folder: " + ec.message());
    if (entries.empty()) fail(dir.string(), "the folder is empty: there is no capture in it", kLayoutsHint);

    if (isDirectory(dir / "color") && isDirectory(dir / "depth")) return readRgbd(dir, options);
    if (isFile(dir / "rgb.txt")) return readTum(dir, options);
    if (isFile(dir / "transforms.json")) return readNerfstudio(dir / "transforms.json", options);
    std::vector<std::string> notes;
    if (std::optional<fs::path> model = findColmapModel(dir, notes)) {
        Capture capture = readColmap(*model, options);
        capture.notes.insert(capture.notes.begin(), notes.begin(), notes.end());
        return capture;
    }
    std::vector<fs::path> images, videos;
    for (const fs::path& file : listFiles(dir)) {
        std::string ext = extensionOf(file);
        if (isImageExtension(ext)) images.push_back(file);
        if (isVideoExtension(ext)) videos.push_back(file);
    }
    if (!images.empty()) return readImageFolder(dir, images, options);

    std::string hint = kLayoutsHint;
    if (!videos.empty())
        hint = fmt::format("the folder holds a video: name the video file itself ({})", videos.front().string());
    else if (isDirectory(dir / "color") || isDirectory(dir / "depth"))
        hint = fmt::format("an rgbd capture needs both color/ and depth/; {}", kRgbdHint);
    fail(dir.string(),
         "no capture layout recognised: looked for color/ and depth/ folders (rgbd), rgb.txt (TUM RGB-D), "
         "transforms.json (nerfstudio), cameras + images .txt/.bin here or in sparse/0/ or sparse/ (COLMAP), "
         "and .jpg/.jpeg/.png files (image folder)",
         hint);
}

}  // namespace

Capture readCapture(const std::string& path, const CaptureOptions& options) {
    if (path.empty()) throw Error(ErrorKind::Usage, "no capture given", std::nullopt, kLayoutsHint);
    if (!std::isfinite(options.fps))
        throw Error(ErrorKind::Usage, fmt::format("fps must be a number, got {}", options.fps), std::nullopt,
                    "frames per second to sample from videos and TUM sequences; 0 keeps every frame");
    if (options.depthScale) checkDepthScale(*options.depthScale, "depth scale option");
    if (options.intrinsics && options.horizontalFov)
        throw Error(
            ErrorKind::Usage, "give the camera as --camera or as --fov, not both", std::nullopt,
            "--camera fx,fy,cx,cy when the camera is calibrated, --fov DEG when only its field of view is known");
    if (options.horizontalFov) checkFieldOfView(*options.horizontalFov);

    fs::path target(path);
    std::error_code ec;
    auto status = fs::status(target, ec);
    if (!fs::exists(status)) fail(path, "no such file or folder", kLayoutsHint);

    Capture capture;
    if (fs::is_directory(status)) {
        capture = readFolder(target, options);
    } else if (fs::is_regular_file(status)) {
        std::string name = lowerCase(target.filename().string());
        std::string ext = extensionOf(target);
        if (name == "transforms.json") {
            capture = readNerfstudio(target, options);
        } else if (name == "cameras.txt" || name == "images.txt" || name == "points3d.txt" || name == "cameras.bin" ||
                   name == "images.bin" || name == "points3d.bin") {
            capture = readColmap(target.has_parent_path() ? target.parent_path() : fs::path("."), options);
        } else if (isImageExtension(ext)) {
            fail(path, "a single image is not a capture",
                 "name the folder that holds the images; " + std::string(kLayoutsHint));
        } else if (ext == "json" || ext == "txt") {
            fail(path,
                 "not a capture file: smql reads transforms.json (nerfstudio) and COLMAP's cameras/images/points3D",
                 kLayoutsHint);
        } else {
            capture = readVideo(target, options);
        }
    } else {
        fail(path, "neither a folder nor a regular file", kLayoutsHint);
    }
    capture.path = path;
    refuseMirroredCameras(capture);
    return capture;
}

}  // namespace smql::ingest
