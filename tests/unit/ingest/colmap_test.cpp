// --geometry colmap: an RGB-only synthetic capture through Debian's `colmap`
// (CPU), checked against the truth after registering the COLMAP cameras to the
// true cameras with a similarity (Umeyama); and the error when colmap is missing.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include <fmt/format.h>

#include "ingest/capture/capture.hpp"
#include "ingest/pipeline/pipeline.hpp"
#include "ingest/pipeline/progress.hpp"
#include "ingest/pipeline/quality.hpp"
#include "ingest/synth/synth.hpp"
#include "model/error.hpp"
#include "scratch_dir.hpp"

using namespace smql;
using namespace smql::ingest;
using smql::ingest::test::ScratchDir;

namespace {

// PATH replaced for one scope.
struct PathOverride {
    std::string saved;
    explicit PathOverride(const std::string& path) {
        const char* old = std::getenv("PATH");
        saved = old ? old : "";
        setenv("PATH", path.c_str(), 1);
    }
    ~PathOverride() { setenv("PATH", saved.c_str(), 1); }
};

}  // namespace

TEST_CASE("an RGB-only synthetic capture through COLMAP meets the quality thresholds after a similarity") {
    ScratchDir dir;
    auto capturePath = (dir.path / "capture").string();
    auto synth = synth::writeSynth(capturePath, {.seed = 3, .frames = 30, .objects = 24});
    Capture truth = readCapture(capturePath);
    Capture rgb = truth;
    for (auto& f : rgb.frames) {
        f.depthPath.clear();
        f.pose.reset();
    }
    SilentProgress silent;
    IngestOptions options;
    options.sceneName = "synth-3-colmap";
    options.geometry = GeometrySource::Auto;  // no poses: COLMAP
    options.colmap.keepWorkDirectory = false;
    auto result = ingestCapture(rgb, options, silent);

    double colmapSeconds = 0;
    for (const auto& s : result.stages)
        if (s.stage == "colmap") colmapSeconds = s.seconds;
    REQUIRE(colmapSeconds > 0);
    REQUIRE(result.cameraCentres.size() >= 0.7 * rgb.frames.size());

    // The aligned frame -> the truth frame: a similarity from the camera centres.
    std::vector<std::pair<model::Vec3, model::Vec3>> cameras;
    for (const auto& [frame, centre] : result.cameraCentres)
        cameras.push_back({centre, truth.frames[frame].pose->translation});
    auto registration = registerByCameras(result.scene, cameras);
    QualityOptions quality;
    for (const auto& [id, frames] : synth.framesSeen)
        if (frames > 0) quality.visible.insert(id);
    auto r = compareToTruth(registration.mapped, synth.scene.truth, quality);
    double scaleError = std::abs(registration.scale - 1);
    std::cout << fmt::format(
        "COLMAP synth seed 3, 30 frames RGB only: {} frames registered, colmap {:.1f} s; similarity scale {:.3f} "
        "(scale error {:.1f}%), camera residual {:.3f} m; objects F1 {:.2f} (P {:.2f} R {:.2f}), "
        "anchors F1 {:.2f}, centre error {:.2f} m\n",
        cameras.size(), colmapSeconds, registration.scale, 100 * scaleError, registration.residual, r.objects.f1(),
        r.objects.precision(), r.objects.recall(), r.anchors.f1(), r.meanCenterError);
    CHECK(scaleError <= 0.10);
    CHECK(r.objects.f1() >= 0.7);
}

TEST_CASE("a missing colmap command gives a clear error") {
    ScratchDir dir;
    std::filesystem::create_directories(dir.path / "empty");
    PathOverride path((dir.path / "empty").string());
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
