#include "ingest/geometry/colmap_runner.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstring>
#include <thread>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <Eigen/Geometry>
#include <opencv2/imgproc.hpp>

#include "ingest/capture/capture_detail.hpp"
#include "ingest/capture/frame_loader.hpp"
#include "ingest/capture/media.hpp"
#include "ingest/geometry/colmap_database.hpp"
#include "ingest/geometry/sift_matching.hpp"
#include "model/error.hpp"
#include "model/presentation.hpp"

namespace smql::ingest {

namespace fs = std::filesystem;

namespace {

constexpr const char* kInstallHint =
    "install Debian's colmap (apt-get install colmap), or give a capture with camera poses";
// The mapper's settings, tried in turn (docs/ingest.md, "Geometry from COLMAP"). COLMAP drops
// models under min(10, 0.8 x the images) by default, which loses a model of 6 of 8 photos: both
// keep models from 3 images, and the largest is judged here. Frames a short step apart (a video)
// see their points under small angles, which COLMAP's defaults will not start a model from.
struct MapperSettings {
    const char* name;
    const char* folder;
    const char* arguments;
};
constexpr MapperSettings kMapperSettings[] = {
    {"its default settings", "default", "--Mapper.min_model_size 3"},
    {"a relaxed start (4 degrees between views, 50 inliers to start, 15 to add a frame)", "relaxed",
     "--Mapper.min_model_size 3 --Mapper.init_min_tri_angle 4 --Mapper.init_min_num_inliers 50 "
     "--Mapper.abs_pose_min_num_inliers 15 --Mapper.abs_pose_min_inlier_ratio 0.15"},
};

// COLMAP's steps that draw random samples or sum in parallel run on one thread, so that the same photos give the
// same memory on every run (features are extracted on every core: colmap_database.hpp says what that takes). Its
// verification of each pair's matches draws RANSAC's samples from a generator per thread, each seeded alike, so
// on two threads the pairs a thread happens to take decide its draws: of four runs over the five dining photos,
// one verified a pair to 65 inliers as a general scene where the others found 64 on a plane, and its model held
// 155 points where theirs held 149. The mapper's bundle adjustment on two threads sums in the order they finish:
// TUM fr1/rpy's 100 frames, mapped twice from one database, gave two models with the same points a few bits
// apart, and one thread gave the same bytes twice, in 12.2 s where two took 10.8.
constexpr int kRepeatableThreads = 1;

// Bundle adjustment shorter and, over the whole model, less often than COLMAP's defaults (after
// the model doubled rather than grew by 10 %; 15 and 10 iterations rather than 50 and 25): 300
// frames' mapper 174 -> 146 s with every frame placed and the same reprojection error (docs/ingest.md,
// "Real captures").
constexpr const char* kMapperAdjustment =
    "--Mapper.ba_global_images_ratio 2 --Mapper.ba_global_points_ratio 2 "
    "--Mapper.ba_global_max_num_iterations 15 --Mapper.ba_local_max_num_iterations 10";

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

// A frame as COLMAP sees it: its image in the work folder, scaled down to the
// run's maximum size, and the camera group (one COLMAP camera) it belongs to.
struct WorkFrame {
    std::size_t frame = 0;  // position in the capture
    std::string name;       // relative to images/: "<group>/frame000000.png"
    cv::Size original;      // the frame as stored (as OpenCV reads it)
    cv::Size work;          // as COLMAP sees it
    fs::path source;        // the frame's file
    bool upright = true;    // stored upright (no EXIF turn)
    // The frame's known camera at its stored size when its lens distorts: the work image is undistorted
    // (frame_loader.hpp), as every stage sees the frame, and COLMAP's camera is its pinhole. COLMAP's own
    // OPENCV models registered none of TUM fr1/rpy's frames with Freiburg 1's calibration fixed.
    std::optional<Intrinsics> lens{};
};

// Frames of one image size with one known camera (or an unknown one): one COLMAP camera.
struct CameraGroup {
    std::string folder;  // "1920x1080", "1920x1080-2" for a second known camera of that size
    cv::Size original, work;
    std::optional<Intrinsics> known;  // at the work size
    std::vector<std::size_t> frames;  // indices into the work frames
};

cv::Size scaledDown(cv::Size size, int maxSize) {
    int longSide = std::max(size.width, size.height);
    if (maxSize <= 0 || longSide <= maxSize) return size;
    double s = static_cast<double>(maxSize) / longSide;
    return {std::max(1, static_cast<int>(std::lround(size.width * s))),
            std::max(1, static_cast<int>(std::lround(size.height * s)))};
}

// The work folder: a new one under /tmp, or the one given (created when missing).
fs::path makeWorkFolder(const std::string& given) {
    if (!given.empty()) {
        std::error_code ec;
        fs::create_directories(given, ec);
        if (ec || !fs::is_directory(given))
            throw Error(ErrorKind::Input, fmt::format("cannot create the COLMAP work folder {}: {}", given,
                                                      ec ? ec.message() : "not a folder"));
        return fs::absolute(given);
    }
    std::string pattern = (fs::temp_directory_path() / "smql-colmap-XXXXXX").string();
    if (!mkdtemp(pattern.data()))
        throw Error(ErrorKind::Input,
                    fmt::format("cannot create a work folder under {}", fs::temp_directory_path().string()));
    return pattern;
}

// Empties a work folder before a run. A folder holding anything but an earlier run (its colmap.log)
// is someone else's: refused rather than emptied.
void clearWorkFolder(const fs::path& work) {
    std::error_code ec;
    if (fs::is_empty(work, ec)) return;
    if (!fs::exists(work / "colmap.log"))
        throw Error(
            ErrorKind::Input,
            fmt::format("the COLMAP work folder {} holds files of no COLMAP run; it would be emptied", work.string()),
            std::nullopt, "give a new or empty folder, or one an earlier ingest ran COLMAP in");
    for (const auto& entry : fs::directory_iterator(work)) fs::remove_all(entry.path());
}

// Links a frame into COLMAP's image folder when COLMAP can read it as it is, else writes it scaled
// down and upright (as OpenCV reads it).
void writeWorkImage(const WorkFrame& w, const fs::path& target) {
    if (w.work == w.original && w.upright && !w.lens) {
        std::error_code ec;
        fs::create_symlink(w.source, target, ec);
        if (ec) fs::copy_file(w.source, target);
        return;
    }
    cv::Mat image = media::read(w.source.string(), cv::IMREAD_COLOR), small;
    if (w.lens) image = undistorted(image, *w.lens, cv::INTER_LINEAR);
    cv::resize(image, small, w.work, 0, 0, cv::INTER_AREA);
    if (!media::write(target.string(), small, {cv::IMWRITE_JPEG_QUALITY, 95}))
        throw Error(ErrorKind::Input, fmt::format("cannot write {}", target.string()));
}

std::string readText(const fs::path& file) {
    std::ifstream in(file);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// What a run's result depends on: its options and, per frame, the file (its length and time), its
// size, the camera and any given pose. Two runs that describe alike give the same model.
std::string describeRun(const Capture& capture, const std::vector<WorkFrame>& workFrames,
                        const std::vector<CameraGroup>& groups, const ColmapOptions& options) {
    std::string out = fmt::format(
        "smql COLMAP run: max size {}, exhaustive up to {} ({} in order), overlap {}, fine features up to {}, every "
        "pair up to {} ({} matches, {} a frame), loop frames {}, min matches {}, vocabulary tree '{}', layout {}, "
        "mapper settings {} ({})\n",
        options.maxImageSize, options.exhaustiveUpTo, options.exhaustiveOrderedUpTo, options.sequentialOverlap,
        options.fineFeaturesUpTo, options.everyPairUpTo, options.loopMatches, options.loopsPerFrame, options.loopFrames,
        options.minMatches, options.vocabularyTree, capture.layout, std::size(kMapperSettings), kMapperAdjustment);
    for (const CameraGroup& g : groups) {
        out += fmt::format("camera {} {}x{}", g.folder, g.work.width, g.work.height);
        if (g.known)
            out += fmt::format(" {:.17g} {:.17g} {:.17g} {:.17g}", g.known->fx, g.known->fy, g.known->cx, g.known->cy);
        out += "\n";
    }
    for (const WorkFrame& w : workFrames) {
        std::error_code ec;
        out += fmt::format("{} {} {} bytes, written {}, {}x{}", w.name, w.source.string(), fs::file_size(w.source, ec),
                           fs::last_write_time(w.source, ec).time_since_epoch().count(), w.original.width,
                           w.original.height);
        if (w.lens) out += fmt::format(" undistorted {:.17g}", fmt::join(w.lens->distortion, " "));
        if (const auto& pose = capture.frames[w.frame].pose)
            out += fmt::format(" pose {:.17g} {:.17g} {:.17g} {:.17g}", fmt::join(pose->rotation, " "),
                               pose->translation.x, pose->translation.y, pose->translation.z);
        out += "\n";
    }
    return out;
}

// The frame's camera at its stored size when the capture knows it; the guess is left to COLMAP.
std::optional<Intrinsics> knownCamera(const Capture& capture, const CaptureFrame& frame, cv::Size size) {
    if (capture.intrinsicsOrigin == IntrinsicsOrigin::Guessed) return std::nullopt;
    const Intrinsics& k = frame.intrinsics ? *frame.intrinsics : capture.intrinsics;
    if (!(k.fx > 0) || !(k.fy > 0) || k.width <= 0 || k.height <= 0) return std::nullopt;
    if (std::abs(static_cast<double>(k.height) * size.width / k.width - size.height) > 1.0) return std::nullopt;
    return capture_detail::scaleIntrinsics(k, size.width, size.height);
}

// Every pair of the names, each once, in their order.
std::vector<std::pair<std::string, std::string>> allPairs(const std::vector<std::string>& names) {
    std::vector<std::pair<std::string, std::string>> pairs;
    for (std::size_t a = 0; a < names.size(); ++a)
        for (std::size_t b = a + 1; b < names.size(); ++b) pairs.emplace_back(names[a], names[b]);
    return pairs;
}

// The pairs with `least` matches or more.
std::vector<ColmapPairCount> withMatches(std::vector<ColmapPairCount> pairs, std::size_t least) {
    std::erase_if(pairs, [&](const ColmapPairCount& pair) { return pair.matches < least; });
    return pairs;
}

// Of the pairs, those among the `perFrame` with the most matches of either of their frames (of pairs with as many,
// the first in the table's order).
std::vector<ColmapPairCount> strongestPerFrame(const std::vector<ColmapPairCount>& pairs, std::size_t perFrame) {
    std::map<long long, std::vector<std::size_t>> byFrame;
    for (std::size_t i = 0; i < pairs.size(); ++i) {
        byFrame[pairs[i].first].push_back(i);
        byFrame[pairs[i].second].push_back(i);
    }
    std::vector<bool> kept(pairs.size(), false);
    for (auto& entry : byFrame) {
        std::vector<std::size_t>& links = entry.second;
        std::stable_sort(links.begin(), links.end(),
                         [&](std::size_t a, std::size_t b) { return pairs[a].matches > pairs[b].matches; });
        for (std::size_t k = 0; k < std::min(perFrame, links.size()); ++k) kept[links[k]] = true;
    }
    std::vector<ColmapPairCount> out;
    for (std::size_t i = 0; i < pairs.size(); ++i)
        if (kept[i]) out.push_back(pairs[i]);
    return out;
}

const char* originWords(IntrinsicsOrigin origin) {
    switch (origin) {
        case IntrinsicsOrigin::Measured:
            return "kept fixed as given";
        case IntrinsicsOrigin::Approximate:
            return "refined from the approximate focal length (--fov or EXIF)";
        case IntrinsicsOrigin::Guessed:
            return "estimated by COLMAP, the camera being unknown";
    }
    return "";
}

// How many photos a refusal names before "and N more".
constexpr std::size_t kPhotosNamed = 5;

// The file names of the frames that `kept` holds, in the capture's order.
template <class Kept>
std::vector<std::string> fileNames(const std::vector<WorkFrame>& frames, Kept kept) {
    std::vector<std::string> out;
    for (const auto& f : frames)
        if (kept(f)) out.push_back(f.source.filename().string());
    return out;
}

// Where photos taken in order part, and which of them gave no features, by their own file names: a walk
// through plain rooms (RTAB-Map's corridor: a blank wall, a door seen close up) breaks where it turned to a
// view that the one before does not share. Each parting is a frame in no overlapping group with the frame before
// it (ColmapDatabaseSummary::overlapGroup), in the capture's order: the order taken.
std::string wherePhotosPart(const ColmapDatabaseSummary& s, const std::vector<WorkFrame>& frames) {
    auto group = [&](const WorkFrame& f) {
        auto g = s.overlapGroup.find(f.name);
        return g == s.overlapGroup.end() ? std::optional<std::int64_t>() : g->second;
    };
    std::vector<std::string> partings;
    for (std::size_t i = 1; i < frames.size(); ++i) {
        const auto before = group(frames[i - 1]), after = group(frames[i]);
        if (!before || !after || *before != *after) partings.push_back(frames[i].source.filename().string());
    }
    const std::vector<std::string> featureless =
        fileNames(frames, [&](const WorkFrame& f) { return s.featureless.contains(f.name); });
    std::string out;
    if (!partings.empty())
        out = fmt::format(
            "; in the order taken they part {} {}, at {}, each sharing too few matches with the photo "
            "before it",
            partings.size(), partings.size() == 1 ? "time" : "times", model::listFirst(partings, kPhotosNamed));
    if (!featureless.empty())
        out += fmt::format("; {} gave no features (a plain surface, or a dark or blurred photo)",
                           model::listFirst(featureless, kPhotosNamed));
    return out;
}

// "only 2 of 8 photos overlap enough ...": what the database says, for an error. `started`: the
// mapper grew a model, too small, rather than none.
std::string diagnosis(const fs::path& database, const std::vector<WorkFrame>& workFrames, int minMatches,
                      bool started = false) {
    std::error_code ec;
    if (!fs::exists(database, ec)) return {};
    const std::size_t frames = workFrames.size();
    try {
        ColmapDatabaseSummary s = readColmapDatabase(database.string(), minMatches);
        // A cause is named only when it is most of the story: two photos of 84 without features do
        // not stop a model from growing (a real corridor set did fail, for want of a starting pair).
        auto most = [](std::size_t part, std::size_t whole) { return 5 * part >= 4 * whole; };
        if (!most(s.imagesWithFeatures, s.images))
            return fmt::format(
                "only {} of {} photos gave image features (blank, dark, blurred or textureless photos give none): "
                "take sharper photos of textured surfaces",
                s.imagesWithFeatures, frames);
        std::string overlap = fmt::format("{} {} of photos {} {} or more verified matches", s.overlappingPairs,
                                          s.overlappingPairs == 1 ? "pair" : "pairs",
                                          s.overlappingPairs == 1 ? "shares" : "share", minMatches);
        if (!most(s.overlappingImages, frames)) {
            const auto alone =
                fileNames(workFrames, [&](const WorkFrame& f) { return !s.overlapGroup.contains(f.name); });
            return fmt::format(
                "only {} of {} photos overlap enough with another ({}); {} {} with none: take more views with "
                "overlap, each neighbouring photo seeing much of what the last one saw",
                s.overlappingImages, frames, overlap, model::listFirst(alone, kPhotosNamed),
                alone.size() == 1 ? "overlaps" : "overlap");
        }
        if (!most(s.largestOverlapGroup, frames))
            return fmt::format(
                "every photo overlaps with another, but they fall apart into separate groups: the largest holds only "
                "{} of {} photos ({}){}: take views that link the groups, with overlap",
                s.largestOverlapGroup, frames, overlap, wherePhotosPart(s, workFrames));
        if (started)
            return fmt::format(
                "{} of {} photos are linked by overlap ({}), but most would not join the model: the camera may have "
                "turned more than it moved (views from one spot give no depth), or neighbouring views overlap too "
                "little",
                s.largestOverlapGroup, frames, overlap);
        return fmt::format(
            "{} of {} photos are linked by overlap ({}), but COLMAP found no pair to start a model from (two views "
            "with many matches seen from places far enough apart): the views may be too close together (move the "
            "camera between photos, not only turn it) or the matches fall on repeated patterns; take views from more "
            "places, with overlap",
            s.largestOverlapGroup, frames, overlap);
    } catch (const Error& e) {
        return e.what();
    }
}

// The capture's poses as a COLMAP text model without points, its images and cameras numbered as the
// database numbers them: what point_triangulator starts from. Each camera is a PINHOLE at the size
// COLMAP sees its frames (a lens's distortion is undone in the work images).
void writePosedModel(const fs::path& folder, const fs::path& database, const Capture& capture,
                     const std::vector<WorkFrame>& workFrames) {
    fs::create_directories(folder);
    std::map<std::string, const WorkFrame*> byName;
    for (const WorkFrame& w : workFrames) byName[w.name] = &w;
    std::ofstream cameras(folder / "cameras.txt"), images(folder / "images.txt");
    std::ofstream(folder / "points3D.txt").close();
    std::map<long long, bool> written;
    for (const auto& image : readColmapImages(database.string())) {
        auto it = byName.find(image.name);
        if (it == byName.end()) continue;
        const WorkFrame& w = *it->second;
        const CaptureFrame& frame = capture.frames[w.frame];
        if (!written[image.camera]) {
            Intrinsics k = capture_detail::scaleIntrinsics(frame.intrinsics ? *frame.intrinsics : capture.intrinsics,
                                                           w.work.width, w.work.height);
            cameras << fmt::format("{} PINHOLE {} {} {:.17g} {:.17g} {:.17g} {:.17g}\n", image.camera, k.width,
                                   k.height, k.fx, k.fy, k.cx + 0.5, k.cy + 0.5);
            written[image.camera] = true;
        }
        // COLMAP stores world-to-camera: R' = R^T, t' = -R^T c.
        const Pose& pose = *frame.pose;
        Eigen::Matrix3d toCamera;
        for (int row = 0; row < 3; ++row)
            for (int col = 0; col < 3; ++col) toCamera(row, col) = pose.rotation[col * 3 + row];
        Eigen::Vector3d t = -toCamera * Eigen::Vector3d(pose.translation.x, pose.translation.y, pose.translation.z);
        Eigen::Quaterniond q(toCamera);
        images << fmt::format("{} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {} {}\n\n", image.id, q.w(),
                              q.x(), q.y(), q.z(), t.x(), t.y(), t.z(), image.camera, image.name);
    }
}

// Signals that stop a process from outside (the kernel out of memory, a user, a supervisor), as opposed to
// COLMAP's own crashes (an abort on a failed check, a fault), which may come of what it read.
bool stoppedFromOutside(int signal) {
    return signal == SIGKILL || signal == SIGTERM || signal == SIGINT || signal == SIGHUP || signal == SIGQUIT;
}

// How far a running COLMAP command is, from the lines it adds to its log: "Processed file [12/100]" (the feature
// extractor), "Matching image [12/100]" (the sequential matcher), "Matching block [3/9, ..." (the exhaustive
// matcher, by blocks of images), "Registering image #31 (12)" (the mapper: 12 registered so far), each read as
// frames of the capture's `frames`.
struct LogProgress {
    std::string path;
    std::uintmax_t offset = 0;  // where the command's lines begin
    std::size_t frames = 0;
    std::size_t reported = 0;

    // The frames done, when more than reported before.
    std::optional<std::size_t> read() {
        std::ifstream in(path, std::ios::binary);
        in.seekg(static_cast<std::streamoff>(offset));
        std::string added((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        // Only whole lines: the last may still be written.
        const std::size_t end = added.rfind('\n');
        if (end == std::string::npos) return std::nullopt;
        offset += end + 1;
        std::size_t done = reported;
        std::istringstream lines(added.substr(0, end));
        for (std::string text; std::getline(lines, text);) {
            unsigned long part = 0, whole = 0, id = 0;
            if (std::sscanf(text.c_str(), "Processed file [%lu/%lu]", &part, &whole) == 2 ||
                std::sscanf(text.c_str(), "Matching image [%lu/%lu]", &part, &whole) == 2 ||
                std::sscanf(text.c_str(), "Matching block [%lu/%lu", &part, &whole) == 2) {
                if (whole > 0) done = frames * part / whole;
            } else if (std::sscanf(text.c_str(), "Registering image #%lu (%lu)", &id, &part) == 2) {
                done = part;
            }
        }
        done = std::min(done, frames);
        if (done <= reported) return std::nullopt;
        reported = done;
        return done;
    }
};

// One run of COLMAP over a capture, phase by phase: the frames into its image folder, features,
// matches (and loops closed), then points triangulated with the capture's own poses, or a model
// made by the mapper and the largest one read back. Each phase is a method; the state they share
// is the run's.
class ColmapSession {
public:
    ColmapSession(Capture& capture, const ColmapOptions& options, std::string colmap, ColmapWatch watch)
        : capture_(capture),
          options_(options),
          colmap_(std::move(colmap)),
          work_(makeWorkFolder(options.workDirectory)),
          images_(work_ / "images"),
          database_(work_ / "database.db"),
          sparse_(work_ / "sparse"),
          record_(work_ / "smql-run.txt"),
          threads_(fmt::format("{}", options.threads)),
          watch_(std::move(watch)) {
        run_.workDirectory = work_.string();
        run_.logPath = (work_ / "colmap.log").string();
    }

    ColmapRun run() {
        gatherFrames();
        prepareWorkFolder();
        try {
            fine_ = static_cast<int>(workFrames_.size()) <= options_.fineFeaturesUpTo;
            findAndMatchFeatures();
            // Frames that all have a pose (transforms.json without depth, RGB-D frames with the depth left
            // out) keep it: COLMAP only triangulates the matched features with the given poses and cameras.
            const bool posed = std::all_of(workFrames_.begin(), workFrames_.end(), [&](const WorkFrame& w) {
                return capture_.frames[w.frame].pose.has_value();
            });
            if (posed)
                triangulateWithPoses();
            else
                adoptModel(placeFrames());
        } catch (const Error&) {
            // A run the user stopped leaves no folder of its own behind; a failed one keeps it for its log, and
            // says where its time went.
            std::error_code removeError;
            if (stopped_ && options_.workDirectory.empty() && !options_.keepWorkDirectory)
                fs::remove_all(work_, removeError);
            else
                noteSteps();
            throw;
        }
        leaveWorkFolder();
        return std::move(run_);
    }

private:
    // Each note is kept in the run and passed on as it comes, so that a run that fails has said
    // what COLMAP did up to there.
    void note(std::string text) {
        if (watch_.notes) watch_.notes(text);
        run_.notes.push_back(std::move(text));
    }

    void noteSteps() {
        if (run_.reused || run_.steps.empty()) return;
        std::vector<std::string> times;
        for (const auto& [step, seconds] : run_.steps) times.push_back(fmt::format("{} {:.1f} s", step, seconds));
        note(fmt::format("COLMAP's steps: {}", fmt::join(times, ", ")));
    }

    // Frames into groups of one image size and one known camera: linked when COLMAP can read them
    // as they are, else written scaled down (and turned upright, as OpenCV reads them).
    void gatherFrames() {
        for (std::size_t i = 0; i < capture_.frames.size(); ++i) {
            const CaptureFrame& frame = capture_.frames[i];
            std::error_code ec;
            cv::Mat image;
            if (fs::is_regular_file(frame.colorPath, ec)) image = media::read(frame.colorPath, cv::IMREAD_COLOR);
            if (image.empty()) {
                note(fmt::format("frame {} ({}) is listed but its image is missing or unreadable: skipped", frame.index,
                                 frame.colorPath));
                continue;
            }
            WorkFrame w{
                i, {}, image.size(), scaledDown(image.size(), options_.maxImageSize), fs::absolute(frame.colorPath)};
            std::optional<Intrinsics> known = knownCamera(capture_, frame, image.size());
            if (known && known->distorted()) {
                w.lens = known;
                known->distortion = {};
            }
            if (known) known = capture_detail::scaleIntrinsics(*known, w.work.width, w.work.height);
            auto group = std::find_if(groups_.begin(), groups_.end(), [&](const CameraGroup& g) {
                return g.original == w.original && g.known == known;
            });
            if (group == groups_.end()) {
                std::size_t sameSize = std::count_if(groups_.begin(), groups_.end(),
                                                     [&](const CameraGroup& g) { return g.original == w.original; });
                std::string folder = fmt::format("{}x{}", w.original.width, w.original.height);
                if (sameSize > 0) folder += fmt::format("-{}", sameSize + 1);
                groups_.push_back(CameraGroup{folder, w.original, w.work, known, {}});
                group = groups_.end() - 1;
            }
            group->frames.push_back(workFrames_.size());
            std::string extension = capture_detail::lowerCase(w.source.extension().string());
            w.name = fmt::format("{}/frame{:06d}{}", group->folder, i, extension);
            w.upright = capture_detail::readExif(w.source).orientation == 1;
            scaled_ += w.work != w.original;
            workFrames_.push_back(std::move(w));
        }
        if (workFrames_.size() < 2)
            throw Error(ErrorKind::Input,
                        fmt::format("{}: COLMAP needs at least 2 frames, {} of {} have a readable image", capture_.path,
                                    workFrames_.size(), capture_.frames.size()),
                        std::nullopt, kRetryHint);
        run_.cameras = groups_.size();
    }

    // The run's inputs are recorded last: a folder whose record matches them holds this run,
    // finished, and is read instead of running COLMAP again.
    void prepareWorkFolder() {
        inputs_ = describeRun(capture_, workFrames_, groups_, options_);
        run_.reused = !options_.workDirectory.empty() && readText(record_) == inputs_;
        if (run_.reused) {
            note(
                fmt::format("COLMAP's model of these {} frames read from {}, run there before (empty the "
                            "folder to run COLMAP again)",
                            workFrames_.size(), run_.workDirectory));
        } else {
            clearWorkFolder(work_);
            fs::create_directories(sparse_);
            for (const CameraGroup& group : groups_) fs::create_directories(images_ / group.folder);
            for (const WorkFrame& w : workFrames_) writeWorkImage(w, images_ / w.name);
        }
        if (scaled_ > 0)
            note(
                fmt::format("COLMAP sees {} of {} frames scaled down to {} pixels on the long side "
                            "(--max-size); poses and intrinsics are mapped back to the frames' own pixels",
                            scaled_, workFrames_.size(), options_.maxImageSize));
    }

    // One COLMAP command, its output appended to the log and its time to the step's.
    // With `failureIsAnswer` a failure is returned (false) rather than thrown: the mapper exits with
    // a failure when it grows no model, which the next settings may.
    bool runStep(const std::string& step, const std::string& arguments, bool failureIsAnswer = false) {
        if (run_.reused) return true;
        std::ofstream(run_.logPath, std::ios::app) << fmt::format("$ colmap {} {}\n", step, arguments);
        // The shell becomes COLMAP (exec), so that stopping the command stops COLMAP.
        const std::string line = fmt::format("exec env QT_QPA_PLATFORM=offscreen {} {} {} >> {} 2>&1",
                                             shellQuoted(colmap_), step, arguments, shellQuoted(run_.logPath));
        auto start = std::chrono::steady_clock::now();
        const int status = runCommand(line);
        countStep(step, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        const int code = status == -1 ? -1 : WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        if (const int signal = code - 128; stoppedFromOutside(signal))
            throw Error(ErrorKind::Input,
                        fmt::format("colmap {} was stopped by signal {} ({}), not by what it read; its output is in {}",
                                    step, signal, strsignal(signal), run_.logPath),
                        std::nullopt,
                        signal == SIGKILL
                            ? "something outside the ingest stopped COLMAP: the kernel stops a process with signal 9 "
                              "when memory runs out (dmesg says so); fewer frames or a smaller --max-size need less"
                            : "something outside the ingest stopped COLMAP (a user, a closed terminal, a service "
                              "manager): run the ingest again; the photos were not at fault");
        if (code == 0) return true;
        if (failureIsAnswer) return false;
        std::string facts =
            step == "feature_extractor" ? std::string() : diagnosis(database_, workFrames_, options_.minMatches);
        throw Error(ErrorKind::Input,
                    fmt::format("colmap {} failed (exit status {}){}{}; its output is in {}", step, code,
                                facts.empty() ? "" : ": ", facts, run_.logPath),
                    std::nullopt, kRetryHint);
    }

    // The command line run by /bin/sh, waited for, the ingest still hearing SIGINT meanwhile (std::system would
    // hold it deaf until the command ends). Every 50 ms, and once the command has ended, the log's new lines tell
    // how far it is (watch_.progress) and watch_.stop may stop the run, and then the command. The command stays in
    // the ingest's process group, so a terminal's Ctrl-C or a supervisor's signal to the group reaches it too, as
    // before. The command's wait status, or -1 when it could not be started.
    int runCommand(const std::string& line) {
        const char* argv[] = {"sh", "-c", line.c_str(), nullptr};
        std::error_code ec;
        LogProgress log{run_.logPath, fs::file_size(run_.logPath, ec), capture_.frames.size()};
        pid_t child = 0;
        if (posix_spawn(&child, "/bin/sh", nullptr, nullptr, const_cast<char* const*>(argv), environ) != 0) return -1;
        int status = 0;
        for (bool ended = false; !ended;) {
            const pid_t done = waitpid(child, &status, WNOHANG);
            if (done == -1 && errno != EINTR) return -1;
            ended = done == child;
            try {
                if (const auto frames = log.read(); frames && watch_.progress) watch_.progress(*frames);
                if (watch_.stop) watch_.stop();
            } catch (...) {
                stopped_ = true;
                if (!ended) {
                    kill(child, SIGTERM);
                    waitpid(child, &status, 0);
                }
                throw;
            }
            if (!ended) std::this_thread::sleep_for(std::chrono::milliseconds(50));
        }
        return status;
    }

    void countStep(const std::string& step, double seconds) {
        if (!run_.steps.empty() && run_.steps.back().first == step)
            run_.steps.back().second += seconds;
        else
            run_.steps.emplace_back(step, seconds);
    }

    // The pairs a COLMAP matcher is about to match, matched here first (sift_matching.hpp: the same rule,
    // exactly, six times faster), so that COLMAP only verifies them. Should the database not read as
    // expected, COLMAP matches them itself, as it does the loops its vocabulary tree finds.
    // Returns whether they were matched here.
    bool matchFirst(const std::function<std::vector<std::pair<std::string, std::string>>()>& pairs) {
        if (run_.reused) return false;
        try {
            const ColmapMatching done = matchColmapPairs(database_.string(), pairs(), options_.threads);
            countStep("feature matching (smql)", done.seconds);
            return true;
        } catch (const Error& e) {
            note(fmt::format("features left to COLMAP's matcher: {}", e.what()));
            return false;
        }
    }

    // The pairs COLMAP's matcher matches (in the database's name order, as it orders them): all of them,
    // or each frame's next ones (and with `farther_`, those 2^k on).
    std::vector<std::pair<std::string, std::string>> matcherPairs() const {
        const std::vector<std::string> names = databaseNames();
        if (exhaustive_) return allPairs(names);
        std::vector<std::pair<std::string, std::string>> pairs;
        for (const auto& [a, b] : sequentialPairs(names.size(), options_.sequentialOverlap, farther_))
            pairs.emplace_back(names[a], names[b]);
        return pairs;
    }

    // The database's images' names by their ids.
    std::map<long long, std::string> namesById() const {
        std::map<long long, std::string> names;
        for (const auto& image : readColmapImages(database_.string())) names.emplace(image.id, image.name);
        return names;
    }

    // The database's images' names, in name order.
    std::vector<std::string> databaseNames() const {
        std::vector<std::string> names;
        for (auto& [id, name] : namesById()) names.push_back(std::move(name));
        std::sort(names.begin(), names.end());
        return names;
    }

    void findAndMatchFeatures() {
        extractFeatures();
        matchFeatures();
        if (!exhaustive_ && !loops_) closeLoops();
    }

    // What the mapper's runs made: the largest model (none when no run made one), and how many frames
    // the other models placed apart from it.
    struct MapperOutcome {
        std::optional<Capture> largest;
        std::size_t placedApart = 0;
    };

    // A long capture's features at the frames' own size place its frames in half the time; when they
    // leave more than a fifth of the frames out (too few features shared across a wide step), the
    // frames doubled give the finer features, found and matched again in a new database: 20 frames of
    // a generated walk, 11 placed, then all 20 (tests/unit/ingest/colmap_test.cpp). The finer pass
    // matches its frames farther apart too from the start (mapWithFartherPairs); the pass at the frames' own
    // size no longer does first: on ScanNet's apartment and bathroom its farther round still left more than a
    // fifth out (203 and 134 of 300 placed), so the finer pass ran after it anyway, and it cost 41 and 72 s.
    Capture placeFrames() {
        if (fine_ || run_.reused) return accepted(mapWithFartherPairs());
        MapperOutcome outcome = mapLargestModel("");
        if (mostPlaced(placedBy(outcome))) return std::move(*outcome.largest);
        const auto reach = fartherReach();
        farther_ = !exhaustive_ && !reach.empty();
        note(
            fmt::format("COLMAP placed {} of {} frames with features at their own size; it runs again with the "
                        "finer features of the frames doubled{}",
                        placedBy(outcome), workFrames_.size(),
                        farther_ ? fmt::format(", each frame matched also with the frames {} on (COLMAP's "
                                               "quadratic overlap)",
                                               model::listFirst(reach, reach.size()))
                                 : std::string()));
        fine_ = true;
        fs::remove(database_);
        fs::remove_all(sparse_);
        fs::create_directories(sparse_);
        run_.models = 0;
        findAndMatchFeatures();
        return accepted(mapWithFartherPairs());
    }

    static constexpr const char* kFartherRound = "farther-";
    bool roundRan(const std::string& round) const {
        std::error_code ec;
        for (const auto& entry : fs::directory_iterator(sparse_, ec))
            if (entry.path().filename().string().starts_with(round)) return true;
        return false;
    }
    static std::size_t placedBy(const MapperOutcome& outcome) {
        return outcome.largest ? outcome.largest->frames.size() : 0;
    }
    // The share of the frames a model must hold for the mapper's runs to stop (and no finer pass to follow).
    bool mostPlaced(std::size_t placed) const { return 5 * placed >= 4 * workFrames_.size(); }

    // What COLMAP's quadratic overlap adds to the frames 1 to overlap - 1 on: those 2^k on, k < the overlap.
    std::vector<std::string> fartherReach() const {
        std::vector<std::string> reach;
        for (int k = 0; k < std::min(options_.sequentialOverlap, 20); ++k)
            if ((1 << k) >= options_.sequentialOverlap) reach.push_back(std::to_string(1 << k));
        return reach;
    }

    // The mapper on the pairs matched; when its largest model leaves more than a fifth of the frames out
    // of frames matched with the few after each alone, each frame is matched again with those 2^k on
    // (COLMAP's quadratic overlap: 8 and 16 on with the overlap 5; the pairs matched already are
    // skipped) and the mapper runs again. 300 frames of a walk through ScanNet's apartment: 123 in one
    // model with the frames after each, 283 and 205 in two runs with those farther on (docs/ingest.md,
    // "Geometry from COLMAP").
    MapperOutcome mapWithFartherPairs() {
        MapperOutcome outcome = mapLargestModel("");
        // A run read back went farther only if its folder holds that round.
        if (mostPlaced(placedBy(outcome)) || exhaustive_ || farther_ || (run_.reused && !roundRan(kFartherRound)))
            return outcome;
        const auto reach = fartherReach();
        if (reach.empty()) return outcome;
        note(
            fmt::format("COLMAP placed {} of {} frames together with each frame matched with the {} after it; it "
                        "matches each frame again with the frames {} on (COLMAP's quadratic overlap) and maps again",
                        placedBy(outcome), workFrames_.size(), options_.sequentialOverlap - 1,
                        model::listFirst(reach, reach.size())));
        farther_ = true;
        matchFeatures();
        MapperOutcome farther = mapLargestModel(kFartherRound);
        return placedBy(farther) > placedBy(outcome) ? std::move(farther) : std::move(outcome);
    }

    // One feature_extractor run per group, so that each image size gets a camera of its own even
    // when the sizes share a folder of photos (COLMAP's single_camera would force one size on all).
    void extractFeatures() {
        // A run read back says what its models hold, not what was run to make them (its colmap.log does).
        if (!fine_ && !run_.reused)
            note(
                fmt::format("COLMAP looks for features at the frames' own size, not doubled as for captures of up to "
                            "{} frames: half the time, and each frame has neighbours enough",
                            options_.fineFeaturesUpTo));
        for (const CameraGroup& group : groups_) {
            fs::path list = work_ / fmt::format("images-{}.txt", group.folder);
            std::ofstream out(list);
            for (std::size_t index : group.frames) out << workFrames_[index].name << "\n";
            out.close();
            std::string camera =
                group.known ? fmt::format(
                                  "--ImageReader.camera_model PINHOLE --ImageReader.camera_params "
                                  "{},{},{},{}",
                                  group.known->fx, group.known->fy, group.known->cx + 0.5, group.known->cy + 0.5)
                            : std::string("--ImageReader.camera_model SIMPLE_RADIAL");
            runStep("feature_extractor",
                    fmt::format("--database_path {} --image_path {} --image_list_path {} --ImageReader.single_camera 1 "
                                "{} --SiftExtraction.use_gpu 0 --SiftExtraction.num_threads {} "
                                "--SiftExtraction.first_octave {}",
                                shellQuoted(database_.string()), shellQuoted(images_.string()),
                                shellQuoted(list.string()), camera, threads_, fine_ ? -1 : 0));
        }
        if (!run_.reused) {
            numberColmapImagesByName(database_.string());
            clearUnwrittenDescriptors(database_.string());
        }
        ColmapDatabaseSummary extracted = readColmapDatabase(database_.string(), options_.minMatches);
        if (extracted.imagesWithFeatures < 2)
            throw Error(ErrorKind::Input,
                        fmt::format("colmap feature_extractor: only {} of {} photos gave image features; its output "
                                    "is in {}",
                                    extracted.imagesWithFeatures, workFrames_.size(), run_.logPath),
                        std::nullopt,
                        "blank, dark, blurred or textureless photos give no features: take sharper photos of "
                        "textured surfaces");
    }

    // Frames in capture order (videos, RGB-D sequences) are matched with their neighbours; a photo
    // folder's order says little, so small ones are matched all against all, as are a few frames of
    // a video, which every pair may help to place.
    void matchFeatures() {
        ordered_ = capture_.layout != "images";
        exhaustive_ = static_cast<int>(workFrames_.size()) <=
                      (ordered_ ? options_.exhaustiveOrderedUpTo : options_.exhaustiveUpTo);
        std::error_code treeError;
        loops_ =
            !exhaustive_ && !options_.vocabularyTree.empty() && fs::is_regular_file(options_.vocabularyTree, treeError);
        run_.matcher = exhaustive_ ? "exhaustive_matcher" : "sequential_matcher";
        std::string matching = fmt::format(
            "--database_path {} --SiftMatching.use_gpu 0 --SiftMatching.num_threads {} "
            "--SiftMatching.min_num_inliers {}",
            shellQuoted(database_.string()), kRepeatableThreads, options_.minMatches);
        if (!exhaustive_) {
            matching += fmt::format(" --SequentialMatching.overlap {} --SequentialMatching.quadratic_overlap {}",
                                    options_.sequentialOverlap, farther_ ? 1 : 0);
            if (loops_)
                matching +=
                    fmt::format(" --SequentialMatching.loop_detection 1 --SequentialMatching.vocab_tree_path {}",
                                shellQuoted(options_.vocabularyTree));
        }
        matchFirst([this] { return matcherPairs(); });
        runStep(run_.matcher, matching);
    }

    // Without a vocabulary tree, a walk that comes back to where it started is closed by the pairs of
    // frames that share many features wherever they lie in it: every pair is matched here, and those
    // with loopMatches matches or more are verified. ScanNet's apartment, 100 frames spread over a walk
    // through its rooms: with the frames after each and 20 frames spread through it all against all, the
    // mapper placed 35 together; every pair verified, 78 (COLMAP's verification 35 s); the pairs with 30
    // matches or more beside the frames after each, 76: most pairs with 15 to 29 are chance matches that
    // RANSAC tries to its limit (104 of 737 verified, against 178 of 180 with 30 to 59). In a small room most
    // pairs share that many, and each frame keeps its loopsPerFrame strongest: ScanNet's bathroom, 296 frames,
    // had 4,195 such pairs with the finer features, and the mapper took 271 s on them and placed 215; with each
    // frame's 10 strongest, 1,334 pairs, 200 s and 243 placed; with its 5, 105 (with 20 frames spread through
    // it, 193 to 217). The finer features of a second pass are matched on the pairs that had minMatches or
    // more with the first's (every pair of those 296 frames again took 34 s). A longer capture, or a database
    // that does not read, matches loopFrames frames spread evenly through it all against all.
    void closeLoops() {
        if (run_.reused) return;
        const std::size_t frames = workFrames_.size();
        std::vector<std::pair<std::string, std::string>> loops;
        const bool again = !loopCandidates_.empty();
        const bool everyPair = static_cast<int>(frames) <= options_.everyPairUpTo && matchFirst([this, again] {
                                   return again ? loopCandidates_ : allPairs(databaseNames());
                               });
        std::size_t count = 0;
        if (everyPair) {
            const std::map<long long, std::string> names = namesById();
            auto named = [&](const std::vector<ColmapPairCount>& pairs) {
                std::vector<std::pair<std::string, std::string>> out;
                for (const auto& pair : pairs) out.emplace_back(names.at(pair.first), names.at(pair.second));
                return out;
            };
            const auto loopMatches = static_cast<std::size_t>(std::max(options_.loopMatches, 0));
            const auto minMatches = static_cast<std::size_t>(std::max(options_.minMatches, 0));
            const std::vector<ColmapPairCount> overlapping =
                readUnverifiedPairs(database_.string(), std::min(loopMatches, minMatches));
            loops = named(strongestPerFrame(withMatches(overlapping, loopMatches),
                                            static_cast<std::size_t>(std::max(options_.loopsPerFrame, 0))));
            if (!again && !fine_) loopCandidates_ = named(withMatches(overlapping, minMatches));
        } else {
            count = std::min<std::size_t>(frames, std::max(options_.loopFrames, 0));
            std::vector<std::string> spread;
            for (std::size_t a = 0; a < count; ++a) spread.push_back(workFrames_[a * frames / count].name);
            loops = allPairs(spread);
            if (count >= 2) matchFirst([&loops] { return loops; });
        }
        const fs::path pairsFile = work_ / "loop-pairs.txt";
        std::ofstream pairs(pairsFile);
        for (const auto& [a, b] : loops) pairs << a << " " << b << "\n";
        pairs.close();
        if (!loops.empty())
            runStep("matches_importer",
                    fmt::format("--database_path {} --match_list_path {} --match_type pairs --SiftMatching.use_gpu 0 "
                                "--SiftMatching.num_threads {} --SiftMatching.min_num_inliers {}",
                                shellQuoted(database_.string()), shellQuoted(pairsFile.string()), kRepeatableThreads,
                                options_.minMatches));
        note(fmt::format(
            "COLMAP matched each frame with the {} after it in {} order; loop detection {}, so loops are closed by {}",
            options_.sequentialOverlap - 1, ordered_ ? "capture" : "name",
            options_.vocabularyTree.empty()
                ? "needs a vocabulary tree (vocab_tree_*.bin from COLMAP's site, given with --vocab-tree; "
                  "Debian ships none)"
                : fmt::format("is off: the vocabulary tree {} is not a file", options_.vocabularyTree),
            everyPair ? fmt::format("matching {} and verifying the {} others with {} matches or more that are among "
                                    "the {} with the most of either frame",
                                    again ? fmt::format("the {} pairs that had {} or more with the features at the "
                                                        "frames' own size",
                                                        loopCandidates_.size(), options_.minMatches)
                                          : std::string("every pair of frames"),
                                    loops.size(), options_.loopMatches, options_.loopsPerFrame)
                      : fmt::format("matching {} frames spread through the capture all against all", count)));
    }

    void triangulateWithPoses() {
        const fs::path given = work_ / "given", triangulated = work_ / "triangulated";
        writePosedModel(given, database_, capture_, workFrames_);
        fs::create_directories(triangulated);
        runStep("point_triangulator",
                fmt::format("--database_path {} --image_path {} --input_path {} --output_path {} "
                            "--Mapper.num_threads {} --Mapper.ba_refine_focal_length 0 "
                            "--Mapper.ba_refine_principal_point 0 --Mapper.ba_refine_extra_params 0",
                            shellQuoted(database_.string()), shellQuoted(images_.string()), shellQuoted(given.string()),
                            shellQuoted(triangulated.string()), kRepeatableThreads));
        CaptureOptions readOptions;
        readOptions.imageDirectory = images_.string();
        capture_.points = capture_detail::readColmap(triangulated, readOptions).points;
        run_.points = capture_.points.size();
        run_.registered = std::count_if(capture_.frames.begin(), capture_.frames.end(),
                                        [](const CaptureFrame& f) { return f.pose.has_value(); });
        note(fmt::format("COLMAP triangulated {} points with the capture's own poses and cameras", run_.points));
        if (run_.points == 0)
            throw Error(ErrorKind::Input,
                        fmt::format("colmap point_triangulator found no 3D point: {}; its output is in {}",
                                    diagnosis(database_, workFrames_, options_.minMatches), run_.logPath),
                        std::nullopt, kRetryHint);
    }

    // The mapper, with each of kMapperSettings in turn (video frames relaxed first, and any frames once a
    // mapping of them has fallen short: each setting's run stands alone, and the relaxed start is the one
    // likelier to hold most of frames that defeated the defaults) until a model holds most of the frames; the
    // largest model of all, joined with the models that share its frames, is kept when it holds at least half of
    // them. ScanNet's bathroom, 296 frames, in the second pass (the finer features): the defaults placed 206 in
    // 105 s, then the relaxed start 243 in 95 s, which alone would have done.
    // Each run writes its models (sparse/<round><settings>/0, 1...) and says what it made in the notes.
    // Measured intrinsics stay as given; approximate and guessed ones are refined (principal points stay).
    // `round` prefixes the folders (a second round of the mapper keeps the first one's models).
    MapperOutcome mapLargestModel(const std::string& round) {
        const bool fixed =
            capture_.intrinsicsOrigin == IntrinsicsOrigin::Measured &&
            std::all_of(groups_.begin(), groups_.end(), [](const CameraGroup& g) { return g.known.has_value(); });
        std::vector<const MapperSettings*> order;
        for (const auto& settings : kMapperSettings) order.push_back(&settings);
        if (capture_.layout == "video" || fellShort_) std::reverse(order.begin(), order.end());
        const std::size_t frames = workFrames_.size();
        std::optional<Capture> best;
        std::set<std::string> placed;  // by any model of any run
        for (const MapperSettings* settings : order) {
            const fs::path output = sparse_ / (round + settings->folder);
            if (!run_.reused) fs::create_directories(output);
            const bool finished = runStep(
                "mapper",
                fmt::format("--database_path {} --image_path {} --output_path {} --Mapper.num_threads {} "
                            "--Mapper.min_num_matches {} {} {}{}",
                            shellQuoted(database_.string()), shellQuoted(images_.string()),
                            shellQuoted(output.string()), kRepeatableThreads, options_.minMatches, kMapperAdjustment,
                            settings->arguments,
                            fixed ? " --Mapper.ba_refine_focal_length 0 --Mapper.ba_refine_extra_params 0" : ""),
                true);
            std::vector<ColmapModel> models = readModels(output);
            run_.models += models.size();
            std::size_t largest = 0;
            for (const ColmapModel& model : models) largest = std::max(largest, model.capture.frames.size());
            note(!models.empty()
                     ? fmt::format("COLMAP's mapper with {}: {} {}, the largest with {} of {} frames", settings->name,
                                   models.size(), models.size() == 1 ? "model" : "models", largest, frames)
                     : fmt::format("COLMAP's mapper with {}: no model{}", settings->name,
                                   finished ? "" : " (it stopped with a failure; see the log)"));
            for (const ColmapModel& model : models)
                for (const CaptureFrame& f : model.capture.frames) placed.insert(f.colorPath);
            std::optional<Capture> joined =
                joinModels(std::move(models), sparse_ / fmt::format("{}{}-joined", round, settings->folder));
            if (joined && (!best || joined->frames.size() > best->frames.size())) best = std::move(joined);
            if (best && mostPlaced(best->frames.size())) break;
        }
        if (best)
            for (const CaptureFrame& f : best->frames) placed.erase(f.colorPath);
        fellShort_ = fellShort_ || !best || !mostPlaced(best->frames.size());
        return {std::move(best), placed.size()};
    }

    // The largest model, when it holds at least half of the frames: else an error that says why.
    Capture accepted(MapperOutcome outcome) {
        std::optional<Capture>& best = outcome.largest;
        const std::size_t frames = workFrames_.size();
        if (!best)
            throw Error(ErrorKind::Input,
                        fmt::format("colmap mapper made no model: {}; its output is in {}",
                                    diagnosis(database_, workFrames_, options_.minMatches), run_.logPath),
                        std::nullopt, kRetryHint);
        if (2 * best->frames.size() < frames)
            throw Error(
                ErrorKind::Input,
                fmt::format("colmap mapper placed only {} of {} frames together (its largest model){}: {}; its output "
                            "is in {}",
                            best->frames.size(), frames,
                            outcome.placedApart == 0
                                ? std::string()
                                : fmt::format("; {} more are placed in other models that share too "
                                              "few frames with it to be joined",
                                              outcome.placedApart),
                            diagnosis(database_, workFrames_, options_.minMatches, true), run_.logPath),
                std::nullopt, kRetryHint);
        return std::move(*best);
    }

    // The models in `folder` (one sub-folder per model).
    std::vector<ColmapModel> readModels(const fs::path& folder) {
        std::vector<ColmapModel> models;
        std::error_code ec;
        for (const auto& entry : fs::directory_iterator(folder, ec))
            if (entry.is_directory())
                if (std::optional<Capture> model = readModel(entry.path()))
                    models.push_back({entry.path(), std::move(*model)});
        return models;
    }

    // The model in `folder`, when it holds one that reads.
    std::optional<Capture> readModel(const fs::path& folder) {
        if (!capture_detail::colmapModelFormat(folder)) return std::nullopt;
        CaptureOptions readOptions;
        readOptions.imageDirectory = images_.string();
        try {
            return capture_detail::readColmap(folder, readOptions);
        } catch (const Error& e) {
            note(fmt::format("COLMAP model {} skipped: {}", folder.string(), e.what()));
            return std::nullopt;
        }
    }

    // The largest model with those that share its frames (joinColmapModels), its joins noted.
    std::optional<Capture> joinModels(std::vector<ColmapModel> models, const fs::path& output) {
        std::vector<std::string> joins;
        std::optional<ColmapModel> joined = joinColmapModels(
            std::move(models), output,
            [&](const fs::path& model1, const fs::path& model2, const fs::path& merged) {
                if (!run_.reused) fs::create_directories(merged);
                runStep("model_merger",
                        fmt::format("--input_path1 {} --input_path2 {} --output_path {}", shellQuoted(model1.string()),
                                    shellQuoted(model2.string()), shellQuoted(merged.string())),
                        true);
            },
            [&](const fs::path& folder) { return readModel(folder); }, joins);
        if (!joined) return std::nullopt;
        if (!joins.empty())
            note(fmt::format("COLMAP's models joined where they share frames ({}): {} frames in one model",
                             fmt::join(joins, "; "), joined->capture.frames.size()));
        return std::move(joined->capture);
    }

    // The model's poses onto the capture's frames (poses are the same at any image size) and its
    // cameras back in each frame's own pixels.
    void adoptModel(const Capture& best) {
        std::map<std::string, const WorkFrame*> byName;
        for (const WorkFrame& w : workFrames_) byName[w.name] = &w;
        for (auto& frame : capture_.frames) frame.pose.reset();
        std::vector<std::pair<std::size_t, Intrinsics>> cameras;
        for (const auto& frame : best.frames) {
            auto it = byName.find(fs::path(frame.colorPath).lexically_relative(images_).generic_string());
            if (it == byName.end()) continue;
            const WorkFrame& w = *it->second;
            capture_.frames[w.frame].pose = frame.pose;
            Intrinsics k = capture_detail::scaleIntrinsics(frame.intrinsics ? *frame.intrinsics : best.intrinsics,
                                                           w.original.width, w.original.height);
            if (w.lens) k.distortion = w.lens->distortion;  // COLMAP saw the frame undistorted
            cameras.emplace_back(w.frame, k);
            ++run_.registered;
        }
        std::sort(cameras.begin(), cameras.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        for (auto& frame : capture_.frames) frame.intrinsics.reset();
        for (const auto& [index, k] : cameras) {
            if (index == cameras.front().first) capture_.intrinsics = k;
            if (!(k == capture_.intrinsics)) capture_.frames[index].intrinsics = k;
        }
        std::vector<std::string> described;
        for (const auto& [index, k] : cameras) {
            std::string text = fmt::format("{}x{}: fx {:.1f}, fy {:.1f}, cx {:.1f}, cy {:.1f}", k.width, k.height, k.fx,
                                           k.fy, k.cx, k.cy);
            if (k.distorted()) text += fmt::format(", distortion {:.3g}", fmt::join(k.distortion, " "));
            if (std::find(described.begin(), described.end(), text) == described.end()) described.push_back(text);
        }
        note(fmt::format("COLMAP's cameras in the frames' own pixels, {}: {}", originWords(capture_.intrinsicsOrigin),
                         fmt::join(described, "; ")));
        capture_.points = best.points;
        capture_.metric = false;
        run_.points = capture_.points.size();
        if (run_.registered < capture_.frames.size()) {
            // Every frame without a pose, those whose image could not be read for COLMAP too.
            std::vector<std::string> left;
            for (const CaptureFrame& frame : capture_.frames)
                if (!frame.pose) left.push_back(fs::path(frame.colorPath).filename().string());
            note(fmt::format("COLMAP registered {} of {} frames; left out: {}", run_.registered, capture_.frames.size(),
                             model::listFirst(left, 12)));
        }
    }

    // A successful run says where its time went and records its inputs; its work folder goes unless
    // asked to stay. A failed one stays for its log.
    void leaveWorkFolder() {
        if (run_.reused) return;
        noteSteps();
        std::ofstream(record_) << inputs_;
        std::error_code removeError;
        if (options_.keepWorkDirectory || !options_.workDirectory.empty())
            note(fmt::format("COLMAP work folder (images, database, models, log): {}", run_.workDirectory));
        else
            fs::remove_all(work_, removeError);
    }

    Capture& capture_;
    const ColmapOptions& options_;
    const std::string colmap_;
    const fs::path work_, images_, database_, sparse_, record_;
    const std::string threads_;
    ColmapRun run_;
    std::vector<WorkFrame> workFrames_;
    std::vector<CameraGroup> groups_;
    std::size_t scaled_ = 0;
    std::string inputs_;
    bool ordered_ = false, exhaustive_ = false, loops_ = false;
    bool fine_ = true;        // SIFT from the frames doubled (COLMAP's first_octave -1), else at their own size
    bool fellShort_ = false;  // a mapping of these frames left more than a fifth of them out
    // The pairs of frames found overlapping with the features at their own size, matched again with the finer ones.
    std::vector<std::pair<std::string, std::string>> loopCandidates_;
    bool farther_ = false;  // sequential matching reaches frames farther on (quadratic overlap)
    ColmapWatch watch_;
    bool stopped_ = false;  // the run stopped by watch_.stop
};

}  // namespace

std::optional<ColmapModel> joinColmapModels(std::vector<ColmapModel> models, const fs::path& output,
                                            const ColmapMerger& merge, const ColmapModelReader& read,
                                            std::vector<std::string>& joins) {
    constexpr std::size_t kMinSharedFrames = 3;
    if (models.empty()) return std::nullopt;
    std::stable_sort(models.begin(), models.end(), [](const ColmapModel& a, const ColmapModel& b) {
        return a.capture.frames.size() > b.capture.frames.size();
    });
    ColmapModel joined = std::move(models.front());
    models.erase(models.begin());
    std::map<fs::path, std::size_t> refused;  // the frames shared when COLMAP would not join them
    int attempts = 0;
    for (bool grew = true; grew && !models.empty();) {
        grew = false;
        std::set<std::string> held;
        for (const CaptureFrame& f : joined.capture.frames) held.insert(f.colorPath);
        for (auto other = models.begin(); other != models.end(); ++other) {
            const std::size_t shared = std::count_if(other->capture.frames.begin(), other->capture.frames.end(),
                                                     [&](const CaptureFrame& f) { return held.count(f.colorPath); });
            if (shared < kMinSharedFrames || refused[other->folder] >= shared) continue;
            const fs::path merged = output / std::to_string(++attempts);
            merge(joined.folder, other->folder, merged);
            std::optional<Capture> result = read(merged);
            if (!result || result->frames.size() <= joined.capture.frames.size()) {
                refused[other->folder] = shared;  // tried again only once it shares more
                continue;
            }
            joins.push_back(fmt::format("{} and {} frames sharing {}", joined.capture.frames.size(),
                                        other->capture.frames.size(), shared));
            joined = {merged, std::move(*result)};
            models.erase(other);
            grew = true;
            break;
        }
    }
    return joined;
}

ColmapRun runColmap(Capture& capture, const ColmapOptions& options, ColmapWatch watch) {
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
    return ColmapSession(capture, options, *colmap, std::move(watch)).run();
}

}  // namespace smql::ingest
