#include "ingest/capture/depth_png.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

#include <libdeflate.h>

namespace smql::ingest {

namespace {

constexpr std::array<std::uint8_t, 8> kSignature{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
constexpr int kBytesPerPixel = 2;  // one 16-bit sample

std::uint32_t bigEndian32(const std::uint8_t* p) {
    return std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 | p[3];
}

bool named(const std::uint8_t* type, const char (&name)[5]) { return std::memcmp(type, name, 4) == 0; }

// Chunks that leave the samples as OpenCV reads them: text, time, physical size. Any other
// ancillary chunk (transparency, significant bits, gamma, colour profiles) is read by OpenCV.
bool harmless(const std::uint8_t* type) {
    return named(type, "tEXt") || named(type, "zTXt") || named(type, "iTXt") || named(type, "tIME") ||
           named(type, "pHYs");
}

// PNG's predictor of a byte from the one to its left (a), above (b) and above-left (c): the one nearest
// a + b - c, ties to a, then b.
// Written as selects, not branches: the compiler makes them conditional moves (Paeth is most rows of
// a depth image, and its branches are taken at random).
std::uint8_t paeth(int a, int b, int c) {
    const int pa = std::abs(b - c), pb = std::abs(a - c), pc = std::abs(a + b - 2 * c);
    const int nearer = pb < pa ? b : a, distance = pb < pa ? pb : pa;
    return static_cast<std::uint8_t>(pc < distance ? c : nearer);
}

// Undoes a row's filter in place; `above` is the previous row, unfiltered (zeros for the first).
bool unfilter(int filter, std::uint8_t* row, const std::uint8_t* above, std::size_t length) {
    constexpr std::size_t left = kBytesPerPixel;
    switch (filter) {
        case 0:  // none
            return true;
        case 1:  // sub
            for (std::size_t x = left; x < length; ++x) row[x] += row[x - left];
            return true;
        case 2:  // up
            for (std::size_t x = 0; x < length; ++x) row[x] += above[x];
            return true;
        case 3:  // average
            for (std::size_t x = 0; x < left; ++x) row[x] += above[x] >> 1;
            for (std::size_t x = left; x < length; ++x) row[x] += (row[x - left] + above[x]) >> 1;
            return true;
        case 4:  // Paeth
            for (std::size_t x = 0; x < left; ++x) row[x] += above[x];
            for (std::size_t x = left; x < length; ++x) row[x] += paeth(row[x - left], above[x], above[x - left]);
            return true;
        default:
            return false;
    }
}

struct Decompressor {
    Decompressor() : state(libdeflate_alloc_decompressor()) {}
    ~Decompressor() { libdeflate_free_decompressor(state); }
    Decompressor(const Decompressor&) = delete;
    Decompressor& operator=(const Decompressor&) = delete;
    libdeflate_decompressor* state;
};

}  // namespace

std::optional<cv::Mat> decodeDepthPng(std::span<const std::uint8_t> file, long long maxPixels) {
    if (file.size() < kSignature.size() || !std::equal(kSignature.begin(), kSignature.end(), file.begin()))
        return std::nullopt;
    int width = 0, height = 0;
    std::vector<std::uint8_t> compressed;
    bool ended = false;
    for (std::size_t at = kSignature.size(); !ended;) {
        if (file.size() - at < 12) return std::nullopt;  // length, type and checksum
        const std::uint32_t length = bigEndian32(&file[at]);
        if (length > file.size() - at - 12) return std::nullopt;
        const std::uint8_t* type = &file[at + 4];
        const std::uint8_t* data = type + 4;
        if (libdeflate_crc32(0, type, length + 4) != bigEndian32(data + length)) return std::nullopt;
        const bool first = at == kSignature.size();
        if (first != named(type, "IHDR")) return std::nullopt;
        if (first) {
            // 16-bit greyscale, deflate, adaptive filters, not interlaced.
            if (length != 13 || data[8] != 16 || data[9] != 0 || data[10] != 0 || data[11] != 0 || data[12] != 0)
                return std::nullopt;
            const std::uint32_t w = bigEndian32(data), h = bigEndian32(data + 4);
            // PNG's sides are under 2^31; their product is taken unsigned, where it cannot overflow.
            if (w == 0 || h == 0 || w > 0x7fffffffu || h > 0x7fffffffu ||
                std::uint64_t{w} * h > static_cast<std::uint64_t>(std::max(maxPixels, 0LL)))
                return std::nullopt;
            width = static_cast<int>(w);
            height = static_cast<int>(h);
        } else if (named(type, "IDAT")) {
            compressed.insert(compressed.end(), data, data + length);
        } else if (named(type, "IEND")) {
            ended = true;
        } else if (!harmless(type)) {
            return std::nullopt;
        }
        at += 12 + std::size_t{length};
    }

    const std::size_t rowBytes = static_cast<std::size_t>(width) * kBytesPerPixel, stride = rowBytes + 1;
    std::vector<std::uint8_t> filtered(stride * static_cast<std::size_t>(height));
    thread_local Decompressor decompressor;
    if (libdeflate_zlib_decompress(decompressor.state, compressed.data(), compressed.size(), filtered.data(),
                                   filtered.size(), nullptr) != LIBDEFLATE_SUCCESS)
        return std::nullopt;  // damaged, or not exactly the rows the header says

    cv::Mat depth(height, width, CV_16U);
    const std::vector<std::uint8_t> zeros(rowBytes, 0);
    const std::uint8_t* above = zeros.data();
    for (int y = 0; y < height; ++y) {
        std::uint8_t* row = &filtered[static_cast<std::size_t>(y) * stride];
        if (!unfilter(row[0], row + 1, above, rowBytes)) return std::nullopt;
        auto* out = depth.ptr<std::uint16_t>(y);
        for (int x = 0; x < width; ++x)
            out[x] = static_cast<std::uint16_t>(row[1 + 2 * x] << 8 | row[2 + 2 * x]);  // big-endian samples
        above = row + 1;
    }
    return depth;
}

}  // namespace smql::ingest
