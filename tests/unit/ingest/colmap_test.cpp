// --geometry colmap: an RGB-only synthetic capture through Debian's `colmap`
// (CPU), its objects from masks and from detections without depth, checked
// against the truth after registering the COLMAP cameras to the true cameras
// with a similarity (Umeyama); and the error when colmap is missing.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>

#include <fmt/format.h>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "ingest/capture/capture.hpp"
#include "ingest/capture/frame_loader.hpp"
#include "ingest/geometry/colmap_runner.hpp"
#include "ingest/geometry/robust.hpp"
#include "ingest/pipeline/pipeline.hpp"
#include "ingest/pipeline/progress.hpp"
#include "ingest/pipeline/quality.hpp"
#include "ingest/synth/synth.hpp"
#include "model/error.hpp"
#include "scoped_env.hpp"
#include "scratch_dir.hpp"

using namespace smql;
using namespace smql::ingest;
using smql::ingest::test::ScratchDir;

namespace {

// One object source's ingest of the reconstructed capture, registered to the truth.
struct Measured {
    double scale = 0, residual = 0;
    QualityReport report;
};

Measured ingestRegistered(const Capture& reconstructed, const Capture& truth, const synth::SynthResult& synth,
                          const std::string& objects) {
    SilentProgress silent;
    IngestOptions options;
    options.sceneName = "synth-3-colmap";
    options.objects = objects;
    auto result = ingestCapture(reconstructed, options, silent);
    // The aligned frame -> the truth frame: a similarity from the camera centres.
    std::vector<std::pair<model::Vec3, model::Vec3>> cameras;
    for (const auto& [frame, centre] : result.cameraCentres)
        cameras.push_back({centre, truth.frames[frame].pose->translation});
    auto registration = registerByCameras(result.scene, cameras);
    QualityOptions quality;
    for (const auto& [id, frames] : synth.framesSeen)
        if (frames > 0) quality.visible.insert(id);
    return {registration.scale, registration.residual, compareToTruth(registration.mapped, synth.scene.truth, quality)};
}

// The run's notes, a line each.
std::string notesOf(const ColmapRun& run) {
    std::string notes;
    for (const auto& n : run.notes) notes += n + "\n";
    return notes;
}

// Whether exactly the frames whose photos' paths hold `place` got a pose.
void checkOnlyPlaced(const Capture& capture, const std::string& place) {
    for (const auto& frame : capture.frames)
        CHECK(frame.pose.has_value() == (frame.colorPath.find(place) != std::string::npos));
}

// Real photos of two places, their names interleaved (TUM's office photos, then a photo of the dining room,
// in turn): the next photo of each place is two names on.
Capture interleavedPlaces(const ScratchDir& dir) {
    const std::filesystem::path shared(SMQL_SHARED_DATA);
    auto firstPhotos = [](const std::filesystem::path& folder, std::size_t count) {
        std::vector<std::filesystem::path> all;
        for (const auto& entry : std::filesystem::directory_iterator(folder))
            if (entry.path().extension() == ".png") all.push_back(entry.path());
        std::sort(all.begin(), all.end());
        all.resize(std::min(all.size(), count));
        return all;
    };
    const auto office = firstPhotos(shared / "captures/tum-fr3-office-photos", 6);
    const auto dining = firstPhotos(shared / "rgbd-dining/color", 5);
    REQUIRE(office.size() == 6);
    REQUIRE(dining.size() == 5);
    const auto photos = dir.path / "photos";
    std::filesystem::create_directories(photos);
    for (std::size_t i = 0; i < office.size(); ++i) {
        std::filesystem::copy_file(office[i], photos / fmt::format("{:02d}-office.png", 2 * i));
        if (i < dining.size())
            std::filesystem::copy_file(dining[i], photos / fmt::format("{:02d}-dining.png", 2 * i + 1));
    }
    Capture capture = readCapture(photos.string());
    REQUIRE(capture.frames.size() == 11);
    return capture;
}

}  // namespace

// COLMAP runs once; its poses and sparse points then place the masks, the detections with their
// outlines, and the detections as boxes only (what a detector gives), each without depth.
TEST_CASE("an RGB-only synthetic capture through COLMAP meets the quality thresholds after a similarity") {
    ScratchDir dir;
    auto capturePath = (dir.path / "capture").string();
    // SMQL_COLMAP_SEED measures another room, without the thresholds, which hold for seed 3 alone today
    // (docs/ingest.md, "Detections without depth").
    const char* seedVariable = std::getenv("SMQL_COLMAP_SEED");
    const std::uint64_t seed = seedVariable ? std::strtoull(seedVariable, nullptr, 10) : 3;
    auto synth = synth::writeSynth(capturePath, {.seed = seed, .frames = 30, .objects = 24});
    Capture truth = readCapture(capturePath);
    Capture rgb = truth;
    for (auto& f : rgb.frames) {
        f.depthPath.clear();
        f.pose.reset();
    }
    auto start = std::chrono::steady_clock::now();
    ColmapRun run = runColmap(rgb);
    double colmapSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    REQUIRE(run.registered >= 0.7 * rgb.frames.size());

    auto report = [&](const char* source, const Measured& m) {
        const auto& r = m.report;
        std::cout << fmt::format(
            "COLMAP synth seed {}, 30 frames RGB only, {}: {} frames registered, colmap {:.1f} s; similarity scale "
            "{:.3f} (scale error {:.1f}%), camera residual {:.3f} m; objects F1 {:.2f} (P {:.2f} R {:.2f}), "
            "anchors F1 {:.2f}, centre error {:.2f} m\n",
            seed, source, run.registered, colmapSeconds, m.scale, 100 * std::abs(m.scale - 1), m.residual,
            r.objects.f1(), r.objects.precision(), r.objects.recall(), r.anchors.f1(), r.meanCenterError);
    };
    auto masks = ingestRegistered(rgb, truth, synth, "masks");
    report("masks", masks);
    auto polygons = ingestRegistered(rgb, truth, synth, "detections");
    report("detections with outlines", polygons);
    auto file = std::filesystem::path(capturePath) / "detections.json";
    nlohmann::json j = nlohmann::json::parse(std::ifstream(file));
    for (auto& d : j["detections"]) d.erase("segmentation");
    std::ofstream(file) << j.dump();
    auto boxes = ingestRegistered(rgb, truth, synth, "detections");
    report("detection boxes", boxes);
    if (seedVariable) return;

    // COLMAP is not bit-for-bit repeatable, so the floors sit below the runs measured (docs/ingest.md,
    // "Detections without depth"): masks F1 0.81-0.92 until 2026-11-30, 0.70 and 0.81 in two runs of
    // 2026-12-01 (unexplained yet: the same build's kept COLMAP walks score as before), outlined detections
    // 0.73-0.77 (0.82-0.88 when a hull was still cut to its kind's largest footprint: typical sizes no
    // longer set boxes) at 1-2 % scale error, boxes 0.65-0.77.
    CHECK(std::abs(masks.scale - 1) <= 0.10);
    CHECK(masks.report.objects.f1() >= 0.65);
    CHECK(std::abs(polygons.scale - 1) <= 0.05);
    CHECK(polygons.report.objects.f1() >= 0.68);
    CHECK(boxes.report.objects.f1() >= 0.6);
}

// 20 frames of a generated walk are a wide step apart: features at the frames' own size place 11 of
// them, the finer ones of the frames doubled all 20 (with the relaxed start).
TEST_CASE(
    "a long capture's features found at the frames' own size, and the finer ones when too few frames are "
    "placed") {
    ScratchDir dir;
    auto capturePath = (dir.path / "capture").string();
    synth::writeSynth(capturePath, {.seed = 3, .frames = 20, .objects = 24});
    Capture capture = readCapture(capturePath);
    for (auto& f : capture.frames) {
        f.depthPath.clear();
        f.pose.reset();
    }
    ColmapOptions options;
    options.fineFeaturesUpTo = 10;
    ColmapRun run = runColmap(capture, options);
    const std::string notes = notesOf(run);
    INFO(notes);
    CHECK_THAT(notes, Catch::Contains("COLMAP looks for features at the frames' own size"));
    CHECK_THAT(notes, Catch::Contains("frames with features at their own size; it runs again with the finer features"));
    // Each pass's features matched by smql, before COLMAP's matcher (20 frames: all against all) verifies them.
    const auto matchedHere = std::count_if(run.steps.begin(), run.steps.end(),
                                           [](const auto& step) { return step.first == "feature matching (smql)"; });
    CHECK(matchedHere == 2);
    CHECK(run.registered >= 0.9 * capture.frames.size());
}

// Matched with the photo after each alone (COLMAP's overlap 2), no two photos of one place are matched and no
// model starts; matched again with the photos two on (its quadratic overlap), the office's six make a model, and
// the capture is placed by it. The second mapping starts with the relaxed start, since the defaults fell short.
TEST_CASE("frames the pairs with the frames after them leave out are matched farther on, and mapped again") {
    ScratchDir dir;
    Capture capture = interleavedPlaces(dir);
    ColmapOptions options;
    options.exhaustiveUpTo = 0;  // name order, as a folder of more photos is matched
    options.sequentialOverlap = 2;
    options.everyPairUpTo = 0;  // loops closed by the frames spread through the capture: none here
    options.loopFrames = 0;
    const ColmapRun run = runColmap(capture, options);
    const std::string notes = notesOf(run);
    INFO(notes);
    CHECK_THAT(notes, Catch::Contains("with each frame matched with the 1 after it; it matches each frame again with "
                                      "the frames 2 on (COLMAP's quadratic overlap) and maps again"));
    const auto again = notes.find("maps again");
    const auto nextMapping = notes.find("COLMAP's mapper with ", again);
    REQUIRE(nextMapping != std::string::npos);
    const std::string relaxed = "COLMAP's mapper with a relaxed start";
    CHECK(notes.compare(nextMapping, relaxed.size(), relaxed) == 0);
    CHECK(run.registered == 6);
    checkOnlyPlaced(capture, "office");
}

// The same photos with every pair matched to close loops: the office's photos two names apart share 30 matches or
// more, so they are verified with the pairs in name order, and the first mapping places the six (the five dining
// photos, which none of them overlaps, still send the mapper farther on, to no avail).
TEST_CASE("frames far apart in name order that share many features are verified, and placed at once") {
    ScratchDir dir;
    Capture capture = interleavedPlaces(dir);
    ColmapOptions options;
    options.exhaustiveUpTo = 0;
    options.sequentialOverlap = 2;
    options.loopFrames = 0;  // no frames spread through the capture: the pairs found by matching every pair alone
    const ColmapRun run = runColmap(capture, options);
    const std::string notes = notesOf(run);
    INFO(notes);
    CHECK_THAT(notes, Catch::Contains("loops are closed by matching every pair of frames and verifying the"));
    CHECK_THAT(notes, Catch::Contains("others with 30 matches or more"));
    CHECK_THAT(notes, !Catch::Contains("verifying the 0 others"));
    const auto firstModel = notes.find("the largest with ");
    REQUIRE(firstModel != std::string::npos);
    const std::string six = "the largest with 6 of 11";
    CHECK(notes.compare(firstModel, six.size(), six) == 0);
    CHECK(run.registered == 6);
    checkOnlyPlaced(capture, "office");
}

TEST_CASE("a missing colmap command gives a clear error") {
    ScratchDir dir;
    std::filesystem::create_directories(dir.path / "empty");
    const smql::testing::ScopedEnv path("PATH", (dir.path / "empty").string());
    Capture capture;
    capture.path = "frames";
    capture.frames.resize(3);
    SilentProgress silent;
    IngestOptions options;
    options.geometry = GeometrySource::Colmap;
    try {
        ingestCapture(capture, options, silent);
        FAIL("expected an error");
    } catch (const Error& e) {
        CHECK(e.kind() == ErrorKind::Input);
        CHECK_THAT(std::string(e.what()), Catch::Contains("apt-get install colmap"));
    }
}

TEST_CASE("a small real photo set with a group of photos of elsewhere: the largest group kept, the others named") {
    // The five real photos of ../shared/data/rgbd-dining without their depth and poses, and three
    // photos of somewhere else: overlapping crops of one drawn picture of random shapes, which share
    // no feature with the room. COLMAP's own rule, a model of at least min(10, 0.8 x 8) images, would
    // drop the five; the ingest keeps them and names the three. (Mirror images of the room are not
    // "elsewhere": a relaxed start can register them through the room's symmetric things.)
    ScratchDir dir;
    const auto photos = dir.path / "photos";
    std::filesystem::create_directories(photos);
    const std::string dining = std::string(SMQL_SHARED_DATA) + "/rgbd-dining/color/";
    for (int n = 1; n <= 5; ++n) {
        cv::Mat image = cv::imread(dining + std::to_string(n) + ".png");
        REQUIRE_FALSE(image.empty());
        cv::imwrite((photos / fmt::format("room-{}.png", n)).string(), image);
    }
    cv::Mat elsewhere(720, 1000, CV_8UC3, cv::Scalar(128, 128, 128));
    cv::RNG rng(20261125);
    for (int i = 0; i < 400; ++i) {
        const cv::Point centre(rng.uniform(0, elsewhere.cols), rng.uniform(0, elsewhere.rows));
        const cv::Scalar colour(rng.uniform(0, 256), rng.uniform(0, 256), rng.uniform(0, 256));
        if (i % 2 == 0)
            cv::circle(elsewhere, centre, rng.uniform(4, 40), colour, cv::FILLED);
        else
            cv::rectangle(elsewhere, centre, centre + cv::Point(rng.uniform(5, 60), rng.uniform(5, 60)), colour,
                          cv::FILLED);
    }
    for (int n = 1; n <= 3; ++n)
        cv::imwrite((photos / fmt::format("elsewhere-{}.png", n)).string(),
                    elsewhere(cv::Rect(90 * n, 60 * n, 640, 480)).clone());
    std::ofstream(photos / "camera.json") << R"({"width": 640, "height": 480, "fx": 518.0, "fy": 519.0,
                                                 "cx": 325.5, "cy": 253.5})";
    Capture capture = readCapture(photos.string());
    REQUIRE(capture.frames.size() == 8);
    // COLMAP's matching seeds its worker threads from the clock, so a run may differ from the last:
    // in one run of many (a CI run from a clean clone) its mapper joined only 3 of the five. Then the
    // refusal must say what is true of the photos: the five overlap, and no model holds them.
    ColmapRun run;
    try {
        run = runColmap(capture);
    } catch (const Error& e) {
        CHECK_THAT(e.message(), Catch::Contains("frames together (its largest model)") &&
                                    Catch::Contains("the largest holds only 5 of 8 photos"));
        WARN("COLMAP's mapper did not join the five room photos in this run: " << e.message());
        return;
    }
    const std::string notes = notesOf(run);
    INFO(notes);
    CHECK(run.registered == 5);
    checkOnlyPlaced(capture, "room-");
    CHECK_THAT(notes, Catch::Contains("COLMAP registered 5 of 8 frames; left out: elsewhere-1.png, elsewhere-2.png, "
                                      "elsewhere-3.png"));
    CHECK_THAT(notes, Catch::Contains("COLMAP's mapper with its default settings"));
}

TEST_CASE("a real capture with lens distortion: COLMAP places its frames undistorted, turned as the truth") {
    // 20 colour frames of TUM fr1/rpy (every sixth, 1.2 s apart) with Freiburg 1's published calibration, its
    // lens distortion included, which TUM's images keep. COLMAP sees each frame undistorted as every stage
    // after it does (a fixed FULL_OPENCV camera registered none of them), and the capture keeps the distortion.
    // The camera turns on the spot, so its turns between frames are what the motion capture can judge.
    const std::filesystem::path source = std::filesystem::path(SMQL_SHARED_DATA) / "captures/tum-fr1-rpy";
    std::vector<std::filesystem::path> frames;
    for (const auto& entry : std::filesystem::directory_iterator(source / "rgb")) frames.push_back(entry.path());
    std::sort(frames.begin(), frames.end());
    REQUIRE(frames.size() == 121);
    // The motion capture's turn of every colour frame: TUM's reader gives each its ground-truth pose.
    CaptureOptions everyFrame;
    everyFrame.fps = 0;
    std::map<std::string, Eigen::Matrix3d> truth;
    for (const auto& frame : readCapture(source.string(), everyFrame).frames)
        if (frame.pose)
            truth[std::filesystem::path(frame.colorPath).filename().string()] = detail::rotationOf(*frame.pose);

    // COLMAP's runs repeat (colmap_runner.cpp: kRepeatableThreads): a second run, once taken when one CI run's
    // default settings placed 3 of the 21 frames and the relaxed start 19, 5.45 deg off, would place the same.
    ScratchDir dir;
    const auto photos = dir.path / "photos";
    std::filesystem::create_directories(photos);
    for (std::size_t i = 0; i < frames.size(); i += 6)
        std::filesystem::copy_file(frames[i], photos / frames[i].filename());
    std::ofstream(photos / "camera.json") << R"({"width": 640, "height": 480, "fx": 517.3, "fy": 516.5,
        "cx": 318.6, "cy": 255.3, "k1": 0.2624, "k2": -0.9531, "p1": -0.0054, "p2": 0.0026, "k3": 1.1633})";
    Capture capture = readCapture(photos.string());
    REQUIRE(capture.frames.size() == 21);
    const Intrinsics lens = capture.intrinsics;
    REQUIRE(lens.distorted());

    ColmapOptions options;
    options.workDirectory = (dir.path / "colmap").string();
    ColmapRun placed = runColmap(capture, options);
    const std::string notes = notesOf(placed);
    INFO(notes);
    CHECK(capture.intrinsics == lens);  // kept fixed, distortion and all
    // COLMAP's copy of the first frame is the frame undistorted.
    const cv::Mat work = cv::imread((dir.path / "colmap/images/640x480/frame000000.png").string());
    const cv::Mat expected = undistorted(cv::imread(capture.frames[0].colorPath), lens, cv::INTER_LINEAR);
    REQUIRE(work.size() == expected.size());
    CHECK(cv::norm(work, expected, cv::NORM_INF) == 0);

    // The turn between each two placed frames against the motion capture's.
    std::vector<std::pair<Eigen::Quaterniond, Eigen::Quaterniond>> poses;  // (stored, true)
    for (const auto& frame : capture.frames) {
        const auto real = truth.find(std::filesystem::path(frame.colorPath).filename().string());
        if (frame.pose && real != truth.end())
            poses.emplace_back(Eigen::Quaterniond(detail::rotationOf(*frame.pose)), Eigen::Quaterniond(real->second));
    }
    REQUIRE(poses.size() >= 18);
    std::vector<double> errors, turns;
    for (std::size_t a = 0; a < poses.size(); ++a)
        for (std::size_t b = a + 1; b < poses.size(); ++b) {
            const Eigen::Quaterniond stored = poses[a].first.inverse() * poses[b].first;
            const Eigen::Quaterniond real = poses[a].second.inverse() * poses[b].second;
            errors.push_back(stored.angularDistance(real) * 180 / M_PI);
            turns.push_back(real.angularDistance(Eigen::Quaterniond::Identity()) * 180 / M_PI);
        }
    std::nth_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(errors.size() / 2), errors.end());
    std::nth_element(turns.begin(), turns.begin() + static_cast<std::ptrdiff_t>(turns.size() / 2), turns.end());
    const double medianError = errors[errors.size() / 2];
    const double medianTurn = turns[turns.size() / 2];
    std::cout << fmt::format(
        "TUM fr1/rpy, 21 frames with lens distortion: {} placed; turns between them median {:.1f} deg, off the "
        "motion capture's by {:.2f} deg (median)\n",
        placed.registered, medianTurn, medianError);
    CHECK(medianTurn > 10);  // the frames turn: the check below means something
    // Measured 1.9-2.1 deg; 2.6 with the lens taken for a pinhole. The rest is the motion capture's and its
    // timing: the camera turns fast (about 1 rad/s in the rolls).
    CHECK(medianError < 2.3);
}
