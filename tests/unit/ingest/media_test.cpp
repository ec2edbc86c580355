// Image files through ingest/capture/media.hpp: the crops' JPEGs made by TurboJPEG are the bytes OpenCV's
// encoder makes, the signatures known without the module agree with OpenCV's readers, and what goes through
// libsmql_media.so comes back as OpenCV reads it.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "capture_support.hpp"
#include "ingest/capture/media.hpp"

using namespace smql::ingest;

namespace {

cv::Mat tumFrame() {
    const std::string file = std::string(SMQL_SHARED_DATA) + "/captures/tum-fr1-rpy/rgb/1305031229.729064.png";
    cv::Mat image = cv::imread(file, cv::IMREAD_COLOR);
    REQUIRE(!image.empty());
    return image;
}

}  // namespace

TEST_CASE("media: a crop's JPEG is the bytes cv::imencode makes of it") {
    const cv::Mat frame = tumFrame();
    cv::Mat scaled;
    cv::resize(frame(cv::Rect(100, 60, 300, 220)), scaled, cv::Size(160, 117), 0, 0, cv::INTER_AREA);
    // A view into the frame (its rows a frame's width apart), a crop scaled down, an odd size, a single pixel.
    for (const cv::Mat& image :
         {frame(cv::Rect(37, 21, 211, 157)), scaled, frame(cv::Rect(5, 5, 33, 17)), frame(cv::Rect(0, 0, 1, 1))}) {
        for (int quality : {85, 95}) {
            std::vector<std::uint8_t> theirs;
            REQUIRE(cv::imencode(".jpg", image, theirs, {cv::IMWRITE_JPEG_QUALITY, quality}));
            INFO(image.cols << " x " << image.rows << ", quality " << quality);
            CHECK(media::encodeJpeg(image, quality) == std::string(theirs.begin(), theirs.end()));
        }
    }
}

TEST_CASE("media: an image file's signature is known as OpenCV knows it") {
    TempDir dir;
    const cv::Mat image = tumFrame()(cv::Rect(0, 0, 64, 48)).clone();
    for (const char* name : {"frame.png", "frame.jpg", "frame.bmp", "frame.tiff"}) {
        REQUIRE(cv::imwrite(dir.path(name), image));
        CHECK(media::readable(dir.path(name)) == cv::haveImageReader(dir.path(name)));
        CHECK(media::readable(dir.path(name)));
        // What the module reads is what OpenCV reads.
        const cv::Mat read = media::read(dir.path(name), cv::IMREAD_COLOR);
        CHECK(cv::norm(read, cv::imread(dir.path(name), cv::IMREAD_COLOR), cv::NORM_INF) == 0);
    }
    dir.write("notes.png", "not an image");
    dir.write("short.jpg", "\xFF\xD8");
    for (const char* name : {"notes.png", "short.jpg"}) {
        INFO(name);
        CHECK_FALSE(media::readable(dir.path(name)));
        CHECK_FALSE(cv::haveImageReader(dir.path(name)));
    }
}
