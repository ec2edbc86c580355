// The frames' image files decoded here before OpenCV is asked (png_decoder.hpp, pgm_decoder.hpp,
// jpeg_decoder.hpp): each decoder gives OpenCV's pixels for the files it takes and leaves the rest
// (std::nullopt), so that a depth camera's capture is read without OpenCV's image module (media.hpp).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "ingest/capture/jpeg_decoder.hpp"
#include "ingest/capture/pgm_decoder.hpp"
#include "ingest/capture/png_decoder.hpp"

namespace smql::ingest {

using FrameDecoder = std::optional<cv::Mat> (*)(std::span<const std::uint8_t> file, long long maxPixels);

// The decoders of a kind of frame, tried in order, and how OpenCV reads that kind (the flags of
// cv::imdecode whose pixels each decoder gives).
struct FrameDecoders {
    std::array<FrameDecoder, 2> decoders;
    int openCvFlags;
};
inline constexpr FrameDecoders kColourFrameDecoders{{decodeColorPng, decodeColorJpeg}, cv::IMREAD_COLOR};
inline constexpr FrameDecoders kDepthFrameDecoders{{decodeDepthPng, decodeDepthPgm}, cv::IMREAD_UNCHANGED};

}  // namespace smql::ingest
