// libsmql_media.so: OpenCV's image files and videos (media.hpp), loaded by smql_capture when first needed,
// so that a program that ingests a depth camera's PNGs starts without GDAL, GStreamer and FFmpeg.
#include <memory>

#include "ingest/capture/media.hpp"

namespace {

cv::Mat readFile(const std::string& file, int flags) { return cv::imread(file, flags); }

cv::Mat decodeBytes(std::span<const std::uint8_t> bytes, int flags) {
    // imdecode reads a Mat of bytes; this one views the caller's without copying them.
    const cv::Mat buffer(1, static_cast<int>(bytes.size()), CV_8U, const_cast<std::uint8_t*>(bytes.data()));
    return cv::imdecode(buffer, flags);
}

bool writeFile(const std::string& file, const cv::Mat& image, const std::vector<int>& params) {
    return cv::imwrite(file, image, params);
}

bool hasReader(const std::string& file) { return cv::haveImageReader(file); }

void* openVideo(const std::string& file) {
    auto video = std::make_unique<cv::VideoCapture>();
    // FFmpeg first: it reads nearly everything, and the other back-ends are noisy when they fail.
    if (!video->open(file, cv::CAP_FFMPEG)) video->open(file, cv::CAP_ANY);
    return video->isOpened() ? video.release() : nullptr;
}

void closeVideo(void* video) { delete static_cast<cv::VideoCapture*>(video); }
double videoProperty(void* video, int property) { return static_cast<cv::VideoCapture*>(video)->get(property); }
bool grab(void* video) { return static_cast<cv::VideoCapture*>(video)->grab(); }
bool retrieve(void* video, cv::Mat& image) { return static_cast<cv::VideoCapture*>(video)->retrieve(image); }

constexpr smql::ingest::media::Calls kCalls{readFile,   decodeBytes,   writeFile, hasReader, openVideo,
                                            closeVideo, videoProperty, grab,      retrieve};

}  // namespace

extern "C" __attribute__((visibility("default"))) const smql::ingest::media::Calls* smql_media_calls() {
    return &kCalls;
}
