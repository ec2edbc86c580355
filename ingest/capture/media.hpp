// Image files and videos. OpenCV's imgcodecs and videoio, as Debian builds them, bring GDAL, GStreamer,
// FFmpeg and their kin: some 210 libraries, whose loading took 0.2-0.3 s of every start of smql-ingest
// (docs/benchmarks.md, "Ingest"). They live in a module of their own, libsmql_media.so, loaded (dlopen)
// the first time one of the calls below needs it: a frame that is not one of the PNGs decoded here
// (png_decoder.hpp), an image written, a video read. A depth camera's capture never loads it: its
// frames are such PNGs and its things' crops are JPEGs made by TurboJPEG (encodeJpeg).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>  // the flags and parameters below (constants only: nothing of it is linked)
#include <opencv2/videoio.hpp>

namespace smql::ingest::media {

// cv::imread, cv::imdecode and cv::imwrite (EXIF orientation applied as they apply it). OpenCV's errors
// (cv::Exception) come through as it throws them; a module that cannot be loaded throws smql::Error.
cv::Mat read(const std::string& file, int flags);
cv::Mat decode(std::span<const std::uint8_t> bytes, int flags);
bool write(const std::string& file, const cv::Mat& image, const std::vector<int>& params = {});

// Whether the file begins as an image OpenCV reads (cv::haveImageReader): a PNG's, a JPEG's or a portable
// map's (PGM, PPM) signature is known here; any other is asked of the module.
bool readable(const std::string& file);

// An 8-bit BGR image as the baseline JPEG cv::imencode(".jpg") makes of it (4:2:0), by TurboJPEG.
std::string encodeJpeg(const cv::Mat& bgr, int quality);

// A video file read frame by frame (cv::VideoCapture: FFmpeg first, then any back-end).
class Video {
public:
    // Not opened (isOpened false) when no back-end can read it.
    explicit Video(const std::string& file);
    ~Video();
    Video(const Video&) = delete;
    Video& operator=(const Video&) = delete;
    bool isOpened() const { return video_ != nullptr; }
    double get(int property) const;
    bool grab();
    bool retrieve(cv::Mat& image);

private:
    void* video_ = nullptr;  // the module's cv::VideoCapture
};

// The module's calls, as libsmql_media.so exports them (media_module.cpp): one table, so that the
// loader and the module agree on every signature.
struct Calls {
    cv::Mat (*read)(const std::string& file, int flags);
    cv::Mat (*decode)(std::span<const std::uint8_t> bytes, int flags);
    bool (*write)(const std::string& file, const cv::Mat& image, const std::vector<int>& params);
    bool (*readable)(const std::string& file);
    void* (*openVideo)(const std::string& file);
    void (*closeVideo)(void* video);
    double (*videoProperty)(void* video, int property);
    bool (*grab)(void* video);
    bool (*retrieve)(void* video, cv::Mat& image);
};
extern "C" typedef const Calls* (*CallsEntry)();
inline constexpr const char* kMediaModuleFile = "libsmql_media.so";
inline constexpr const char* kMediaEntry = "smql_media_calls";

}  // namespace smql::ingest::media
