// Depth and colour PNGs decoded with libdeflate (ingest/capture/png_decoder.hpp) against OpenCV's reading
// of the same files: real cameras' images, PNGs written here with each of PNG's row filters (OpenCV's writer
// only uses one), and the files the decoder leaves to OpenCV.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <libdeflate.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "capture_support.hpp"
#include "ingest/capture/capture_detail.hpp"
#include "ingest/capture/png_decoder.hpp"

using namespace smql;
using namespace smql::ingest;

namespace {

using Bytes = std::vector<std::uint8_t>;
constexpr long long kAnySize = 100'000'000;

void appendBigEndian(Bytes& out, std::uint32_t value) {
    for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<std::uint8_t>(value >> shift));
}

void appendChunk(Bytes& png, const char* type, const Bytes& data) {
    appendBigEndian(png, static_cast<std::uint32_t>(data.size()));
    Bytes typed(type, type + 4);
    typed.insert(typed.end(), data.begin(), data.end());
    png.insert(png.end(), typed.begin(), typed.end());
    appendBigEndian(png, libdeflate_crc32(0, typed.data(), typed.size()));
}

// The predictor as the PNG specification words it.
int paethPredictor(int a, int b, int c) {
    const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    if (pa <= pb && pa <= pc) return a;
    if (pb <= pc) return b;
    return c;
}

struct PngOptions {
    std::optional<std::uint8_t> bitDepth = std::nullopt, colourType = std::nullopt;  // the image's own when not given
    std::uint8_t interlace = 0;
    std::vector<std::string> extraChunks;  // ancillary chunks (empty data) before the image data
};

// A PNG of `image` (16-bit greyscale, or 8-bit colour in OpenCV's blue-green-red), row y filtered with
// filters[y % filters.size()].
Bytes pngOf(const cv::Mat& image, const std::vector<int>& filters, const PngOptions& options = {}) {
    REQUIRE((image.type() == CV_16UC1 || image.type() == CV_8UC3));
    const bool depth = image.type() == CV_16UC1;
    const std::size_t pixelBytes = depth ? 2 : 3, rowBytes = static_cast<std::size_t>(image.cols) * pixelBytes;
    Bytes raw, previous(rowBytes, 0);
    for (int y = 0; y < image.rows; ++y) {
        Bytes row;
        for (int x = 0; x < image.cols; ++x) {
            if (depth) {
                row.push_back(static_cast<std::uint8_t>(image.at<std::uint16_t>(y, x) >> 8));
                row.push_back(static_cast<std::uint8_t>(image.at<std::uint16_t>(y, x) & 0xff));
            } else {
                const auto& bgr = image.at<cv::Vec3b>(y, x);
                row.insert(row.end(), {bgr[2], bgr[1], bgr[0]});
            }
        }
        const int filter = filters[static_cast<std::size_t>(y) % filters.size()];
        raw.push_back(static_cast<std::uint8_t>(filter));
        for (std::size_t x = 0; x < rowBytes; ++x) {
            const int a = x >= pixelBytes ? row[x - pixelBytes] : 0, b = previous[x],
                      c = x >= pixelBytes ? previous[x - pixelBytes] : 0;
            const int predicted = filter == 1   ? a
                                  : filter == 2 ? b
                                  : filter == 3 ? (a + b) / 2
                                  : filter == 4 ? paethPredictor(a, b, c)
                                                : 0;
            raw.push_back(static_cast<std::uint8_t>(row[x] - predicted));
        }
        previous = row;
    }
    libdeflate_compressor* compressor = libdeflate_alloc_compressor(6);
    Bytes compressed(libdeflate_zlib_compress_bound(compressor, raw.size()));
    compressed.resize(
        libdeflate_zlib_compress(compressor, raw.data(), raw.size(), compressed.data(), compressed.size()));
    libdeflate_free_compressor(compressor);
    REQUIRE(!compressed.empty());

    Bytes png{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'}, header;
    appendBigEndian(header, static_cast<std::uint32_t>(image.cols));
    appendBigEndian(header, static_cast<std::uint32_t>(image.rows));
    header.insert(header.end(), {options.bitDepth.value_or(depth ? 16 : 8), options.colourType.value_or(depth ? 0 : 2),
                                 0, 0, options.interlace});
    appendChunk(png, "IHDR", header);
    for (const auto& type : options.extraChunks)
        appendChunk(png, type.c_str(), Bytes(type == "tRNS" ? pixelBytes : 0, 0));
    // The data in two chunks, as encoders split it.
    const std::size_t half = compressed.size() / 2;
    appendChunk(png, "IDAT", Bytes(compressed.begin(), compressed.begin() + static_cast<std::ptrdiff_t>(half)));
    appendChunk(png, "IDAT", Bytes(compressed.begin() + static_cast<std::ptrdiff_t>(half), compressed.end()));
    appendChunk(png, "IEND", {});
    return png;
}

// Depth-like samples: smooth surfaces, edges, holes (0) and the full 16-bit range.
cv::Mat1w depthLike(int width, int height) {
    std::mt19937 random(7);
    std::uniform_int_distribution<int> noise(0, 40), any(0, 65535);
    cv::Mat1w samples(height, width);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            int value = 1500 + 9 * x + 4 * y + noise(random);
            if ((x / 7 + y / 5) % 6 == 0) value = 0;
            if (x > width * 3 / 4) value = any(random);
            samples(y, x) = static_cast<std::uint16_t>(value);
        }
    return samples;
}

// After the header's width (bytes 16-19) or height (20-23) changed: its chunk's checksum (29-32) again.
void setHeaderChecksum(Bytes& png) {
    const std::uint32_t crc = libdeflate_crc32(0, &png[12], 17);
    for (int i = 0; i < 4; ++i) png[29 + i] = static_cast<std::uint8_t>(crc >> (24 - 8 * i));
}

bool sameAsOpenCv(const Bytes& png) {
    const auto ours = decodeDepthPng(png, kAnySize);
    const cv::Mat theirs = cv::imdecode(png, cv::IMREAD_UNCHANGED);
    REQUIRE(ours);
    REQUIRE(theirs.type() == CV_16UC1);
    return ours->size() == theirs.size() && cv::norm(*ours, theirs, cv::NORM_INF) == 0;
}

bool sameColourAsOpenCv(const Bytes& png) {
    const auto ours = decodeColorPng(png, kAnySize);
    const cv::Mat theirs = cv::imdecode(png, cv::IMREAD_COLOR);
    REQUIRE(ours);
    REQUIRE(theirs.type() == CV_8UC3);
    return ours->type() == CV_8UC3 && ours->size() == theirs.size() && cv::norm(*ours, theirs, cv::NORM_INF) == 0;
}

// Colour-like pixels: gradients, flat patches, and noise over the whole byte range.
cv::Mat3b colourLike(int width, int height) {
    std::mt19937 random(11);
    std::uniform_int_distribution<int> any(0, 255);
    cv::Mat3b pixels(height, width);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            cv::Vec3b value(static_cast<std::uint8_t>(3 * x + y), static_cast<std::uint8_t>(90 + (y / 4) * 7),
                            static_cast<std::uint8_t>(200 - 2 * x));
            if (x > width * 3 / 4)
                value = cv::Vec3b(static_cast<std::uint8_t>(any(random)), static_cast<std::uint8_t>(any(random)),
                                  static_cast<std::uint8_t>(any(random)));
            pixels(y, x) = value;
        }
    return pixels;
}

Bytes readBytes(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

TEST_CASE("depth PNGs: each row filter decodes to OpenCV's pixels", "[capture][png]") {
    const cv::Mat1w samples = depthLike(97, 41);  // an odd width: rows end mid-way through a filter's reach
    for (int filter = 0; filter <= 4; ++filter) {
        INFO("every row filtered with " << filter);
        CHECK(sameAsOpenCv(pngOf(samples, {filter})));
    }
    CHECK(sameAsOpenCv(pngOf(samples, {4, 3, 2, 1, 0, 3, 4})));  // mixed, as encoders choose row by row
    CHECK(sameAsOpenCv(pngOf(samples, {1}, {.extraChunks = {"tEXt", "pHYs"}})));
    CHECK(sameAsOpenCv(pngOf(depthLike(1, 1), {4})));
}

TEST_CASE("depth PNGs: a real depth camera's images decode to OpenCV's pixels", "[capture][png]") {
    // TUM fr1/rpy's 121 Kinect depth images.
    std::vector<std::filesystem::path> files;
    for (const auto& entry :
         std::filesystem::directory_iterator(std::filesystem::path(SMQL_SHARED_DATA) / "captures/tum-fr1-rpy/depth"))
        files.push_back(entry.path());
    REQUIRE(files.size() == 121);
    for (const auto& file : files) {
        INFO(file.string());
        const Bytes png = readBytes(file);
        REQUIRE(sameAsOpenCv(png));
        CHECK(cv::countNonZero(*decodeDepthPng(png, kAnySize)) > 0);
    }
}

TEST_CASE("depth PNGs: what the decoder does not take is left to OpenCV", "[capture][png]") {
    const cv::Mat1w samples = depthLike(32, 24);
    const Bytes good = pngOf(samples, {4});
    REQUIRE(decodeDepthPng(good, kAnySize));

    SECTION("other kinds of PNG") {
        Bytes eightBit;
        cv::imencode(".png", cv::Mat1b(24, 32, std::uint8_t{90}), eightBit);
        CHECK_FALSE(decodeDepthPng(eightBit, kAnySize));
        Bytes colour;
        cv::imencode(".png", cv::Mat(24, 32, CV_16UC3, cv::Scalar(1, 2, 3)), colour);
        CHECK_FALSE(decodeDepthPng(colour, kAnySize));
        CHECK_FALSE(decodeDepthPng(pngOf(samples, {4}, {.interlace = 1, .extraChunks = {}}), kAnySize));
        CHECK_FALSE(decodeDepthPng(pngOf(samples, {4}, {.extraChunks = {"tRNS"}}), kAnySize));  // alpha to OpenCV
        CHECK_FALSE(decodeDepthPng(pngOf(samples, {4}, {.extraChunks = {"sBIT"}}), kAnySize));
        Bytes jpeg;
        cv::imencode(".jpg", cv::Mat3b(24, 32, cv::Vec3b(1, 2, 3)), jpeg);
        CHECK_FALSE(decodeDepthPng(jpeg, kAnySize));
    }
    SECTION("damaged files") {
        Bytes flipped = good;
        flipped[flipped.size() - 30] ^= 0x40;  // inside the image data: its chunk's checksum no longer holds
        CHECK_FALSE(decodeDepthPng(flipped, kAnySize));
        for (std::size_t cut : {good.size() - 1, good.size() / 2, std::size_t{20}, std::size_t{0}})
            CHECK_FALSE(decodeDepthPng(Bytes(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(cut)), kAnySize));
        CHECK_FALSE(decodeDepthPng(pngOf(samples, {5}), kAnySize));  // no such filter
        // Rows that are not the header's: a 32 x 24 header over 32 x 23 rows.
        Bytes shortRows = pngOf(samples.rowRange(0, 23), {1});
        shortRows[23] = 24;  // the height's low byte
        setHeaderChecksum(shortRows);
        CHECK_FALSE(decodeDepthPng(shortRows, kAnySize));
    }
    SECTION("more pixels than allowed") {
        CHECK_FALSE(decodeDepthPng(good, 32 * 24 - 1));
        CHECK(decodeDepthPng(good, 32 * 24));
        // Sides whose product overflows 64-bit signed arithmetic (found by fuzz_depth_png).
        Bytes huge = good;
        for (int at : {16, 20}) huge[at] = 0xe2;
        setHeaderChecksum(huge);
        CHECK_FALSE(decodeDepthPng(huge, kAnySize));
        // A side past OpenCV's 2^20, though the pixels are few: OpenCV throws on it, so it is OpenCV's to refuse.
        const Bytes wide = pngOf(cv::Mat1w(1, capture_detail::kMaxDecodedSide + 1, std::uint16_t{7}), {0});
        CHECK_FALSE(decodeDepthPng(wide, kAnySize));
        bool openCvReads = false;
        try {
            openCvReads = !cv::imdecode(wide, cv::IMREAD_UNCHANGED).empty();
        } catch (const cv::Exception&) {
        }
        CHECK_FALSE(openCvReads);
        CHECK(decodeDepthPng(pngOf(cv::Mat1w(1, capture_detail::kMaxDecodedSide, std::uint16_t{7}), {0}), kAnySize));
    }
    SECTION("read through OpenCV: the errors are its reading's") {
        test::TempDir dir;
        Bytes damaged = good;
        damaged.resize(good.size() / 2);
        std::ofstream(dir.path("damaged.png"), std::ios::binary)
            .write(reinterpret_cast<const char*>(damaged.data()), static_cast<std::streamsize>(damaged.size()));
        CHECK_THROWS_WITH(capture_detail::readDepthImage(dir.path("damaged.png")),
                          Catch::Contains("cannot decode the depth image"));
        std::ofstream(dir.path("good.png"), std::ios::binary)
            .write(reinterpret_cast<const char*>(good.data()), static_cast<std::streamsize>(good.size()));
        CHECK(cv::norm(capture_detail::readDepthImage(dir.path("good.png")), samples, cv::NORM_INF) == 0);
    }
}

TEST_CASE("colour PNGs: each row filter decodes to OpenCV's pixels", "[capture][png]") {
    const cv::Mat3b pixels = colourLike(97, 41);
    for (int filter = 0; filter <= 4; ++filter) {
        INFO("every row filtered with " << filter);
        CHECK(sameColourAsOpenCv(pngOf(pixels, {filter})));
    }
    CHECK(sameColourAsOpenCv(pngOf(pixels, {4, 3, 2, 1, 0, 3, 4})));
    CHECK(sameColourAsOpenCv(pngOf(colourLike(1, 1), {4})));
    // What OpenCV reads past in a colour image, and what it does not.
    CHECK(sameColourAsOpenCv(pngOf(pixels, {1}, {.extraChunks = {"tEXt", "pHYs"}})));
    for (const char* chunk : {"tRNS", "sBIT", "iCCP"}) {
        INFO(chunk);
        CHECK_FALSE(decodeColorPng(pngOf(pixels, {1}, {.extraChunks = {chunk}}), kAnySize));
    }
    // A 16-bit image's gamma is left to OpenCV: it reads that kind unchanged, not as a colour image.
    CHECK_FALSE(decodeDepthPng(pngOf(depthLike(8, 8), {1}, {.extraChunks = {"gAMA"}}), kAnySize));
}

TEST_CASE("colour PNGs: real cameras' frames decode to OpenCV's pixels", "[capture][png]") {
    // TUM fr1/rpy's 121 Kinect colour frames, and the dining room's five, which carry gamma,
    // chromaticities, sRGB and a background colour.
    const std::filesystem::path data(SMQL_SHARED_DATA);
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(data / "captures/tum-fr1-rpy/rgb"))
        files.push_back(entry.path());
    REQUIRE(files.size() == 121);
    for (int i = 1; i <= 5; ++i) files.push_back(data / "rgbd-dining/color" / (std::to_string(i) + ".png"));
    for (const auto& file : files) {
        INFO(file.string());
        REQUIRE(sameColourAsOpenCv(readBytes(file)));
    }
}

TEST_CASE("colour PNGs: what the decoder does not take is left to OpenCV", "[capture][png]") {
    const cv::Mat3b pixels = colourLike(32, 24);
    const Bytes good = pngOf(pixels, {4});
    REQUIRE(decodeColorPng(good, kAnySize));
    Bytes grey, rgba, sixteen, depth;
    cv::imencode(".png", cv::Mat1b(24, 32, std::uint8_t{90}), grey);
    cv::imencode(".png", cv::Mat4b(24, 32, cv::Vec4b(1, 2, 3, 4)), rgba);
    cv::imencode(".png", cv::Mat(24, 32, CV_16UC3, cv::Scalar(1, 2, 3)), sixteen);
    CHECK_FALSE(decodeColorPng(grey, kAnySize));
    CHECK_FALSE(decodeColorPng(rgba, kAnySize));
    CHECK_FALSE(decodeColorPng(sixteen, kAnySize));
    CHECK_FALSE(decodeColorPng(pngOf(depthLike(32, 24), {4}), kAnySize));
    CHECK_FALSE(decodeDepthPng(good, kAnySize));
    CHECK_FALSE(decodeColorPng(pngOf(pixels, {4}, {.interlace = 1, .extraChunks = {}}), kAnySize));
    Bytes flipped = good;
    flipped[flipped.size() - 30] ^= 0x40;
    CHECK_FALSE(decodeColorPng(flipped, kAnySize));
    CHECK_FALSE(
        decodeColorPng(Bytes(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(good.size() / 2)), kAnySize));
    CHECK_FALSE(decodeColorPng(good, 32 * 24 - 1));

    // Read as a capture reads a colour frame: the same pixels, and OpenCV's errors for what it cannot read.
    test::TempDir dir;
    std::ofstream(dir.path("good.png"), std::ios::binary)
        .write(reinterpret_cast<const char*>(good.data()), static_cast<std::streamsize>(good.size()));
    CHECK(cv::norm(capture_detail::readColorImage(dir.path("good.png")), pixels, cv::NORM_INF) == 0);
    std::ofstream(dir.path("damaged.png"), std::ios::binary)
        .write(reinterpret_cast<const char*>(good.data()), static_cast<std::streamsize>(good.size() / 2));
    CHECK_THROWS_WITH(capture_detail::readColorImage(dir.path("damaged.png")),
                      Catch::Contains("cannot decode the colour image"));
}
