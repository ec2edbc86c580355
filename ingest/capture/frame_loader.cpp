#include "ingest/capture/frame_loader.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "ingest/capture/capture_detail.hpp"
#include "model/error.hpp"

namespace smql::ingest {

using namespace capture_detail;

namespace capture_detail {

bool sameAspect(cv::Size a, cv::Size b) {
    return a.width > 0 && a.height > 0 && std::abs(static_cast<double>(a.height) * b.width / a.width - b.height) <= 1.0;
}

RawFrame readRawFrame(const CaptureFrame& frame) {
    RawFrame raw;
    raw.color = readColorImage(frame.colorPath);
    auto sizeError = [&](const cv::Mat& image, const std::string& file, std::string_view what, std::string_view why) {
        fail(file, fmt::format("{} is {}x{} but the colour image {} is {}x{}{}", what, image.cols, image.rows,
                               frame.colorPath, raw.color.cols, raw.color.rows, why));
    };
    if (!frame.depthPath.empty()) {
        raw.depth = readDepthImage(frame.depthPath);
        if (!sameAspect(raw.depth.size(), raw.color.size()))
            sizeError(raw.depth, frame.depthPath, "the depth image",
                      ", another aspect ratio: depth registered to the colour camera has its aspect ratio");
    }
    if (!frame.instancePath.empty()) {
        raw.instances = readMaskImage(frame.instancePath);
        if (raw.instances.size() != raw.color.size())
            sizeError(raw.instances, frame.instancePath, "the instance mask", "");
    }
    return raw;
}

std::optional<std::string> depthResolutionNote(const RawFrame& frame) {
    if (frame.depth.empty() || frame.depth.size() == frame.color.size()) return std::nullopt;
    return fmt::format(
        "depth: {}x{} images beside {}x{} colour, the same aspect ratio: taken as registered to the colour camera, "
        "each resized to the colour image's size (the nearest reading)",
        frame.depth.cols, frame.depth.rows, frame.color.cols, frame.color.rows);
}

Intrinsics fitIntrinsics(const Intrinsics& in, int width, int height, const std::string& imageFile,
                         std::string_view source) {
    if (in.width == width && in.height == height) return in;
    // The same camera with the image resized (COLMAP run on full-size photos,
    // nerfstudio's downscaled images/): same aspect ratio within a pixel.
    if (sameAspect({in.width, in.height}, {width, height})) return scaleIntrinsics(in, width, height);
    fail(imageFile, fmt::format("the image is {}x{} but the intrinsics ({}) are for {}x{}, another aspect ratio", width,
                                height, source, in.width, in.height));
}

}  // namespace capture_detail

cv::Mat undistorted(const cv::Mat& image, const Intrinsics& camera, int interpolation) {
    // A capture has one camera or few: the maps of the last one are kept for its next frame.
    struct Maps {
        Intrinsics camera;
        cv::Mat x, y;
    };
    thread_local Maps maps;
    if (!(maps.camera == camera)) {
        const cv::Matx33d matrix(camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
        cv::initUndistortRectifyMap(matrix, camera.distortion, cv::noArray(), matrix,
                                    cv::Size(camera.width, camera.height), CV_32FC1, maps.x, maps.y);
        maps.camera = camera;
    }
    cv::Mat out;
    cv::remap(image, out, maps.x, maps.y, interpolation, cv::BORDER_CONSTANT, cv::Scalar::all(0));
    return out;
}

FrameImages loadFrame(const Capture& capture, const CaptureFrame& frame, int workingWidth) {
    RawFrame raw = readRawFrame(frame);
    FrameImages out;
    const int width = raw.color.cols, height = raw.color.rows;
    const Intrinsics& stored = frame.intrinsics ? *frame.intrinsics : capture.intrinsics;
    if (capture.layout == "images" && !frame.intrinsics &&
        !sameAspect({stored.width, stored.height}, {width, height})) {
        // A folder of photos may mix portrait and landscape: the guess follows each image.
        out.intrinsics = guessedIntrinsics(width, height);
    } else {
        out.intrinsics = fitIntrinsics(stored, width, height, frame.colorPath, "the capture's");
    }

    if (!raw.depth.empty()) {
        if (raw.depth.depth() == CV_16U) {
            if (!(capture.depthScale > 0)) fail(frame.depthPath, "the capture's depth scale is not positive");
            raw.depth.convertTo(out.depth, CV_32F, 1.0 / capture.depthScale);
        } else {
            out.depth = raw.depth.clone();  // already metres
            cv::patchNaNs(out.depth, 0);
            cv::max(out.depth, 0.0, out.depth);
            out.depth.setTo(0, out.depth == std::numeric_limits<float>::infinity());
        }
    }
    out.instances = raw.instances;
    out.color = raw.color;
    // Depth of another resolution is resized once: to the colour's size where the lens is undone on its pixels,
    // else at the end, to the size the colour is given.
    auto resizeDepth = [&](cv::Size size) {
        if (out.depth.empty() || out.depth.size() == size) return;
        cv::Mat resized;
        cv::resize(out.depth, resized, size, 0, 0, cv::INTER_NEAREST);
        out.depth = resized;
    };
    if (out.intrinsics.distorted()) {
        resizeDepth({width, height});
        out.color = undistorted(out.color, out.intrinsics, cv::INTER_LINEAR);
        if (!out.depth.empty()) out.depth = undistorted(out.depth, out.intrinsics, cv::INTER_NEAREST);
        if (!out.instances.empty()) out.instances = undistorted(out.instances, out.intrinsics, cv::INTER_NEAREST);
        out.intrinsics.distortion = {};
    }

    if (workingWidth > 0 && width > workingWidth) {
        int newHeight = std::max(1, static_cast<int>(std::lround(static_cast<double>(height) * workingWidth / width)));
        cv::Size size(workingWidth, newHeight);
        cv::Mat small;
        cv::resize(out.color, small, size, 0, 0, cv::INTER_AREA);
        out.color = small;
        if (!out.instances.empty()) {
            cv::Mat small;
            cv::resize(out.instances, small, size, 0, 0, cv::INTER_NEAREST);
            out.instances = small;
        }
        out.intrinsics = scaleIntrinsics(out.intrinsics, workingWidth, newHeight);
    }
    resizeDepth(out.color.size());
    return out;
}

}  // namespace smql::ingest
