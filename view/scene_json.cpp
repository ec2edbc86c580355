#include "view/scene_json.hpp"

#include <string>
#include <vector>

#include <fmt/format.h>

#include "engine/format.hpp"
#include "model/presentation.hpp"

namespace smql::view {

nlohmann::ordered_json sceneJson(const model::SceneData& scene) {
    const std::vector<std::string> paths = model::nodePaths(scene);
    const model::Palette palette(scene.nodes);
    auto nodes = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
        const model::Node& n = scene.nodes[i];
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
                         {"path", paths[i]},
                         {"colour", model::hexColour(palette(n.category))},
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
