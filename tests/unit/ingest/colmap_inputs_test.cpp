// How COLMAP is driven (ingest/geometry/colmap_runner.cpp): one camera per
// image size, frames scaled down before extraction with the intrinsics mapped
// back to the frames' pixels, and failures that say how many photos overlap.
// Photo sets are cut from `smql synth` frames (neighbouring frames overlap).
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <Eigen/Geometry>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "ingest/capture/capture.hpp"
#include "ingest/capture/capture_detail.hpp"
#include "ingest/geometry/colmap_database.hpp"
#include "ingest/geometry/colmap_runner.hpp"
#include "ingest/synth/synth.hpp"
#include "model/error.hpp"
#include "scoped_env.hpp"
#include "scratch_dir.hpp"

using namespace smql;
using namespace smql::ingest;
using smql::ingest::test::KeptWork;
using smql::ingest::test::ScratchDir;
namespace fs = std::filesystem;

namespace {

// A synthetic walk of 30 frames; neighbouring frames overlap well.
std::string writeWalk(const ScratchDir& dir) {
    std::string path = (dir.path / "walk").string();
    synth::writeSynth(path, {.seed = 3, .frames = 30, .objects = 24});
    return path;
}

// Frame `number` (1-based) of the walk, resized to `size` when given, as photos/<name>.
void copyFrame(const std::string& walk, int number, const fs::path& photos, const std::string& name,
               cv::Size size = {}) {
    cv::Mat image = cv::imread(fmt::format("{}/color/{}.png", walk, number), cv::IMREAD_COLOR);
    REQUIRE(!image.empty());
    if (!size.empty()) cv::resize(image, image, size, 0, 0, cv::INTER_CUBIC);
    fs::create_directories(photos);
    REQUIRE(cv::imwrite((photos / name).string(), image));
}

// The walk's first `count` frames as photos/p1.png, p2.png ... under `dir`.
fs::path walkPhotos(const ScratchDir& dir, const std::string& walk, int count) {
    fs::path photos = dir.path / "photos";
    for (int i = 1; i <= count; ++i) copyFrame(walk, i, photos, fmt::format("p{}.png", i));
    return photos;
}

}  // namespace

TEST_CASE("a photo set of mixed sizes gets one COLMAP camera per size", "[colmap]") {
    ScratchDir dir;
    std::string walk = writeWalk(dir);
    fs::path photos = dir.path / "photos";
    for (int i = 1; i <= 8; ++i)
        copyFrame(walk, i, photos, fmt::format("p{}.png", i), i % 2 == 0 ? cv::Size(480, 360) : cv::Size());
    Capture capture = readCapture(photos.string());
    REQUIRE(capture.intrinsicsOrigin == IntrinsicsOrigin::Guessed);

    ColmapOptions options;
    options.keepWorkDirectory = true;
    ColmapRun run = runColmap(capture, options);
    KeptWork kept{run.workDirectory};

    CHECK(run.cameras == 2);
    CHECK(run.matcher == "exhaustive_matcher");  // a small unordered set
    ColmapDatabaseSummary db = readColmapDatabase(run.workDirectory + "/database.db");
    REQUIRE(db.cameras.size() == 2);
    CHECK(db.cameras[0].width == 640);
    CHECK(db.cameras[0].height == 480);
    CHECK(db.cameras[1].width == 480);
    CHECK(db.cameras[1].height == 360);
    CHECK(db.cameras[0].model == "SIMPLE_RADIAL");  // unknown camera: COLMAP estimates it
    CHECK(db.images == 8);

    // Registered frames carry COLMAP's camera in their own pixels.
    CHECK(run.registered >= 6);
    for (const CaptureFrame& frame : capture.frames) {
        if (!frame.pose) continue;
        const Intrinsics& k = frame.intrinsics ? *frame.intrinsics : capture.intrinsics;
        CHECK(k.width == cv::imread(frame.colorPath).cols);
    }
}

TEST_CASE("photos that do not overlap fail at the mapper, saying how many overlap", "[colmap]") {
    ScratchDir dir;
    std::string walk = writeWalk(dir);
    fs::path photos = dir.path / "photos";
    copyFrame(walk, 1, photos, "p1.png");
    copyFrame(walk, 2, photos, "p2.png");
    // Six unrelated photos: smooth random blotches, each of its own seed.
    for (int i = 3; i <= 8; ++i) {
        cv::Mat noise(480, 640, CV_8UC3);
        cv::RNG rng(static_cast<std::uint64_t>(1000 + i));
        rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
        cv::GaussianBlur(noise, noise, cv::Size(0, 0), 4);
        REQUIRE(cv::imwrite((photos / fmt::format("p{}.png", i)).string(), noise));
    }
    Capture capture = readCapture(photos.string());
    try {
        runColmap(capture);
        FAIL("expected COLMAP to fail");
    } catch (const Error& e) {
        INFO(e.message());
        CHECK(e.kind() == ErrorKind::Input);
        const std::string& message = e.message();
        CHECK(message.find("colmap mapper") != std::string::npos);
        CHECK(message.find("only 2 of 8 photos overlap enough") != std::string::npos);
        CHECK_THAT(message, Catch::Contains("; p3.png, p4.png, p5.png, p6.png, p7.png and 1 more overlap with none"));
        CHECK(message.find("take more views with overlap") != std::string::npos);
        CHECK(message.find("colmap.log") != std::string::npos);
        // The failed run's folder stays for its log; it goes with the test.
        std::size_t at = message.find("/tmp/smql-colmap-");
        if (at != std::string::npos) {
            std::error_code ignored;
            fs::remove_all(message.substr(at, std::string("/tmp/smql-colmap-XXXXXX").size()), ignored);
        }
    }
}

TEST_CASE("1920-pixel frames reach COLMAP at 1024 and come back in their own pixels", "[colmap]") {
    ScratchDir dir;
    std::string walk = writeWalk(dir);
    fs::path photos = dir.path / "photos";
    for (int i = 1; i <= 6; ++i) copyFrame(walk, i, photos, fmt::format("p{}.png", i), cv::Size(1920, 1440));
    // The synthetic camera (fx = fy = 525 at 640 x 480) at three times the size.
    std::ofstream(photos / "camera.json")
        << R"({"width": 1920, "height": 1440, "fx": 1575, "fy": 1575, "cx": 959.5, "cy": 719.5})";
    Capture capture = readCapture(photos.string());
    REQUIRE(capture.intrinsicsOrigin == IntrinsicsOrigin::Measured);

    ColmapOptions options;
    options.keepWorkDirectory = true;
    ColmapRun run = runColmap(capture, options);
    KeptWork kept{run.workDirectory};

    // COLMAP saw 1024 x 768 frames with the camera scaled to them.
    ColmapDatabaseSummary db = readColmapDatabase(run.workDirectory + "/database.db");
    REQUIRE(db.cameras.size() == 1);
    CHECK(db.cameras[0].model == "PINHOLE");
    CHECK(db.cameras[0].width == 1024);
    CHECK(db.cameras[0].height == 768);
    CHECK(db.cameras[0].params[0] == Approx(1575.0 * 1024 / 1920));
    CHECK(db.cameras[0].params[2] == Approx(512));  // COLMAP's pixel centres at +0.5: the image centre
    cv::Mat seen = cv::imread(run.workDirectory + "/images/1920x1440/frame000000.png");
    CHECK(seen.cols == 1024);
    CHECK(seen.rows == 768);

    // The frames keep their files; the camera comes back at 1920 x 1440, kept fixed as given.
    CHECK(run.registered >= 5);
    CHECK(capture.frames[0].colorPath == (photos / "p1.png").string());
    CHECK(capture.intrinsics.width == 1920);
    CHECK(capture.intrinsics.height == 1440);
    CHECK(capture.intrinsics.fx == Approx(1575).epsilon(1e-9));
    CHECK(capture.intrinsics.fy == Approx(1575).epsilon(1e-9));
    CHECK(capture.intrinsics.cx == Approx(959.5).epsilon(1e-9));
    CHECK(capture.intrinsics.cy == Approx(719.5).epsilon(1e-9));
}

TEST_CASE("a work folder of one's own keeps COLMAP's run for the same frames to read back", "[colmap]") {
    ScratchDir dir;
    std::string walk = writeWalk(dir);
    fs::path photos = walkPhotos(dir, walk, 6);
    ColmapOptions options;
    options.workDirectory = (dir.path / "work").string();

    Capture first = readCapture(photos.string());
    ColmapRun ran = runColmap(first, options);
    CHECK(!ran.reused);
    CHECK(!ran.steps.empty());
    REQUIRE(fs::exists(dir.path / "work" / "smql-run.txt"));
    REQUIRE(ran.registered >= 5);

    // The same frames again: no step runs, and the poses and points are the run's.
    Capture second = readCapture(photos.string());
    ColmapRun read = runColmap(second, options);
    CHECK(read.reused);
    CHECK(read.steps.empty());
    CHECK(read.registered == ran.registered);
    CHECK(second.points.size() == first.points.size());
    for (std::size_t i = 0; i < first.frames.size(); ++i) {
        REQUIRE(second.frames[i].pose.has_value() == first.frames[i].pose.has_value());
        if (first.frames[i].pose) CHECK(second.frames[i].pose->translation.x == first.frames[i].pose->translation.x);
    }

    // A photo written again is another input: COLMAP runs again (here `false`, which fails at once).
    copyFrame(walk, 7, photos, "p3.png");
    options.command = "false";
    Capture changed = readCapture(photos.string());
    CHECK_THROWS_WITH(runColmap(changed, options), Catch::Contains("colmap feature_extractor failed"));

    // A folder of other files is refused, not emptied.
    fs::create_directories(dir.path / "mine");
    std::ofstream(dir.path / "mine" / "notes.txt") << "keep me";
    options.workDirectory = (dir.path / "mine").string();
    CHECK_THROWS_WITH(runColmap(changed, options), Catch::Contains("holds files of no COLMAP run"));
    CHECK(fs::exists(dir.path / "mine" / "notes.txt"));
}

namespace {

// One COLMAP command on model folders, as the runner runs it; true when it exits with 0.
bool colmapCommand(const std::string& step, const std::string& arguments) {
    return std::system(
               fmt::format("QT_QPA_PLATFORM=offscreen colmap {} {} > /dev/null 2>&1", step, arguments).c_str()) == 0;
}

// The model in `folder` with its images in `images`, if it reads.
std::optional<Capture> readModelIn(const fs::path& folder, const fs::path& images) {
    if (!capture_detail::colmapModelFormat(folder)) return std::nullopt;
    CaptureOptions options;
    options.imageDirectory = images.string();
    return capture_detail::readColmap(folder, options);
}

// The camera centres of `model`, by image path.
std::map<std::string, Eigen::Vector3d> centresOf(const Capture& model) {
    std::map<std::string, Eigen::Vector3d> centres;
    for (const CaptureFrame& f : model.frames)
        centres[f.colorPath] = {f.pose->translation.x, f.pose->translation.y, f.pose->translation.z};
    return centres;
}

}  // namespace

// A model cut in two that overlap in three frames, the second moved, turned and scaled: COLMAP's
// model_merger, driven by joinColmapModels, puts it back together, every camera where it was (up to
// one similarity); a model sharing two frames is not taken in.
TEST_CASE("two COLMAP models that share frames are joined into one", "[colmap]") {
    ScratchDir dir;
    fs::path photos = walkPhotos(dir, writeWalk(dir), 8);
    ColmapOptions options;
    options.workDirectory = (dir.path / "work").string();
    Capture capture = readCapture(photos.string());
    REQUIRE(runColmap(capture, options).registered >= 7);

    // The mapper's largest model, and the names of its frames in capture order.
    const fs::path images = dir.path / "work" / "images";
    std::optional<ColmapModel> whole;
    for (const auto& settings : fs::directory_iterator(dir.path / "work" / "sparse"))
        for (const auto& folder : fs::directory_iterator(settings.path()))
            if (std::optional<Capture> model = readModelIn(folder.path(), images))
                if (!whole || model->frames.size() > whole->capture.frames.size()) whole = {folder.path(), *model};
    REQUIRE(whole);
    std::vector<std::string> names;
    for (const CaptureFrame& f : whole->capture.frames)
        names.push_back(fs::path(f.colorPath).lexically_relative(images).string());
    const std::size_t n = names.size();
    REQUIRE(n >= 7);

    // Without `keep` of the frames (by position), the model written to `name`.
    auto cut = [&](const std::string& name, std::size_t from, std::size_t to) {
        fs::path list = dir.path / (name + ".txt"), output = dir.path / name;
        std::ofstream out(list);
        for (std::size_t i = 0; i < n; ++i)
            if (i < from || i >= to) out << names[i] << "\n";
        out.close();
        fs::create_directories(output);
        REQUIRE(colmapCommand("image_deleter", fmt::format("--input_path {} --output_path {} --image_names_path {}",
                                                           whole->folder.string(), output.string(), list.string())));
        return output;
    };
    const fs::path first = cut("first", 0, n - 2), second = cut("second", n - 5, n), pair = cut("pair", 0, 2);
    // The second in a frame of reference of its own: 2.5 times as large, turned 40 degrees, moved.
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    std::ofstream transform(dir.path / "transform.txt");
    for (int r = 0; r < 3; ++r)
        transform << 2.5 * turn(r, 0) << " " << 2.5 * turn(r, 1) << " " << 2.5 * turn(r, 2) << " "
                  << Eigen::Vector3d(3, -1, 2)(r) << "\n";
    transform << "0 0 0 1\n";
    transform.close();
    const fs::path moved = dir.path / "moved";
    fs::create_directories(moved);
    REQUIRE(colmapCommand("model_transformer",
                          fmt::format("--input_path {} --output_path {} --transform_path {}", second.string(),
                                      moved.string(), (dir.path / "transform.txt").string())));

    std::vector<ColmapModel> models;
    for (const fs::path& folder : {first, moved, pair}) models.push_back({folder, *readModelIn(folder, images)});
    CHECK(models[1].capture.frames.size() == 5);
    std::vector<std::string> joins;
    std::optional<ColmapModel> joined = joinColmapModels(
        models, dir.path / "joined",
        [&](const fs::path& model1, const fs::path& model2, const fs::path& output) {
            fs::create_directories(output);
            colmapCommand("model_merger", fmt::format("--input_path1 {} --input_path2 {} --output_path {}",
                                                      model1.string(), model2.string(), output.string()));
        },
        [&](const fs::path& folder) { return readModelIn(folder, images); }, joins);
    REQUIRE(joined);
    INFO(fmt::format("joins: {}", fmt::join(joins, "; ")));
    REQUIRE(joins.size() == 1);
    CHECK(joins[0] == fmt::format("{} and 5 frames sharing 3", n - 2));
    REQUIRE(joined->capture.frames.size() == n);

    // Every camera where the whole model has it, up to one similarity.
    std::map<std::string, Eigen::Vector3d> truth = centresOf(whole->capture), found = centresOf(joined->capture);
    Eigen::Matrix3Xd from(3, n), to(3, n);
    std::size_t column = 0;
    for (const auto& [name, centre] : truth) {
        REQUIRE(found.count(name));
        from.col(column) = found[name];
        to.col(column++) = centre;
    }
    const Eigen::Matrix4d similarity = Eigen::umeyama(from, to, true);
    double spread = 0, worst = 0;
    for (std::size_t i = 0; i < n; ++i) {
        spread = std::max(spread, (to.col(i) - to.col(0)).norm());
        const Eigen::Vector3d mapped = (similarity * from.col(i).homogeneous()).head<3>();
        worst = std::max(worst, (mapped - to.col(i)).norm());
    }
    INFO(fmt::format("cameras spread {:.3f}, worst {:.4f} after the similarity", spread, worst));
    CHECK(worst < 0.01 * spread);
}

// Three places, five neighbouring photos of each: a walk through a generated room, the real dining
// room of ../shared/data/rgbd-dining and TUM's real office (../shared/data/captures), and a plain grey photo
// between the office's and the walk's. COLMAP places each five in a model of its own, which share no frame, so no
// model holds half of the 16; the refusal says that the rest are placed apart, in models that could not be joined,
// and where, in the order taken, the photos part, by their names: at the first of each place, and at the plain
// photo, which gave no features.
TEST_CASE("frames placed in models that share no frame are refused, saying where the rest are and where they part",
          "[colmap]") {
    const fs::path office = fs::path(SMQL_SHARED_DATA) / "captures" / "tum-fr3-office-photos";
    if (!fs::is_directory(office)) {
        WARN("skipped: " << office.string() << " is absent");
        return;
    }
    ScratchDir dir;
    fs::path photos = dir.path / "photos";
    const std::string walk = writeWalk(dir);
    for (int i = 1; i <= 5; ++i) copyFrame(walk, i, photos, fmt::format("walk-{}.png", i));
    for (int i = 1; i <= 5; ++i)
        fs::copy_file(fs::path(SMQL_SHARED_DATA) / "rgbd-dining" / "color" / fmt::format("{}.png", i),
                      photos / fmt::format("dining-{}.png", i));
    std::vector<fs::path> shots;
    for (const auto& entry : fs::directory_iterator(office))
        if (entry.path().extension() == ".png") shots.push_back(entry.path());
    std::sort(shots.begin(), shots.end());
    REQUIRE(shots.size() >= 5);
    for (int i = 0; i < 5; ++i) fs::copy_file(shots[i], photos / fmt::format("office-{}.png", i + 1));
    REQUIRE(cv::imwrite((photos / "plain.png").string(), cv::Mat(480, 640, CV_8UC3, cv::Scalar(128, 128, 128))));
    Capture capture = readCapture(photos.string());
    KeptWork work;
    try {
        runColmap(capture);
        FAIL("expected COLMAP's largest model to hold under half of the frames");
    } catch (const Error& e) {
        const std::string& message = e.message();
        INFO(message);
        if (std::size_t at = message.find("/tmp/smql-colmap-"); at != std::string::npos)
            work.path = message.substr(at, std::string("/tmp/smql-colmap-XXXXXX").size());
        CHECK(e.kind() == ErrorKind::Input);
        CHECK_THAT(message, Catch::Matches(".*placed only [1-7] of 16 frames together \\(its largest model\\); "
                                           "[0-9]+ more are placed in other models that share too few "
                                           "frames with it to be joined: .*"));
        CHECK_THAT(message, Catch::Contains("they fall apart into separate groups: the largest holds only 5 of 16 "
                                            "photos"));
        CHECK_THAT(message, Catch::Contains("; in the order taken they part 3 times, at office-1.png, plain.png, "
                                            "walk-1.png, each sharing too few matches with the photo before it; "
                                            "plain.png gave no features"));
    }
}

namespace {

// An executable shell script standing in for COLMAP.
std::string fakeColmap(const ScratchDir& dir, const std::string& name, const std::string& body) {
    const fs::path script = dir.path / name;
    std::ofstream(script) << "#!/bin/sh\n" << body << "\n";
    fs::permissions(script, fs::perms::owner_all);
    return script.string();
}

// The error a run of `dir`'s photos that fails throws, if it throws one; the work folder it keeps for its log
// (named at the message's end) goes at the end of the test.
std::optional<Error> failureOf(const ScratchDir& dir, const ColmapOptions& options, KeptWork& kept) {
    Capture capture = readCapture(dir.path.string());
    try {
        runColmap(capture, options);
    } catch (const Error& e) {
        kept.path = fs::path(e.message().substr(e.message().rfind(' ') + 1)).parent_path().string();
        return e;
    }
    return std::nullopt;
}

}  // namespace

TEST_CASE("a COLMAP command stops when the ingest is stopped; one stopped from outside is not blamed on the photos",
          "[colmap]") {
    ScratchDir dir;
    const fs::path office = fs::path(SMQL_SHARED_DATA) / "captures" / "tum-fr3-office-photos";
    for (const char* name : {"1341847980.722988.png", "1341847981.726650.png", "1341847982.730674.png"})
        fs::copy_file(office / name, dir.path / name);
    ColmapOptions options;
    SECTION("stopped by the ingest (the user's Ctrl-C): the command ends, its work folder goes") {
        // A COLMAP that would take 30 s; the stop comes after 0.3 s.
        options.command = fakeColmap(dir, "slow-colmap", "exec sleep 29.75");
        fs::create_directories(dir.path / "tmp");
        const smql::testing::ScopedEnv tmp("TMPDIR", (dir.path / "tmp").string());  // the run's own work folder
        Capture capture = readCapture(dir.path.string());
        const auto start = std::chrono::steady_clock::now();
        auto stop = [&] {
            if (std::chrono::steady_clock::now() - start > std::chrono::milliseconds(300))
                throw Error(ErrorKind::Usage, "cancelled; nothing was written");
        };
        CHECK_THROWS_WITH(runColmap(capture, options, {.stop = stop}), Catch::Contains("cancelled"));
        CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(20));
        CHECK(std::system("pgrep -f '^sleep 29.75$' > /dev/null") != 0);
        CHECK(fs::is_empty(dir.path / "tmp"));
    }
    SECTION("killed from outside (as the kernel kills a process when memory runs out)") {
        options.command = fakeColmap(dir, "killed-colmap", "kill -9 $$");
        KeptWork kept;
        const auto failure = failureOf(dir, options, kept);
        REQUIRE(failure);
        CHECK_THAT(failure->message(),
                   Catch::Contains("colmap feature_extractor was stopped by signal 9 (Killed), not by what it read"));
        CHECK_THAT(failure->hint(), Catch::Contains("memory runs out"));
    }
    SECTION("a terminal's Ctrl-C, which reaches COLMAP too: the user's stop where the ingest heard it") {
        options.command = fakeColmap(dir, "interrupted-colmap", "kill -INT $$");
        fs::create_directories(dir.path / "tmp");
        const smql::testing::ScopedEnv tmp("TMPDIR", (dir.path / "tmp").string());  // the run's own work folder
        Capture capture = readCapture(dir.path.string());
        auto heard = [] { throw Error(ErrorKind::Usage, "cancelled; nothing was written"); };
        CHECK_THROWS_WITH(runColmap(capture, options, {.stop = heard}), Catch::Contains("cancelled"));
        CHECK(fs::is_empty(dir.path / "tmp"));
        // An embedding program that does not stop the ingest is told what stopped COLMAP.
        KeptWork kept;
        const auto failure = failureOf(dir, options, kept);
        REQUIRE(failure);
        CHECK_THAT(failure->message(), Catch::Contains("was stopped by signal 2 (Interrupt), not by what it read"));
        // Memory is named only for the kernel's signal 9: a Ctrl-C is nobody's lack of memory.
        CHECK_THAT(failure->hint(), !Catch::Contains("memory") && Catch::Contains("run the ingest again"));
    }
    SECTION("the stage's bar follows the lines the command logs") {
        // As the extractor, a matcher and the mapper write them; then a failure, which ends the run.
        options.command = fakeColmap(dir, "logging-colmap",
                                     "echo 'Processed file [1/3]'; sleep 0.3; echo 'Matching image [2/3]'; sleep 0.3; "
                                     "echo 'Registering image #31 (3)'; sleep 0.3; exit 1");
        fs::create_directories(dir.path / "tmp");
        const smql::testing::ScopedEnv tmp("TMPDIR", (dir.path / "tmp").string());  // the failed run's folder
        Capture capture = readCapture(dir.path.string());
        std::vector<std::size_t> frames;
        CHECK_THROWS_WITH(runColmap(capture, options, {.progress = [&](std::size_t done) { frames.push_back(done); }}),
                          Catch::Contains("colmap feature_extractor failed (exit status 1)"));
        REQUIRE(!frames.empty());
        CHECK(frames.back() == 3);
        CHECK(std::adjacent_find(frames.begin(), frames.end(), std::greater_equal<>()) == frames.end());
    }
    SECTION("a crash of its own (an abort) is COLMAP's failure, as before") {
        options.command = fakeColmap(dir, "aborting-colmap", "kill -6 $$");
        KeptWork kept;
        const auto failure = failureOf(dir, options, kept);
        REQUIRE(failure);
        CHECK_THAT(failure->message(), Catch::Contains("colmap feature_extractor failed (exit status 134)"));
    }
}
