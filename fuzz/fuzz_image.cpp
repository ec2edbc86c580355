// The frames' image decoders (ingest/capture/frame_decoders.hpp) on arbitrary bytes, against OpenCV: whatever one
// decodes, OpenCV must read as the same pixels; what they leave, OpenCV reads (or refuses) as before. A PNG's chunks'
// checksums would stop nearly every mutation at the first chunk, so the input's chunks are checksummed again before it
// is decoded, unless its last byte is odd.
#include <cstdint>
#include <cstdlib>
#include <vector>

#include <libdeflate.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "ingest/capture/frame_decoders.hpp"

namespace {

std::uint32_t bigEndian32(const std::uint8_t* p) {
    return std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 | p[3];
}

void checksumChunks(std::vector<std::uint8_t>& png) {
    for (std::size_t at = 8; png.size() >= 12 && at <= png.size() - 12;) {
        const std::uint32_t length = bigEndian32(&png[at]);
        if (length > png.size() - at - 12) return;
        const std::uint32_t crc = libdeflate_crc32(0, &png[at + 4], length + 4);
        for (int i = 0; i < 4; ++i) png[at + 8 + length + i] = static_cast<std::uint8_t>(crc >> (24 - 8 * i));
        at += 12 + std::size_t{length};
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    // A few megapixels at most: more would only spend the run's memory on zeros.
    constexpr long long kMaxPixels = 4'000'000;
    std::vector<std::uint8_t> file(data, data + size);
    if (!file.empty() && file.back() % 2 == 0) checksumChunks(file);
    // An image both read, read differently.
    for (const auto& kind : {smql::ingest::kColourFrameDecoders, smql::ingest::kDepthFrameDecoders})
        for (const smql::ingest::FrameDecoder decode : kind.decoders)
            if (const auto ours = decode(file, kMaxPixels)) {
                const cv::Mat theirs = cv::imdecode(file, kind.openCvFlags);
                if (theirs.type() != ours->type() || theirs.size() != ours->size() ||
                    cv::norm(*ours, theirs, cv::NORM_INF) != 0)
                    std::abort();
            }
    return 0;
}
