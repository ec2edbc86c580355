// The PNGs cameras' frames are stored as, decoded with libdeflate at about twice the speed of OpenCV's
// libpng and zlib: depth cameras' 16-bit greyscale images (Kinect, TUM, ScanNet, 7-Scenes) and the 8-bit RGB
// colour frames beside them (TUM's: a depth image in 1.7 ms against 2.9, a colour frame in 2.5 against 4.9;
// docs/benchmarks.md, "Ingest"). Any other PNG, and one whose chunks or data do not check out, is left to
// OpenCV (std::nullopt), which reads every kind and words the errors.
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

// The file's pixels as CV_8UC3 in OpenCV's order (blue, green, red), equal to cv::imdecode(file,
// IMREAD_COLOR)'s, when the file is an 8-bit RGB, non-interlaced PNG of at most maxPixels pixels, sound
// as above. Its colour-space chunks (gamma, chromaticities, sRGB) and background colour are read past,
// as OpenCV reads past them; transparency and significant bits leave it to OpenCV.
std::optional<cv::Mat> decodeColorPng(std::span<const std::uint8_t> file, long long maxPixels);

}  // namespace smql::ingest
