// --geometry colmap: an RGB-only synthetic capture through Debian's `colmap`
// (CPU), checked against the truth after registering the COLMAP cameras to the
// true cameras with a similarity (Umeyama); and the error when colmap is missing.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "engine/error.hpp"
#include "ingest/capture/capture.hpp"
#include "ingest/pipeline/pipeline.hpp"
#include "ingest/pipeline/quality.hpp"
#include "ingest/synth/synth.hpp"

using namespace smql;
using namespace smql::ingest;

namespace {

struct ScratchDir {
    std::filesystem::path path;
    ScratchDir() {
        std::string pattern = (std::filesystem::temp_directory_path() / "smql-colmap-test-XXXXXX").string();
        path = mkdtemp(pattern.data());
    }
    ~ScratchDir() { std::filesystem::remove_all(path); }
};

class Silent : public ProgressSink {
public:
    void stageStarted(const std::string&, std::size_t) override {}
    void advanced(std::size_t) override {}
    void stageFinished(const std::string&, double, const std::string&) override {}
    void note(const std::string&) override {}
};

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
    Silent silent;
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
    const auto n = static_cast<Eigen::Index>(result.cameraCentres.size());
    Eigen::Matrix3Xd from(3, n), to(3, n);
    for (Eigen::Index k = 0; k < n; ++k) {
        const auto& [frame, c] = result.cameraCentres[static_cast<std::size_t>(k)];
        const auto& t = truth.frames[frame].pose->translation;
        from.col(k) << c.x, c.y, c.z;
        to.col(k) << t.x, t.y, t.z;
    }
    Eigen::Matrix4d T = Eigen::umeyama(from, to, true);
    double s = T.block<3, 1>(0, 0).norm();
    Eigen::Matrix3d R = T.block<3, 3>(0, 0) / s;
    Eigen::Vector3d shift = T.block<3, 1>(0, 3);
    double residual = 0;
    for (Eigen::Index k = 0; k < n; ++k) residual += ((s * R * from.col(k) + shift) - to.col(k)).norm();
    residual /= n;
    double yaw = std::atan2(R(1, 0), R(0, 0));

    model::SceneData mapped = result.scene;
    for (auto& node : mapped.nodes) {
        Eigen::Vector3d c(node.box.center.x, node.box.center.y, node.box.center.z);
        Eigen::Vector3d m = s * R * c + shift;
        node.box.center = {m.x(), m.y(), m.z()};
        node.box.size = {node.box.size.x * s, node.box.size.y * s, node.box.size.z * s};
        node.box.yaw += yaw;
    }
    QualityOptions quality;
    for (const auto& [id, frames] : synth.framesSeen)
        if (frames > 0) quality.visible.insert(id);
    auto r = compareToTruth(mapped, synth.scene.truth, quality);
    if (std::getenv("SMQL_COLMAP_DEBUG"))
        for (const auto& t : synth.scene.truth.nodes) {
            if (t.kind != model::NodeKind::Object || !quality.visible.count(t.id)) continue;
            double best = 0;
            const model::Node* m = nullptr;
            for (const auto& g : mapped.nodes)
                if (g.category == t.category && boxIou(g.box, t.box) >= best) best = boxIou(g.box, t.box), m = &g;
            std::cout << fmt::format("{:12} truth {:.2f} {:.2f} {:.2f} @ {:.2f} {:.2f} {:.2f}", t.category, t.box.size.x,
                                     t.box.size.y, t.box.size.z, t.box.center.x, t.box.center.y, t.box.center.z);
            if (m)
                std::cout << fmt::format(" | got {:.2f} {:.2f} {:.2f} @ {:.2f} {:.2f} {:.2f} iou {:.2f}", m->box.size.x,
                                         m->box.size.y, m->box.size.z, m->box.center.x, m->box.center.y, m->box.center.z, best);
            std::cout << "\n";
        }
    double scaleError = std::abs(s - 1);
    std::cout << fmt::format(
        "COLMAP synth seed 3, 30 frames RGB only: {} frames registered, colmap {:.1f} s; similarity scale {:.3f} "
        "(scale error {:.1f}%), up tilt {:.3f}, camera residual {:.3f} m; objects F1 {:.2f} (P {:.2f} R {:.2f}), "
        "anchors F1 {:.2f}, centre error {:.2f} m\n",
        n, colmapSeconds, s, 100 * scaleError, R(2, 2), residual, r.objects.f1(), r.objects.precision(),
        r.objects.recall(), r.anchors.f1(), r.meanCenterError);
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
    Silent silent;
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
