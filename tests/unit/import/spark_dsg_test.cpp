// Spark-DSG both ways: the graph as Spark-DSG's JSON reader expects it (header, layers, NodeSymbol
// ids, attribute types, interlayer parent edges, label spaces), the round trip smql -> Spark-DSG ->
// smql on the Replica room, a Hydra-style graph with places, agents and a mesh, and malformed files.
#include <cmath>
#include <numbers>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "exported_scenes.hpp"
#include "ingest/import/importers.hpp"
#include "ingest/import/registry.hpp"
#include "model/category.hpp"

using namespace smql;
using Catch::Detail::Approx;
using import::test::requireInputError;
using import::test::TempDir;
using Json = nlohmann::json;

namespace {

constexpr std::uint64_t kObject = std::uint64_t{'O'} << 56;
constexpr std::uint64_t kRoom = std::uint64_t{'R'} << 56;
constexpr std::uint64_t kBuilding = std::uint64_t{'B'} << 56;
constexpr std::uint64_t kPlace = std::uint64_t{'p'} << 56;

const Json& nodeById(const Json& graph, std::uint64_t id) {
    for (const Json& node : graph.at("nodes"))
        if (node.at("id") == id) return node;
    FAIL("no node " << id);
    throw;
}

// The end in the higher layer of every edge between layers, by the other end.
std::map<std::uint64_t, std::uint64_t> interlayerParents(const Json& graph) {
    std::map<std::uint64_t, int> layer;
    for (const Json& node : graph.at("nodes")) layer[node.at("id")] = node.at("layer");
    std::map<std::uint64_t, std::uint64_t> parents;
    for (const Json& edge : graph.at("edges")) {
        std::uint64_t source = edge.at("source"), target = edge.at("target");
        if (layer.at(source) > layer.at(target)) CHECK(parents.emplace(target, source).second);
        if (layer.at(source) < layer.at(target)) CHECK(parents.emplace(source, target).second);
    }
    return parents;
}

double turned(double yaw) { return std::remainder(yaw, 2 * std::numbers::pi); }

// What the round trip keeps: categories, kinds, boxes, parents, hidden, source ids and attributes.
void requireSameScene(const model::SceneData& back, const model::SceneData& scene) {
    REQUIRE(back.nodes.size() == scene.nodes.size());
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
        const model::Node& a = scene.nodes[i];
        const model::Node& b = back.nodes[i];
        INFO(a.category << "#" << a.id);
        CHECK(b.id == a.id);
        CHECK(b.category == model::categoryName(a.category));  // stored by its canonical name
        CHECK(b.kind == a.kind);
        CHECK(b.geometry == a.geometry);
        CHECK(b.parent == a.parent);
        CHECK(b.hidden == a.hidden);
        CHECK(b.sourceId == a.sourceId);
        CHECK(b.attributes == a.attributes);
        if (a.geometry == model::GeometryKind::None) continue;
        CHECK(b.box.center.x == Approx(a.box.center.x).margin(1e-9));
        CHECK(b.box.center.y == Approx(a.box.center.y).margin(1e-9));
        CHECK(b.box.center.z == Approx(a.box.center.z).margin(1e-9));
        CHECK(b.box.size.x == Approx(a.box.size.x).margin(1e-9));
        CHECK(b.box.size.y == Approx(a.box.size.y).margin(1e-9));
        CHECK(b.box.size.z == Approx(a.box.size.z).margin(1e-9));
        CHECK(turned(b.box.yaw - a.box.yaw) == Approx(0).margin(1e-9));
    }
}

}  // namespace

TEST_CASE("spark-dsg: the Replica room as Hydra's layers", "[import][spark-dsg]") {
    model::SceneData scene = import::test::replicaScene();
    Json graph = Json::parse(import::writeSparkDsg(scene));

    CHECK(graph.at("SPARK_DSG_header").at("project_name") == "main");
    CHECK(graph.at("SPARK_DSG_header").at("version") == Json{{"major", 1}, {"minor", 1}, {"patch", 3}});
    CHECK(graph.at("directed") == false);
    CHECK(graph.at("layer_names").at("OBJECTS") == Json{{"layer", 2}, {"partition", 0}});
    CHECK(graph.at("layer_names").at("ROOMS") == Json{{"layer", 4}, {"partition", 0}});
    CHECK(graph.at("layer_keys").size() == 4);
    CHECK(graph.at("metadata").at("smql").at("scene") == "replica-room0");
    REQUIRE(graph.at("nodes").size() == scene.nodes.size() + 1);

    // The scene is the room layer's node R(0), every node of the object layer hangs below it.
    const Json& room = nodeById(graph, kRoom);
    CHECK(room.at("layer") == 4);
    CHECK(room.at("attributes").at("type") == "RoomNodeAttributes");
    CHECK(room.at("attributes").at("name") == "replica-room0");
    CHECK(room.at("attributes").at("bounding_box").at("type") == "AABB");
    std::map<std::uint64_t, std::uint64_t> parents = interlayerParents(graph);

    std::map<std::uint64_t, std::string> labels;
    for (const Json& pair : graph.at("metadata").at("labelspaces").at("_l2p0")) labels[pair[0]] = pair[1];
    for (const model::Node& n : scene.nodes) {
        INFO(n.category << "#" << n.id);
        const Json& node = nodeById(graph, kObject | n.id);
        const Json& attributes = node.at("attributes");
        CHECK(node.at("layer") == 2);
        CHECK(node.at("partition") == 0);
        CHECK(attributes.at("type") == "ObjectNodeAttributes");
        CHECK(attributes.at("name") == n.category + "#" + std::to_string(n.id));
        CHECK(labels.at(attributes.at("semantic_label")) == n.category);
        CHECK(attributes.at("bounding_box").at("type") == "OBB");
        CHECK(attributes.at("bounding_box").at("dimensions")[2].get<double>() == Approx(n.box.size.z));
        CHECK(attributes.at("bounding_box").at("world_R_center").at("z").get<double>() ==
              Approx(std::sin(n.box.yaw / 2)));
        CHECK(attributes.at("position")[0].get<double>() == Approx(n.box.center.x));
        CHECK(parents.at(kObject | n.id) == kRoom);
        CHECK(attributes.at("metadata").at("smql").at("kind") == model::toString(n.kind));
        if (n.parent != model::kNoNode)
            CHECK(attributes.at("metadata").at("smql").at("parent") == (kObject | n.parent));
    }
}

TEST_CASE("spark-dsg: the round trip smql -> Spark-DSG -> smql keeps the Replica room", "[import][spark-dsg]") {
    model::SceneData scene = import::test::replicaScene();
    std::size_t nested = 0;
    for (const model::Node& n : scene.nodes) nested += n.parent != model::kNoNode;
    REQUIRE(nested > 40);  // objects below walls, and on other objects

    TempDir dir;
    std::string file = dir.write("room.json", import::write("spark-dsg", scene));
    model::SceneData back = import::read("spark-dsg", file);
    CHECK(back.info.name == "replica-room0");
    CHECK(back.info.source == "spark-dsg:" + file);
    requireSameScene(back, scene);
    CHECK(import::read("spark-dsg", file, "again").info.name == "again");
}

TEST_CASE("spark-dsg: a scene with rooms is a building; nested objects keep their parents", "[import][spark-dsg]") {
    model::SceneData scene = import::test::roomsScene();
    Json graph = Json::parse(import::writeSparkDsg(scene));
    const Json& building = nodeById(graph, kBuilding);
    CHECK(building.at("layer") == 5);
    CHECK(nodeById(graph, kRoom | 1).at("attributes").at("type") == "RoomNodeAttributes");
    std::map<std::uint64_t, std::uint64_t> parents = interlayerParents(graph);
    CHECK(parents.at(kRoom | 1) == kBuilding);
    CHECK(parents.at(kObject | 5) == (kRoom | 1));  // the mug is in the kitchen...
    bool onTable = false;                           // ...and on the table, an edge in the object layer
    for (const Json& edge : graph.at("edges"))
        onTable = onTable || (edge.at("source") == (kObject | 4) && edge.at("target") == (kObject | 5));
    CHECK(onTable);
    std::map<std::uint64_t, std::string> roomLabels;
    for (const Json& pair : graph.at("metadata").at("labelspaces").at("_l4p0")) roomLabels[pair[0]] = pair[1];
    CHECK(roomLabels == std::map<std::uint64_t, std::string>{{0, "kitchen"}, {1, "living room"}});

    TempDir dir;
    model::SceneData back = import::read("spark-dsg", dir.write("flat.json", import::writeSparkDsg(scene)));
    CHECK(back.info.name == "flat");
    requireSameScene(back, scene);
}

TEST_CASE("spark-dsg: a Hydra graph's objects and rooms; places, agents and the mesh skipped", "[import][spark-dsg]") {
    auto bbox = [](Json center, Json extra) {
        Json box = {
            {"type", "AABB"}, {"world_P_center", center}, {"world_R_center", {{"w", 1}, {"x", 0}, {"y", 0}, {"z", 0}}}};
        box.update(extra);
        return box;
    };
    auto node = [](std::uint64_t id, int layer, Json attributes) {
        return Json{{"id", id}, {"layer", layer}, {"partition", 0}, {"attributes", attributes}};
    };
    Json graph = {
        {"SPARK_DSG_header", {{"project_name", "main"}, {"version", {{"major", 1}, {"minor", 1}, {"patch", 2}}}}},
        {"metadata", {{"labelspaces", {{"_l2p0", Json::array({Json::array({3, "chair"})})}}}}},
        {"nodes",
         {node(kObject | 0, 2,
               {{"type", "ObjectNodeAttributes"},
                {"semantic_label", 3},
                {"name", "O(0)"},
                {"bounding_box", bbox({1.0, 2.0, 0.45}, {{"dimensions", {0.5, 0.6, 0.9}}})}}),
          // Before Spark-DSG 1.0.3 a box gave min and max.
          node(kObject | 1, 2,
               {{"type", "ObjectNodeAttributes"},
                {"semantic_label", 5},
                {"bounding_box", bbox({3.0, 1.0, 0.5}, {{"min", {2.5, 0.5, 0.0}}, {"max", {3.5, 1.5, 1.0}}})}}),
          node(kPlace | 7, 3, {{"type", "PlaceNodeAttributes"}, {"distance", 0.8}, {"position", {1, 2, 1}}}),
          node(kRoom | 0, 4,
               {{"type", "RoomNodeAttributes"},
                {"name", "R(0)"},
                {"semantic_label", 0},
                {"bounding_box", {{"type", "INVALID"}}}}),
          node(std::uint64_t{'B'} << 56, 5, {{"type", "SemanticNodeAttributes"}}),
          {{"id", std::uint64_t{'a'} << 56},
           {"layer", 2},
           {"partition", 97},
           {"attributes", {{"type", "AgentNodeAttributes"}, {"position", {0, 0, 1}}}}}}},
        {"edges",
         {{{"source", kPlace | 7}, {"target", kObject | 0}},
          {{"source", kRoom | 0}, {"target", kPlace | 7}},
          {{"source", kObject | 1}, {"target", kObject | 0}}}},
        {"mesh", {{"vertices", Json::array()}, {"faces", Json::array()}}},
    };
    TempDir dir;
    model::SceneData scene = import::read("spark-dsg", dir.write("hydra_dsg.json", graph.dump()));
    CHECK(scene.info.name == "hydra_dsg");
    REQUIRE(scene.nodes.size() == 3);
    const model::Node& chair = scene.nodes[0];
    CHECK(chair.category == "chair");
    CHECK(chair.kind == model::NodeKind::Object);
    CHECK(chair.box.size.y == Approx(0.6));
    CHECK(chair.sourceId == static_cast<std::int64_t>(kObject));
    CHECK(chair.parent == 3);  // through its place, the room
    const model::Node& unnamed = scene.nodes[1];
    CHECK(unnamed.category == "label-5");
    CHECK(unnamed.box.size.x == Approx(1.0));
    CHECK(unnamed.parent == model::kNoNode);  // an edge within the layer makes no parent
    CHECK(scene.nodes[2].kind == model::NodeKind::Room);
    CHECK(scene.nodes[2].category == "room");
    CHECK(scene.nodes[2].geometry == model::GeometryKind::None);
}

TEST_CASE("spark-dsg: malformed graphs are input errors naming the field", "[import][spark-dsg]") {
    TempDir dir;
    Json object = {{"id", kObject | 1}, {"layer", 2}, {"attributes", {{"type", "ObjectNodeAttributes"}}}};
    auto withNodes = [](Json nodes, Json edges = Json::array()) {
        return Json{{"nodes", std::move(nodes)}, {"edges", std::move(edges)}}.dump();
    };
    auto read = [&](const std::string& text) {
        std::string path = dir.write("bad.json", text);
        return [path] { import::read("spark-dsg", path); };
    };

    requireInputError(read(R"({"edges": []})"), {"bad.json", "missing field 'nodes'"});
    requireInputError(read(withNodes({object, object})), {"nodes[1].id", "duplicate node id"});
    requireInputError(read(withNodes({object}, {{{"source", kObject | 1}, {"target", kObject | 9}}})),
                      {"edges[0].target", "no node of the file has id"});
    Json tilted = object;
    tilted["attributes"]["bounding_box"] = {{"type", "OBB"},
                                            {"dimensions", {1, 1, 1}},
                                            {"world_P_center", {0, 0, 0}},
                                            {"world_R_center", {{"w", 2}, {"x", 0}, {"y", 0}, {"z", 0}}}};
    requireInputError(read(withNodes({tilted})), {"nodes[0].attributes.bounding_box.world_R_center", "norm 2"});
    Json flat = tilted;
    flat["attributes"]["bounding_box"]["world_R_center"]["w"] = 1;
    flat["attributes"]["bounding_box"]["dimensions"] = {1, 0, 1};
    requireInputError(read(withNodes({flat})), {"bounding_box.dimensions", "size 0 is out of range"});
    Json unknownBox = flat;
    unknownBox["attributes"]["bounding_box"]["type"] = "SPHERE";
    requireInputError(read(withNodes({unknownBox})), {"bounding_box.type", "unknown bounding box type 'SPHERE'"});
    Json lostParent = object;
    lostParent["attributes"]["metadata"] = {{"smql", {{"kind", "object"}, {"parent", kObject | 4}}}};
    requireInputError(read(withNodes({lostParent})), {"metadata.smql.parent", "no node of the file smql reads"});
    // An object of the object layer that says it is the scene would take the scene's place.
    Json sceneObject = object;
    sceneObject["attributes"]["metadata"] = {{"smql", {{"kind", "scene"}}}};
    requireInputError(
        read(withNodes({sceneObject, object})),
        {"nodes[0].attributes.metadata.smql.kind", "the scene is a room or building node, not one of layer 2"});
}
