// GeoJSON (docs/formats.md, "GeoJSON"): the floor plan, one Polygon Feature per drawn box (its
// footprint), in the scene's own metres.
#include "ingest/import/export_support.hpp"
#include "ingest/import/importers.hpp"
#include "ingest/import/json_field.hpp"
#include "model/geometry.hpp"

namespace smql::import {

namespace {

using detail::Json;

// RFC 7946's exterior ring: counter-clockwise, closed by repeating its first corner.
Json footprintRing(const model::Box& box) {
    std::array<model::Vec2, 4> corners = model::footprint(box);
    Json ring = Json::array();
    for (std::size_t i = 0; i <= corners.size(); ++i) {
        const model::Vec2& c = corners[i % corners.size()];
        ring.push_back(Json::array({c.x, c.y}));
    }
    return Json::array({std::move(ring)});
}

Json feature(const model::Node& node, const std::string& path) {
    Json properties;
    properties["id"] = node.id;
    properties["category"] = node.category;
    properties["kind"] = model::toString(node.kind);
    properties["path"] = path;
    properties["z_min"] = model::bottom(node.box);
    properties["z_max"] = model::top(node.box);
    properties["attributes"] = Json::object();
    for (const model::Attribute& a : node.attributes) properties["attributes"][a.name] = a.value;

    Json out;
    out["type"] = "Feature";
    out["id"] = node.id;
    out["geometry"] = {{"type", "Polygon"}, {"coordinates", footprintRing(node.box)}};
    out["properties"] = std::move(properties);
    return out;
}

// Text that is not UTF-8 (a database older than the import's check may hold some) becomes U+FFFD
// rather than failing the export, as in the smql JSON export.
std::string jsonText(const Json& value) { return value.dump(-1, ' ', false, Json::error_handler_t::replace); }

}  // namespace

std::string writeGeoJson(const model::SceneData& scene) {
    std::vector<std::string> paths = model::nodePaths(scene);
    // One feature a line, so that two exports of a scene compare line by line.
    std::string out =
        R"({"type": "FeatureCollection", "name": )" + jsonText(Json(scene.info.name)) + R"(, "features": [)";
    const char* separator = "\n";
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
        if (!detail::isDrawn(scene.nodes[i])) continue;
        out += separator + jsonText(feature(scene.nodes[i], paths[i]));
        separator = ",\n";
    }
    return out + "\n]}\n";
}

}  // namespace smql::import
