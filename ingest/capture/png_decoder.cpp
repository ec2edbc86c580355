#include "ingest/capture/png_decoder.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

#include <libdeflate.h>

#include "ingest/capture/capture_detail.hpp"

namespace smql::ingest {

namespace {

constexpr std::array<std::uint8_t, 8> kSignature{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

std::uint32_t bigEndian32(const std::uint8_t* p) {
    return std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 | p[3];
}

bool named(const std::uint8_t* type, const char (&name)[5]) { return std::memcmp(type, name, 4) == 0; }

// The two kinds of PNG decoded here, by their header's bit depth and colour type.
struct Kind {
    std::uint8_t bitDepth, colourType;
    bool colourSpaceHarmless;  // see harmless()
};
constexpr Kind kDepth{16, 0, false};  // 16-bit greyscale, two bytes a pixel
constexpr Kind kColour{8, 2, true};   // 8-bit RGB, three bytes a pixel

// Chunks that leave the samples as OpenCV reads them: text, time, physical size; for an RGB image read
// as colour, also gamma, chromaticities, sRGB and the background colour, which OpenCV applies to no
// image it reads (held to its pixels on the dining frames, which carry all four). Any other ancillary
// chunk (transparency, significant bits, colour profiles, and the colour-space chunks of a 16-bit
// image read unchanged) is read by OpenCV.
bool harmless(const std::uint8_t* type, const Kind& kind) {
    if (named(type, "tEXt") || named(type, "zTXt") || named(type, "iTXt") || named(type, "tIME") || named(type, "pHYs"))
        return true;
    return kind.colourSpaceHarmless &&
           (named(type, "gAMA") || named(type, "cHRM") || named(type, "sRGB") || named(type, "bKGD"));
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

// Undoes a row's filter in place; `above` is the previous row, unfiltered (zeros for the first); `left`
// is the bytes of a pixel (a constant, so that the loops are unrolled for it).
template <std::size_t left>
bool unfilter(int filter, std::uint8_t* row, const std::uint8_t* above, std::size_t length) {
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

// A thread's decompressor and buffers, kept from frame to frame: a frame's compressed and inflated bytes
// are about a megabyte, and fresh pages for them each time cost the decoder as much as the inflating where
// other allocations come between (docs/benchmarks.md, "Ingest"), where OpenCV's reading fills only the
// image. Buffers grown past a large frame's size are let go after it.
struct Decompressor {
    Decompressor() : state(libdeflate_alloc_decompressor()) {}
    ~Decompressor() { libdeflate_free_decompressor(state); }
    Decompressor(const Decompressor&) = delete;
    Decompressor& operator=(const Decompressor&) = delete;
    libdeflate_decompressor* state;
    std::vector<std::uint8_t> compressed, filtered;
};

class ThreadDecompressor {
public:
    ThreadDecompressor() : kept_(threadDecompressor()) { kept_.compressed.clear(); }
    ~ThreadDecompressor() {
        constexpr std::size_t kKeptBytes = 32u << 20;  // a 4K frame's RGB rows
        if (kept_.compressed.capacity() > kKeptBytes) kept_.compressed = {};
        if (kept_.filtered.capacity() > kKeptBytes) kept_.filtered = {};
    }
    ThreadDecompressor(const ThreadDecompressor&) = delete;
    ThreadDecompressor& operator=(const ThreadDecompressor&) = delete;
    Decompressor* operator->() { return &kept_; }

private:
    static Decompressor& threadDecompressor() {
        thread_local Decompressor decompressor;
        return decompressor;
    }
    Decompressor& kept_;
};

// A PNG of `kind`, its rows unfiltered and each handed to `store` (the row's bytes, the image's row, the
// width) to write in OpenCV's layout; std::nullopt as the header says.
template <std::size_t bytesPerPixel, typename Store>
std::optional<cv::Mat> decodePng(std::span<const std::uint8_t> file, long long maxPixels, const Kind& kind, int matType,
                                 Store store) {
    if (file.size() < kSignature.size() || !std::equal(kSignature.begin(), kSignature.end(), file.begin()))
        return std::nullopt;
    int width = 0, height = 0;
    ThreadDecompressor decompressor;
    std::vector<std::uint8_t>& compressed = decompressor->compressed;
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
            // The kind's bit depth and colour type, deflate, adaptive filters, not interlaced.
            if (length != 13 || data[8] != kind.bitDepth || data[9] != kind.colourType || data[10] != 0 ||
                data[11] != 0 || data[12] != 0)
                return std::nullopt;
            const std::uint32_t w = bigEndian32(data), h = bigEndian32(data + 4);
            // Sides OpenCV reads (it throws past 2^20); their product is taken unsigned.
            if (w == 0 || h == 0 || w > capture_detail::kMaxDecodedSide || h > capture_detail::kMaxDecodedSide ||
                std::uint64_t{w} * h > static_cast<std::uint64_t>(std::max(maxPixels, 0LL)))
                return std::nullopt;
            width = static_cast<int>(w);
            height = static_cast<int>(h);
        } else if (named(type, "IDAT")) {
            compressed.insert(compressed.end(), data, data + length);
        } else if (named(type, "IEND")) {
            ended = true;
        } else if (!harmless(type, kind)) {
            return std::nullopt;
        }
        at += 12 + std::size_t{length};
    }

    const std::size_t rowBytes = static_cast<std::size_t>(width) * bytesPerPixel, stride = rowBytes + 1;
    std::vector<std::uint8_t>& filtered = decompressor->filtered;
    filtered.resize(stride * static_cast<std::size_t>(height));
    if (libdeflate_zlib_decompress(decompressor->state, compressed.data(), compressed.size(), filtered.data(),
                                   filtered.size(), nullptr) != LIBDEFLATE_SUCCESS)
        return std::nullopt;  // damaged, or not exactly the rows the header says

    cv::Mat pixels(height, width, matType);
    const std::vector<std::uint8_t> zeros(rowBytes, 0);
    const std::uint8_t* above = zeros.data();
    for (int y = 0; y < height; ++y) {
        std::uint8_t* row = &filtered[static_cast<std::size_t>(y) * stride];
        if (!unfilter<bytesPerPixel>(row[0], row + 1, above, rowBytes)) return std::nullopt;
        store(row + 1, pixels.ptr(y), width);
        above = row + 1;
    }
    return pixels;
}

}  // namespace

std::optional<cv::Mat> decodeDepthPng(std::span<const std::uint8_t> file, long long maxPixels) {
    return decodePng<2>(file, maxPixels, kDepth, CV_16U, [](const std::uint8_t* row, std::uint8_t* out, int width) {
        auto* samples = reinterpret_cast<std::uint16_t*>(out);
        for (int x = 0; x < width; ++x)
            samples[x] = static_cast<std::uint16_t>(row[2 * x] << 8 | row[2 * x + 1]);  // big-endian samples
    });
}

std::optional<cv::Mat> decodeColorPng(std::span<const std::uint8_t> file, long long maxPixels) {
    return decodePng<3>(file, maxPixels, kColour, CV_8UC3, [](const std::uint8_t* row, std::uint8_t* out, int width) {
        for (int x = 0; x < width; ++x) {  // red, green, blue to OpenCV's blue, green, red
            out[3 * x] = row[3 * x + 2];
            out[3 * x + 1] = row[3 * x + 1];
            out[3 * x + 2] = row[3 * x];
        }
    });
}

}  // namespace smql::ingest
