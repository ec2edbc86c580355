#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <optional>
#include <span>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "ingest/capture/capture_detail.hpp"
#include "ingest/capture/frame_decoders.hpp"
#include "ingest/capture/media.hpp"
#include "ingest/capture/pgm_decoder.hpp"
#include "ingest/import/common.hpp"
#include "model/error.hpp"

namespace smql::ingest::capture_detail {

void fail(const std::string& file, std::string_view what, std::string_view hint) {
    throw Error(ErrorKind::Input, fmt::format("{}: {}", file, what), std::nullopt, std::string(hint));
}

void failAt(const std::string& file, int line, std::string_view what, std::string_view hint) {
    if (line <= 0) fail(file, what, hint);  // binary files: `file` already says where
    throw Error(ErrorKind::Input, fmt::format("{}:{}: {}", file, line, what), SourceLocation{line, 0, 1},
                std::string(hint));
}

std::string lowerCase(std::string_view text) { return import::detail::lowerCase(text); }

std::string extensionOf(const fs::path& path) {
    std::string ext = path.extension().string();
    if (!ext.empty() && ext[0] == '.') ext.erase(0, 1);
    return lowerCase(ext);
}

bool isImageExtension(std::string_view ext) { return ext == "jpg" || ext == "jpeg" || ext == "png"; }

bool isVideoExtension(std::string_view ext) {
    static constexpr std::string_view kVideo[] = {"mp4", "avi", "mov", "mkv", "webm", "m4v",  "mpg", "mpeg",
                                                  "wmv", "flv", "3gp", "ts",  "mts",  "m2ts", "ogv", "mjpeg"};
    return std::find(std::begin(kVideo), std::end(kVideo), ext) != std::end(kVideo);
}

namespace {
bool isDigit(char c) { return c >= '0' && c <= '9'; }
}  // namespace

bool naturalLess(std::string_view a, std::string_view b) {
    std::size_t i = 0, j = 0;
    while (i < a.size() && j < b.size()) {
        if (isDigit(a[i]) && isDigit(b[j])) {
            std::size_t iEnd = i, jEnd = j;
            while (iEnd < a.size() && isDigit(a[iEnd])) ++iEnd;
            while (jEnd < b.size() && isDigit(b[jEnd])) ++jEnd;
            std::string_view da = a.substr(i, iEnd - i), db = b.substr(j, jEnd - j);
            da.remove_prefix(std::min(da.find_first_not_of('0'), da.size()));
            db.remove_prefix(std::min(db.find_first_not_of('0'), db.size()));
            if (da.size() != db.size()) return da.size() < db.size();
            if (da != db) return da < db;
            i = iEnd;
            j = jEnd;
        } else {
            if (a[i] != b[j]) return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]);
            ++i;
            ++j;
        }
    }
    if (i == a.size() && j != b.size()) return true;
    if (j == b.size() && i != a.size()) return false;
    return a < b;  // equal but for leading zeros
}

std::vector<fs::path> listFiles(const fs::path& dir) {
    std::vector<fs::path> files;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        std::string name = it->path().filename().string();
        if (name.empty() || name[0] == '.') continue;
        std::error_code statError;
        if (it->is_regular_file(statError)) files.push_back(it->path());
    }
    if (ec) fail(dir.string(), "cannot list the folder: " + ec.message());
    std::sort(files.begin(), files.end(), [](const fs::path& x, const fs::path& y) {
        return naturalLess(x.filename().string(), y.filename().string());
    });
    return files;
}

std::optional<long long> frameNumber(const fs::path& file) {
    std::string stem = file.stem().string();
    if (stem.empty() || stem.size() > 15 || !std::all_of(stem.begin(), stem.end(), isDigit)) return std::nullopt;
    return std::stoll(stem);
}

std::string readText(const fs::path& file, std::string_view hint) {
    return import::detail::readTextFile(file.string(), std::string(hint));
}

std::vector<TextLine> allLines(std::string_view text) {
    std::vector<TextLine> lines;
    int number = 0;
    std::size_t pos = 0;
    while (pos < text.size()) {
        std::size_t end = text.find('\n', pos);
        if (end == std::string_view::npos) end = text.size();
        std::string_view line = text.substr(pos, end - pos);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        lines.push_back(TextLine{++number, line});
        pos = end + 1;
    }
    return lines;
}

std::vector<TextLine> dataLines(std::string_view text) {
    std::vector<TextLine> lines;
    for (const TextLine& line : allLines(text)) {
        std::size_t first = line.text.find_first_not_of(" \t");
        if (first == std::string_view::npos || line.text[first] == '#') continue;
        lines.push_back(line);
    }
    return lines;
}

std::vector<std::string_view> splitWhitespace(std::string_view text) {
    std::vector<std::string_view> tokens;
    std::size_t pos = 0;
    while (true) {
        pos = text.find_first_not_of(" \t\r\n", pos);
        if (pos == std::string_view::npos) break;
        std::size_t end = text.find_first_of(" \t\r\n", pos);
        if (end == std::string_view::npos) end = text.size();
        tokens.push_back(text.substr(pos, end - pos));
        pos = end;
    }
    return tokens;
}

std::optional<double> parseNumber(std::string_view token) {
    if (!token.empty() && token[0] == '+') token.remove_prefix(1);
    double value = 0;
    auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (token.empty() || ec != std::errc() || end != token.data() + token.size()) return std::nullopt;
    return value;
}

std::vector<double> parseNumbers(const std::string& file, int line, const std::vector<std::string_view>& tokens,
                                 std::string_view hint) {
    std::vector<double> values;
    values.reserve(tokens.size());
    for (std::size_t i = 0; i < tokens.size(); ++i) {
        std::optional<double> value = parseNumber(tokens[i]);
        if (!value) failAt(file, line, fmt::format("value {} '{}' is not a number", i + 1, tokens[i]), hint);
        if (!std::isfinite(*value))
            failAt(file, line, fmt::format("value {} '{}' is not finite", i + 1, tokens[i]), hint);
        values.push_back(*value);
    }
    return values;
}

Pose poseFromQuaternion(const std::string& file, int line, double tx, double ty, double tz, double qx, double qy,
                        double qz, double qw, std::string_view hint) {
    for (double v : {tx, ty, tz, qx, qy, qz, qw})
        if (!std::isfinite(v)) failAt(file, line, "the pose holds a number that is not finite", hint);
    Eigen::Quaterniond q(qw, qx, qy, qz);
    double norm = q.norm();
    if (!(norm > 1e-9)) failAt(file, line, "the rotation quaternion has zero norm", hint);
    q.coeffs() /= norm;
    Eigen::Matrix3d r = q.toRotationMatrix();
    Pose pose;
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) pose.rotation[row * 3 + col] = r(row, col);
    pose.translation = {tx, ty, tz};
    return pose;
}

Pose inverse(const Pose& pose) {
    Pose out;
    const auto& r = pose.rotation;
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) out.rotation[row * 3 + col] = r[col * 3 + row];
    const model::Vec3& t = pose.translation;
    const auto& o = out.rotation;
    out.translation = {-(o[0] * t.x + o[1] * t.y + o[2] * t.z), -(o[3] * t.x + o[4] * t.y + o[5] * t.z),
                       -(o[6] * t.x + o[7] * t.y + o[8] * t.z)};
    return out;
}

void checkPosition(const std::string& file, int line, std::string_view what, const model::Vec3& position,
                   std::string_view hint) {
    constexpr double limit = import::detail::kMaxCoordinate;
    if (std::abs(position.x) <= limit && std::abs(position.y) <= limit && std::abs(position.z) <= limit) return;
    failAt(file, line,
           fmt::format("{} is at ({:g}, {:g}, {:g}), beyond {:g} m from the origin: positions must lie within {:g} "
                       "on every axis (a unit mix-up or a geo-referenced model?)",
                       what, position.x, position.y, position.z, limit, limit),
           hint);
}

Intrinsics kinectDefault(int width, int height) {
    double f = 525.0 * width / 640.0;
    return Intrinsics{width, height, f, f, (width - 1) / 2.0, (height - 1) / 2.0};
}

Intrinsics guessedIntrinsics(int width, int height) {
    double f = 1.2 * width;
    return Intrinsics{width, height, f, f, (width - 1) / 2.0, (height - 1) / 2.0};
}

Intrinsics scaleIntrinsics(const Intrinsics& in, int width, int height) {
    if (in.width == width && in.height == height) return in;
    double sx = static_cast<double>(width) / in.width, sy = static_cast<double>(height) / in.height;
    // Pixel centres at integer coordinates: the image edge is at -0.5. The distortion is of normalised
    // coordinates, which resizing leaves as they are.
    return Intrinsics{width,        height, in.fx * sx, in.fy * sy, (in.cx + 0.5) * sx - 0.5, (in.cy + 0.5) * sy - 0.5,
                      in.distortion};
}

Intrinsics userIntrinsics(const Intrinsics& given, int width, int height) {
    auto bad = [](std::string_view what) {
        throw Error(ErrorKind::Usage, fmt::format("intrinsics: {}", what), std::nullopt,
                    "give fx, fy > 0 and cx, cy in pixels (width and height 0 = the images' size)");
    };
    for (double v : {given.fx, given.fy, given.cx, given.cy})
        if (!std::isfinite(v)) bad("a value is not finite");
    if (given.fx <= 0 || given.fy <= 0)
        bad(fmt::format("fx and fy must be > 0 (a negative focal length is a mirrored camera), got {} and {}", given.fx,
                        given.fy));
    if (given.width < 0 || given.height < 0 || (given.width == 0) != (given.height == 0))
        bad(fmt::format("width and height must both be > 0 or both 0, got {}x{}", given.width, given.height));
    Intrinsics out = given;
    if (out.width == 0) {
        out.width = width;
        out.height = height;
    }
    return out;
}

void checkDepthScale(double scale, const std::string& from) {
    if (!std::isfinite(scale) || scale <= 0)
        throw Error(ErrorKind::Usage, fmt::format("{}: depth scale must be a positive number, got {}", from, scale),
                    std::nullopt, "the depth scale is depth image units per metre: 1000 for millimetres");
}

namespace {

// `count` bytes of `in` from `at`, fewer past the end.
std::string bytesAt(std::ifstream& in, std::streamoff at, std::size_t count) {
    std::string bytes(count, '\0');
    in.clear();
    in.seekg(at);
    in.read(bytes.data(), static_cast<std::streamsize>(count));
    bytes.resize(static_cast<std::size_t>(in.gcount()));
    return bytes;
}

}  // namespace

std::optional<std::pair<int, int>> storedImageSize(const fs::path& file) {
    // A PNG's and a PGM's header lie in the first bytes; a JPEG's frame header follows the segments before it
    // (EXIF may take 64 KB) within its first MiB, which are stepped over, not read: the whole file is read once,
    // to decode it.
    constexpr std::size_t kHeadBytes = 4096;
    constexpr std::streamoff kSegmentsReach = 1 << 20;
    std::ifstream in(file, std::ios::binary);
    const std::string head = bytesAt(in, 0, kHeadBytes);
    auto byte = [](const std::string& bytes, std::size_t i) {
        return static_cast<unsigned>(static_cast<unsigned char>(bytes[i]));
    };
    auto big16 = [&](const std::string& bytes, std::size_t i) { return (byte(bytes, i) << 8) | byte(bytes, i + 1); };
    auto big32 = [&](const std::string& bytes, std::size_t i) { return (big16(bytes, i) << 16) | big16(bytes, i + 2); };
    if (head.size() >= 24 && head.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0 && head.compare(12, 4, "IHDR") == 0)
        return std::pair{static_cast<int>(std::min(big32(head, 16), 1u << 30)),
                         static_cast<int>(std::min(big32(head, 20), 1u << 30))};
    if (const auto pgm = readPgmHeader({reinterpret_cast<const std::uint8_t*>(head.data()), head.size()}))
        return std::pair{pgm->width, pgm->height};
    if (head.size() < 4 || byte(head, 0) != 0xFF || byte(head, 1) != 0xD8) return std::nullopt;
    for (std::streamoff at = 2; at < kSegmentsReach;) {
        const std::string segment = bytesAt(in, at, 9);
        if (segment.size() < 9 || byte(segment, 0) != 0xFF) return std::nullopt;
        const unsigned marker = byte(segment, 1);
        if (marker == 0xFF) {  // fill byte
            ++at;
            continue;
        }
        // SOF0 to SOF15, less DHT (C4), JPG (C8) and DAC (CC): the frame header, height then width.
        if (marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC)
            return std::pair{static_cast<int>(big16(segment, 7)), static_cast<int>(big16(segment, 5))};
        at += 2 + big16(segment, 2);
    }
    return std::nullopt;
}

namespace {

// Before anything is decoded: an image past kMaxImagePixels is refused on its header's word.
void refuseHugeImage(const fs::path& file, std::string_view what) {
    auto size = storedImageSize(file);
    if (size && static_cast<long long>(size->first) * size->second > kMaxImagePixels)
        fail(file.string(),
             fmt::format("{} of {} x {} pixels: more than {} megapixels", what, size->first, size->second,
                         kMaxImagePixels / 1'000'000),
             "scale the images down (a capture needs no more than a few megapixels a frame)");
}

}  // namespace

std::optional<std::string> cutShort(const fs::path& file) {
    std::ifstream in(file, std::ios::binary | std::ios::ate);
    const std::streamoff size = in.tellg();
    if (!in || size <= 0) return std::nullopt;
    const std::string head = bytesAt(in, 0, 1024);
    if (head.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0) {
        constexpr std::streamoff kTail = 4096;
        if (bytesAt(in, std::max<std::streamoff>(0, size - kTail), kTail).find("IEND") == std::string::npos)
            return "a PNG without its end chunk";
        return std::nullopt;
    }
    if (head.compare(0, 2, "\xFF\xD8") == 0) {
        if (bytesAt(in, size - 2, 2) == "\xFF\xD9") return std::nullopt;
        // A trailer after the end-of-image marker, or no marker. In a scan's coded data a 0xFF byte is followed
        // by 0x00 (stuffing) or a marker, so the first 0xFF 0xD9 after the first scan's start is that marker.
        const std::string bytes = bytesAt(in, 0, static_cast<std::size_t>(size));
        const std::size_t scan = bytes.find("\xFF\xDA");
        if (scan != std::string::npos && bytes.find("\xFF\xD9", scan) != std::string::npos) return std::nullopt;
        return "a JPEG without its end-of-image marker";
    }
    if (const auto pgm = readPgmHeader({reinterpret_cast<const std::uint8_t*>(head.data()), head.size()})) {
        const auto expected = static_cast<std::streamoff>(pgm->dataOffset) +
                              static_cast<std::streamoff>(pgm->width) * pgm->height * (pgm->maxValue > 255 ? 2 : 1);
        if (size < expected)
            return fmt::format("a PGM of {} x {} pixels with {} of its {} bytes", pgm->width, pgm->height, size,
                               expected);
    }
    return std::nullopt;
}

bool ImageFileChecks::check(const fs::path& file, std::string_view what) {
    std::error_code ec;
    auto status = fs::status(file, ec);
    auto unreadable = [&](std::string why) {
        unreadable_.emplace_back(file.string(), std::move(why));
        return false;
    };
    if (!fs::exists(status)) return unreadable(fmt::format("{} is missing", what));
    if (!fs::is_regular_file(status)) return unreadable(fmt::format("{} is not a regular file", what));
    if (fs::file_size(file, ec) == 0 && !ec) return unreadable(fmt::format("{} is empty", what));
    refuseHugeImage(file, what);
    bool readable = false;
    try {
        readable = media::readable(file.string());
    } catch (const cv::Exception&) {
        readable = false;
    }
    if (!readable)
        return unreadable(fmt::format("{}: not an image OpenCV can read (unknown or damaged file signature)", what));
    if (const auto cut = cutShort(file))
        return unreadable(fmt::format("{} cut short, {}: a copy or a download that stopped", what, *cut));
    return true;
}

void ImageFileChecks::refuseUnreadable() const {
    if (unreadable_.empty()) return;
    const std::string hint = hint_ + "; copy the files named again, or remove them";
    if (unreadable_.size() == 1) fail(unreadable_.front().first, unreadable_.front().second, hint);
    // The reasons hold commas: the files are parted by semicolons.
    constexpr std::size_t kNamed = 5;
    std::string named;
    for (std::size_t i = 0; i < std::min(kNamed, unreadable_.size()); ++i)
        named += fmt::format("{}{} ({})", i == 0 ? "" : "; ", unreadable_[i].first, unreadable_[i].second);
    if (unreadable_.size() > kNamed) named += fmt::format("; and {} more", unreadable_.size() - kNamed);
    throw Error(ErrorKind::Input, fmt::format("{} image files cannot be read: {}", unreadable_.size(), named),
                std::nullopt, hint);
}

namespace {

// The file's bytes, or none when it cannot be read whole (OpenCV's reading then words the error).
std::optional<std::vector<std::uint8_t>> fileBytes(const std::string& file) {
    std::error_code ec;
    const auto size = fs::file_size(file, ec);
    std::ifstream in(file, std::ios::binary);
    if (ec || !in) return std::nullopt;
    std::vector<std::uint8_t> bytes(size);
    if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size))) return std::nullopt;
    return bytes;
}

// With `decoders`, the file's bytes are read first and given to each in turn; what they leave
// (std::nullopt), OpenCV decodes from those bytes, not from the file again.
cv::Mat readImage(const std::string& file, int flags, std::string_view what, const FrameDecoders* decoders = nullptr) {
    std::error_code ec;
    auto status = fs::status(file, ec);
    if (!fs::exists(status)) fail(file, fmt::format("{} is missing", what));
    if (!fs::is_regular_file(status)) fail(file, fmt::format("{} is not a regular file", what));
    refuseHugeImage(file, what);
    std::optional<std::vector<std::uint8_t>> bytes;
    if (decoders) bytes = fileBytes(file);
    if (bytes && !bytes->empty())
        for (const FrameDecoder decode : decoders->decoders)
            if (auto image = decode(*bytes, kMaxImagePixels)) return std::move(*image);
    cv::Mat image;
    try {
        image = bytes && !bytes->empty() ? media::decode(*bytes, flags) : media::read(file, flags);
    } catch (const cv::Exception& e) {
        fail(file, fmt::format("cannot decode the {}: {}", what, e.err));
    }
    if (image.empty())
        fail(file, fmt::format("cannot decode the {} (damaged, or a format OpenCV does not read)", what));
    return image;
}

const char* depthName(int depth) {
    switch (depth) {
        case CV_8U:
            return "8-bit";
        case CV_8S:
            return "8-bit signed";
        case CV_16U:
            return "16-bit";
        case CV_16S:
            return "16-bit signed";
        case CV_32S:
            return "32-bit integer";
        case CV_32F:
            return "32-bit float";
        case CV_64F:
            return "64-bit float";
        default:
            return "unknown";
    }
}

}  // namespace

cv::Mat readColorImage(const std::string& file) {
    return readImage(file, kColourFrameDecoders.openCvFlags, "colour image", &kColourFrameDecoders);
}

cv::Mat readDepthImage(const std::string& file) {
    cv::Mat depth = readImage(file, kDepthFrameDecoders.openCvFlags, "depth image", &kDepthFrameDecoders);
    if (depth.channels() != 1)
        fail(file, fmt::format("a depth image has one channel, this one has {}", depth.channels()));
    if (depth.depth() != CV_16U && depth.depth() != CV_32F)
        fail(file, fmt::format("depth must be a 16-bit image (or 32-bit float metres), this one is {}",
                               depthName(depth.depth())));
    return depth;
}

cv::Mat readMaskImage(const std::string& file) {
    cv::Mat mask = readImage(file, cv::IMREAD_UNCHANGED, "instance mask");
    if (mask.channels() != 1)
        fail(file, fmt::format("an instance mask has one channel, this one has {}", mask.channels()));
    if (mask.depth() == CV_8U) {
        cv::Mat wide;
        mask.convertTo(wide, CV_16U);
        return wide;
    }
    if (mask.depth() != CV_16U)
        fail(file, fmt::format("an instance mask is a 16-bit image, this one is {}", depthName(mask.depth())));
    return mask;
}

bool Sampler::take(double time) {
    if (step_ <= 0) return true;
    if (!next_) {
        next_ = time + step_;
        return true;
    }
    if (time < *next_ - tolerance_) return false;
    while (*next_ - tolerance_ <= time) *next_ += step_;
    return true;
}

}  // namespace smql::ingest::capture_detail
