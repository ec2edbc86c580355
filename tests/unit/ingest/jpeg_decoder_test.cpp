// JPEG colour frames decoded by TurboJPEG (ingest/capture/jpeg_decoder.hpp) against OpenCV's reading of
// the same bytes: real cameras' frames (the dining room's, TUM's desk) written as JPEGs of each kind a
// camera or a converter writes, and the files the decoder leaves to OpenCV.
#include <catch2/catch.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include <turbojpeg.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "capture_support.hpp"
#include "ingest/capture/jpeg_decoder.hpp"

// Named, tests and all: the unity build joins the test files, and their anonymous namespaces with them.
namespace jpeg_decoder_test {

using namespace smql::ingest;
using Bytes = std::vector<std::uint8_t>;
constexpr long long kAnyJpegSize = 100'000'000;

// Real frames: the five of the dining room and two of TUM's fr1/rpy.
std::vector<cv::Mat> realFrames() {
    std::vector<cv::Mat> frames;
    for (int i = 1; i <= 5; ++i)
        frames.push_back(cv::imread(smql::ingest::test::diningPath() + "/color/" + std::to_string(i) + ".png"));
    std::vector<cv::String> tum;
    cv::glob(std::string(SMQL_SHARED_DATA) + "/captures/tum-fr1-rpy/rgb/*.png", tum);
    if (tum.size() >= 2) {
        frames.push_back(cv::imread(tum.front()));
        frames.push_back(cv::imread(tum.back()));
    }
    for (const auto& f : frames) REQUIRE(!f.empty());
    return frames;
}

// `bgr` as TurboJPEG writes it with the given chroma subsampling (TJSAMP_*), or as CMYK.
Bytes turboJpeg(const cv::Mat& bgr, int subsampling, bool cmyk = false) {
    const std::unique_ptr<void, int (*)(tjhandle)> encoder(tjInitCompress(), tjDestroy);
    REQUIRE(encoder);
    cv::Mat pixels = bgr;
    int format = TJPF_BGR;
    if (cmyk) {  // ink as 255 less each colour: enough for a CMYK file's bytes
        cv::Mat inverted = cv::Scalar::all(255) - bgr, channels[3];
        cv::split(inverted, channels);
        cv::merge(std::vector<cv::Mat>{channels[2], channels[1], channels[0], cv::Mat::zeros(bgr.size(), CV_8U)},
                  pixels);
        format = TJPF_CMYK;
    }
    unsigned char* out = nullptr;
    unsigned long size = 0;
    REQUIRE(tjCompress2(encoder.get(), pixels.data, pixels.cols, static_cast<int>(pixels.step), pixels.rows, format,
                        &out, &size, subsampling, 90, 0) == 0);
    Bytes file(out, out + size);
    tjFree(out);
    return file;
}

Bytes openCvJpeg(const cv::Mat& image, std::vector<int> parameters = {}) {
    Bytes file;
    REQUIRE(cv::imencode(".jpg", image, file, parameters));
    return file;
}

void requireSameAsOpenCv(const Bytes& file) {
    smql::ingest::test::requireAsOpenCvReads(decodeColorJpeg(file, kAnyJpegSize), file, cv::IMREAD_COLOR);
}

TEST_CASE("colour JPEGs: real frames in each kind of JPEG decode to OpenCV's pixels", "[capture][jpeg][real]") {
    for (const cv::Mat& frame : realFrames()) {
        // OpenCV's writer (4:2:0): its default quality, a low one, progressive, optimised tables, restarts.
        requireSameAsOpenCv(openCvJpeg(frame));
        requireSameAsOpenCv(openCvJpeg(frame, {cv::IMWRITE_JPEG_QUALITY, 40}));
        requireSameAsOpenCv(openCvJpeg(frame, {cv::IMWRITE_JPEG_PROGRESSIVE, 1}));
        requireSameAsOpenCv(openCvJpeg(frame, {cv::IMWRITE_JPEG_OPTIMIZE, 1, cv::IMWRITE_JPEG_RST_INTERVAL, 7}));
        // Each chroma subsampling, and greyscale, read as colour.
        for (int subsampling : {TJSAMP_444, TJSAMP_422, TJSAMP_440, TJSAMP_411, TJSAMP_GRAY})
            requireSameAsOpenCv(turboJpeg(frame, subsampling));
        cv::Mat grey;
        cv::cvtColor(frame, grey, cv::COLOR_BGR2GRAY);
        requireSameAsOpenCv(openCvJpeg(grey));
    }
}

TEST_CASE("colour JPEGs: what the decoder does not take is left to OpenCV", "[capture][jpeg]") {
    const cv::Mat frame = realFrames().front();
    const Bytes jpeg = openCvJpeg(frame);
    // EXIF data, which may turn the image (OpenCV applies its orientation): an APP1 segment with a
    // little-endian TIFF header and no entries, right after the start of the image.
    Bytes exif(jpeg.begin(), jpeg.begin() + 2);
    const Bytes segment{0xFF, 0xE1, 0x00, 0x10, 'E', 'x', 'i', 'f', 0, 0, 'I', 'I', 42, 0, 8, 0, 0, 0};
    exif.insert(exif.end(), segment.begin(), segment.end());
    exif.insert(exif.end(), jpeg.begin() + 2, jpeg.end());
    CHECK(!decodeColorJpeg(exif, kAnyJpegSize));
    CHECK(!cv::imdecode(exif, cv::IMREAD_COLOR).empty());
    // CMYK, which OpenCV turns into colour itself.
    const Bytes cmyk = turboJpeg(frame, TJSAMP_444, /*cmyk=*/true);
    CHECK(!decodeColorJpeg(cmyk, kAnyJpegSize));
    CHECK(!cv::imdecode(cmyk, cv::IMREAD_COLOR).empty());
    // Cut short: decoded with a warning, so left to OpenCV, which reads the rows it has.
    const Bytes cut(jpeg.begin(), jpeg.begin() + static_cast<std::ptrdiff_t>(jpeg.size() * 2 / 3));
    CHECK(!decodeColorJpeg(cut, kAnyJpegSize));
    CHECK(!cv::imdecode(cut, cv::IMREAD_COLOR).empty());
    // More pixels than asked for; not a JPEG.
    CHECK(!decodeColorJpeg(jpeg, frame.total() - 1));
    CHECK(decodeColorJpeg(jpeg, frame.total()));
    CHECK(!decodeColorJpeg(Bytes{0xFF, 0xD8, 0xFF}, kAnyJpegSize));
    CHECK(!decodeColorJpeg(Bytes(jpeg.begin() + 1, jpeg.end()), kAnyJpegSize));
}

}  // namespace jpeg_decoder_test
