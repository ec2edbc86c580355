#include "ingest/capture/pgm_decoder.hpp"

#include <climits>

#include "ingest/capture/capture_detail.hpp"

namespace smql::ingest {

namespace {

bool space(std::uint8_t c) { return c == ' ' || (c >= '\t' && c <= '\r'); }
bool digit(std::uint8_t c) { return c >= '0' && c <= '9'; }

// A header's number from `at`: white space and comments (from '#' to the line's end) skipped before it,
// its digits, and the one byte after them read past, as OpenCV's PxM reader does; std::nullopt for any
// other byte before it, a number past INT_MAX, or the file's end.
std::optional<int> readNumber(std::span<const std::uint8_t> file, std::size_t& at) {
    while (at < file.size() && !digit(file[at])) {
        if (file[at] == '#') {
            while (at < file.size() && file[at] != '\n' && file[at] != '\r') ++at;
            ++at;
        } else if (space(file[at])) {
            ++at;
        } else {
            return std::nullopt;
        }
    }
    long long value = 0;
    for (; at < file.size() && digit(file[at]); ++at) {
        value = value * 10 + (file[at] - '0');
        if (value > INT_MAX) return std::nullopt;
    }
    if (at >= file.size()) return std::nullopt;
    ++at;
    return static_cast<int>(value);
}

}  // namespace

std::optional<PgmHeader> readPgmHeader(std::span<const std::uint8_t> file) {
    if (file.size() < 3 || file[0] != 'P' || file[1] != '5' || !space(file[2])) return std::nullopt;
    std::size_t at = 2;
    const auto width = readNumber(file, at), height = readNumber(file, at), maxValue = readNumber(file, at);
    if (!width || !height || !maxValue) return std::nullopt;
    return PgmHeader{*width, *height, *maxValue, at};
}

std::optional<cv::Mat> decodeDepthPgm(std::span<const std::uint8_t> file, long long maxPixels) {
    const auto header = readPgmHeader(file);
    if (!header || header->maxValue < 256 || header->maxValue > 65535 || header->width <= 0 || header->height <= 0 ||
        header->width > capture_detail::kMaxDecodedSide || header->height > capture_detail::kMaxDecodedSide ||
        static_cast<long long>(header->width) * header->height > maxPixels)
        return std::nullopt;
    const std::size_t pixels = static_cast<std::size_t>(header->width) * static_cast<std::size_t>(header->height);
    if (file.size() - header->dataOffset < 2 * pixels) return std::nullopt;
    cv::Mat depth(header->height, header->width, CV_16U);
    const std::uint8_t* in = file.data() + header->dataOffset;
    auto* out = depth.ptr<std::uint16_t>();
    for (std::size_t i = 0; i < pixels; ++i) out[i] = static_cast<std::uint16_t>(in[2 * i] << 8 | in[2 * i + 1]);
    return depth;
}

}  // namespace smql::ingest
