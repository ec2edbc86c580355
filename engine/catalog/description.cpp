#include "engine/catalog/description.hpp"

#include <cmath>

#include <fmt/format.h>

#include "engine/catalog/scene_snapshot.hpp"
#include "model/geometry.hpp"

namespace smql::catalog {

void describeNode(ResultSet& rows, const model::Node& n, std::string_view path,
                  const std::vector<const model::Node*>& children, const std::vector<EvidenceInfo>& evidence) {
    auto id = static_cast<std::int64_t>(n.id);
    auto add = [&](std::string_view name, std::string value) {
        rows.rows.push_back({id, std::string(name), std::move(value)});
    };
    add("kind", std::string(model::toString(n.kind)));
    add("category", n.category);
    add("path", std::string(path));
    if (n.sourceId) add("source_id", std::to_string(*n.sourceId));
    if (n.geometry != model::GeometryKind::None) {
        const auto& b = n.box;
        add("center", fmt::format("({:.3f}, {:.3f}, {:.3f}) m", b.center.x, b.center.y, b.center.z));
        add("dimensions", fmt::format("{:.3f} x {:.3f} x {:.3f} m", b.size.x, b.size.y, b.size.z));
        add("yaw", fmt::format("{:.1f} deg", b.yaw / model::kDegree));
        add("geometry", n.geometry == model::GeometryKind::Plane ? "plane segment" : "box");
    }
    add("confidence", fmt::format("{:.2f}", n.confidence));
    for (const auto& a : n.attributes) add(a.name, a.value);
    if (!n.text.empty()) add("text", n.text);
    if (n.hidden) add("hidden", "yes (left out of queries unless named)");
    std::string kids;
    for (const model::Node* child : children) {
        if (child->kind == model::NodeKind::Description)
            add("description", child->text);
        else
            kids += (kids.empty() ? "" : ", ") + SceneSnapshot::label(*child);
    }
    if (!kids.empty()) add("children", kids);
    for (const auto& blob : evidence)
        add("evidence", fmt::format("{} ({}, {} bytes)", blob.name, blob.mediaType, blob.size));
}

}  // namespace smql::catalog
