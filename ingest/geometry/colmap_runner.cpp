#include "ingest/geometry/colmap_runner.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <map>

#include <fmt/format.h>

#include "ingest/capture/capture_detail.hpp"
#include "model/error.hpp"

namespace smql::ingest {

namespace fs = std::filesystem;

namespace {

constexpr const char* kInstallHint =
    "install Debian's colmap (apt-get install colmap), or give a capture with camera poses";
constexpr const char* kRetryHint =
    "COLMAP needs overlapping, textured views: try more frames (a higher --fps for videos), slower camera motion "
    "with more overlap between neighbouring frames, or a capture with camera poses";

std::string shellQuoted(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

// The command's full path when it is an executable on PATH (or a path itself).
std::optional<std::string> findExecutable(const std::string& command) {
    if (command.find('/') != std::string::npos)
        return access(command.c_str(), X_OK) == 0 ? std::optional<std::string>(command) : std::nullopt;
    const char* path = std::getenv("PATH");
    if (!path) return std::nullopt;
    std::string all = path;
    std::size_t start = 0;
    while (start <= all.size()) {
        std::size_t end = all.find(':', start);
        if (end == std::string::npos) end = all.size();
        std::string dir = all.substr(start, end - start);
        if (!dir.empty()) {
            std::string candidate = fmt::format("{}/{}", dir, command);
            std::error_code ec;
            if (fs::is_regular_file(candidate, ec) && access(candidate.c_str(), X_OK) == 0) return candidate;
        }
        start = end + 1;
    }
    return std::nullopt;
}

}  // namespace

ColmapRun runColmap(Capture& capture, const ColmapOptions& options) {
    auto colmap = findExecutable(options.command);
    if (!colmap)
        throw Error(ErrorKind::Input,
                    fmt::format("--geometry colmap: the '{}' command is not on PATH; install Debian's colmap "
                                "(apt-get install colmap)",
                                options.command),
                    std::nullopt, kInstallHint);
    if (capture.frames.size() < 2)
        throw Error(
            ErrorKind::Input,
            fmt::format("{}: COLMAP needs at least 2 frames, the capture has {}", capture.path, capture.frames.size()),
            std::nullopt, kRetryHint);

    ColmapRun run;
    std::string pattern = (fs::temp_directory_path() / "smql-colmap-XXXXXX").string();
    if (!mkdtemp(pattern.data()))
        throw Error(ErrorKind::Input,
                    fmt::format("cannot create a work folder under {}", fs::temp_directory_path().string()));
    const fs::path work = pattern;
    run.workDirectory = work.string();
    run.logPath = (work / "colmap.log").string();
    const fs::path images = work / "images", database = work / "database.db", sparse = work / "sparse";
    fs::create_directories(images);
    fs::create_directories(sparse);

    // Images by frame position, linked (not copied): names map back to frames.
    std::map<std::string, std::size_t> frameByName;
    for (std::size_t i = 0; i < capture.frames.size(); ++i) {
        fs::path source = fs::absolute(capture.frames[i].colorPath);
        std::string name = fmt::format("frame{:06d}{}", i, capture_detail::lowerCase(source.extension().string()));
        std::error_code ec;
        fs::create_symlink(source, images / name, ec);
        if (ec) fs::copy_file(source, images / name, fs::copy_options::overwrite_existing);
        frameByName[name] = i;
    }

    const Intrinsics& K = capture.intrinsics;
    bool known = K.fx > 0 && K.fy > 0 &&
                 std::none_of(capture.frames.begin(), capture.frames.end(),
                              [](const CaptureFrame& f) { return f.intrinsics.has_value(); });
    std::string camera = known ? fmt::format(
                                     " --ImageReader.camera_model PINHOLE --ImageReader.single_camera 1 "
                                     "--ImageReader.camera_params {},{},{},{}",
                                     K.fx, K.fy, K.cx, K.cy)
                               : std::string(" --ImageReader.camera_model SIMPLE_RADIAL --ImageReader.single_camera 1");
    std::string threads = fmt::format("{}", options.threads);
    bool exhaustive = static_cast<int>(capture.frames.size()) <= options.exhaustiveUpTo;
    struct Step {
        std::string name, arguments;
    };
    std::vector<Step> steps = {
        {"feature_extractor",
         fmt::format("--database_path {} --image_path {}{} --SiftExtraction.use_gpu 0 --SiftExtraction.num_threads {}",
                     shellQuoted(database.string()), shellQuoted(images.string()), camera, threads)},
        {exhaustive ? "exhaustive_matcher" : "sequential_matcher",
         fmt::format("--database_path {} --SiftMatching.use_gpu 0 --SiftMatching.num_threads {}",
                     shellQuoted(database.string()), threads)},
        {"mapper", fmt::format("--database_path {} --image_path {} --output_path {} --Mapper.num_threads {}",
                               shellQuoted(database.string()), shellQuoted(images.string()),
                               shellQuoted(sparse.string()), threads)},
    };
    for (const auto& step : steps) {
        std::string line = fmt::format("echo '$ colmap {}' >> {}; QT_QPA_PLATFORM=offscreen {} {} {} >> {} 2>&1",
                                       step.name, shellQuoted(run.logPath), shellQuoted(*colmap), step.name,
                                       step.arguments, shellQuoted(run.logPath));
        int status = std::system(line.c_str());
        int code = status == -1 ? -1 : WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        if (code != 0)
            throw Error(
                ErrorKind::Input,
                fmt::format("colmap {} failed (exit status {}); its output is in {}", step.name, code, run.logPath),
                std::nullopt, kRetryHint);
    }

    // The mapper writes one folder per model (sparse/0, sparse/1...): take the one with the most images.
    CaptureOptions readOptions;
    readOptions.imageDirectory = images.string();
    std::optional<Capture> best;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(sparse, ec)) {
        if (!entry.is_directory() || !capture_detail::colmapModelFormat(entry.path())) continue;
        ++run.models;
        try {
            Capture model = capture_detail::readColmap(entry.path(), readOptions);
            if (!best || model.frames.size() > best->frames.size()) best = std::move(model);
        } catch (const Error& e) {
            run.notes.push_back(fmt::format("COLMAP model {} skipped: {}", entry.path().string(), e.what()));
        }
    }
    if (!best)
        throw Error(
            ErrorKind::Input,
            fmt::format("colmap mapper produced no model: no pair of frames could be registered; its output is in {}",
                        run.logPath),
            std::nullopt, kRetryHint);

    for (auto& frame : capture.frames) frame.pose.reset();
    for (const auto& frame : best->frames) {
        auto it = frameByName.find(fs::path(frame.colorPath).filename().string());
        if (it == frameByName.end()) continue;
        capture.frames[it->second].pose = frame.pose;
        ++run.registered;
    }
    capture.points = best->points;
    capture.metric = false;
    run.points = capture.points.size();
    if (run.models > 1)
        run.notes.push_back(fmt::format("COLMAP made {} separate models; the largest ({} frames) is used", run.models,
                                        best->frames.size()));
    if (run.registered < capture.frames.size())
        run.notes.push_back(fmt::format("COLMAP registered {} of {} frames; the others are skipped", run.registered,
                                        capture.frames.size()));
    // A successful run's work folder goes unless asked to stay; a failed one stays for its log.
    if (options.keepWorkDirectory)
        run.notes.push_back(fmt::format("COLMAP work folder (images, database, models, log): {}", run.workDirectory));
    else
        fs::remove_all(work, ec);
    return run;
}

}  // namespace smql::ingest
