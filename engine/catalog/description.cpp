#include "engine/catalog/description.hpp"

#include <algorithm>
#include <cmath>
#include <map>

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
    std::size_t frames = 0;
    for (const model::Node* child : children) {
        if (child->kind == model::NodeKind::Description)
            add("description", child->text);
        else if (child->kind == model::NodeKind::Frame)
            ++frames;
        else
            kids += (kids.empty() ? "" : ", ") + SceneSnapshot::label(*child);
    }
    if (!kids.empty()) add("children", kids);
    if (frames > 0) add("frames", fmt::format("{} camera frame{}", frames, frames == 1 ? "" : "s"));
    for (const auto& blob : evidence)
        add("evidence", fmt::format("{} ({}, {} bytes)", blob.name, blob.mediaType, blob.size));
}

void describePlace(ResultSet& rows, const model::Node& place, const std::vector<const model::Node*>& within) {
    auto id = static_cast<std::int64_t>(place.id);
    auto add = [&](std::string_view name, std::string value) {
        rows.rows.push_back({id, std::string(name), std::move(value)});
    };
    const model::Node *floor = nullptr, *ceiling = nullptr;
    std::size_t walls = 0;
    std::vector<std::string> doors, windows;
    std::map<std::string, std::size_t> kinds;
    std::size_t things = 0;
    for (const model::Node* n : within) {
        if (n->hidden) continue;
        if (n->kind == model::NodeKind::Anchor) {
            if (n->category == "floor" && (!floor || model::footprintArea(n->box) > model::footprintArea(floor->box)))
                floor = n;
            if (n->category == "ceiling" &&
                (!ceiling || model::footprintArea(n->box) > model::footprintArea(ceiling->box)))
                ceiling = n;
            walls += n->category == relations::kWall;
            if (n->category == "door") doors.push_back(SceneSnapshot::label(*n));
            if (n->category == "window") windows.push_back(SceneSnapshot::label(*n));
        } else if (n->kind == model::NodeKind::Object) {
            ++kinds[n->category];
            ++things;
        }
    }
    if (floor)
        add("floor", fmt::format("{:.2f} x {:.2f} m, {:.1f} m²", floor->box.size.x, floor->box.size.y,
                                 model::footprintArea(floor->box)));
    if (floor && ceiling)
        add("height", fmt::format("{:.2f} m, floor to ceiling", model::bottom(ceiling->box) - model::top(floor->box)));
    add("walls", std::to_string(walls));
    auto listedOrNone = [](const std::vector<std::string>& labels) {
        std::string out;
        for (const auto& l : labels) out += (out.empty() ? "" : ", ") + l;
        return out.empty() ? std::string("none found") : out;
    };
    add("doors", listedOrNone(doors));
    add("windows", listedOrNone(windows));
    // Most first, then by name: what a room holds many of says most about it.
    std::vector<std::pair<std::string, std::size_t>> byCount(kinds.begin(), kinds.end());
    std::stable_sort(byCount.begin(), byCount.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
    std::string tally;
    for (const auto& [category, count] : byCount)
        tally += fmt::format("{}{} {}", tally.empty() ? "" : ", ", category, count);
    add("things", tally.empty() ? "0" : fmt::format("{}: {}", things, tally));
}

}  // namespace smql::catalog
