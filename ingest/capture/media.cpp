#include "ingest/capture/media.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <fstream>
#include <memory>

#include <fmt/format.h>
#include <turbojpeg.h>

#include "model/error.hpp"
#include "model/module.hpp"

namespace smql::ingest::media {

namespace {

// The module's calls, loaded once per process; an error that says where it looked when it cannot be.
const Calls& calls() {
    static const std::pair<const Calls*, std::string> loaded = [] {
        const Module opened =
            openModule(kMediaModuleFile, reinterpret_cast<const void*>(&calls), SMQL_MEDIA_MODULE_BUILT, kMediaEntry);
        const Calls* table = opened.entry ? reinterpret_cast<CallsEntry>(opened.entry)() : nullptr;
        return std::pair{table, opened.failure};
    }();
    if (!loaded.first)
        throw Error(ErrorKind::Usage, fmt::format("image files and videos: {}", loaded.second), std::nullopt,
                    "make install puts libsmql_media.so in the library folder; SMQL_MODULE_DIR names another");
    return *loaded.first;
}

}  // namespace

cv::Mat read(const std::string& file, int flags) { return calls().read(file, flags); }

cv::Mat decode(std::span<const std::uint8_t> bytes, int flags) { return calls().decode(bytes, flags); }

bool write(const std::string& file, const cv::Mat& image, const std::vector<int>& params) {
    return calls().write(file, image, params);
}

bool readable(const std::string& file) {
    // The signatures OpenCV's PNG and JPEG readers check (their first 8 and 3 bytes).
    constexpr std::array<unsigned char, 8> kPng{0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    constexpr std::array<unsigned char, 3> kJpeg{0xFF, 0xD8, 0xFF};
    std::array<unsigned char, 8> start{};
    std::ifstream in(file, std::ios::binary);
    in.read(reinterpret_cast<char*>(start.data()), start.size());
    const auto got = static_cast<std::size_t>(in.gcount());
    if (got == kPng.size() && std::equal(kPng.begin(), kPng.end(), start.begin())) return true;
    if (got >= kJpeg.size() && std::equal(kJpeg.begin(), kJpeg.end(), start.begin())) return true;
    // A portable map's, as OpenCV's PxM reader checks it: 'P', its kind 1 to 6, white space.
    if (got >= 3 && start[0] == 'P' && start[1] >= '1' && start[1] <= '6' && std::isspace(start[2])) return true;
    return calls().readable(file);
}

std::string encodeJpeg(const cv::Mat& bgr, int quality) {
    CV_Assert(bgr.type() == CV_8UC3);
    // The accurate DCT, as OpenCV's encoder uses it (TurboJPEG's own default is the fast one): the bytes
    // cv::imencode(".jpg", {IMWRITE_JPEG_QUALITY, quality}) makes.
    const std::unique_ptr<void, int (*)(tjhandle)> encoder(tjInitCompress(), tjDestroy);
    unsigned char* bytes = nullptr;
    unsigned long size = 0;
    if (!encoder || tjCompress2(encoder.get(), bgr.data, bgr.cols, static_cast<int>(bgr.step), bgr.rows, TJPF_BGR,
                                &bytes, &size, TJSAMP_420, quality, TJFLAG_ACCURATEDCT) != 0) {
        tjFree(bytes);
        throw Error(ErrorKind::Input, fmt::format("cannot encode a {} x {} image as JPEG: {}", bgr.cols, bgr.rows,
                                                  encoder ? tjGetErrorStr2(encoder.get()) : "no encoder"));
    }
    std::string out(reinterpret_cast<const char*>(bytes), size);
    tjFree(bytes);
    return out;
}

Video::Video(const std::string& file) : video_(calls().openVideo(file)) {}

Video::~Video() {
    if (video_) calls().closeVideo(video_);
}

double Video::get(int property) const { return calls().videoProperty(video_, property); }
bool Video::grab() { return calls().grab(video_); }
bool Video::retrieve(cv::Mat& image) { return calls().retrieve(video_, image); }

}  // namespace smql::ingest::media
