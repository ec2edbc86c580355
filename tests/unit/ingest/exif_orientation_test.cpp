// Photos whose EXIF orientation turns them reach COLMAP upright, as smql
// reads them (COLMAP reads the pixels as stored); other photos reach it as
// they are (ingest/geometry/colmap_runner.cpp, docs/ingest.md "Sizes").
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "capture_support.hpp"
#include "exif_jpeg.hpp"
#include "ingest/capture/capture.hpp"
#include "ingest/geometry/colmap_runner.hpp"
#include "model/error.hpp"
#include "scratch_dir.hpp"

using namespace smql;
using namespace smql::ingest;
using namespace smql::ingest::test;

namespace {

// Whether the two files hold the same bytes (a link is followed).
bool sameBytes(const fs::path& a, const fs::path& b) {
    auto bytes = [](const fs::path& file) {
        std::ifstream in(file, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    };
    return fs::is_regular_file(a) && bytes(a) == bytes(b);
}

// The pixels as stored, whatever the file's EXIF orientation says.
cv::Mat storedPixels(const fs::path& file) {
    return cv::imread(file.string(), cv::IMREAD_COLOR | cv::IMREAD_IGNORE_ORIENTATION);
}

}  // namespace

TEST_CASE("a photo stored on its side reaches COLMAP upright; upright photos reach it unchanged", "[exif]") {
    TempDir dir;
    const cv::Mat landscape = markedImage(64, 48);
    const std::string turned = writeExifJpeg(dir, "photos/p1.jpg", landscape, {.orientation = 6});
    const std::string upright = writeExifJpeg(dir, "photos/p2.jpg", landscape, {.orientation = 1});
    const std::string plain = dir.path("photos/p3.jpg");
    // Another quality than the 95 smql writes at: a copy written anew would not keep its bytes.
    REQUIRE(cv::imwrite(plain, landscape, {cv::IMWRITE_JPEG_QUALITY, 80}));
    Capture capture = readCapture(dir.path("photos"));
    REQUIRE(capture.frames.size() == 3);

    // The images folder is written before COLMAP's first step, so COLMAP itself is not needed: `false`
    // stands in for it and fails that step, and the failed run leaves its work folder for the log.
    ColmapOptions options;
    options.command = "false";
    KeptWork kept;
    try {
        runColmap(capture, options);
        FAIL("expected the stand-in for COLMAP to fail");
    } catch (const Error& e) {
        INFO(e.message());
        const std::string logAt = "its output is in ";
        std::size_t at = e.message().find(logAt);
        REQUIRE(at != std::string::npos);
        kept.path = fs::path(e.message().substr(at + logAt.size())).parent_path().string();
    }
    const fs::path images = fs::path(kept.path) / "images";

    // One folder per image size as OpenCV reads the frames: the turned photo is 48 x 64.
    const fs::path written = images / "48x64/frame000000.jpg";
    REQUIRE(fs::is_regular_file(written));
    CHECK_FALSE(fs::is_symlink(written));
    cv::Mat seen = storedPixels(written);
    REQUIRE(seen.cols == 48);
    REQUIRE(seen.rows == 64);
    CHECK(brightCorner(seen) == "top-right");
    // Pixel for pixel the original turned 90 degrees clockwise, but for JPEG's loss.
    cv::Mat expected;
    cv::rotate(storedPixels(turned), expected, cv::ROTATE_90_CLOCKWISE);
    CHECK(cv::norm(seen, expected, cv::NORM_L1) / static_cast<double>(seen.total() * seen.channels()) < 2.0);

    // Orientation 1 and no EXIF at all: the file itself, linked or copied, byte for byte.
    CHECK(sameBytes(images / "64x48/frame000001.jpg", upright));
    CHECK(sameBytes(images / "64x48/frame000002.jpg", plain));
}
