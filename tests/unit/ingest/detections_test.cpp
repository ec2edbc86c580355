// Objects from detections.json: the file's checks, and a synthetic capture's
// perfect-detector output ingested with masks ignored (polygons, then boxes only).
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/engine.hpp"
#include "ingest/capture/capture.hpp"
#include "ingest/capture/detections.hpp"
#include "ingest/pipeline/pipeline.hpp"
#include "ingest/pipeline/progress.hpp"
#include "ingest/pipeline/quality.hpp"
#include "ingest/synth/synth.hpp"
#include "model/embedding.hpp"
#include "model/error.hpp"
#include "scratch_dir.hpp"

using namespace smql;
using namespace smql::ingest;
using smql::ingest::test::ScratchDir;
namespace fs = std::filesystem;

namespace {

// A capture of two 640x480 frames (1.png, 2.png); no images are read by readDetections.
Capture twoFrames(const ScratchDir& dir, const std::string& detections) {
    Capture c;
    c.path = dir.path.string();
    c.intrinsics = {640, 480, 525, 525, 319.5, 239.5};
    for (int i = 0; i < 2; ++i) {
        CaptureFrame f;
        f.index = i;
        f.colorPath = (dir.path / "color" / fmt::format("{}.png", i + 1)).string();
        c.frames.push_back(f);
    }
    c.detectionsPath = (dir.path / "detections.json").string();
    std::ofstream(c.detectionsPath) << detections;
    return c;
}

void expectError(const std::string& json, const std::string& field) {
    ScratchDir dir;
    auto capture = twoFrames(dir, json);
    INFO(json);
    try {
        readDetections(capture);
        FAIL("no error");
    } catch (const Error& e) {
        CHECK(e.kind() == ErrorKind::Input);
        CHECK_THAT(e.message(), Catch::Contains("detections.json"));
        CHECK_THAT(e.message(), Catch::Contains(field));
    }
}

struct DetectionScores {
    double objectsF1 = 0, color = 0;
};

DetectionScores ingestDetections(const std::string& capturePath, const synth::SynthResult& synth) {
    SilentProgress silent;
    IngestOptions options;
    options.sceneName = "synth-3";
    options.objects = "detections";
    auto result = ingestCapture(readCapture(capturePath), options, silent);
    QualityOptions quality;
    for (const auto& [id, frames] : synth.framesSeen)
        if (frames > 0) quality.visible.insert(id);
    auto r = compareToTruth(inCaptureFrame(result.scene), synth.scene.truth, quality);
    return {r.objects.f1(), r.colorAccuracy()};
}

}  // namespace

TEST_CASE("detections.json: a valid file, by name and by frame number", "[ingest][detections]") {
    ScratchDir dir;
    auto capture = twoFrames(dir, R"({"detections": [
        {"image": "2.png", "label": "mug", "score": 0.9, "bbox": [10, 20, 30, 40]},
        {"image_id": 1, "category": "chair", "score": 0.5, "bbox": [0, 0, 640, 480],
         "segmentation": [[1, 1, 100, 1, 100, 100]]}]})");
    auto detections = readDetections(capture);
    REQUIRE(detections.size() == 2);
    REQUIRE(detections[0].size() == 1);
    REQUIRE(detections[1].size() == 1);
    CHECK(detections[1][0].category == "mug");
    CHECK(detections[1][0].box == cv::Rect2d(10, 20, 30, 40));
    CHECK(detections[1][0].polygons.empty());
    CHECK(detections[0][0].category == "chair");
    REQUIRE(detections[0][0].polygons.size() == 1);
    CHECK(detections[0][0].polygons[0].size() == 3);
}

TEST_CASE("detections.json: format errors name the file and the field", "[ingest][detections]") {
    expectError(R"({"nothing": 1})", "detections: expected an array");
    expectError(R"([{"label": "mug", "score": 0.9, "bbox": [1, 2, 3, 4]}])", "detections[0].image: missing");
    expectError(R"([{"image": "1.png", "score": 0.9, "bbox": [1, 2, 3, 4]}])", "detections[0].label: missing");
    expectError(R"([{"image": "1.png", "label": "mug", "bbox": [1, 2, 3, 4]}])", "detections[0].score: missing");
    expectError(R"([{"image": "1.png", "label": "mug", "score": "high", "bbox": [1, 2, 3, 4]}])",
                "detections[0].score: expected a number");
    expectError(R"([{"image": "1.png", "label": "mug", "score": 0.9}])", "detections[0].bbox: missing");
    expectError(R"([{"image": "1.png", "label": "mug", "score": 0.9, "bbox": [1, 2, 3]}])",
                "detections[0].bbox: expected");
    expectError(R"([{"image": "1.png", "label": "mug", "score": 0.9, "bbox": [600, 2, 100, 4]}])",
                "detections[0].bbox: [600, 2, 100, 4] lies outside the 640x480 image");
    expectError(R"([{"image": "1.png", "label": "mug", "score": 0.9, "bbox": [1, 2, 3, 4]},
                    {"image": "9.png", "label": "mug", "score": 0.9, "bbox": [1, 2, 3, 4]}])",
                "detections[1].image: '9.png' is not a frame");
    expectError(R"([{"image_id": 7, "label": "mug", "score": 0.9, "bbox": [1, 2, 3, 4]}])",
                "detections[0].image_id: 7 is not a frame number");
    expectError(R"([{"image": "1.png", "label": 3, "score": 0.9, "bbox": [1, 2, 3, 4]}])",
                "detections[0].label: expected");
    expectError(R"([{"image": "1.png", "label": "mug", "score": 0.9, "bbox": [1, 2, 3, 4],
                     "segmentation": {"size": [480, 640], "counts": "abc"}}])",
                "detections[0].segmentation: RLE mask: counts string is truncated");
    // Thirteen 5-bit groups: the old decoder shifted -1 by 65 bits (undefined behaviour).
    expectError(R"([{"image": "1.png", "label": "mug", "score": 0.9, "bbox": [1, 2, 3, 4],
                     "segmentation": {"size": [480, 640], "counts": "PPPPPPPPPPPP@"}}])",
                "detections[0].segmentation: RLE mask: a run in the counts string is longer than any image");
    // Bytes of the file quoted in the message are escaped: messages stay UTF-8 (JSON error output needs it).
    expectError("[{\"image\": \"1.png\", \"label\": \"caf\xE9\"}]", "not valid JSON");
    expectError("[{\"image\": \"1.png\", \"label\": \"caf\xE9\"}]", "caf\\xE9");
    expectError(R"([{"image": "1.png", "label": "mug", "score": 0.9, "bbox": [1, 2, 3, 4],
                     "segmentation": {"size": [48, 64], "counts": [3072]}}])",
                "detections[0].segmentation: RLE mask of 64x48 for a 640x480 image");
    expectError(
        R"([{"image": "1.png", "label": "mug", "score": 0.9, "bbox": [1, 2, 3, 4], "segmentation": [[1, 2, 3]]}])",
        "detections[0].segmentation[0]: expected a polygon");
    expectError(R"([{"image": "1.png", "label": "mug", "score": 0.9, "bbox": [1, 2, -3, 4]}])",
                "detections[0].bbox: width and height must be positive");
}

TEST_CASE("detections: a synthetic capture's perfect detections, polygons and boxes only", "[ingest][detections]") {
    ScratchDir dir;
    auto capturePath = (dir.path / "capture").string();
    auto synth = synth::writeSynth(capturePath, {.seed = 3, .frames = 30, .objects = 24});

    auto withPolygons = ingestDetections(capturePath, synth);
    std::cout << fmt::format("synth seed 3, 30 frames, detections with polygons: objects F1 {:.2f}, color {:.2f}\n",
                             withPolygons.objectsF1, withPolygons.color);
    CHECK(withPolygons.objectsF1 >= 0.8);
    CHECK(withPolygons.color >= 0.8);

    // The same detections without their outlines: the box and the depth band must do.
    auto file = fs::path(capturePath) / "detections.json";
    nlohmann::json j = nlohmann::json::parse(std::ifstream(file));
    for (auto& d : j["detections"]) d.erase("segmentation");
    std::ofstream(file) << j.dump();
    auto boxesOnly = ingestDetections(capturePath, synth);
    std::cout << fmt::format("synth seed 3, 30 frames, detections as boxes only: objects F1 {:.2f}, color {:.2f}\n",
                             boxesOnly.objectsF1, boxesOnly.color);
    CHECK(boxesOnly.objectsF1 >= 0.6);
}

TEST_CASE("detections.json: an embedding per entry, checked like the other fields", "[ingest][detections]") {
    ScratchDir dir;
    auto capture = twoFrames(dir, R"([
        {"image": "1.png", "label": "mug", "score": 0.9, "bbox": [1, 2, 3, 4], "embedding": [0.5, -1, 2e-3]},
        {"image": "2.png", "label": "cup", "score": 0.9, "bbox": [1, 2, 3, 4]}])");
    auto detections = readDetections(capture);
    CHECK(detections[0].at(0).embedding == std::vector<float>{0.5F, -1.0F, 2e-3F});
    CHECK(detections[1].at(0).embedding.empty());  // an entry may go without one

    const std::string entry = R"({"image": "1.png", "label": "mug", "score": 0.9, "bbox": [1, 2, 3, 4], "embedding": )";
    expectError("[" + entry + R"("0.5 1"}])", "detections[0].embedding: expected a list of numbers");
    expectError("[" + entry + R"([0.5, "1"]}])", "detections[0].embedding: expected a list of numbers");
    expectError("[" + entry + "[]}]", "detections[0].embedding: an embedding needs at least one number");
    expectError("[" + entry + "[0, 0, 0]}]", "detections[0].embedding: every value is 0");
    expectError("[" + entry + "[1, 1e39]}]", "detections[0].embedding: value 1 (1e+39) is not a finite");
    expectError("[" + entry + "[1, 2]}, " + entry + "[1, 2, 3]}]",
                "detections[1].embedding: 3 numbers, detections[0].embedding has 2");
    std::string tooLong = "[1";
    for (int i = 1; i < 4097; ++i) tooLong += ", 0";
    expectError("[" + entry + tooLong + "]}]", "detections[0].embedding: 4097 numbers; an embedding has at most 4096");
}

TEST_CASE("detections: embeddings in detections.json become the objects' embedding blobs", "[ingest][detections]") {
    ScratchDir dir;
    auto capturePath = (dir.path / "capture").string();
    synth::writeSynth(capturePath, {.seed = 5, .frames = 20, .objects = 10});

    // Each label's own axis, plus a little of the next one that differs from view to view: the
    // node's vector must still point along its category's axis, at unit length.
    auto file = fs::path(capturePath) / "detections.json";
    nlohmann::json j = nlohmann::json::parse(std::ifstream(file));
    std::vector<std::string> labels;
    for (const auto& d : j["detections"]) labels.push_back(d["label"].get<std::string>());
    std::sort(labels.begin(), labels.end());
    labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
    const std::size_t dimensions = labels.size() + 1;
    auto axis = [&](const std::string& label) {
        return static_cast<std::size_t>(std::find(labels.begin(), labels.end(), label) - labels.begin());
    };
    std::size_t n = 0;
    for (auto& d : j["detections"]) {
        std::vector<float> v(dimensions, 0.0F);
        const std::size_t a = axis(d["label"].get<std::string>());
        v[a] = 3.0F;
        v[a + 1] = static_cast<float>(n++ % 5) * 0.2F;
        d["embedding"] = v;
    }
    std::ofstream(file) << j.dump();

    SilentProgress silent;
    IngestOptions options;
    options.sceneName = "synth-5";
    options.objects = "detections";
    auto result = ingestCapture(readCapture(capturePath), options, silent);

    std::size_t objects = 0;
    for (const auto& node : result.scene.nodes) {
        if (node.kind != model::NodeKind::Object) continue;
        ++objects;
        INFO(node.category);
        auto blob = std::find_if(result.scene.blobs.begin(), result.scene.blobs.end(),
                                 [&](const model::Blob& b) { return b.node == node.id && b.name == "embedding"; });
        REQUIRE(blob != result.scene.blobs.end());
        CHECK(blob->mediaType == "application/x-float32");
        const std::vector<float> v = model::readEmbedding(*blob);
        REQUIRE(v.size() == dimensions);
        double norm = 0;
        for (float x : v) norm += static_cast<double>(x) * x;
        CHECK(norm == Approx(1.0).epsilon(1e-5));
        CHECK(static_cast<std::size_t>(std::max_element(v.begin(), v.end()) - v.begin()) == axis(node.category));
    }
    REQUIRE(objects >= 3);

    // Stored, they answer a query vector along one category's axis with a thing of that category.
    ScratchDir database;
    auto engine = Engine::open((database.path / "db").string());
    engine->importScene(result.scene);
    const std::string wanted = std::find_if(result.scene.nodes.begin(), result.scene.nodes.end(), [](const auto& n) {
                                   return n.kind == model::NodeKind::Object;
                               })->category;
    std::vector<float> query(dimensions, 0.0F);
    query[axis(wanted)] = 1.0F;
    auto statement = engine->prepare("FIND object SIMILAR TO ? LIMIT 1");
    statement.bind(1, query);
    auto rows = statement.execute().rows;
    REQUIRE(rows.size() == 1);
    CHECK(std::get<std::string>(rows[0][1]) == wanted);
}

TEST_CASE("COCO RLE masks decode, as counts and as the compressed string") {
    // Columns 10 and 11, rows 100..149, of a 640x480 image: runs in column-major order.
    const long long h = 480, first = 10 * h + 100;
    std::string counts = fmt::format("[{}, 50, 430, 50, {}]", first, 640 * h - (first + 50 + 430 + 50));
    for (const std::string& form : {counts, std::string(R"("Ti4b1^=0lXV9")")}) {
        ScratchDir dir;
        auto capture = twoFrames(dir, R"([{"image": "1.png", "label": "mug", "score": 0.9, "bbox": [10, 100, 2, 50],
                                           "segmentation": {"size": [480, 640], "counts": )" +
                                          form + "}}]");
        auto detections = readDetections(capture);
        INFO(form);
        REQUIRE(detections[0].size() == 1);
        const cv::Mat1b& mask = detections[0][0].mask;
        REQUIRE(mask.rows == 480);
        REQUIRE(mask.cols == 640);
        CHECK(cv::countNonZero(mask) == 100);
        CHECK(mask(100, 10) == 255);
        CHECK(mask(149, 11) == 255);
        CHECK(mask(99, 10) == 0);
        CHECK(mask(100, 12) == 0);
    }
}
