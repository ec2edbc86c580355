// The JPEG colour frames many RGB-D captures are stored as (ScanNet's, Redwood's), decoded by TurboJPEG,
// which the ingest links already for its crops, so that such a capture is read without OpenCV's image
// codecs, whose module (libsmql_media.so, media.hpp) takes about 0.27 s and 55 MB to load. A JPEG with
// EXIF data (OpenCV turns the image as its orientation says), a CMYK one, and one TurboJPEG decodes only
// with a warning (damaged data) is left to OpenCV (std::nullopt), which reads every kind and words the
// errors.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include <opencv2/core.hpp>

namespace smql::ingest {

// The file's pixels as CV_8UC3 in OpenCV's order (blue, green, red), equal to cv::imdecode(file,
// IMREAD_COLOR)'s, when the file is a JPEG (baseline or progressive, colour or greyscale) without EXIF
// data, of at most maxPixels pixels and sides OpenCV reads (2^20), that decodes without a warning.
std::optional<cv::Mat> decodeColorJpeg(std::span<const std::uint8_t> file, long long maxPixels);

}  // namespace smql::ingest
