// VSI-Bench's meta-info JSON: rooms of oriented boxes (ScanNet, ARKitScenes), picked by name,
// upright boxes around leaning ones, doors and windows as anchors, the room on its floor.
#include <catch2/catch.hpp>

#include <cmath>

#include "import_support.hpp"
#include "ingest/import/importers.hpp"
#include "ingest/import/registry.hpp"
#include "model/geometry.hpp"

using smql::import::readVsiBench;
using smql::import::readVsiBenchAll;
using smql::import::test::requireInputError;
using smql::import::test::TempDir;
using namespace smql::model;

namespace {

std::string layouts(const char* file) { return std::string(SMQL_SHARED_DATA) + "/real-layouts/" + file; }

// Two rooms; in "leaning", a chair leans 12 degrees about x and a door stands upright. The floor
// is at z = -0.9, where the chair's and the table's bottoms are.
const char* const kTwoRooms = R"({
 "leaning": {"object_bbox": {
   "chair": [{"centroid": [1, 2, -0.45], "axesLengths": [0.5, 0.6, 0.9],
              "normalizedAxes": [1, 0, 0,  0, 0.9781476, -0.2079117,  0, 0.2079117, 0.9781476]}],
   "table": [{"centroid": [2, 2, -0.5], "axesLengths": [1.2, 0.8, 0.8],
              "normalizedAxes": [0, 1, 0,  -1, 0, 0,  0, 0, 1]}],
   "door": [{"centroid": [0, 0, 0.1], "axesLengths": [0.9, 0.05, 2.0],
             "normalizedAxes": [1, 0, 0,  0, 1, 0,  0, 0, 1]}],
   "trash bin": [{"centroid": [3, 1, -0.7], "axesLengths": [0.3, 0.3, 0.4],
                  "normalizedAxes": [1, 0, 0,  0, 1, 0,  0, 0, 1]}]}},
 "other": {"object_bbox": {"sofa": [{"centroid": [0, 0, 0.4], "axesLengths": [2, 1, 0.8],
                                     "normalizedAxes": [1, 0, 0,  0, 1, 0,  0, 0, 1]}]}}
})";

const Node& byCategory(const SceneData& scene, const std::string& category) {
    for (const Node& n : scene.nodes)
        if (n.category == category) return n;
    FAIL("no " << category);
    return scene.nodes.front();
}

}  // namespace

TEST_CASE("VSI-Bench: a room by name, its boxes upright on its floor", "[import][vsibench]") {
    TempDir dir;
    const std::string path = dir.write("rooms.json", kTwoRooms);
    std::vector<SceneData> all = readVsiBenchAll(path);
    REQUIRE(all.size() == 2);
    CHECK(all[0].info.name == "leaning");
    CHECK(all[1].info.name == "other");
    CHECK(all[0].nodes.size() == readVsiBench(path, "leaning").nodes.size());

    SceneData scene = readVsiBench(path, "leaning");
    CHECK(scene.info.name == "leaning");
    REQUIRE(scene.nodes.size() == 4);

    // The floor is where the lowest things stand: 0.9 m down, kept in the alignment.
    CHECK(scene.info.alignment[11] == Approx(0.9));
    const Node& table = byCategory(scene, "table");
    CHECK(bottom(table.box) == Approx(0).margin(1e-9));
    CHECK(table.box.yaw == Approx(M_PI / 2));
    CHECK(table.box.size.x == Approx(1.2));
    CHECK(table.box.size.y == Approx(0.8));
    CHECK(table.box.size.z == Approx(0.8));
    CHECK(table.attribute("tilt") == nullptr);

    // A box leaning 12 degrees is held as the upright box around it, its lean kept.
    const Node& chair = byCategory(scene, "chair");
    REQUIRE(chair.attribute("tilt") != nullptr);
    CHECK(*chair.attribute("tilt") == "12.0");
    const double s = std::sin(12 * M_PI / 180), c = std::cos(12 * M_PI / 180);
    CHECK(chair.box.size.x == Approx(0.5));
    CHECK(chair.box.size.y == Approx(0.6 * c + 0.9 * s));
    CHECK(chair.box.size.z == Approx(0.6 * s + 0.9 * c));

    // Doors and windows are the room's anchors; two-word categories are written as Replica's.
    CHECK(byCategory(scene, "door").kind == NodeKind::Anchor);
    CHECK(byCategory(scene, "trash-bin").kind == NodeKind::Object);
    CHECK(byCategory(scene, "trash-bin").sourceId == 4);
}

TEST_CASE("VSI-Bench: a file of several rooms needs a room's name; a wrong name is an error", "[import][vsibench]") {
    TempDir dir;
    const std::string path = dir.write("rooms.json", kTwoRooms);
    try {
        readVsiBench(path, "");
        FAIL("no error");
    } catch (const smql::Error& e) {
        CHECK(e.kind() == smql::ErrorKind::Usage);
        CHECK_THAT(e.message(), Catch::Contains("holds 2 rooms") && Catch::Contains("leaning"));
        CHECK_THAT(e.hint(), Catch::Contains("--all"));
    }
    requireInputError([&] { readVsiBench(path, "kitchen"); }, {"rooms.json", "no room named 'kitchen'"});
    const std::string one = dir.write("one.json", R"({"solo": {"object_bbox": {"bed": [
        {"centroid": [0, 0, 0.3], "axesLengths": [2, 1.6, 0.6], "normalizedAxes": [1, 0, 0, 0, 1, 0, 0, 0, 1]}]}}})");
    CHECK(readVsiBench(one, "").info.name == "solo");
    // A room of one bed whose lengths and axes are written in: each fault named by its field.
    auto bed = [&](const std::string& file, const std::string& lengths, const std::string& axes) {
        return dir.write(file, R"({"r": {"object_bbox": {"bed": [{"centroid": [0, 0, 0.3], "axesLengths": )" + lengths +
                                   R"(, "normalizedAxes": )" + axes + "}]}}}");
    };
    const std::string skew = bed("skew.json", "[2, 1.6, 0.6]", "[1, 0, 0, 1, 0, 0, 0, 0, 1]");
    requireInputError([&] { readVsiBench(skew, "r"); },
                      {"skew.json", "object_bbox.bed[0].normalizedAxes", "not perpendicular"});
    const std::string flat = bed("flat.json", "[2, 0, 0.6]", "[1, 0, 0, 0, 1, 0, 0, 0, 1]");
    requireInputError([&] { readVsiBench(flat, "r"); }, {"flat.json", "axesLengths", "out of range"});
}

TEST_CASE("VSI-Bench: every real room reads, stands on its floor, and keeps the leaning boxes' tilt",
          "[import][vsibench]") {
    std::size_t rooms = 0, leaning = 0, boxes = 0;
    for (const char* file : {"scannet_meta_info_val.json", "arkitscenes_meta_info_val.json"}) {
        for (const SceneData& scene : readVsiBenchAll(layouts(file))) {
            ++rooms;
            // The floor found is where things stand: some thing's bottom is within 0.25 m of it,
            // and none is more than 1 m below it.
            bool standing = false;
            for (const Node& n : scene.nodes) {
                ++boxes;
                leaning += n.attribute("tilt") != nullptr;
                standing |= std::abs(bottom(n.box)) <= 0.25;
                INFO(scene.info.name << ": " << n.category);
                CHECK(bottom(n.box) > -1.0);
            }
            INFO(scene.info.name);
            CHECK(standing);
        }
    }
    CHECK(rooms == 238);
    CHECK(boxes > 2000);
    CHECK(leaning > 0);  // ScanNet's boxes are fitted to scans: some lean
}
