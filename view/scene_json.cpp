#include "view/scene_json.hpp"

#include <string>
#include <unordered_map>
#include <vector>

#include <fmt/format.h>

#include "engine/format.hpp"

namespace smql::view {

namespace {

// "replica-room0 / wall#19 / sofa#50", as PATH prints it.
std::string pathOf(const model::Node& node, const std::unordered_map<model::NodeId, const model::Node*>& byId,
                   const std::string& sceneName) {
    std::vector<const model::Node*> chain{&node};
    for (auto it = byId.find(node.parent); it != byId.end() && it->second->kind != model::NodeKind::Scene;
         it = byId.find(it->second->parent))
        chain.push_back(it->second);
    std::string path = sceneName;
    for (auto n = chain.rbegin(); n != chain.rend(); ++n) path += fmt::format(" / {}#{}", (*n)->category, (*n)->id);
    return path;
}

}  // namespace

nlohmann::ordered_json sceneJson(const model::SceneData& scene) {
    std::unordered_map<model::NodeId, const model::Node*> byId;
    for (const auto& n : scene.nodes) byId.emplace(n.id, &n);
    auto nodes = nlohmann::ordered_json::array();
    for (const auto& n : scene.nodes) {
        if (n.hidden || n.kind == model::NodeKind::Scene || n.kind == model::NodeKind::Frame ||
            n.geometry == model::GeometryKind::None)
            continue;
        auto attributes = nlohmann::ordered_json::object();
        for (const auto& a : n.attributes) attributes[a.name] = a.value;
        nodes.push_back({{"id", n.id},
                         {"kind", toString(n.kind)},
                         {"category", n.category},
                         {"parent", n.parent},
                         {"geometry", model::toString(n.geometry)},
                         {"box", valueJson(n.box)},
                         {"path", pathOf(n, byId, scene.info.name)},
                         {"text", n.text},
                         {"attributes", attributes}});
    }
    const auto& view = scene.info.viewpoint;
    return {{"name", scene.info.name},
            {"source", scene.info.source},
            {"viewpoint", {{"position", {view.position.x, view.position.y, view.position.z}}, {"yaw", view.facingYaw}}},
            {"nodes", nodes}};
}

nlohmann::ordered_json answerJson(const ResultSet& result) {
    nlohmann::ordered_json out = resultJson(result);
    auto hits = nlohmann::ordered_json::array();
    auto route = nlohmann::ordered_json::array();
    const int id = result.columnIndex("id"), x = result.columnIndex("x"), y = result.columnIndex("y");
    const int step = result.columnIndex("step"), instruction = result.columnIndex("instruction");
    const int landmark = result.columnIndex("landmark_id");
    for (const auto& row : result.rows) {
        if (id >= 0 && std::holds_alternative<std::int64_t>(row[id])) hits.push_back(std::get<std::int64_t>(row[id]));
        if (x >= 0 && y >= 0 && step >= 0 && std::holds_alternative<double>(row[x]))
            route.push_back({{"step", valueJson(row[step])},
                             {"x", std::get<double>(row[x])},
                             {"y", std::get<double>(row[y])},
                             {"instruction", instruction >= 0 ? valueJson(row[instruction]) : nullptr}});
    }
    // A route's goal is its last landmark.
    if (!route.empty() && landmark >= 0 && std::holds_alternative<std::int64_t>(result.rows.back()[landmark]))
        hits.push_back(std::get<std::int64_t>(result.rows.back()[landmark]));
    out["hits"] = hits;
    out["route"] = route;
    return out;
}

}  // namespace smql::view
