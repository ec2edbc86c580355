// Captures without poses: a folder of images, or a video file decoded to PNGs.
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "ingest/capture/capture_detail.hpp"
#include "ingest/capture/media.hpp"
#include "model/error.hpp"

namespace smql::ingest::capture_detail {

namespace {

// Each photo's camera from its EXIF focal length (35 mm equivalent) when every photo has one, else
// the stated guess for all: a capture's intrinsics are either all known or all guessed.
void cameraFromExif(Capture& capture, const fs::path& dir, int width, int height) {
    std::vector<std::optional<double>> focals;
    std::size_t known = 0;
    for (const CaptureFrame& frame : capture.frames) {
        focals.push_back(readExif(frame.colorPath).focal35mm);
        known += focals.back().has_value();
    }
    if (known == capture.frames.size()) {
        capture.intrinsicsOrigin = IntrinsicsOrigin::Approximate;
        for (std::size_t i = 0; i < capture.frames.size(); ++i) {
            cv::Size size = i == 0 ? cv::Size(width, height) : readColorImage(capture.frames[i].colorPath).size();
            Intrinsics k = intrinsicsFrom35mm(*focals[i], size.width, size.height);
            if (i == 0)
                capture.intrinsics = k;
            else if (!(k == capture.intrinsics))
                capture.frames[i].intrinsics = k;
        }
        capture.notes.push_back(fmt::format(
            "{}: camera from the photos' EXIF focal length ({:g} mm equivalent in the first photo: fx = fy = {:.1f} "
            "for {}x{}); give --camera or camera.json for exact geometry",
            dir.string(), *focals.front(), capture.intrinsics.fx, width, height));
        return;
    }
    capture.intrinsics = guessedIntrinsics(width, height);
    capture.intrinsicsOrigin = IntrinsicsOrigin::Guessed;
    capture.notes.push_back(fmt::format(
        "{}: the camera is unknown ({} of {} photos give an EXIF focal length): intrinsics guessed as fx = fy = 1.2 x "
        "width = {:g} with a centred principal point; give --camera, --fov or camera.json for better geometry",
        dir.string(), known, capture.frames.size(), capture.intrinsics.fx));
}

}  // namespace

namespace {

std::vector<fs::path> imagesIn(const fs::path& dir) {
    std::vector<fs::path> images;
    for (const fs::path& file : listFiles(dir))
        if (isImageExtension(extensionOf(file))) images.push_back(file);
    return images;
}

}  // namespace

Capture readImageFolder(const fs::path& dir, const CaptureOptions& options) {
    const std::vector<fs::path> images = imagesIn(dir);
    Capture capture;
    capture.layout = "images";
    capture.metric = false;
    ImageFileChecks checks(kImagesHint);
    for (std::size_t i = 0; i < images.size(); ++i) {
        checks.check(images[i], "image");
        CaptureFrame frame;
        frame.index = static_cast<int>(i);
        frame.time = options.fps > 0 ? i / options.fps : static_cast<double>(i);
        frame.colorPath = images[i].string();
        capture.frames.push_back(std::move(frame));
    }
    checks.refuseUnreadable();
    RawFrame first = readRawFrame(capture.frames.front());
    const int width = first.color.cols, height = first.color.rows;
    const fs::path cameraFile = dir / "camera.json";
    std::error_code ec;
    if (std::optional<Intrinsics> given = optionIntrinsics(options, width, height)) {
        capture.intrinsics =
            fitIntrinsics(*given, width, height, capture.frames.front().colorPath, optionName(options));
        capture.intrinsicsOrigin = optionOrigin(options);
        capture.notes.push_back(fmt::format("camera from {}: fx {:.1f}, fy {:.1f}, cx {:.1f}, cy {:.1f} for {}x{}",
                                            optionName(options), capture.intrinsics.fx, capture.intrinsics.fy,
                                            capture.intrinsics.cx, capture.intrinsics.cy, width, height));
    } else if (fs::is_regular_file(cameraFile, ec)) {
        CameraJson camera = readCameraJson(cameraFile, kImagesHint);
        capture.intrinsics =
            fitIntrinsics(camera.intrinsics, width, height, capture.frames.front().colorPath, cameraFile.string());
        capture.notes.push_back(fmt::format("camera from {}: fx {:.1f}, fy {:.1f}, cx {:.1f}, cy {:.1f} for {}x{}",
                                            cameraFile.string(), capture.intrinsics.fx, capture.intrinsics.fy,
                                            capture.intrinsics.cx, capture.intrinsics.cy, width, height));
    } else {
        cameraFromExif(capture, dir, width, height);
    }
    if (options.depthScale) capture.depthScale = *options.depthScale;
    // A detector's output beside the photos, as beside an rgbd capture's frames.
    if (fs::is_regular_file(dir / "detections.json", ec))
        capture.detectionsPath =
            checkedJson(dir / "detections.json", "detections.json holds COCO-results style detections");
    return capture;
}

namespace {

fs::path makeWorkDirectory(const CaptureOptions& options, std::vector<std::string>& notes) {
    std::error_code ec;
    if (!options.workDirectory.empty()) {
        fs::path dir = options.workDirectory;
        fs::create_directories(dir, ec);
        if (ec || !fs::is_directory(dir, ec))
            throw Error(ErrorKind::Usage, fmt::format("{}: cannot create the work folder for decoded video frames: {}",
                                                      dir.string(), ec ? ec.message() : "not a folder"));
        return dir;
    }
    fs::path base = fs::temp_directory_path(ec);
    if (ec) base = "/tmp";
    std::string pattern = (base / "smql-video-XXXXXX").string();
    if (!mkdtemp(pattern.data()))
        throw Error(ErrorKind::Usage, fmt::format("{}: cannot create a temporary folder for decoded video frames: {}",
                                                  base.string(), std::strerror(errno)));
    notes.push_back(
        fmt::format("decoded video frames written to {} (remove it when done, or choose the folder with "
                    "--video-frames)",
                    pattern));
    return pattern;
}

}  // namespace

Capture readVideo(const fs::path& file, const CaptureOptions& options) {
    Capture capture;
    capture.layout = "video";
    capture.metric = false;
    const std::string path = file.string();

    std::optional<media::Video> opened;
    try {
        opened.emplace(path);
    } catch (const cv::Exception& e) {
        fail(path, fmt::format("cannot open the video: {}", e.err), kVideoHint);
    }
    media::Video& video = *opened;
    if (!video.isOpened())
        fail(path, "not a video OpenCV can open (unknown format, missing decoder or damaged file)", kVideoHint);

    double containerFps = video.get(cv::CAP_PROP_FPS);
    if (!std::isfinite(containerFps) || containerFps <= 0 || containerFps > 1000) {
        capture.notes.push_back(fmt::format("{}: the container gives no frame rate ({}): 30 frames per second assumed",
                                            path, containerFps));
        containerFps = 30;
    }

    fs::path workDir = makeWorkDirectory(options, capture.notes);
    // A temporary folder of ours does not outlive a failed read.
    struct RemoveOnFailure {
        fs::path dir;
        bool armed;
        ~RemoveOnFailure() {
            std::error_code ignored;
            if (armed) fs::remove_all(dir, ignored);
        }
    } cleanup{workDir, options.workDirectory.empty()};
    Sampler sampler(options.fps, 0.5 / containerFps);
    cv::Mat image, written;
    cv::Size nativeSize;
    long long number = 0;
    try {
        for (; video.grab(); ++number) {
            double time = number / containerFps;
            if (!sampler.take(time)) continue;
            if (!video.retrieve(image) || image.empty())
                fail(path, fmt::format("cannot decode frame {} (at {:.2f} s)", number, time), kVideoHint);
            if (image.channels() == 1)
                cv::cvtColor(image, image, cv::COLOR_GRAY2BGR);
            else if (image.channels() == 4)
                cv::cvtColor(image, image, cv::COLOR_BGRA2BGR);
            if (nativeSize.empty()) nativeSize = image.size();
            if (options.workingWidth > 0 && image.cols > options.workingWidth) {
                int height = std::max(1, static_cast<int>(std::lround(static_cast<double>(image.rows) *
                                                                      options.workingWidth / image.cols)));
                cv::resize(image, written, cv::Size(options.workingWidth, height), 0, 0, cv::INTER_AREA);
            } else {
                written = image;
            }
            CaptureFrame frame;
            frame.index = static_cast<int>(capture.frames.size());
            frame.time = time;
            frame.colorPath = (workDir / fmt::format("frame_{:06d}.png", frame.index)).string();
            if (!media::write(frame.colorPath, written))
                throw Error(ErrorKind::Usage, fmt::format("{}: cannot write a decoded video frame", frame.colorPath));
            capture.frames.push_back(std::move(frame));
        }
    } catch (const cv::Exception& e) {
        fail(path, fmt::format("decoding failed at frame {}: {}", number, e.err), kVideoHint);
    }
    if (capture.frames.empty()) fail(path, "no frame could be decoded from the video", kVideoHint);
    if (capture.frames.size() < static_cast<std::size_t>(number))
        capture.notes.push_back(
            fmt::format("{} of the video's {} frames kept, {:g} a second (--fps; --fps 0 keeps "
                        "every frame)",
                        capture.frames.size(), number, options.fps));

    cv::Mat first = readColorImage(capture.frames.front().colorPath);
    const fs::path cameraFile = file.has_parent_path() ? file.parent_path() / "camera.json" : fs::path("camera.json");
    std::error_code ec;
    if (std::optional<Intrinsics> given = optionIntrinsics(options, nativeSize.width, nativeSize.height)) {
        given = fitIntrinsics(*given, nativeSize.width, nativeSize.height, path, optionName(options));
        capture.intrinsics = scaleIntrinsics(*given, first.cols, first.rows);
        capture.intrinsicsOrigin = optionOrigin(options);
    } else if (fs::is_regular_file(cameraFile, ec)) {
        CameraJson camera = readCameraJson(cameraFile, kVideoHint);
        Intrinsics native =
            fitIntrinsics(camera.intrinsics, nativeSize.width, nativeSize.height, path, cameraFile.string());
        capture.intrinsics = scaleIntrinsics(native, first.cols, first.rows);
        capture.notes.push_back(fmt::format("camera from {}: fx {:.1f}, fy {:.1f} for the video's {}x{}",
                                            cameraFile.string(), native.fx, native.fy, nativeSize.width,
                                            nativeSize.height));
    } else {
        capture.intrinsics = guessedIntrinsics(first.cols, first.rows);
        capture.intrinsicsOrigin = IntrinsicsOrigin::Guessed;
        capture.notes.push_back(fmt::format(
            "{}: the camera is unknown: intrinsics guessed as fx = fy = 1.2 x width with a centred principal point; "
            "give --camera, --fov or camera.json beside the video for better geometry",
            path));
    }
    if (options.depthScale) capture.depthScale = *options.depthScale;
    cleanup.armed = false;
    return capture;
}

// A folder of photos (.jpg, .jpeg, .png), the last folder layout tried.
extern const CaptureLayout kImageFolderLayout{
    "images", "a folder of .jpg/.png images", ".jpg/.jpeg/.png files (image folder)",
    [](const fs::path& target, std::vector<std::string>&) -> std::optional<fs::path> {
        if (isDirectory(target) && !imagesIn(target).empty()) return target;
        return std::nullopt;
    },
    readImageFolder};

// A video file: any file that is no image, JSON or text file (OpenCV says whether it can read it).
extern const CaptureLayout kVideoLayout{
    "video", "a video file", "a video file",
    [](const fs::path& target, std::vector<std::string>&) -> std::optional<fs::path> {
        std::string ext = extensionOf(target);
        if (isFile(target) && !isImageExtension(ext) && ext != "json" && ext != "txt") return target;
        return std::nullopt;
    },
    readVideo};

}  // namespace smql::ingest::capture_detail
