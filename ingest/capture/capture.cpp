// readCapture: the first capture layout (capture_layouts.cpp) that recognises a folder or file reads
// it. The detection order is documented in docs/formats.md.
#include "ingest/capture/capture.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "ingest/capture/capture_detail.hpp"
#include "model/error.hpp"

namespace smql::ingest {

using namespace capture_detail;

namespace {

// What was looked for, from the table: "color/ and depth/ folders (rgbd), rgb.txt (TUM RGB-D), ...".
std::string lookedFor() {
    std::vector<std::string_view> all;
    for (const CaptureLayout* layout : captureLayouts())
        if (layout->name != "video") all.push_back(layout->looksFor);
    return fmt::format("{}", fmt::join(all, ", "));
}

// The first layout that recognises `target`, read.
std::optional<Capture> readLayout(const fs::path& target, const CaptureOptions& options) {
    for (const CaptureLayout* layout : captureLayouts()) {
        std::vector<std::string> notes;
        std::optional<fs::path> path = layout->recognise(target, notes);
        if (!path) continue;
        Capture capture = layout->read(*path, options);
        capture.notes.insert(capture.notes.begin(), notes.begin(), notes.end());
        return capture;
    }
    return std::nullopt;
}

// A folder no layout recognises: why, with the likeliest mistake as the hint.
[[noreturn]] void unrecognisedFolder(const fs::path& dir) {
    std::vector<fs::path> entries;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        std::string name = it->path().filename().string();
        if (!name.empty() && name[0] != '.') entries.push_back(it->path());
    }
    if (ec) fail(dir.string(), "cannot list the folder: " + ec.message());
    if (entries.empty()) fail(dir.string(), "the folder is empty: there is no capture in it", layoutsHint());
    std::string hint = layoutsHint();
    std::vector<fs::path> videos;
    for (const fs::path& file : listFiles(dir))
        if (isVideoExtension(extensionOf(file))) videos.push_back(file);
    if (!videos.empty())
        hint = fmt::format("the folder holds a video: name the video file itself ({})", videos.front().string());
    else if (isDirectory(dir / "color") || isDirectory(dir / "depth"))
        hint = fmt::format("an rgbd capture needs both color/ and depth/; {}", kRgbdHint);
    fail(dir.string(), "no capture layout recognised: looked for " + lookedFor(), hint);
}

// A file no layout recognises.
[[noreturn]] void unrecognisedFile(const fs::path& file) {
    if (isImageExtension(extensionOf(file)))
        fail(file.string(), "a single image is not a capture",
             "name the folder that holds the images; " + layoutsHint());
    fail(file.string(),
         "not a capture file: smql reads transforms.json (nerfstudio) and COLMAP's cameras/images/points3D",
         layoutsHint());
}

}  // namespace

bool Intrinsics::distorted() const {
    return std::any_of(distortion.begin(), distortion.end(), [](double k) { return k != 0; });
}

Capture readCapture(const std::string& path, const CaptureOptions& options) {
    if (path.empty()) throw Error(ErrorKind::Usage, "no capture given", std::nullopt, layoutsHint());
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
    if (!fs::exists(status)) fail(path, "no such file or folder", layoutsHint());
    if (!fs::is_directory(status) && !fs::is_regular_file(status))
        fail(path, "neither a folder nor a regular file", layoutsHint());
    std::optional<Capture> capture = readLayout(target, options);
    if (!capture) {
        if (fs::is_directory(status)) unrecognisedFolder(target);
        unrecognisedFile(target);
    }
    capture->path = path;
    refuseMirroredCameras(*capture);
    return std::move(*capture);
}

}  // namespace smql::ingest
