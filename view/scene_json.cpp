#include "view/scene_json.hpp"

#include <cstring>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "engine/format.hpp"
#include "model/base64.hpp"
#include "model/points.hpp"
#include "model/presentation.hpp"

namespace smql::view {

namespace {

// The capture's points as the page draws them: positions as little-endian float32 x, y, z and
// colours as bytes r, g, b, each base64, so that the page makes typed arrays of them at once.
nlohmann::ordered_json pointsJson(const model::ScenePoints& points) {
    std::string positions(points.positions.size() * 3 * sizeof(float), '\0'), colours;
    colours.reserve(points.colours.size() * 3);
    for (std::size_t i = 0; i < points.positions.size(); ++i) {
        const model::Vec3& p = points.positions[i];
        const float xyz[3] = {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)};
        std::memcpy(positions.data() + i * sizeof xyz, xyz, sizeof xyz);
        for (std::uint8_t channel : {points.colours[i].r, points.colours[i].g, points.colours[i].b})
            colours += static_cast<char>(channel);
    }
    return {{"count", points.positions.size()},
            {"positions", model::toBase64(positions)},
            {"colours", model::toBase64(colours)}};
}

}  // namespace

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
    nlohmann::ordered_json out = {
        {"name", scene.info.name},
        {"source", scene.info.source},
        {"viewpoint", {{"position", {view.position.x, view.position.y, view.position.z}}, {"yaw", view.facingYaw}}},
        {"nodes", nodes}};
    if (const model::Blob* blob = model::pointsBlob(scene))
        out["points"] = pointsJson(model::readPointsPly(blob->bytes));
    return out;
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
