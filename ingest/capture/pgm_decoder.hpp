// The 16-bit binary PGMs some depth captures are stored as (OpenCV's RGB-D samples, the dining frames),
// read here so that a capture of PNG colour and PGM depth is read without OpenCV's image codecs, whose
// module (libsmql_media.so, media.hpp) takes about 0.27 s to load. Any other PGM or PPM, and one whose
// header or data fall short, is left to OpenCV (std::nullopt), which reads every kind and words the errors.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include <opencv2/core.hpp>

namespace smql::ingest {

// A binary greyscale portable map's header ("P5", its width, height and largest value), as OpenCV reads
// it: white space and '#' comments between the numbers, one byte of any kind after the largest value.
struct PgmHeader {
    int width = 0, height = 0, maxValue = 0;
    std::size_t dataOffset = 0;  // where the pixels start
};
std::optional<PgmHeader> readPgmHeader(std::span<const std::uint8_t> file);

// The file's pixels as CV_16U, equal to cv::imdecode(file, IMREAD_UNCHANGED)'s, when the file is a binary
// PGM whose largest value is 256 to 65535 (two big-endian bytes a pixel, taken as they are), of at most
// maxPixels pixels and sides OpenCV reads (2^20), holding all of its rows.
std::optional<cv::Mat> decodeDepthPgm(std::span<const std::uint8_t> file, long long maxPixels);

}  // namespace smql::ingest
