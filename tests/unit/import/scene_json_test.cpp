#include <fstream>
#include <functional>
#include <iterator>

#include <nlohmann/json.hpp>

#include "import_support.hpp"
#include "ingest/import/importers.hpp"
#include "model/utf8.hpp"

using smql::import::readReplica;
using smql::import::readSceneJson;
using smql::import::writeSceneJson;
using smql::import::test::replicaPath;
using smql::import::test::requireInputError;
using smql::import::test::TempDir;
using namespace smql::model;
using OrderedJson = nlohmann::ordered_json;

namespace {

// The Replica scene with every field of the format in use.
SceneData richScene() {
    SceneData scene = readReplica(replicaPath(), "room0");
    scene.info.captureTime = "2019-06-11T10:00:00Z";
    scene.info.alignment = {0, -1, 0, 0.5, 1, 0, 0, 1.0 / 3, 0, 0, 1, 0, 0, 0, 0, 1};
    scene.info.scale = 0.999;
    scene.nodes[0].parent = 60;  // table 93 on the rug
    scene.nodes[0].attributes = {{"color", "brown"}, {"material", "wood"}, {"size", "small"}};
    scene.nodes[0].text = "a small \"wooden\" table\nby the window";
    scene.nodes[0].confidence = 0.7f;
    Node frame;
    frame.id = scene.nodes.size() + 1;
    frame.kind = NodeKind::Frame;
    frame.text = "frame 1";
    scene.nodes.push_back(frame);
    scene.info.nodeCount = scene.nodes.size();
    scene.relations.push_back({1, 60, RelationType::On, 0.9f, 3, kNoNode});
    scene.relations.push_back({2, 1, RelationType::LeftOf, 0.55f, 1, frame.id});
    return scene;
}

}  // namespace

TEST_CASE("smql JSON: the Replica scene round-trips", "[import][json]") {
    TempDir dir;
    SECTION("as imported") {
        SceneData scene = readReplica(replicaPath(), "room0");
        std::string written = writeSceneJson(scene);
        std::string path = dir.write("room0.json", written);
        SceneData back = readSceneJson(path);
        CHECK(back.info == scene.info);
        CHECK(back.nodes == scene.nodes);
        CHECK(back.relations == scene.relations);
        CHECK(writeSceneJson(back) == written);
    }
    SECTION("with attributes, parents, text, a frame and relations") {
        SceneData scene = richScene();
        std::string written = writeSceneJson(scene);
        SceneData back = readSceneJson(dir.write("rich.json", written));
        CHECK(back.info == scene.info);
        CHECK(back.nodes == scene.nodes);
        CHECK(back.relations == scene.relations);
        CHECK(writeSceneJson(back) == written);
        CHECK_THAT(written, Catch::Contains("\"confidence\": 0.7,"));
    }
    SECTION("with evidence blobs of every length modulo 3, binary bytes included") {
        SceneData scene = readReplica(replicaPath(), "room0");
        scene.blobs.push_back({1, "evidence-frame3.jpg", "image/jpeg", std::string("\xff\xd8\xff\0\x01\x80", 6)});
        scene.blobs.push_back({2, "a.bin", "application/octet-stream", "ab"});
        scene.blobs.push_back({2, "b.bin", "application/octet-stream", "abcd"});
        std::string written = writeSceneJson(scene);
        SceneData back = readSceneJson(dir.write("blobs.json", written));
        CHECK(back.blobs == scene.blobs);
        CHECK(writeSceneJson(back) == written);
    }
}

TEST_CASE("smql JSON: optional fields take their defaults", "[import][json]") {
    TempDir dir;
    std::string path = dir.write("min.json", R"({"smql_scene": 1, "scene": {"name": "tiny"}, "nodes": [
        {"id": 1, "kind": "anchor", "category": "floor", "geometry": "plane",
         "box": {"center": [0, 0, 0], "size": [4, 3, 0.05]}},
        {"id": 2, "kind": "object", "parent": 1, "category": "mug",
         "box": {"center": [1, 1, 0.1], "size": [0.1, 0.1, 0.12], "yaw": 0.5}}]})");
    SceneData scene = readSceneJson(path);
    CHECK(scene.info.name == "tiny");
    // The floor's top was 2.5 cm up: the scene stands on it, the move kept in the alignment.
    Transform moved = kIdentity;
    moved[11] = -0.025;
    CHECK(scene.info.alignment == moved);
    CHECK(scene.nodes[1].box.center.z == Approx(0.075));
    CHECK(scene.info.scale == 1.0);
    CHECK(scene.info.nodeCount == 2);
    REQUIRE(scene.nodes.size() == 2);
    CHECK(scene.nodes[0].geometry == GeometryKind::Plane);
    CHECK(scene.nodes[1].geometry == GeometryKind::Box);  // a box without "geometry" is a box
    CHECK(scene.nodes[1].parent == 1);
    CHECK(scene.nodes[1].confidence == 1.0f);
    CHECK_FALSE(scene.nodes[1].sourceId);
    CHECK_FALSE(scene.nodes[1].hidden);
    CHECK(scene.relations.empty());
    std::string written = writeSceneJson(scene);
    CHECK(writeSceneJson(readSceneJson(dir.write("again.json", written))) == written);
}

TEST_CASE("smql JSON: malformed scenes are rejected with the file and the JSON path", "[import][json][malformed]") {
    TempDir dir;
    OrderedJson base = OrderedJson::parse(writeSceneJson(richScene()));
    auto mutated = [&](const std::function<void(OrderedJson&)>& change) {
        OrderedJson file = base;
        change(file);
        return dir.write("scene.json", file.dump(2));
    };
    auto read = [](const std::string& path) { return [path] { readSceneJson(path); }; };

    SECTION("missing file") {
        std::string path = dir.path("none.json");
        requireInputError(read(path), {path, "no such file"});
    }
    SECTION("truncated") {
        std::string path = dir.write("cut.json", base.dump(2).substr(0, 300));
        requireInputError(read(path), {path + ":", "not valid JSON"});
    }
    SECTION("a blob that is not base64, or of no node") {
        std::string path = mutated([](OrderedJson& f) {
            f["blobs"] = OrderedJson::array(
                {{{"node", 1}, {"name", "x.jpg"}, {"media_type", "image/jpeg"}, {"base64", "ab!d"}}});
        });
        requireInputError(read(path), {path, "blobs[0].base64", "not base64"});
        path = mutated([](OrderedJson& f) {
            f["blobs"] = OrderedJson::array(
                {{{"node", 99999}, {"name", "x.jpg"}, {"media_type", "image/jpeg"}, {"base64", ""}}});
        });
        requireInputError(read(path), {path, "blobs[0].node", "not the id of a node"});
    }
    SECTION("a capture time that is no time, an alignment that is no rotation, a scale of no room") {
        std::string path = mutated([](OrderedJson& f) { f["scene"]["capture_time"] = "yesterday-ish"; });
        requireInputError(read(path), {path, "scene.capture_time", "'yesterday-ish' is no date and time"});
        path = mutated([](OrderedJson& f) {
            f["scene"]["alignment"] = OrderedJson::array({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
        });
        requireInputError(read(path), {path, "scene.alignment", "not a rotation and a scale"});
        path = mutated([](OrderedJson& f) {
            f["scene"]["alignment"] = OrderedJson::array({1e300, 0, 0, 0, 0, 1e300, 0, 0, 0, 0, 1e300, 0, 0, 0, 0, 1});
        });
        requireInputError(read(path), {path, "scene.alignment", "not a rotation and a scale"});
        path = mutated([](OrderedJson& f) {
            f["scene"]["alignment"] = OrderedJson::array({1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1});
        });
        requireInputError(read(path), {path, "scene.alignment", "not a rotation and a scale"});
        path = mutated([](OrderedJson& f) { f["scene"]["scale"] = 1e300; });
        requireInputError(read(path), {path, "scene.scale", "not a plausible number of metres per capture unit"});
        // A time in another written form is kept in UTC's one form, so that AS OF compares it.
        path = mutated([](OrderedJson& f) { f["scene"]["capture_time"] = "2026-11-21 12:00+02:00"; });
        CHECK(readSceneJson(path).info.captureTime == "2026-11-21T10:00:00Z");
    }
    SECTION("a NUL in a name or a text, which would cut it short and stop every later fleet push") {
        std::string path = mutated([](OrderedJson& f) { f["nodes"][0]["text"] = std::string("a\0b", 3); });
        requireInputError(read(path), {path, "nodes[0].text", "NUL"});
        path = mutated([](OrderedJson& f) { f["nodes"][0]["category"] = std::string("so\0fa", 5); });
        requireInputError(read(path), {path, "nodes[0].category", "NUL"});
    }
    SECTION("a yaw that is not a plausible number of radians") {
        std::string path = mutated([](OrderedJson& f) { f["nodes"][0]["box"]["yaw"] = 1e300; });
        requireInputError(read(path), {path, "nodes[0].box.yaw: 1e+300 is not an angle in radians"});
        path = mutated([](OrderedJson& f) { f["scene"]["viewpoint"]["facing_yaw"] = -180; });
        requireInputError(read(path), {path, "scene.viewpoint.facing_yaw: -180 is not an angle", "degrees"});
    }
    SECTION("text that is not UTF-8 is named by line and column, and the message stays UTF-8") {
        std::string text = base.dump(2);
        std::size_t at = text.find("\"category\": \"") + 13;
        text.insert(at, "caf\xE9");
        std::string path = dir.write("latin1.json", text);
        requireInputError(read(path), {path + ":", "not valid JSON", "\\xE9"});
        try {
            readSceneJson(path);
        } catch (const smql::Error& e) {
            CHECK_FALSE(smql::model::invalidUtf8At(e.message()).has_value());
        }
    }
    SECTION("unsupported version") {
        std::string path = mutated([](OrderedJson& f) { f["smql_scene"] = 2; });
        requireInputError(read(path), {path, "smql_scene: unsupported version 2"});
    }
    SECTION("missing scene name") {
        std::string path = mutated([](OrderedJson& f) { f["scene"].erase("name"); });
        requireInputError(read(path), {path, "scene: missing field 'name'"});
    }
    SECTION("alignment with 15 numbers") {
        std::string path = mutated([](OrderedJson& f) { f["scene"]["alignment"].erase(15); });
        requireInputError(read(path), {path, "scene.alignment: expected 16 numbers, got 15"});
    }
    SECTION("a misspelt field") {
        std::string path = mutated([](OrderedJson& f) { f["nodes"][4]["hiden"] = true; });
        requireInputError(read(path), {path, "nodes[4].hiden: unknown field"});
    }
    SECTION("unknown kind") {
        std::string path = mutated([](OrderedJson& f) { f["nodes"][3]["kind"] = "furniture"; });
        requireInputError(read(path), {path, "nodes[3].kind: unknown kind 'furniture'"});
    }
    SECTION("unknown geometry") {
        std::string path = mutated([](OrderedJson& f) { f["nodes"][3]["geometry"] = "sphere"; });
        requireInputError(read(path), {path, "nodes[3].geometry: unknown geometry 'sphere'"});
    }
    SECTION("geometry without a box") {
        std::string path = mutated([](OrderedJson& f) { f["nodes"][5].erase("box"); });
        requireInputError(read(path), {path, "nodes[5]: missing field 'box'"});
    }
    SECTION("negative size") {
        std::string path = mutated([](OrderedJson& f) { f["nodes"][6]["box"]["size"][0] = -1.0; });
        requireInputError(read(path), {path, "nodes[6].box.size", "-1"});
    }
    SECTION("parent that is not a node") {
        std::string path = mutated([](OrderedJson& f) { f["nodes"][2]["parent"] = 500; });
        requireInputError(read(path), {path, "nodes[2].parent: parent 500 is not the id of a node"});
    }
    SECTION("cycle in parents") {
        std::string path = mutated([](OrderedJson& f) {
            f["nodes"][1]["parent"] = 3;
            f["nodes"][2]["parent"] = 2;
        });
        requireInputError(read(path), {path, "parents form a cycle: 2 -> 3 -> 2"});
    }
    SECTION("duplicate node ids") {
        std::string path = mutated([](OrderedJson& f) { f["nodes"][7]["id"] = 3; });
        requireInputError(read(path), {path, "nodes[7].id: duplicate id 3"});
    }
    SECTION("an id out of range") {
        std::string path = mutated([](OrderedJson& f) { f["nodes"][7]["id"] = 0; });
        requireInputError(read(path), {path, "nodes[7].id: id 0 is out of range"});
    }
    SECTION("an attribute that is not a string") {
        std::string path = mutated([](OrderedJson& f) { f["nodes"][0]["attributes"]["size"] = 3; });
        requireInputError(read(path), {path, "nodes[0].attributes.size: expected a string"});
    }
    SECTION("confidence above 1") {
        std::string path = mutated([](OrderedJson& f) { f["nodes"][0]["confidence"] = 1.5; });
        requireInputError(read(path), {path, "nodes[0].confidence", "out of range"});
    }
    SECTION("unknown relation type") {
        std::string path = mutated([](OrderedJson& f) { f["relations"][0]["type"] = "under"; });
        requireInputError(read(path), {path, "relations[0].type: unknown relation type 'under'"});
    }
    SECTION("relation to a missing node") {
        std::string path = mutated([](OrderedJson& f) { f["relations"][1]["object"] = 1000; });
        requireInputError(read(path), {path, "relations[1].object: 1000 is not the id of a node"});
    }
    SECTION("relation frame that is not a frame") {
        std::string path = mutated([](OrderedJson& f) { f["relations"][1]["frame"] = 5; });
        requireInputError(read(path), {path, "relations[1].frame: node 5 has kind anchor, not frame"});
    }
    SECTION("support of zero") {
        std::string path = mutated([](OrderedJson& f) { f["relations"][0]["support"] = 0; });
        requireInputError(read(path), {path, "relations[0].support"});
    }
}

TEST_CASE("smql JSON: text that is not UTF-8 is written with U+FFFD rather than failing the export", "[import][json]") {
    // A database written before imports checked their text may hold some.
    smql::model::SceneData scene = richScene();
    scene.nodes[0].category = "caf\xE9";
    std::string written;
    REQUIRE_NOTHROW(written = writeSceneJson(scene));
    CHECK_THAT(written, Catch::Contains("\"caf\xEF\xBF\xBD\""));
}

TEST_CASE("smql JSON: the example in docs/formats.md reads and writes back unchanged", "[import][json]") {
    std::ifstream doc(std::string(SMQL_SOURCE_DIR) + "/docs/formats.md");
    std::string text((std::istreambuf_iterator<char>(doc)), std::istreambuf_iterator<char>());
    std::size_t begin = text.find("```json\n");
    REQUIRE(begin != std::string::npos);
    begin += 8;
    std::string example = text.substr(begin, text.find("```", begin) - begin);

    TempDir dir;
    SceneData scene = readSceneJson(dir.write("example.json", example));
    CHECK(scene.nodes.size() == 3);
    CHECK(scene.relations.size() == 1);
    CHECK(writeSceneJson(scene) == example);
}
