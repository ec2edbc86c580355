// COLMAP sparse models, text (cameras.txt images.txt points3D.txt) and binary
// (cameras.bin images.bin points3D.bin), as COLMAP's documentation describes
// them ("Output Format"). Binary files are little-endian.
#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <map>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "ingest/capture/capture_detail.hpp"
#include "model/error.hpp"

namespace smql::ingest::capture_detail {

static_assert(std::endian::native == std::endian::little, "COLMAP's binary files are read as little-endian");

namespace {

// COLMAP's camera models, by id (the binary files) and name (the text files).
struct CameraModel {
    int id;
    const char* name;
    int params;
};
constexpr CameraModel kModels[] = {
    {0, "SIMPLE_PINHOLE", 3},
    {1, "PINHOLE", 4},
    {2, "SIMPLE_RADIAL", 4},
    {3, "RADIAL", 5},
    {4, "OPENCV", 8},
    {5, "OPENCV_FISHEYE", 8},
    {6, "FULL_OPENCV", 12},
    {7, "FOV", 5},
    {8, "SIMPLE_RADIAL_FISHEYE", 4},
    {9, "RADIAL_FISHEYE", 5},
    {10, "THIN_PRISM_FISHEYE", 12},
};

const CameraModel* modelById(long long id) {
    for (const CameraModel& m : kModels)
        if (m.id == id) return &m;
    return nullptr;
}

const CameraModel* modelByName(std::string_view name) {
    for (const CameraModel& m : kModels)
        if (name == m.name) return &m;
    return nullptr;
}

struct Camera {
    const CameraModel* model = nullptr;
    long long width = 0, height = 0;
    std::vector<double> params;
    std::string where;  // "cameras.txt:3" or "cameras.bin: camera 2", for errors
};

struct Image {
    long long id = 0;
    long long camera = 0;
    std::string name;
    Pose worldToCamera;
    std::string where;
};

std::optional<long long> parseInteger(std::string_view token) {
    long long value = 0;
    auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (token.empty() || ec != std::errc() || end != token.data() + token.size()) return std::nullopt;
    return value;
}

long long integerAt(const std::string& file, int line, std::string_view token, std::string_view what) {
    std::optional<long long> value = parseInteger(token);
    if (!value) failAt(file, line, fmt::format("{} '{}' is not an integer", what, token), kColmapHint);
    return *value;
}

// ----- text -----

std::map<long long, Camera> readCamerasText(const fs::path& path) {
    const std::string file = path.string();
    std::string text = readText(path, kColmapHint);
    std::map<long long, Camera> cameras;
    for (const TextLine& line : dataLines(text)) {
        std::vector<std::string_view> tokens = splitWhitespace(line.text);
        if (tokens.size() < 4)
            failAt(file, line.number, "expected CAMERA_ID MODEL WIDTH HEIGHT PARAMS...", kColmapHint);
        long long id = integerAt(file, line.number, tokens[0], "camera id");
        Camera camera;
        camera.model = modelByName(tokens[1]);
        if (!camera.model) failAt(file, line.number, fmt::format("unknown camera model '{}'", tokens[1]), kColmapHint);
        camera.width = integerAt(file, line.number, tokens[2], "width");
        camera.height = integerAt(file, line.number, tokens[3], "height");
        camera.params = parseNumbers(file, line.number, {tokens.begin() + 4, tokens.end()}, kColmapHint);
        if (static_cast<int>(camera.params.size()) != camera.model->params)
            failAt(file, line.number,
                   fmt::format("{} takes {} parameters, got {}", camera.model->name, camera.model->params,
                               camera.params.size()),
                   kColmapHint);
        camera.where = fmt::format("{}:{}", file, line.number);
        if (!cameras.emplace(id, std::move(camera)).second)
            failAt(file, line.number, fmt::format("camera {} appears twice", id), kColmapHint);
    }
    return cameras;
}

std::vector<Image> readImagesText(const fs::path& path) {
    const std::string file = path.string();
    std::string text = readText(path, kColmapHint);
    std::vector<TextLine> lines = allLines(text);
    std::vector<Image> images;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const TextLine& line = lines[i];
        std::size_t first = line.text.find_first_not_of(" \t");
        if (first == std::string_view::npos || line.text[first] == '#') continue;
        std::vector<std::string_view> tokens = splitWhitespace(line.text);
        if (tokens.size() != 10)
            failAt(file, line.number,
                   fmt::format("expected IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME (10 values), got {} values; "
                               "each image takes two lines, the second one its 2D points",
                               tokens.size()),
                   kColmapHint);
        Image image;
        image.id = integerAt(file, line.number, tokens[0], "image id");
        std::vector<double> v = parseNumbers(file, line.number, {tokens.begin() + 1, tokens.begin() + 8}, kColmapHint);
        image.worldToCamera =
            poseFromQuaternion(file, line.number, v[4], v[5], v[6], v[1], v[2], v[3], v[0], kColmapHint);
        checkPosition(file, line.number, fmt::format("the camera of image {} ('{}')", image.id, tokens[9]),
                      inverse(image.worldToCamera).translation, kColmapHint);
        image.camera = integerAt(file, line.number, tokens[8], "camera id");
        image.name = std::string(tokens[9]);
        image.where = fmt::format("{}:{}", file, line.number);
        // The next line lists the image's 2D points: X Y POINT3D_ID triples (it may be empty).
        if (i + 1 < lines.size()) {
            ++i;
            std::vector<std::string_view> points = splitWhitespace(lines[i].text);
            if (points.size() % 3 != 0 || (!points.empty() && points[0].front() == '#'))
                failAt(file, lines[i].number,
                       fmt::format("expected the 2D points of image {} (X Y POINT3D_ID triples, or an empty line), got "
                                   "{} values; each image takes two lines",
                                   image.id, points.size()),
                       kColmapHint);
        }
        images.push_back(std::move(image));
    }
    return images;
}

std::vector<SparsePoint> readPointsText(const fs::path& path) {
    const std::string file = path.string();
    std::string text = readText(path, kColmapHint);
    std::vector<SparsePoint> points;
    for (const TextLine& line : dataLines(text)) {
        std::vector<std::string_view> tokens = splitWhitespace(line.text);
        if (tokens.size() < 8 || (tokens.size() - 8) % 2 != 0)
            failAt(file, line.number, "expected POINT3D_ID X Y Z R G B ERROR and (IMAGE_ID POINT2D_IDX) pairs",
                   kColmapHint);
        std::vector<double> xyz =
            parseNumbers(file, line.number, {tokens.begin() + 1, tokens.begin() + 4}, kColmapHint);
        checkPosition(file, line.number, fmt::format("point {}", tokens[0]), {xyz[0], xyz[1], xyz[2]}, kColmapHint);
        SparsePoint point;
        point.position = {xyz[0], xyz[1], xyz[2]};
        for (int c = 0; c < 3; ++c) {
            long long value = integerAt(file, line.number, tokens[4 + c], "colour");
            if (value < 0 || value > 255)
                failAt(file, line.number, fmt::format("colour {} is not in 0..255", value), kColmapHint);
            point.color[c] = static_cast<std::uint8_t>(value);
        }
        points.push_back(point);
    }
    return points;
}

// ----- binary -----

class BinaryReader {
public:
    explicit BinaryReader(const fs::path& path) : file_(path.string()), data_(readText(path, kColmapHint)) {}

    template <typename T>
    T read(std::string_view what) {
        need(sizeof(T), what);
        T value;
        std::memcpy(&value, data_.data() + pos_, sizeof(T));
        pos_ += sizeof(T);
        return value;
    }
    std::string readString(std::string_view what) {
        std::size_t end = data_.find('\0', pos_);
        if (end == std::string::npos) truncated(what);
        std::string value = data_.substr(pos_, end - pos_);
        pos_ = end + 1;
        return value;
    }
    void skip(std::uint64_t count, std::uint64_t size, std::string_view what) {
        if (size != 0 && count > (data_.size() - pos_) / size) truncated(what);
        pos_ += count * size;
    }
    // A count of items that take at least `minSize` bytes each.
    std::uint64_t count(std::uint64_t minSize, std::string_view what) {
        auto n = read<std::uint64_t>(what);
        if (n > (data_.size() - pos_) / minSize)
            fail(file_,
                 fmt::format("the file says it holds {} {} but is too short for them (damaged or not a "
                             "COLMAP binary model)",
                             n, what),
                 kColmapHint);
        return n;
    }
    void expectEnd() {
        if (pos_ != data_.size())
            fail(file_,
                 fmt::format("{} bytes left over after the last entry (damaged or not a COLMAP binary model)",
                             data_.size() - pos_),
                 kColmapHint);
    }
    const std::string& file() const { return file_; }

private:
    void need(std::size_t size, std::string_view what) {
        if (data_.size() - pos_ < size) truncated(what);
    }
    [[noreturn]] void truncated(std::string_view what) {
        fail(file_,
             fmt::format("the file ends at byte {} while reading {} (truncated or not a COLMAP binary model)", pos_,
                         what),
             kColmapHint);
    }

    std::string file_;
    std::string data_;
    std::size_t pos_ = 0;
};

std::map<long long, Camera> readCamerasBinary(const fs::path& path) {
    BinaryReader in(path);
    std::map<long long, Camera> cameras;
    std::uint64_t n = in.count(24, "cameras");
    for (std::uint64_t i = 0; i < n; ++i) {
        std::string what = fmt::format("camera {}", i + 1);
        long long id = in.read<std::int32_t>(what);
        auto modelId = in.read<std::int32_t>(what);
        Camera camera;
        camera.model = modelById(modelId);
        if (!camera.model)
            fail(in.file(), fmt::format("camera {}: unknown camera model id {}", id, modelId), kColmapHint);
        camera.width = static_cast<long long>(in.read<std::uint64_t>(what));
        camera.height = static_cast<long long>(in.read<std::uint64_t>(what));
        for (int p = 0; p < camera.model->params; ++p) {
            double value = in.read<double>(what);
            if (!std::isfinite(value))
                fail(in.file(), fmt::format("camera {}: parameter {} is not finite", id, p + 1), kColmapHint);
            camera.params.push_back(value);
        }
        camera.where = fmt::format("{}: camera {}", in.file(), id);
        if (!cameras.emplace(id, std::move(camera)).second)
            fail(in.file(), fmt::format("camera {} appears twice", id), kColmapHint);
    }
    in.expectEnd();
    return cameras;
}

std::vector<Image> readImagesBinary(const fs::path& path) {
    BinaryReader in(path);
    std::vector<Image> images;
    std::uint64_t n = in.count(4 + 7 * 8 + 4 + 1 + 8, "images");
    for (std::uint64_t i = 0; i < n; ++i) {
        std::string what = fmt::format("image {}", i + 1);
        Image image;
        image.id = in.read<std::uint32_t>(what);
        double q[4], t[3];
        for (double& v : q) v = in.read<double>(what);
        for (double& v : t) v = in.read<double>(what);
        image.camera = in.read<std::uint32_t>(what);
        image.name = in.readString(what);
        image.where = fmt::format("{}: image {} ('{}')", in.file(), image.id, image.name);
        image.worldToCamera = poseFromQuaternion(image.where, 0, t[0], t[1], t[2], q[1], q[2], q[3], q[0], kColmapHint);
        checkPosition(image.where, 0, "the camera", inverse(image.worldToCamera).translation, kColmapHint);
        std::uint64_t points2d = in.read<std::uint64_t>(what);
        in.skip(points2d, 24, what);
        images.push_back(std::move(image));
    }
    in.expectEnd();
    return images;
}

std::vector<SparsePoint> readPointsBinary(const fs::path& path) {
    BinaryReader in(path);
    std::vector<SparsePoint> points;
    std::uint64_t n = in.count(8 + 24 + 3 + 8 + 8, "points");
    points.reserve(n);
    for (std::uint64_t i = 0; i < n; ++i) {
        std::string what = fmt::format("point {}", i + 1);
        auto id = in.read<std::uint64_t>(what);
        SparsePoint point;
        double xyz[3];
        for (double& v : xyz) v = in.read<double>(what);
        if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2]))
            fail(in.file(), fmt::format("point {}: position is not finite", id), kColmapHint);
        checkPosition(in.file(), 0, fmt::format("point {}", id), {xyz[0], xyz[1], xyz[2]}, kColmapHint);
        point.position = {xyz[0], xyz[1], xyz[2]};
        for (auto& c : point.color) c = in.read<std::uint8_t>(what);
        in.read<double>(what);  // reprojection error
        std::uint64_t track = in.read<std::uint64_t>(what);
        in.skip(track, 8, what);
        points.push_back(point);
    }
    in.expectEnd();
    return points;
}

// ----- cameras -> intrinsics -----

bool isSupported(const CameraModel& model) {
    std::string_view name = model.name;
    return name == "SIMPLE_PINHOLE" || name == "PINHOLE" || name == "SIMPLE_RADIAL" || name == "RADIAL" ||
           name == "OPENCV" || name == "FULL_OPENCV";
}

// COLMAP puts pixel centres at +0.5 (the image corner is 0); ours are at integers.
Intrinsics intrinsicsOf(const Camera& camera, bool& distorted) {
    const std::vector<double>& p = camera.params;
    std::string_view name = camera.model->name;
    Intrinsics out;
    out.width = static_cast<int>(camera.width);
    out.height = static_cast<int>(camera.height);
    std::size_t first = 3;  // first distortion parameter
    if (name == "PINHOLE" || name == "OPENCV" || name == "FULL_OPENCV") {
        out.fx = p[0];
        out.fy = p[1];
        out.cx = p[2] - 0.5;
        out.cy = p[3] - 0.5;
        first = 4;
    } else {
        out.fx = out.fy = p[0];
        out.cx = p[1] - 0.5;
        out.cy = p[2] - 0.5;
    }
    // COLMAP's radial terms (k, then k1 k2) and OpenCV's (k1 k2 p1 p2, then k3 k4 k5 k6) are OpenCV's first
    // coefficients in OpenCV's order.
    for (std::size_t i = first; i < p.size() && i - first < out.distortion.size(); ++i)
        out.distortion[i - first] = p[i];
    distorted = distorted || out.distorted();
    if (out.fx < 0 || out.fy < 0)
        fail(
            camera.where,
            fmt::format("the camera is mirrored: focal length {} / {} is negative, which smql refuses", out.fx, out.fy),
            kColmapHint);
    if (camera.width <= 0 || camera.height <= 0 || camera.width > 100000 || camera.height > 100000 || !(out.fx > 0) ||
        !(out.fy > 0))
        fail(camera.where,
             fmt::format("implausible camera: {}x{} pixels, focal length {} / {}", camera.width, camera.height, out.fx,
                         out.fy),
             kColmapHint);
    return out;
}

fs::path findImageDirectory(const fs::path& modelDir, const CaptureOptions& options) {
    std::error_code ec;
    if (!options.imageDirectory.empty()) {
        if (!fs::is_directory(options.imageDirectory, ec))
            fail(options.imageDirectory, "the image directory given for the COLMAP model is not a folder", kColmapHint);
        return options.imageDirectory;
    }
    fs::path absolute = fs::absolute(modelDir, ec).lexically_normal();
    if (!absolute.has_filename()) absolute = absolute.parent_path();  // "sparse/0/
    std::vector<fs::path> candidates = {absolute.parent_path() / "images",
                                        absolute.parent_path().parent_path() / "images", absolute / "images"};
    for (const fs::path& candidate : candidates)
        if (fs::is_directory(candidate, ec)) return candidate;
    fail(modelDir.string(),
         fmt::format("cannot find the images of this COLMAP model: looked for {}, {} and {}", candidates[0].string(),
                     candidates[1].string(), candidates[2].string()),
         "name the folder the model was made from with the image-directory option");
}

}  // namespace

std::optional<std::string> colmapModelFormat(const fs::path& dir) {
    std::error_code ec;
    for (const char* ext : {"bin", "txt"})
        if (fs::is_regular_file(dir / fmt::format("cameras.{}", ext), ec) &&
            fs::is_regular_file(dir / fmt::format("images.{}", ext), ec))
            return std::string(ext);
    return std::nullopt;
}

Capture readColmap(const fs::path& modelDir, const CaptureOptions& options) {
    Capture capture;
    capture.layout = "colmap";
    capture.metric = false;
    std::optional<std::string> format = colmapModelFormat(modelDir);
    if (!format)
        fail(modelDir.string(),
             "not a COLMAP model: expected cameras.txt and images.txt, or cameras.bin and images.bin", kColmapHint);
    const bool binary = *format == "bin";
    const fs::path camerasFile = modelDir / ("cameras." + *format), imagesFile = modelDir / ("images." + *format);
    const fs::path pointsFile = modelDir / ("points3D." + *format);

    std::map<long long, Camera> cameras = binary ? readCamerasBinary(camerasFile) : readCamerasText(camerasFile);
    std::vector<Image> images = binary ? readImagesBinary(imagesFile) : readImagesText(imagesFile);
    if (images.empty()) fail(imagesFile.string(), "no registered images: the reconstruction is empty", kColmapHint);
    std::error_code ec;
    if (fs::exists(pointsFile, ec))
        capture.points = binary ? readPointsBinary(pointsFile) : readPointsText(pointsFile);
    else
        capture.notes.push_back(fmt::format("{} not found: the capture has no sparse points", pointsFile.string()));

    const fs::path imageDir = findImageDirectory(modelDir, options);
    if (options.imageDirectory.empty())
        capture.notes.push_back(fmt::format("COLMAP images read from {}", imageDir.string()));

    std::stable_sort(images.begin(), images.end(),
                     [](const Image& a, const Image& b) { return naturalLess(a.name, b.name); });
    bool distorted = false, perFrame = false;
    ImageFileChecks checks(kColmapHint);
    for (std::size_t i = 0; i < images.size(); ++i) {
        const Image& image = images[i];
        auto camera = cameras.find(image.camera);
        if (camera == cameras.end())
            fail(image.where, fmt::format("camera {} is not in {}", image.camera, camerasFile.string()), kColmapHint);
        if (!isSupported(*camera->second.model))
            fail(camera->second.where,
                 fmt::format("camera model {} is not supported: use PINHOLE, SIMPLE_PINHOLE, SIMPLE_RADIAL, RADIAL, "
                             "OPENCV or FULL_OPENCV (or undistort the images with `colmap image_undistorter`)",
                             camera->second.model->name),
                 kColmapHint);
        Intrinsics intrinsics = intrinsicsOf(camera->second, distorted);
        fs::path colorPath = imageDir / image.name;
        if (!fs::exists(colorPath, ec))
            fail(image.where, fmt::format("image '{}' is not in {}", image.name, imageDir.string()), kColmapHint);
        checks.check(colorPath, "colour image");

        CaptureFrame frame;
        frame.index = static_cast<int>(i);
        frame.time = options.fps > 0 ? i / options.fps : static_cast<double>(i);
        frame.colorPath = colorPath.string();
        frame.pose = inverse(image.worldToCamera);
        if (i == 0) capture.intrinsics = intrinsics;
        if (!hasOptionIntrinsics(options) && !(intrinsics == capture.intrinsics)) {
            frame.intrinsics = intrinsics;
            perFrame = true;
        }
        capture.frames.push_back(std::move(frame));
    }
    checks.refuseUnreadable();

    takeOptionIntrinsics(capture, options, camerasFile.string());
    if (distorted && !hasOptionIntrinsics(options))
        capture.notes.push_back(
            fmt::format("{}: the cameras' lens distortion is undone as each frame is read", camerasFile.string()));
    if (perFrame) capture.notes.push_back(fmt::format("{}: the images use several cameras", camerasFile.string()));
    if (options.depthScale) capture.depthScale = *options.depthScale;
    return capture;
}

namespace {

// The COLMAP model in `dir`, `dir/sparse/0` or `dir/sparse`.
std::optional<fs::path> findColmapModel(const fs::path& dir, std::vector<std::string>& notes) {
    if (colmapModelFormat(dir)) return dir;
    fs::path sparse = dir / "sparse";
    if (colmapModelFormat(sparse / "0")) {
        std::vector<std::string> others;
        std::error_code ec;
        for (fs::directory_iterator it(sparse, ec), end; !ec && it != end; it.increment(ec)) {
            std::string name = it->path().filename().string();
            if (name != "0" && frameNumber(it->path()) && colmapModelFormat(it->path())) others.push_back(name);
        }
        if (!others.empty())
            notes.push_back(fmt::format("{} holds several COLMAP models; reading sparse/0 (the others: {})",
                                        sparse.string(), fmt::join(others, ", ")));
        return sparse / "0";
    }
    if (colmapModelFormat(sparse)) return sparse;
    return std::nullopt;
}

}  // namespace

// A COLMAP sparse model: the folder (or its sparse/0 or sparse/), or one of its files named.
extern const CaptureLayout kColmapLayout{
    "colmap", "a COLMAP sparse model (cameras/images/points3D .txt or .bin, also in sparse/0/)",
    "cameras + images .txt/.bin here or in sparse/0/ or sparse/ (COLMAP)",
    [](const fs::path& target, std::vector<std::string>& notes) -> std::optional<fs::path> {
        if (isDirectory(target)) return findColmapModel(target, notes);
        static constexpr std::string_view kFiles[] = {"cameras.txt", "images.txt", "points3d.txt",
                                                      "cameras.bin", "images.bin", "points3d.bin"};
        std::string name = lowerCase(target.filename().string());
        if (isFile(target) && std::find(std::begin(kFiles), std::end(kFiles), name) != std::end(kFiles))
            return target.has_parent_path() ? target.parent_path() : fs::path(".");
        return std::nullopt;
    },
    readColmap};

}  // namespace smql::ingest::capture_detail
