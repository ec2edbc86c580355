// 16-bit binary PGMs decoded here (ingest/capture/pgm_decoder.hpp) against OpenCV's reading of the same
// bytes: a real depth camera's frames (../shared/data/rgbd-dining), headers in each form the format allows,
// and the files the decoder leaves to OpenCV.
#include <catch2/catch.hpp>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "capture_support.hpp"
#include "ingest/capture/capture_detail.hpp"
#include "ingest/capture/media.hpp"
#include "ingest/capture/pgm_decoder.hpp"

// Named, tests and all: the unity build joins the test files, and their anonymous namespaces with them.
namespace pgm_decoder_test {

using namespace smql::ingest;
using namespace smql::ingest::capture_detail;

using Bytes = std::vector<std::uint8_t>;
constexpr long long kAnySize = 100'000'000;

Bytes readBytes(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// A PGM of `header` followed by the pixels of a width x height ramp, big-endian, two bytes each.
Bytes pgm(const std::string& header, int width, int height) {
    Bytes file(header.begin(), header.end());
    for (int i = 0; i < width * height; ++i) {
        const auto value = static_cast<std::uint16_t>(i * 977 + 13);
        file.push_back(static_cast<std::uint8_t>(value >> 8));
        file.push_back(static_cast<std::uint8_t>(value & 0xFF));
    }
    return file;
}

void requireSameAsOpenCv(const Bytes& file) {
    smql::ingest::test::requireAsOpenCvReads(decodeDepthPgm(file, kAnySize), file, cv::IMREAD_UNCHANGED);
}

// The file without its last `bytes` bytes.
Bytes shortened(Bytes file, std::size_t bytes) {
    file.resize(file.size() - bytes);
    return file;
}

TEST_CASE("depth PGMs: a real depth camera's frames decode to OpenCV's pixels", "[capture][pgm][real]") {
    int frames = 0;
    for (const auto& entry : std::filesystem::directory_iterator(smql::ingest::test::diningPath() + "/depth")) {
        INFO(entry.path());
        const Bytes file = readBytes(entry.path());
        requireSameAsOpenCv(file);
        CHECK(decodeDepthPgm(file, kAnySize)->size() == cv::Size(640, 480));
        // Known by its signature, and its size read from its header, without OpenCV.
        CHECK(media::readable(entry.path().string()));
        CHECK(storedImageSize(entry.path()) == std::pair{640, 480});
        ++frames;
    }
    CHECK(frames == 5);
}

TEST_CASE("depth PGMs: headers with comments, any white space and values past the largest", "[capture][pgm]") {
    // OpenCV takes the samples as they are, not scaled to the largest value nor cut at it.
    requireSameAsOpenCv(pgm("P5 7 3 1000\n", 7, 3));
    requireSameAsOpenCv(pgm("P5\n# a comment\n7\t3\r\n# another\r65535\n", 7, 3));
    requireSameAsOpenCv(pgm("P5\n#comment to a carriage return\r7 3\n#\n300 ", 7, 3));
    // The one byte after the largest value is read past, whatever it is.
    requireSameAsOpenCv(pgm("P5 7 3 4095#", 7, 3));
    // Bytes past the last row are not read.
    Bytes longer = pgm("P5 7 3 65535\n", 7, 3);
    longer.insert(longer.end(), {'e', 'x', 't', 'r', 'a'});
    requireSameAsOpenCv(longer);
}

TEST_CASE("depth PGMs: what the decoder does not take is left to OpenCV", "[capture][pgm]") {
    // 8-bit, text (P2), colour (P6), a row short, no number, a side past OpenCV's 2^20, too many pixels.
    for (const Bytes& file :
         {pgm("P5 7 3 255\n", 7, 3), pgm("P2 7 3 1000\n", 7, 3), pgm("P6 7 1 1000\n", 7, 3),
          shortened(pgm("P5 7 3 1000\n", 7, 3), 2), pgm("P5 7 x 1000\n", 7, 3), pgm("P5 1048577 1 1000\n", 1048577, 1),
          pgm("P5 7 3 1000", 0, 0), pgm("P57 3 1000\n", 7, 3)}) {
        INFO(std::string(file.begin(), file.begin() + std::min<std::size_t>(file.size(), 16)));
        CHECK(!decodeDepthPgm(file, kAnySize));
    }
    CHECK(!decodeDepthPgm(pgm("P5 7 3 1000\n", 7, 3), 20));
    CHECK(decodeDepthPgm(pgm("P5 7 3 1000\n", 7, 3), 21));
}

}  // namespace pgm_decoder_test
