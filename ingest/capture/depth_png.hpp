// Depth images as depth cameras store them (Kinect, TUM, ScanNet, 7-Scenes): 16-bit greyscale PNGs,
// decoded with libdeflate, 2.4 times as fast as OpenCV's libpng and zlib (a 640 x 480 frame of
// ScanNet's in 1.7 ms against 3.9): a depth camera's frames were a tenth of the frame pass's CPU
// outside the models. Any other PNG, and one whose chunks or data do not check out, is left to OpenCV
// (std::nullopt), which reads every kind and words the errors.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include <opencv2/core.hpp>

namespace smql::ingest {

// The file's pixels as CV_16U, equal to cv::imdecode(file, IMREAD_UNCHANGED)'s, when the file is a
// 16-bit greyscale, non-interlaced PNG of at most maxPixels pixels whose chunk checksums, compressed
// data and row filters are all sound and which holds no chunk that would change what OpenCV reads
// (transparency, significant bits, unknown critical chunks).
std::optional<cv::Mat> decodeDepthPng(std::span<const std::uint8_t> file, long long maxPixels);

}  // namespace smql::ingest
