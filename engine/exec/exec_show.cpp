// SHOW SCENES, SHOW SETTINGS, SHOW TREE.
#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "engine/catalog/attributes.hpp"
#include "engine/exec/executor.hpp"
#include "model/category.hpp"
#include "model/error.hpp"
#include "model/geometry.hpp"
#include "model/presentation.hpp"
#include "storage/database.hpp"

namespace smql::exec {

ResultSet Executor::run(const binder::BoundShowScenes&) {
    ResultSet rs;
    rs.columns = {{"name", ValueType::Text},   {"id", ValueType::Integer},     {"nodes", ValueType::Integer},
                  {"source", ValueType::Text}, {"viewpoint", ValueType::Text}, {"current", ValueType::Text}};
    auto scenes = txn_.scenes();
    // No scene chosen yet: the most recently imported one is current, from now on (as for a query).
    if (session_.sceneName.empty() && !scenes.empty())
        session_.sceneName = std::max_element(scenes.begin(), scenes.end(), [](const auto& a, const auto& b) {
                                 return a.id < b.id;
                             })->name;
    for (const auto& s : scenes) {
        // Whole degrees; + 0.0 turns a -0 (a yaw a hair below zero) into 0.
        const double facing = std::round(s.viewpoint.facingYaw / model::kDegree) + 0.0;
        std::string vp = fmt::format("({:.2f}, {:.2f}, {:.2f}) facing {:.0f} deg", s.viewpoint.position.x,
                                     s.viewpoint.position.y, s.viewpoint.position.z, facing);
        bool current = !session_.allScenes && s.name == session_.sceneName;
        rs.rows.push_back({s.name, static_cast<std::int64_t>(s.id), static_cast<std::int64_t>(s.nodeCount), s.source,
                           vp, std::string(current ? "*" : "")});
    }
    return rs;
}

ResultSet Executor::run(const binder::BoundShowSettings&) {
    ResultSet rs;
    rs.columns = {
        {"name", ValueType::Text}, {"value", ValueType::Real}, {"unit", ValueType::Text}, {"meaning", ValueType::Text}};
    for (const auto& s : relations::settingsCatalogue())
        rs.rows.push_back({s.name, thresholds_.*(s.field),
                           std::string(s.unit == relations::SettingUnit::Metres ? "m" : "ratio"), s.meaning});
    for (const auto& s : catalog::limitSettings())
        rs.rows.push_back({std::string(s.name), static_cast<double>(session_.limits.*(s.field)), std::string("count"),
                           std::string(s.meaning)});
    return rs;
}

ResultSet Executor::run(const binder::BoundShowCategories& show) {
    ResultSet rs;
    if (show.allScenes) {
        rs.columns = {{"scene", ValueType::Text}, {"category", ValueType::Text}, {"count", ValueType::Integer}};
        // Each category once, by its canonical name, whatever spellings were stored for it.
        std::map<std::string, std::vector<std::string>> keysByName;
        for (const auto& [key, total] : txn_.categories()) keysByName[model::categoryName(key)].push_back(key);
        for (const auto& s : txn_.scenes())
            for (const auto& [category, keys] : keysByName) {
                poll();
                std::int64_t count = 0;
                for (const auto& key : keys)
                    count += static_cast<std::int64_t>(txn_.nodesWithCategory(key, s.id).size());
                if (count > 0) rs.rows.push_back({s.name, category, count});
            }
        return rs;
    }
    rs.columns = {{"category", ValueType::Text}, {"count", ValueType::Integer}, {"colour", ValueType::Text}};
    const std::vector<std::string> categories = scene().categories();
    const model::Palette palette(categories);
    for (const auto& category : categories)
        rs.rows.push_back({category, static_cast<std::int64_t>(scene().withCategory(category).size()),
                           model::hexColour(palette(category))});
    return rs;
}

ResultSet Executor::run(const binder::BoundShowAttributes&) {
    return catalog::attributeTable(plan_.statement->scene ? scene().attributeNames() : std::vector<std::string>());
}

ResultSet Executor::run(const binder::BoundShowTree& show) {
    const auto& snap = scene();
    catalog::Slot start = *snap.slotOf(snap.info().id);
    if (show.root) start = slots(*show.root, defaultFrame()).front();  // one node, checked as bound
    ResultSet rs;
    rs.columns = {{"id", ValueType::Integer}, {"depth", ValueType::Integer}, {"node", ValueType::Text}};
    std::size_t hidden = 0, descriptions = 0, frames = 0;
    // Depth-first, children in id order, so the listing reads like the path of each node.
    std::vector<std::pair<catalog::Slot, std::int64_t>> stack{{start, 0}};
    while (!stack.empty()) {
        auto [slot, depth] = stack.back();
        stack.pop_back();
        const model::Node& n = snap.node(slot);
        if (n.hidden) {
            ++hidden;
            continue;
        }
        // Descriptions are text about their parent (DESCRIBE shows them) and frames are where the
        // camera stood (FIND frame lists them): neither is a place in the tree.
        if (n.kind == model::NodeKind::Description || n.kind == model::NodeKind::Frame) {
            ++(n.kind == model::NodeKind::Frame ? frames : descriptions);
            continue;
        }
        rs.rows.push_back(
            {static_cast<std::int64_t>(n.id), depth, std::string(2 * depth, ' ') + catalog::SceneSnapshot::label(n)});
        const auto& kids = snap.children(slot);
        for (auto it = kids.rbegin(); it != kids.rend(); ++it) stack.push_back({*it, depth + 1});
    }
    if (hidden)
        rs.message = fmt::format("{} hidden node{} not shown (e.g. unlabelled parts)", hidden, hidden == 1 ? "" : "s");
    if (descriptions)
        rs.message += fmt::format("{}{} description{} not shown (DESCRIBE #id lists an object's)",
                                  rs.message.empty() ? "" : "; ", descriptions, descriptions == 1 ? "" : "s");
    if (frames)
        rs.message += fmt::format("{}{} frame{} not shown (FIND frame lists them)", rs.message.empty() ? "" : "; ",
                                  frames, frames == 1 ? "" : "s");
    return rs;
}

}  // namespace smql::exec
