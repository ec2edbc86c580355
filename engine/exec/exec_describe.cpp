// DESCRIBE: a node's fields, its descriptions and children, and its evidence (from the blob table).
#include <cmath>

#include <fmt/format.h>

#include "engine/exec/executor.hpp"
#include "storage/database.hpp"

namespace smql::exec {

ResultSet Executor::run(const binder::BoundDescribe& d) {
    ResultSet rs;
    rs.columns = {{"id", ValueType::Integer}, {"field", ValueType::Text}, {"value", ValueType::Text}};
    for (catalog::Slot s : slots(d.nodes, defaultFrame())) {
        const model::Node& n = scene().node(s);
        auto id = static_cast<std::int64_t>(n.id);
        auto add = [&](std::string_view name, std::string value) {
            rs.rows.push_back({id, std::string(name), std::move(value)});
        };
        add("kind", std::string(model::toString(n.kind)));
        add("category", n.category);
        add("path", scene().path(s));
        if (n.sourceId) add("source_id", std::to_string(*n.sourceId));
        if (n.geometry != model::GeometryKind::None) {
            const auto& b = n.box;
            add("center", fmt::format("({:.3f}, {:.3f}, {:.3f}) m", b.center.x, b.center.y, b.center.z));
            add("dimensions", fmt::format("{:.3f} x {:.3f} x {:.3f} m", b.size.x, b.size.y, b.size.z));
            add("yaw", fmt::format("{:.1f} deg", b.yaw * 180.0 / M_PI));
            add("geometry", n.geometry == model::GeometryKind::Plane ? "plane segment" : "box");
        }
        add("confidence", fmt::format("{:.2f}", n.confidence));
        for (const auto& a : n.attributes) add(a.name, a.value);
        if (!n.text.empty()) add("text", n.text);
        if (n.hidden) add("hidden", "yes (left out of queries unless named)");
        std::string kids;
        for (catalog::Slot c : scene().children(s)) {
            const model::Node& child = scene().node(c);
            if (child.kind == model::NodeKind::Description)
                add("description", child.text);
            else
                kids += (kids.empty() ? "" : ", ") + catalog::SceneSnapshot::label(child);
        }
        if (!kids.empty()) add("children", kids);
        // Evidence lives in the blob table, not in the snapshot.
        for (const auto& blob : txn_.blobsOf(n.id))
            add("evidence", fmt::format("{} ({}, {} bytes)", blob.name, blob.mediaType, blob.size));
    }
    return rs;
}

}  // namespace smql::exec
