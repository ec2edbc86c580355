// Where a capture's camera comes from when the layout does not say: the
// --camera and --fov options, a photo's EXIF (libexif), and the check that
// refuses mirrored cameras in whatever a reader produced.
#include <cmath>
#include <memory>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <libexif/exif-data.h>

#include "ingest/capture/capture_detail.hpp"
#include "model/error.hpp"
#include "model/geometry.hpp"

namespace smql::ingest {

using namespace capture_detail;

namespace {

constexpr const char* kCameraOptionHint =
    "--camera fx,fy,cx,cy[,k1,k2,p1,p2,k3]: four numbers in pixels of the images as stored, focal lengths > 0, "
    "then the lens's distortion in OpenCV's order when known (e.g. --camera 1450,1450,959.5,539.5 or "
    "--camera 517.3,516.5,318.6,255.3,0.2624,-0.9531,-0.0054,0.0026,1.1633)";
constexpr const char* kFovHint =
    "--fov DEG: the horizontal field of view in degrees, between 0 and 180 (e.g. --fov 66)";

}  // namespace

Intrinsics parseCameraOption(std::string_view text) {
    std::vector<double> values;
    std::size_t start = 0;
    while (start <= text.size()) {
        std::size_t end = std::min(text.find(',', start), text.size());
        std::string_view token = text.substr(start, end - start);
        while (!token.empty() && token.front() == ' ') token.remove_prefix(1);
        while (!token.empty() && token.back() == ' ') token.remove_suffix(1);
        std::optional<double> value = parseNumber(token);
        if (!value || !std::isfinite(*value))
            throw Error(ErrorKind::Usage,
                        fmt::format("--camera: value {} '{}' is not a number", values.size() + 1, token), std::nullopt,
                        kCameraOptionHint);
        values.push_back(*value);
        start = end + 1;
    }
    if (values.size() < 4 || values.size() > 4 + kDistortionNames.size())
        throw Error(ErrorKind::Usage,
                    fmt::format("--camera takes 4 numbers (fx,fy,cx,cy), then up to {} of the lens's distortion "
                                "({}), got {}",
                                kDistortionNames.size(), fmt::join(kDistortionNames, ","), values.size()),
                    std::nullopt, kCameraOptionHint);
    if (values[0] <= 0 || values[1] <= 0)
        throw Error(ErrorKind::Usage,
                    fmt::format("--camera: the focal lengths must be > 0, got fx {} and fy {} (a negative focal "
                                "length is a mirrored camera, which smql refuses)",
                                values[0], values[1]),
                    std::nullopt, kCameraOptionHint);
    Intrinsics out{0, 0, values[0], values[1], values[2], values[3]};
    std::copy(values.begin() + 4, values.end(), out.distortion.begin());
    return out;
}

double checkFieldOfView(double degrees) {
    if (!std::isfinite(degrees) || degrees <= 0 || degrees >= 180)
        throw Error(
            ErrorKind::Usage,
            fmt::format("--fov: the horizontal field of view must be between 0 and 180 degrees, got {}", degrees),
            std::nullopt, kFovHint);
    return degrees;
}

namespace capture_detail {

std::optional<Intrinsics> optionIntrinsics(const CaptureOptions& options, int width, int height) {
    if (options.intrinsics) return userIntrinsics(*options.intrinsics, width, height);
    if (!options.horizontalFov) return std::nullopt;
    double fov = checkFieldOfView(*options.horizontalFov) * model::kDegree;
    double f = 0.5 * width / std::tan(0.5 * fov);
    return Intrinsics{width, height, f, f, (width - 1) / 2.0, (height - 1) / 2.0};
}

const char* optionName(const CaptureOptions& options) { return options.intrinsics ? "--camera" : "--fov"; }

IntrinsicsOrigin optionOrigin(const CaptureOptions& options) {
    return options.intrinsics ? IntrinsicsOrigin::Measured : IntrinsicsOrigin::Approximate;
}

void takeOptionIntrinsics(Capture& capture, const CaptureOptions& options, const std::string& file) {
    const RawFrame first = readRawFrame(capture.frames.front());
    if (std::optional<Intrinsics> given = optionIntrinsics(options, first.color.cols, first.color.rows)) {
        capture.intrinsics = *given;
        capture.intrinsicsOrigin = optionOrigin(options);
    }
    fitIntrinsics(capture.intrinsics, first.color.cols, first.color.rows, capture.frames.front().colorPath,
                  hasOptionIntrinsics(options) ? optionName(options) : file);
}

ExifCamera readExif(const fs::path& file) {
    ExifCamera out;
    std::unique_ptr<ExifData, void (*)(ExifData*)> data(exif_data_new_from_file(file.c_str()), exif_data_unref);
    if (!data) return out;
    ExifByteOrder order = exif_data_get_byte_order(data.get());
    auto shortValue = [&](ExifTag tag) -> std::optional<int> {
        ExifEntry* entry = exif_data_get_entry(data.get(), tag);
        if (!entry || entry->format != EXIF_FORMAT_SHORT || entry->components < 1 || entry->size < 2)
            return std::nullopt;
        return static_cast<int>(exif_get_short(entry->data, order));
    };
    if (std::optional<int> focal = shortValue(EXIF_TAG_FOCAL_LENGTH_IN_35MM_FILM); focal && *focal > 0)
        out.focal35mm = *focal;
    if (std::optional<int> orientation = shortValue(EXIF_TAG_ORIENTATION)) out.orientation = *orientation;
    return out;
}

Intrinsics intrinsicsFrom35mm(double focal35mm, int width, int height) {
    // The 35 mm equivalent keeps the diagonal field of view of a 36 x 24 mm frame (43.27 mm diagonal),
    // so it holds for any aspect ratio and orientation.
    double diagonal = std::hypot(static_cast<double>(width), static_cast<double>(height));
    double f = focal35mm * diagonal / std::hypot(36.0, 24.0);
    return Intrinsics{width, height, f, f, (width - 1) / 2.0, (height - 1) / 2.0};
}

void refuseMirroredCameras(const Capture& capture) {
    auto frameName = [](const CaptureFrame& frame) {
        return fmt::format("frame {} ({})", frame.index, frame.colorPath);
    };
    constexpr const char* hint =
        "smql takes right-handed cameras (x right, y down, looking along +z) with positive focal lengths; a "
        "mirrored pose or camera usually comes from a flipped axis in the exporter: fix the capture's poses";
    auto checkFocal = [&](const Intrinsics& k, const std::string& where) {
        if (!(k.fx > 0) || !(k.fy > 0))
            throw Error(ErrorKind::Input,
                        fmt::format("{}: the camera is mirrored or broken: focal lengths fx {} and fy {} must be > 0",
                                    where, k.fx, k.fy),
                        std::nullopt, hint);
    };
    checkFocal(capture.intrinsics, capture.path.empty() ? std::string("the capture") : capture.path);
    for (const CaptureFrame& frame : capture.frames) {
        if (frame.intrinsics) checkFocal(*frame.intrinsics, frameName(frame));
        if (!frame.pose) continue;
        const auto& r = frame.pose->rotation;
        double det = r[0] * (r[4] * r[8] - r[5] * r[7]) - r[1] * (r[3] * r[8] - r[5] * r[6]) +
                     r[2] * (r[3] * r[7] - r[4] * r[6]);
        if (!(det > 0))
            throw Error(
                ErrorKind::Input,
                fmt::format("{}: the camera pose is mirrored (left-handed): its rotation has determinant {:.3g}",
                            frameName(frame), det),
                std::nullopt, hint);
    }
}

}  // namespace capture_detail

}  // namespace smql::ingest
