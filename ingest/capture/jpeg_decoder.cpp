#include "ingest/capture/jpeg_decoder.hpp"

#include <cstring>
#include <memory>

#include <turbojpeg.h>

#include "ingest/capture/capture_detail.hpp"

namespace smql::ingest {

namespace {

// Whether an APP1 segment holding EXIF data comes before the first scan; std::nullopt when the markers
// before it do not read as a JPEG's.
std::optional<bool> exifBeforeScan(std::span<const std::uint8_t> file) {
    static constexpr char kExif[] = {'E', 'x', 'i', 'f', 0, 0};
    for (std::size_t at = 2; at + 4 <= file.size();) {
        if (file[at] != 0xFF) return std::nullopt;
        const std::uint8_t marker = file[at + 1];
        if (marker == 0xFF) {  // fill byte
            ++at;
            continue;
        }
        if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) {  // without a length (libjpeg reads past)
            at += 2;
            continue;
        }
        if (marker == 0xDA || marker == 0xD9) return false;  // the first scan, or the end
        const std::size_t length = std::size_t{file[at + 2]} << 8 | file[at + 3];
        if (length < 2) return std::nullopt;
        if (marker == 0xE1 && length >= 2 + sizeof kExif && at + 4 + sizeof kExif <= file.size() &&
            std::memcmp(&file[at + 4], kExif, sizeof kExif) == 0)
            return true;
        at += 2 + length;
    }
    return std::nullopt;
}

}  // namespace

std::optional<cv::Mat> decodeColorJpeg(std::span<const std::uint8_t> file, long long maxPixels) {
    if (file.size() < 4 || file[0] != 0xFF || file[1] != 0xD8 || file[2] != 0xFF) return std::nullopt;
    const std::optional<bool> exif = exifBeforeScan(file);
    if (!exif || *exif) return std::nullopt;
    const std::unique_ptr<void, int (*)(tjhandle)> decoder(tjInitDecompress(), tjDestroy);
    if (!decoder) return std::nullopt;
    int width = 0, height = 0, subsampling = 0, colourSpace = 0;
    if (tjDecompressHeader3(decoder.get(), file.data(), static_cast<unsigned long>(file.size()), &width, &height,
                            &subsampling, &colourSpace) != 0)
        return std::nullopt;
    if (colourSpace == TJCS_CMYK || colourSpace == TJCS_YCCK || width <= 0 || height <= 0 ||
        width > capture_detail::kMaxDecodedSide || height > capture_detail::kMaxDecodedSide ||
        static_cast<long long>(width) * height > maxPixels)
        return std::nullopt;
    // The accurate DCT and fancy upsampling (TurboJPEG's defaults, and libjpeg's, which OpenCV keeps); at
    // most 500 scans of a progressive image, as a damaged or hostile one can hold thousands.
    cv::Mat bgr(height, width, CV_8UC3);
    if (tjDecompress2(decoder.get(), file.data(), static_cast<unsigned long>(file.size()), bgr.data, width,
                      static_cast<int>(bgr.step), height, TJPF_BGR, TJFLAG_LIMITSCANS) != 0)
        return std::nullopt;  // an error, or a warning: OpenCV reads past some warnings, and words the errors
    return bgr;
}

}  // namespace smql::ingest
