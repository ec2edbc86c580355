#include <cmath>
#include <functional>
#include <numbers>
#include <set>

#include <nlohmann/json.hpp>

#include "import_support.hpp"
#include "ingest/import/importers.hpp"
#include "model/geometry.hpp"

using smql::import::readReplica;
using smql::import::test::replicaPath;
using smql::import::test::requireInputError;
using smql::import::test::TempDir;
using namespace smql::model;
using OrderedJson = nlohmann::ordered_json;
using Catch::Detail::Approx;

namespace {

const Node& bySourceId(const SceneData& scene, std::int64_t id) {
    for (const Node& n : scene.nodes)
        if (n.sourceId == id) return n;
    FAIL("no node with source id " << id);
    throw;
}

OrderedJson replicaJson() { return OrderedJson::parse(std::ifstream(replicaPath())); }

// One object with the given rotation (x, y, z, w), box-frame centre and translation.
std::string singleObject(const TempDir& dir, OrderedJson rotation, OrderedJson center, OrderedJson translation) {
    OrderedJson file = {
        {"objects",
         OrderedJson::array({{{"id", 7},
                              {"class_name", "box"},
                              {"oriented_bbox",
                               {{"abb", {{"center", center}, {"sizes", {1.0, 2.0, 3.0}}}},
                                {"orientation", {{"rotation", rotation}, {"translation", translation}}}}}}})}};
    return dir.write("single.json", file.dump());
}

}  // namespace

TEST_CASE("Replica room0: node counts, kinds and source ids", "[import][replica]") {
    SceneData scene = readReplica(replicaPath(), "room0");
    REQUIRE(scene.nodes.size() == 92);
    CHECK(scene.info.name == "room0");
    CHECK(scene.info.source == "replica:" + replicaPath());
    CHECK(scene.info.nodeCount == 92);
    CHECK(scene.relations.empty());

    int anchors = 0, planes = 0, objects = 0, hidden = 0;
    for (const Node& n : scene.nodes) {
        anchors += n.kind == NodeKind::Anchor;
        planes += n.geometry == GeometryKind::Plane;
        objects += n.kind == NodeKind::Object;
        hidden += n.hidden;
        CHECK(n.parent == kNoNode);
        CHECK(n.geometry != GeometryKind::None);
    }
    // 5 walls, 1 door, 9 windows, 8 blinds, 1 floor, 1 ceiling are planes; 2 pillars are boxes.
    CHECK(anchors == 27);
    CHECK(planes == 25);
    CHECK(objects == 65);
    CHECK(hidden == 12);  // the `undefined` parts

    // Local ids run 1..n in file order and the file's ids are kept as source ids.
    std::set<std::int64_t> sourceIds;
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
        CHECK(scene.nodes[i].id == i + 1);
        REQUIRE(scene.nodes[i].sourceId);
        sourceIds.insert(*scene.nodes[i].sourceId);
    }
    CHECK(sourceIds.size() == 92);
    CHECK(*scene.nodes.front().sourceId == 93);
    CHECK(*sourceIds.begin() == 1);
    CHECK(*sourceIds.rbegin() == 93);

    CHECK(bySourceId(scene, 35).category == "indoor-plant");
    CHECK(bySourceId(scene, 84).kind == NodeKind::Anchor);  // pillar
    CHECK(bySourceId(scene, 84).geometry == GeometryKind::Box);
    CHECK(bySourceId(scene, 25).category == "floor");
    CHECK(bySourceId(scene, 25).geometry == GeometryKind::Plane);
    CHECK(bySourceId(scene, 81).hidden);
    CHECK(bySourceId(scene, 81).kind == NodeKind::Object);
}

TEST_CASE("Replica room0: box centres are R * abb.center + translation", "[import][replica]") {
    SceneData scene = readReplica(replicaPath(), "room0");
    const Node& table = bySourceId(scene, 93);
    CHECK(table.category == "table");
    CHECK(table.kind == NodeKind::Object);
    CHECK(table.box.center.x == Approx(5.20).margin(1e-2));
    CHECK(table.box.center.y == Approx(2.73).margin(1e-2));
    // Stored in the upright floor frame: the file's z less the floor's top (-1.47), kept in the alignment.
    CHECK(table.box.center.z == Approx(-1.15 + 1.47).margin(1e-2));
    CHECK(scene.info.alignment[11] == Approx(1.47).margin(1e-2));
    CHECK(table.box.yaw == Approx(0.23).margin(1e-2));
    CHECK(table.box.size.x == Approx(0.49288225173950195));
    CHECK(table.box.size.y == Approx(0.4848257303237915));
    CHECK(table.box.size.z == Approx(0.6780940890312195));

    // The floor lies under the table, its top at z = 0, and the door stands on the floor.
    const Node& floor = bySourceId(scene, 25);
    CHECK(footprintContains(floor.box, {table.box.center.x, table.box.center.y}));
    CHECK(top(floor.box) == Approx(0).margin(1e-9));
    CHECK(bottom(bySourceId(scene, 36).box) == Approx(top(floor.box)).margin(0.05));
}

TEST_CASE("Replica room0: default viewpoint inside the room, facing into it", "[import][replica]") {
    SceneData scene = readReplica(replicaPath(), "room0");
    const Viewpoint& view = scene.info.viewpoint;
    const Node& floor = bySourceId(scene, 25);
    const Node& door = bySourceId(scene, 36);
    const Node& largestWall = bySourceId(scene, 33);

    CHECK(footprintContains(floor.box, {view.position.x, view.position.y}));
    CHECK(view.position.z == Approx(top(floor.box) + 1.6));
    // 0.5 m from the door's centre.
    CHECK(std::hypot(view.position.x - door.box.center.x, view.position.y - door.box.center.y) == Approx(0.5));
    // Facing into the room: towards the floor's centre, along an axis of the largest wall.
    double towardsCentre = std::cos(view.facingYaw) * (floor.box.center.x - view.position.x) +
                           std::sin(view.facingYaw) * (floor.box.center.y - view.position.y);
    CHECK(towardsCentre > 1.0);
    double quarterTurns = (view.facingYaw - largestWall.box.yaw) / (std::numbers::pi / 2);
    CHECK(quarterTurns == Approx(std::round(quarterTurns)).margin(1e-9));
    CHECK_THAT(scene.info.viewpointNote, Catch::Contains("door #36") && Catch::Contains("wall #33"));
}

TEST_CASE("Replica: translation is added, tilted boxes fold to their world AABB", "[import][replica]") {
    TempDir dir;
    const double s = std::sin(std::numbers::pi / 8), c = std::cos(std::numbers::pi / 8);

    SECTION("a quarter turn about z, with a translation") {
        double h = std::sqrt(0.5);
        SceneData scene = readReplica(singleObject(dir, {0, 0, h, h}, {1, 0, 0}, {10, 20, 30}), "one");
        const Box& box = scene.nodes.at(0).box;
        CHECK(box.center.x == Approx(10).margin(1e-12));
        CHECK(box.center.y == Approx(21));
        // The one box is what stands lowest: it stands on the floor, 28.5 m below where the file has it.
        CHECK(box.center.z == Approx(1.5));
        CHECK(scene.info.alignment[11] == Approx(-28.5));
        CHECK(box.yaw == Approx(std::numbers::pi / 2));
        CHECK(box.size == Vec3{1, 2, 3});
        // No floor, no door: at the centre of the boxes, eye height above the lowest bottom, facing +y.
        CHECK(scene.info.viewpoint.position.z == Approx(1.6));
        CHECK(scene.info.viewpoint.facingYaw == Approx(std::numbers::pi / 2));
    }
    SECTION("45 degrees about x") {
        SceneData scene = readReplica(singleObject(dir, {s, 0, 0, c}, {0, 0, 0}, {0, 0, 0}), "one");
        const Box& box = scene.nodes.at(0).box;
        CHECK(box.yaw == 0);
        CHECK(box.size.x == Approx(1));
        CHECK(box.size.y == Approx((2 + 3) * std::sqrt(0.5)));
        CHECK(box.size.z == Approx((2 + 3) * std::sqrt(0.5)));
    }
    SECTION("a quaternion slightly off unit norm is normalised") {
        SceneData scene = readReplica(singleObject(dir, {0, 0, 0, 1.0005}, {1, 2, 3}, {0, 0, 0}), "one");
        CHECK(scene.nodes.at(0).box.center.x == Approx(1));
        CHECK(scene.nodes.at(0).box.yaw == 0);
    }
}

TEST_CASE("Replica: malformed files are rejected with the file and the field", "[import][replica][malformed]") {
    TempDir dir;
    auto mutated = [&](const std::function<void(OrderedJson&)>& change) {
        OrderedJson file = replicaJson();
        change(file);
        return dir.write("info_semantic.json", file.dump(1));
    };
    auto box = [](OrderedJson& file, int index) -> OrderedJson& { return file["objects"][index]["oriented_bbox"]; };

    SECTION("missing file") {
        std::string path = dir.path("absent.json");
        requireInputError([&] { readReplica(path, "r"); }, {path, "no such file"});
    }
    SECTION("a directory") {
        std::string path = dir.path("");
        requireInputError([&] { readReplica(path, "r"); }, {path, "directory"});
    }
    SECTION("empty file") {
        std::string path = dir.write("empty.json", "  \n");
        requireInputError([&] { readReplica(path, "r"); }, {path, "empty"});
    }
    SECTION("a class name that is not UTF-8") {
        std::string text = replicaJson().dump(1);
        text.insert(text.find("\"class_name\": \"") + 15, "\xE9");
        std::string path = dir.write("latin1.json", text);
        int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + text.find('\xE9'), '\n'));
        requireInputError([&] { readReplica(path, "r"); }, {path + ":" + std::to_string(line) + ":", "UTF-8", "\\xE9"},
                          line);
    }
    SECTION("truncated JSON reports line and column") {
        std::string text = replicaJson().dump(1);
        std::string path = dir.write("cut.json", text.substr(0, 5000));
        int lines = 1 + static_cast<int>(std::count(text.begin(), text.begin() + 5000, '\n'));
        requireInputError([&] { readReplica(path, "r"); }, {path + ":" + std::to_string(lines) + ":", "not valid JSON"},
                          lines);
    }
    SECTION("NaN is not JSON") {
        std::string path = dir.write("nan.json", "{\"objects\": [\n {\"id\": NaN}]}");
        requireInputError([&] { readReplica(path, "r"); }, {path + ":2:9", "not valid JSON"}, 2);
    }
    SECTION("number overflow") {
        std::string path = dir.write("huge.json", "{\"objects\": [{\"id\": 1e999}]}");
        requireInputError([&] { readReplica(path, "r"); }, {path, "1e999"});
    }
    SECTION("no objects array") {
        std::string path = mutated([](OrderedJson& f) { f.erase("objects"); });
        requireInputError([&] { readReplica(path, "r"); }, {path, "missing field 'objects'"});
    }
    SECTION("objects is not an array") {
        std::string path = mutated([](OrderedJson& f) { f["objects"] = "none"; });
        requireInputError([&] { readReplica(path, "r"); }, {path, "objects: expected an array, got a string"});
    }
    SECTION("empty objects array") {
        std::string path = mutated([](OrderedJson& f) { f["objects"] = OrderedJson::array(); });
        requireInputError([&] { readReplica(path, "r"); }, {path, "objects: empty"});
    }
    SECTION("sizes with two numbers") {
        std::string path = mutated([&](OrderedJson& f) { box(f, 12)["abb"]["sizes"] = {1.0, 2.0}; });
        requireInputError([&] { readReplica(path, "r"); },
                          {path + ": objects[12].oriented_bbox.abb.sizes: expected 3 numbers, got 2"});
    }
    SECTION("class_name of the wrong type") {
        std::string path = mutated([](OrderedJson& f) { f["objects"][3]["class_name"] = 4; });
        requireInputError([&] { readReplica(path, "r"); }, {path, "objects[3].class_name: expected a string"});
    }
    SECTION("missing abb") {
        std::string path = mutated([&](OrderedJson& f) { box(f, 0).erase("abb"); });
        requireInputError([&] { readReplica(path, "r"); }, {path, "objects[0].oriented_bbox: missing field 'abb'"});
    }
    SECTION("a string among the centre's numbers") {
        std::string path = mutated([&](OrderedJson& f) { box(f, 4)["abb"]["center"][1] = "2.0"; });
        requireInputError([&] { readReplica(path, "r"); }, {path, "objects[4].oriented_bbox.abb.center[1]"});
    }
    SECTION("a coordinate far outside any room") {
        std::string path = mutated([&](OrderedJson& f) { box(f, 5)["orientation"]["translation"] = {0.0, 2e4, 0.0}; });
        requireInputError([&] { readReplica(path, "r"); },
                          {path, "objects[5].oriented_bbox.orientation.translation", "from the origin"});
    }
    SECTION("negative size") {
        std::string path = mutated([&](OrderedJson& f) { box(f, 7)["abb"]["sizes"][2] = -0.5; });
        requireInputError([&] { readReplica(path, "r"); }, {path, "objects[7].oriented_bbox.abb.sizes", "-0.5"});
    }
    SECTION("huge size") {
        std::string path = mutated([&](OrderedJson& f) { box(f, 7)["abb"]["sizes"][0] = 5000.0; });
        requireInputError([&] { readReplica(path, "r"); }, {path, "objects[7].oriented_bbox.abb.sizes"});
    }
    SECTION("zero quaternion") {
        std::string path = mutated([&](OrderedJson& f) {
            box(f, 8)["orientation"]["rotation"] = {0.0, 0.0, 0.0, 0.0};
        });
        requireInputError([&] { readReplica(path, "r"); },
                          {path, "objects[8].oriented_bbox.orientation.rotation", "unit quaternion"});
    }
    SECTION("quaternion far from unit norm") {
        std::string path = mutated([&](OrderedJson& f) {
            box(f, 8)["orientation"]["rotation"] = {0.0, 0.0, 0.0, 1.1};
        });
        requireInputError([&] { readReplica(path, "r"); }, {path, "objects[8].oriented_bbox.orientation.rotation"});
    }
    SECTION("duplicate ids") {
        std::string path = mutated([](OrderedJson& f) { f["objects"][9]["id"] = f["objects"][2]["id"]; });
        requireInputError([&] { readReplica(path, "r"); }, {path, "objects[9].id: duplicate id", "objects[2].id"});
    }
    SECTION("a key given twice in one object") {
        std::string path = dir.write("twice.json", "{\"objects\": [{\"id\": 1}, {\"id\": 2, \"id\": 3}]}");
        requireInputError([&] { readReplica(path, "r"); }, {path, "objects[1].id", "twice"});
    }
    SECTION("an id that is not an integer") {
        std::string path = mutated([](OrderedJson& f) { f["objects"][1]["id"] = 1.5; });
        requireInputError([&] { readReplica(path, "r"); }, {path, "objects[1].id: expected an integer"});
    }
}
