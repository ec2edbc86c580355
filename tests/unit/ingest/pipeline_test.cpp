// The ingest pipeline end to end: a synthetic capture against its ground
// truth (the quality thresholds), and the real rgbd-dining frames.
#include <catch2/catch.hpp>
#include <fstream>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include "model/geometry.hpp"
#include "model/points.hpp"

#include "engine/engine.hpp"
#include "ingest/capture/capture.hpp"
#include "ingest/capture/frame_loader.hpp"
#include "ingest/geometry/point_cloud.hpp"
#include "ingest/import/importers.hpp"
#include "ingest/pipeline/object_finder.hpp"
#include "ingest/pipeline/pipeline.hpp"
#include "ingest/pipeline/progress.hpp"
#include "ingest/pipeline/quality.hpp"
#include "ingest/synth/synth.hpp"
#include "scratch_dir.hpp"

using namespace smql;
using namespace smql::ingest;
using smql::ingest::test::ScratchDir;

TEST_CASE("a synthetic RGB-D capture with masks meets the quality thresholds") {
    ScratchDir dir;
    auto capturePath = (dir.path / "capture").string();
    auto synth = synth::writeSynth(capturePath, {.seed = 3, .frames = 40, .objects = 24});
    SilentProgress silent;
    IngestOptions options;
    options.sceneName = "synth-3";
    auto result = ingestCapture(readCapture(capturePath), options, silent);

    QualityOptions quality;
    for (const auto& [id, frames] : synth.framesSeen)
        if (frames > 0) quality.visible.insert(id);
    auto r = compareToTruth(inCaptureFrame(result.scene), synth.scene.truth, quality);
    std::cout << fmt::format(
        "synth seed 3, 40 frames: anchors F1 {:.2f}, objects F1 {:.2f}, color {:.2f}, parent {:.2f}\n", r.anchors.f1(),
        r.objects.f1(), r.colorAccuracy(), r.parentAccuracy());
    CHECK(r.anchors.f1() >= 0.9);
    CHECK(r.objects.f1() >= 0.9);
    CHECK(r.colorAccuracy() >= 0.9);
    CHECK(r.parentAccuracy() >= 0.85);

    // Every object carries evidence, views, and a scene-level phrase; image-level phrases hang below it.
    std::size_t objects = 0, descriptions = 0;
    for (const auto& n : result.scene.nodes) {
        if (n.kind == model::NodeKind::Object) {
            ++objects;
            CHECK_FALSE(n.text.empty());
            CHECK(n.attribute("views"));
            CHECK(n.attribute("first_seen"));
        }
        descriptions += n.kind == model::NodeKind::Description;
    }
    CHECK(descriptions >= objects);
    // Lateral order is recorded per view (edges tagged with a frame node) and consolidated when
    // views agree (allocentric edges, frame 0, support = agreeing views).
    std::size_t viewLocal = 0, consolidated = 0;
    for (const auto& r : result.scene.relations) {
        if (r.type != model::RelationType::LeftOf && r.type != model::RelationType::RightOf) continue;
        if (r.frame == model::kNoNode) {
            ++consolidated;
            CHECK(r.support >= 2);
        } else {
            ++viewLocal;
            CHECK(result.scene.nodes.at(r.frame - 1).kind == model::NodeKind::Frame);
        }
    }
    CHECK(viewLocal > consolidated);
    CHECK(consolidated > 0);

    std::set<model::NodeId> withEvidence;
    for (const auto& blob : result.scene.blobs) {
        if (blob.node == model::kNoNode) continue;     // the scene's own: its points
        CHECK(blob.bytes.substr(0, 2) == "\xff\xd8");  // a JPEG
        withEvidence.insert(blob.node);
    }
    CHECK(model::pointsBlob(result.scene) != nullptr);
    for (const auto& n : result.scene.nodes)
        if (n.kind == model::NodeKind::Object) CHECK(withEvidence.contains(n.id));
}

TEST_CASE("rgbd-dining (real, 5 frames, no labels): floor, walls and table-top objects") {
    // What this checks: after alignment the floor normal is within 5 degrees of +z (the floor is
    // level), at least one wall is found, the clustering fallback yields objects, and one of them
    // (the table-top region) has a box that lies above the floor. (The detector, which `auto`
    // would take when its model is installed, is tested in detector_test.cpp.)
    SilentProgress silent;
    IngestOptions options;
    options.sceneName = "dining";
    options.objects = "cluster";
    auto capture = readCapture(std::string(SMQL_SHARED_DATA) + "/rgbd-dining");
    auto result = ingestCapture(capture, options, silent);
    // Levelness, measured apart from the pipeline: every frame's depth through the stored
    // alignment; the points within 4 cm of z = 0 get a least-squares plane whose normal must be
    // within 5 degrees of +z, and they must be a real share of the points (the floor is seen).
    const auto& a = result.scene.info.alignment;
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    std::size_t floorPoints = 0, allPoints = 0;
    for (std::size_t i = 0; i < capture.frames.size(); ++i) {
        auto cloud = backProject(loadFrame(capture, capture.frames[i], 640), *capture.frames[i].pose,
                                 static_cast<std::uint32_t>(i), 8);
        for (const auto& p : cloud.points) {
            Eigen::Vector3d q(a[0] * p.x + a[1] * p.y + a[2] * p.z + a[3], a[4] * p.x + a[5] * p.y + a[6] * p.z + a[7],
                              a[8] * p.x + a[9] * p.y + a[10] * p.z + a[11]);
            ++allPoints;
            if (std::abs(q.z()) > 0.04) continue;
            ++floorPoints;
            sum += q;
            scatter += q * q.transpose();
        }
    }
    REQUIRE(floorPoints > 100);
    Eigen::Vector3d mean = sum / double(floorPoints);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter / double(floorPoints) - mean * mean.transpose());
    Eigen::Vector3d normal = solver.eigenvectors().col(0);  // smallest spread: the plane's normal
    double tilt = std::acos(std::min(1.0, std::abs(normal.z()))) * 180 / M_PI;
    std::cout << fmt::format("rgbd-dining: floor tilt {:.2f} deg over {} of {} points\n", tilt, floorPoints, allPoints);
    CHECK(tilt < 5.0);
    CHECK(double(floorPoints) / allPoints > 0.05);

    std::size_t floors = 0, walls = 0, above = 0, objects = 0;
    for (const auto& n : result.scene.nodes) {
        if (n.category == "floor") ++floors;
        if (n.category == "wall") ++walls;
        if (n.kind == model::NodeKind::Object) {
            ++objects;
            if (model::bottom(n.box) > 0.3) ++above;  // clear of the floor: on the table top
        }
    }
    CHECK(floors == 1);
    CHECK(walls >= 1);
    CHECK(objects >= 1);
    CHECK(above >= 1);

    // Stored, an ingested scene carries the stamps an imported one does (the engine's, one rule):
    // its capture time, and on every object first_seen_at = last_seen_at = that time.
    ScratchDir database;
    auto engine = Engine::open((database.path / "db").string());
    engine->importScene(result.scene);
    engine->importScene(
        import::readReplica(std::string(SMQL_SHARED_DATA) + "/replica-room0/info_semantic.json", "replica"));
    for (const std::string scene : {"dining", "replica"}) {
        const model::SceneData stored = engine->readScene(scene);
        INFO(scene);
        REQUIRE(!stored.info.captureTime.empty());
        for (const auto& n : stored.nodes) {
            if (n.kind != model::NodeKind::Object) continue;
            auto value = [&](std::string_view name) {
                auto it = std::find_if(n.attributes.begin(), n.attributes.end(),
                                       [&](const model::Attribute& a) { return a.name == name; });
                return it == n.attributes.end() ? std::string("(unset)") : it->value;
            };
            CHECK(value("first_seen_at") == stored.info.captureTime);
            CHECK(value("last_seen_at") == stored.info.captureTime);
        }
    }

    // The capture's points are kept with the scene, in its frame: the floor's points at z = 0 and
    // coloured as the frames saw them; a copy through the JSON format keeps them byte for byte.
    const model::SceneData stored = engine->readScene("dining");
    const model::Blob* blob = model::pointsBlob(stored);
    REQUIRE(blob != nullptr);
    const model::ScenePoints points = model::readPointsPly(blob->bytes);
    std::size_t onFloor = 0, grey = 0;
    for (std::size_t i = 0; i < points.positions.size(); ++i) {
        if (std::abs(points.positions[i].z) < 0.04) ++onFloor;
        const auto& c = points.colours[i];
        if (c.r == c.g && c.g == c.b) ++grey;
    }
    CHECK(points.positions.size() > 5000);
    CHECK(double(onFloor) / points.positions.size() > 0.05);
    CHECK(grey < points.positions.size() / 10);
    CHECK(engine->readScene("replica").blobs.empty());  // a layout has no points
    const auto file = (database.path / "dining.json").string();
    std::ofstream(file) << import::writeSceneJson(engine->exportScene("dining"));
    engine->importScene(import::readSceneJson(file, "copy"));
    const model::SceneData copy = engine->readScene("copy");
    const model::Blob* copied = model::pointsBlob(copy);
    REQUIRE(copied != nullptr);
    CHECK(copied->bytes == blob->bytes);
}

TEST_CASE("object sources: --objects takes the table's names; a misspelt one is an error with the nearest") {
    IngestOptions options;
    options.objects = "clustr";
    try {
        makeObjectFinder(Capture{}, options);
        FAIL("an unknown object source was accepted");
    } catch (const Error& e) {
        CHECK(e.kind() == ErrorKind::Usage);
        CHECK(std::string(e.message()) == "unknown object source 'clustr'");
        CHECK(e.hint().find("did you mean cluster?") != std::string::npos);
    }
    options.objects = "cluster";
    CHECK(makeObjectFinder(Capture{}, options) != nullptr);
    const auto names = objectSourceNames();
    CHECK(names == std::vector<std::string>{"masks", "detections", "detect", "cluster", "auto"});
}
