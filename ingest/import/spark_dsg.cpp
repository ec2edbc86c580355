// Hydra's scene graphs in Spark-DSG's JSON encoding, both ways (docs/formats.md, "Spark-DSG"): walls,
// doors, windows and objects are nodes of the object layer (2), the scene and its rooms nodes of the
// room layer (4), each node hanging below its room by an interlayer edge as Hydra's are; what smql
// keeps and Spark-DSG has no field for rides in each node's `metadata.smql`. On the way in, what smql
// has no place for (places, agents, buildings, the mesh) is skipped.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <unordered_map>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "ingest/import/common.hpp"
#include "ingest/import/export_support.hpp"
#include "ingest/import/importers.hpp"
#include "ingest/import/json_field.hpp"
#include "ingest/import/oriented_box.hpp"
#include "ingest/import/viewpoint.hpp"
#include "model/geometry.hpp"

namespace smql::import {

namespace {

using detail::Field;
using detail::Json;
using detail::vec3Json;

// Spark-DSG's layers (DsgLayers::OBJECTS, ROOMS, BUILDINGS).
constexpr std::int64_t kObjectLayer = 2;
constexpr std::int64_t kRoomLayer = 4;
constexpr std::int64_t kBuildingLayer = 5;
constexpr std::uint32_t kNoSemanticLabel = std::numeric_limits<std::uint32_t>::max();
// The node attribute types of the object layer that are things (Hydra's agents share the layer).
constexpr std::string_view kObjectTypes[] = {"ObjectNodeAttributes", "KhronosObjectAttributes",
                                             "SemanticNodeAttributes"};

// A node id is a NodeSymbol: a letter in the top byte ('O' objects, 'R' rooms, 'B' buildings), an
// index below it.
std::uint64_t symbol(char prefix, std::uint64_t index) {
    return std::uint64_t{static_cast<unsigned char>(prefix)} << 56 | index;
}

// Where Spark-DSG's Labelspace keeps a layer's label names in the graph's metadata.
std::string labelspaceKey(std::int64_t layer) { return fmt::format("_l{}p0", layer); }

// ---- writing ----------------------------------------------------------------------------------

Json yawQuaternion(double yaw) { return {{"w", std::cos(yaw / 2)}, {"x", 0.0}, {"y", 0.0}, {"z", std::sin(yaw / 2)}}; }

// Spark-DSG's BoundingBox: OBB for smql's upright boxes, AABB for a room's extent, INVALID for none.
Json boundingBox(const std::optional<model::Box>& box, const char* type) {
    model::Box b = box.value_or(model::Box{});
    return {{"type", box ? type : "INVALID"},
            {"dimensions", vec3Json(b.size)},
            {"world_P_center", vec3Json(b.center)},
            {"world_R_center", yawQuaternion(b.yaw)}};
}

// The world-aligned box around every placed box: the extent of the scene's room node.
std::optional<model::Box> sceneExtent(const model::SceneData& scene) {
    std::optional<model::Aabb> all;
    for (const model::Node& n : scene.nodes) {
        if (!detail::isDrawn(n)) continue;
        model::Aabb a = model::worldAabb(n.box);
        if (!all) all = a;
        all->min = {std::min(all->min.x, a.min.x), std::min(all->min.y, a.min.y), std::min(all->min.z, a.min.z)};
        all->max = {std::max(all->max.x, a.max.x), std::max(all->max.y, a.max.y), std::max(all->max.z, a.max.z)};
    }
    if (!all) return std::nullopt;
    model::Box box;
    box.center = {(all->min.x + all->max.x) / 2, (all->min.y + all->max.y) / 2, (all->min.z + all->max.z) / 2};
    box.size = {all->max.x - all->min.x, all->max.y - all->min.y, all->max.z - all->min.z};
    return box;
}

class SparkDsgWriter {
public:
    explicit SparkDsgWriter(const model::SceneData& scene) : scene_(scene), palette_(scene.nodes) {
        for (const model::Node& n : scene.nodes) hasRooms_ = hasRooms_ || n.kind == model::NodeKind::Room;
        // Hydra's building holds its rooms: a scene with rooms is a building, one without is a room.
        sceneLayer_ = hasRooms_ ? kBuildingLayer : kRoomLayer;
        sceneId_ = symbol(hasRooms_ ? 'B' : 'R', 0);
        for (const model::Node& n : scene.nodes) {
            if (!kept(n)) continue;
            bool room = n.kind == model::NodeKind::Room;
            idOf_.emplace(n.id, symbol(room ? 'R' : 'O', n.id));
            labels_[room ? kRoomLayer : kObjectLayer].emplace(n.category, 0);
        }
        // Labels number the categories in name order, as a label space lists them.
        for (auto& [layer, labels] : labels_) {
            std::uint32_t next = 0;
            for (auto& [category, label] : labels) label = next++;
        }
        for (std::size_t i = 0; i < scene.nodes.size(); ++i) indexOf_.emplace(scene.nodes[i].id, i);
    }

    std::string write() {
        Json graph;
        // Spark-DSG 1.1.3's encoding (the header from 1.0.2, partitions from 1.1.0, layer keys from 1.1.2).
        graph["SPARK_DSG_header"] = {{"project_name", "main"}, {"version", {{"major", 1}, {"minor", 1}, {"patch", 3}}}};
        graph["directed"] = false;
        graph["multigraph"] = false;
        graph["nodes"] = Json::array();
        graph["edges"] = Json::array();
        addSceneNode(graph);
        for (const model::Node& n : scene_.nodes)
            if (kept(n)) addNode(graph, n);
        // The layers of a default DynamicSceneGraph, as Hydra's graphs have them.
        graph["layer_keys"] = Json::array();
        for (std::int64_t layer : {2, 3, 4, 5}) graph["layer_keys"].push_back({{"layer", layer}, {"partition", 0}});
        graph["layer_names"] = Json::object();
        for (auto [name, layer] :
             {std::pair{"AGENTS", 2}, {"BUILDINGS", 5}, {"OBJECTS", 2}, {"PLACES", 3}, {"ROOMS", 4}})
            graph["layer_names"][name] = {{"layer", layer}, {"partition", 0}};
        graph["metadata"] = {{"labelspaces", Json::object()}, {"smql", {{"scene", scene_.info.name}}}};
        for (const auto& [layer, labels] : labels_) {
            Json pairs = Json::array();
            for (const auto& [category, label] : labels) pairs.push_back(Json::array({label, category}));
            graph["metadata"]["labelspaces"][labelspaceKey(layer)] = std::move(pairs);
        }
        return graph.dump(-1, ' ', false, Json::error_handler_t::replace) + "\n";
    }

private:
    static bool kept(const model::Node& n) {
        return n.kind == model::NodeKind::Anchor || n.kind == model::NodeKind::Object ||
               n.kind == model::NodeKind::Room;
    }

    // SemanticNodeAttributes' fields, which the object and room attributes extend.
    Json semanticAttributes(const char* type, const std::string& name, const std::string& category, const Json& box,
                            const model::Vec3& position, std::uint32_t label) const {
        model::Rgb colour = palette_(category);
        return {{"type", type},
                {"metadata", Json::object()},
                {"position", vec3Json(position)},
                {"last_update_time_ns", 0},
                {"is_active", false},
                {"is_predicted", false},
                {"name", name},
                {"color", {{"r", colour.r}, {"g", colour.g}, {"b", colour.b}, {"a", 255}}},
                {"bounding_box", box},
                {"semantic_label", label}};
    }

    void addSceneNode(Json& graph) const {
        std::optional<model::Box> extent = sceneExtent(scene_);
        Json attributes =
            semanticAttributes(hasRooms_ ? "SemanticNodeAttributes" : "RoomNodeAttributes", scene_.info.name, "",
                               boundingBox(extent, "AABB"), extent.value_or(model::Box{}).center, kNoSemanticLabel);
        attributes["metadata"]["smql"] = {{"kind", "scene"}};
        graph["nodes"].push_back(
            {{"id", sceneId_}, {"layer", sceneLayer_}, {"partition", 0}, {"attributes", attributes}});
    }

    void addNode(Json& graph, const model::Node& n) const {
        bool room = n.kind == model::NodeKind::Room;
        std::int64_t layer = room ? kRoomLayer : kObjectLayer;
        std::optional<model::Box> box;
        if (n.geometry != model::GeometryKind::None) box = n.box;
        Json attributes =
            semanticAttributes(room ? "RoomNodeAttributes" : "ObjectNodeAttributes", model::nodeLabel(n), n.category,
                               boundingBox(box, "OBB"), n.box.center, labels_.at(layer).at(n.category));
        if (!room) {
            attributes["mesh_connections"] = Json::array();
            attributes["registered"] = false;
            attributes["world_R_object"] = yawQuaternion(n.box.yaw);
        }
        attributes["metadata"]["smql"] = smqlFields(n);
        graph["nodes"].push_back(
            {{"id", idOf_.at(n.id)}, {"layer", layer}, {"partition", 0}, {"attributes", attributes}});

        // Below its room (Spark-DSG makes the higher layer's end the parent), and, when its parent is
        // in its own layer (a cushion's sofa), by an edge to that parent too.
        std::uint64_t up = parentId(n, /*roomsOnly=*/true);
        addEdge(graph, up, idOf_.at(n.id));
        std::uint64_t parent = parentId(n, /*roomsOnly=*/false);
        if (parent != up) addEdge(graph, parent, idOf_.at(n.id));
    }

    Json smqlFields(const model::Node& n) const {
        Json out = {{"kind", model::toString(n.kind)}, {"geometry", model::toString(n.geometry)}};
        if (std::uint64_t parent = parentId(n, false); parent != sceneId_) out["parent"] = parent;
        if (n.sourceId) out["source_id"] = *n.sourceId;
        if (n.hidden) out["hidden"] = true;
        if (!n.attributes.empty()) {
            out["attributes"] = Json::object();
            for (const model::Attribute& a : n.attributes) out["attributes"][a.name] = a.value;
        }
        return out;
    }

    // The nearest written ancestor (or, with roomsOnly, the nearest room), else the scene's node.
    std::uint64_t parentId(const model::Node& n, bool roomsOnly) const {
        const model::Node* at = &n;
        for (std::size_t steps = 0; steps < scene_.nodes.size(); ++steps) {
            auto it = indexOf_.find(at->parent);
            if (it == indexOf_.end()) break;
            at = &scene_.nodes[it->second];
            bool wanted = roomsOnly ? at->kind == model::NodeKind::Room : kept(*at);
            if (wanted) return idOf_.at(at->id);
        }
        return sceneId_;
    }

    static void addEdge(Json& graph, std::uint64_t source, std::uint64_t target) {
        graph["edges"].push_back(
            {{"source", source},
             {"target", target},
             {"info",
              {{"type", "EdgeAttributes"}, {"metadata", Json::object()}, {"weighted", false}, {"weight", 1.0}}}});
    }

    const model::SceneData& scene_;
    const model::Palette palette_;
    bool hasRooms_ = false;
    std::int64_t sceneLayer_ = kRoomLayer;
    std::uint64_t sceneId_ = 0;
    std::unordered_map<model::NodeId, std::uint64_t> idOf_;
    std::unordered_map<model::NodeId, std::size_t> indexOf_;
    std::map<std::int64_t, std::map<std::string, std::uint32_t>> labels_;
};

// ---- reading ----------------------------------------------------------------------------------

Eigen::Matrix3d rotation(const Field& field) {
    Eigen::Quaterniond q(field.at("w").number(), field.at("x").number(), field.at("y").number(),
                         field.at("z").number());
    if (std::abs(q.norm() - 1) > detail::kQuaternionNormTolerance)
        field.fail(fmt::format("quaternion (w, x, y, z) has norm {:.6g}, expected a unit quaternion", q.norm()));
    return q.normalized().toRotationMatrix();
}

// Spark-DSG's BoundingBox as an upright box; nullopt for an INVALID one. Files before Spark-DSG
// 1.0.3 give `min` and `max` instead of `dimensions`.
std::optional<model::Box> readBoundingBox(const Field& field) {
    Field type = field.at("type");
    if (type.json().is_null() || type.string() == "INVALID") return std::nullopt;
    if (type.string() != "AABB" && type.string() != "RAABB" && type.string() != "OBB")
        type.fail(fmt::format("unknown bounding box type '{}' (expected INVALID, AABB, RAABB or OBB)", type.string()));
    model::Vec3 size;
    std::optional<Field> sizeField = field.find("dimensions");
    if (sizeField) {
        size = sizeField->vec3();
    } else {
        model::Vec3 low = field.at("min").coordinates(), high = field.at("max").coordinates();
        size = {high.x - low.x, high.y - low.y, high.z - low.z};
    }
    for (double extent : {size.x, size.y, size.z})
        if (!(extent > 0) || extent > detail::kMaxSize)
            (sizeField ? *sizeField : field)
                .fail(fmt::format("size {} is out of range: sizes must be in (0, {}] m", extent, detail::kMaxSize));
    model::Vec3 center = field.at("world_P_center").coordinates();
    std::optional<Field> turn = field.find("world_R_center");
    return detail::uprightBox(center, size, turn ? rotation(*turn) : Eigen::Matrix3d::Identity());
}

// A label space: label -> name pairs, as nlohmann writes Spark-DSG's std::map<SemanticLabel, std::string>.
std::map<std::uint64_t, std::string> readLabelspace(const Field& field) {
    std::map<std::uint64_t, std::string> names;
    for (std::size_t i = 0; i < field.size(); ++i) {
        Field pair = field[i];
        if (pair.size() != 2) pair.fail("expected a [label, name] pair");
        names[pair[0].unsignedInteger()] = pair[1].string();
    }
    return names;
}

// A node of the file smql keeps, before parents are resolved.
struct KeptNode {
    model::Node node;
    std::uint64_t dsgId = 0;
    std::optional<Field> declaredParent;  // metadata.smql.parent: smql's parent in the same layer
};

class SparkDsgReader {
public:
    explicit SparkDsgReader(const std::string& path)
        : source_{path,
                  "expected Spark-DSG's JSON scene graph: {\"nodes\": [{\"id\", \"layer\", \"attributes\": {\"type\", "
                  "...}}], \"edges\": [{\"source\", \"target\"}]} (docs/formats.md, \"Spark-DSG\")"},
          root_(detail::parseJsonFile(source_)) {}

    model::SceneData read(const std::string& sceneName) {
        Field root(root_, source_);
        if (auto metadata = root.find("metadata")) readGraphMetadata(*metadata);
        Field nodes = root.at("nodes");
        for (std::size_t i = 0; i < nodes.size(); ++i) readNode(nodes[i]);
        Field edges = root.at("edges");
        for (std::size_t i = 0; i < edges.size(); ++i) readEdge(edges[i]);

        model::SceneData scene;
        for (KeptNode& kept : kept_) {
            kept.node.parent = parentOf(kept);
            scene.nodes.push_back(std::move(kept.node));
        }
        std::string name = !sceneName.empty()     ? sceneName
                           : !nameInFile_.empty() ? nameInFile_
                                                  : std::filesystem::path(source_.file).stem().string();
        detail::finishScene(scene, name, "spark-dsg:" + source_.file);
        return scene;
    }

private:
    void readGraphMetadata(const Field& metadata) {
        if (auto smql = metadata.find("smql"))
            if (auto scene = smql->find("scene")) nameInFile_ = scene->string();
        if (auto spaces = metadata.find("labelspaces"))
            for (std::int64_t layer : {kObjectLayer, kRoomLayer})
                if (auto space = spaces->find(labelspaceKey(layer))) labelNames_[layer] = readLabelspace(*space);
    }

    void readNode(const Field& field) {
        std::uint64_t id = field.at("id").unsignedInteger();
        std::int64_t layer = field.at("layer").integer();
        std::uint64_t partition = 0;
        if (auto p = field.find("partition")) partition = p->unsignedInteger();
        if (!layerOf_.emplace(id, layer).second) field.at("id").fail(fmt::format("duplicate node id {}", id));

        Field attributes = field.at("attributes");
        std::string type = attributes.at("type").string();
        std::optional<Field> smql;
        if (auto metadata = attributes.find("metadata"); metadata && metadata->json().is_object())
            smql = metadata->find("smql");
        std::string kind = smql ? smql->at("kind").string() : "";
        if (kind == "scene") {
            // smql writes the scene as Hydra's room (or, with rooms, building) node, once.
            if (layer != kRoomLayer && layer != kBuildingLayer)
                smql->at("kind").fail(fmt::format("the scene is a room or building node, not one of layer {}", layer));
            if (sceneId_) smql->at("kind").fail("a second node says it is the scene");
            sceneId_ = id;
            return;
        }
        bool thing = layer == kObjectLayer &&
                     std::find(std::begin(kObjectTypes), std::end(kObjectTypes), type) != std::end(kObjectTypes);
        bool room = layer == kRoomLayer;
        if (partition != 0 || (!thing && !room)) return;  // places, agents, buildings: no place in smql

        KeptNode kept{placedNode(attributes, layer, smql), id, std::nullopt};
        kept.node.id = kept_.size() + 1;
        keptIndex_.emplace(id, kept_.size());
        if (smql) {
            kept.declaredParent = smql->find("parent");
            readSmqlFields(*smql, kept.node);
        } else if (id <= static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
            kept.node.sourceId = static_cast<std::int64_t>(id);
        }
        kept_.push_back(std::move(kept));
    }

    model::Node placedNode(const Field& attributes, std::int64_t layer, const std::optional<Field>& smql) const {
        model::Node node;
        node.kind = layer == kRoomLayer ? model::NodeKind::Room : model::NodeKind::Object;
        node.category = categoryOf(attributes, layer);
        if (auto box = attributes.find("bounding_box"))
            if (std::optional<model::Box> read = readBoundingBox(*box)) {
                node.box = *read;
                node.geometry = model::GeometryKind::Box;
            }
        if (!smql) return node;
        Field kind = smql->at("kind");
        std::string expected = layer == kRoomLayer ? "room" : "anchor or object";
        if (kind.string() == "anchor" && layer == kObjectLayer)
            node.kind = model::NodeKind::Anchor;
        else if (kind.string() != (layer == kRoomLayer ? "room" : "object"))
            kind.fail(fmt::format("kind '{}' in layer {}: expected {} (or scene)", kind.string(), layer, expected));
        if (auto geometry = smql->find("geometry");
            geometry && geometry->string() == "plane" && node.geometry != model::GeometryKind::None)
            node.geometry = model::GeometryKind::Plane;
        return node;
    }

    // The label space's name for the node's label, else `label-<n>` (an object layer without one,
    // as Hydra's older files have), else what the layer holds.
    std::string categoryOf(const Field& attributes, std::int64_t layer) const {
        std::optional<std::uint64_t> label;
        if (auto field = attributes.find("semantic_label")) label = field->unsignedInteger();
        if (label && *label != kNoSemanticLabel) {
            if (auto space = labelNames_.find(layer); space != labelNames_.end())
                if (auto name = space->second.find(*label); name != space->second.end()) return name->second;
            if (layer == kObjectLayer) return fmt::format("label-{}", *label);
        }
        return layer == kRoomLayer ? "room" : "object";
    }

    static void readSmqlFields(const Field& smql, model::Node& node) {
        if (auto f = smql.find("source_id")) node.sourceId = f->integer();
        if (auto f = smql.find("hidden")) node.hidden = f->boolean();
        if (auto f = smql.find("attributes"))
            for (const auto& [name, value] : f->members()) {
                if (name.empty()) value.fail("empty attribute name");
                node.attributes.push_back({name, value.string()});
            }
    }

    // Spark-DSG makes the end in the higher layer the parent of the other; an edge within a layer
    // links siblings.
    void readEdge(const Field& field) {
        std::uint64_t ends[2] = {field.at("source").unsignedInteger(), field.at("target").unsignedInteger()};
        std::int64_t layers[2] = {0, 0};
        for (int end = 0; end < 2; ++end) {
            auto it = layerOf_.find(ends[end]);
            if (it == layerOf_.end())
                field.at(end == 0 ? "source" : "target").fail(fmt::format("no node of the file has id {}", ends[end]));
            layers[end] = it->second;
        }
        if (layers[0] == layers[1]) return;
        int child = layers[0] < layers[1] ? 0 : 1;
        upward_.emplace(ends[child], ends[1 - child]);
    }

    // smql's parent as the node's metadata names it, else the nearest kept node above it along the
    // interlayer edges (an object's place, then the place's room), else the scene.
    model::NodeId parentOf(const KeptNode& kept) const {
        if (kept.declaredParent) {
            std::uint64_t parent = kept.declaredParent->unsignedInteger();
            if (parent == sceneId_) return model::kNoNode;
            auto it = keptIndex_.find(parent);
            if (it == keptIndex_.end())
                kept.declaredParent->fail(fmt::format("no node of the file smql reads has id {}", parent));
            return kept_[it->second].node.id;
        }
        std::uint64_t at = kept.dsgId;
        for (std::size_t steps = 0; steps < layerOf_.size(); ++steps) {
            auto up = upward_.find(at);
            if (up == upward_.end()) break;
            at = up->second;
            if (auto it = keptIndex_.find(at); it != keptIndex_.end()) return kept_[it->second].node.id;
        }
        return model::kNoNode;
    }

    detail::JsonSource source_;
    Json root_;
    std::string nameInFile_;
    std::map<std::int64_t, std::map<std::uint64_t, std::string>> labelNames_;
    std::unordered_map<std::uint64_t, std::int64_t> layerOf_;  // every node of the file
    std::unordered_map<std::uint64_t, std::uint64_t> upward_;  // node -> its parent in a higher layer
    std::unordered_map<std::uint64_t, std::size_t> keptIndex_;
    std::vector<KeptNode> kept_;
    std::optional<std::uint64_t> sceneId_;
};

}  // namespace

model::SceneData readSparkDsg(const std::string& path, const std::string& sceneName) {
    return SparkDsgReader(path).read(sceneName);
}

std::string writeSparkDsg(const model::SceneData& scene) { return SparkDsgWriter(scene).write(); }

}  // namespace smql::import
