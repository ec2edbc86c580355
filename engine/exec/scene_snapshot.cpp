#include "engine/exec/scene_snapshot.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "storage/database.hpp"

namespace smql::exec {

std::shared_ptr<const SceneSnapshot> SceneSnapshot::load(const storage::ReadTransaction& txn,
                                                         const model::SceneInfo& info) {
    auto snap = std::make_shared<SceneSnapshot>();
    snap->info_ = info;
    snap->nodes_.reserve(info.nodeCount + 1);
    txn.forEachNodeInScene(info.id, [&](const model::Node& n) { snap->nodes_.push_back(n); });

    const auto count = static_cast<Slot>(snap->nodes_.size());
    snap->children_.resize(count);
    snap->slotsByKind_.resize(6);
    snap->bounds_.resize(count);
    std::vector<storage::SpatialIndex::Entry> entries;
    entries.reserve(count);
    for (Slot s = 0; s < count; ++s) {
        const auto& n = snap->nodes_[s];
        snap->slotById_.emplace(n.id, s);
        if (n.sourceId) snap->slotBySource_.emplace(*n.sourceId, s);
        snap->slotsByCategory_[n.category].push_back(s);
        snap->slotsByKind_[static_cast<std::size_t>(n.kind)].push_back(s);
        snap->bounds_[s] = model::worldAabb(n.box);
        if (n.geometry != model::GeometryKind::None && n.kind != model::NodeKind::Scene)
            entries.push_back({snap->bounds_[s], s});
        for (const auto& a : n.attributes) snap->attributeNames_.push_back(a.name);
    }
    std::sort(snap->attributeNames_.begin(), snap->attributeNames_.end());
    snap->attributeNames_.erase(std::unique(snap->attributeNames_.begin(), snap->attributeNames_.end()),
                                snap->attributeNames_.end());
    for (Slot s = 0; s < count; ++s) {
        auto parent = snap->slotById_.find(snap->nodes_[s].parent);
        if (parent != snap->slotById_.end()) snap->children_[parent->second].push_back(s);
    }
    snap->rtree_ = storage::SpatialIndex(entries);
    txn.forEachRelationInScene(info.id, [&](const model::Relation& r) { snap->relations_.push_back(r); });
    return snap;
}

std::optional<Slot> SceneSnapshot::slotOf(model::NodeId id) const {
    auto it = slotById_.find(id);
    if (it == slotById_.end()) return std::nullopt;
    return it->second;
}

std::optional<Slot> SceneSnapshot::slotOfSource(std::int64_t sourceId) const {
    auto it = slotBySource_.find(sourceId);
    if (it == slotBySource_.end()) return std::nullopt;
    return it->second;
}

const std::vector<Slot>& SceneSnapshot::withCategory(std::string_view category) const {
    static const std::vector<Slot> none;
    auto it = slotsByCategory_.find(std::string(category));
    return it == slotsByCategory_.end() ? none : it->second;
}

const std::vector<Slot>& SceneSnapshot::children(Slot slot) const { return children_[slot]; }

const std::vector<Slot>& SceneSnapshot::slotsOfKind(model::NodeKind kind) const {
    return slotsByKind_[static_cast<std::size_t>(kind)];
}

std::vector<std::string> SceneSnapshot::categories() const {
    std::vector<std::string> out;
    for (const auto& [name, slots] : slotsByCategory_) {
        // Descriptions and frames are about places, not places: they are not categories to ask for.
        bool queryable = std::any_of(slots.begin(), slots.end(), [&](Slot s) {
            auto kind = nodes_[s].kind;
            return !nodes_[s].hidden && kind != model::NodeKind::Scene && kind != model::NodeKind::Description &&
                   kind != model::NodeKind::Frame;
        });
        if (queryable) out.push_back(name);
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::string SceneSnapshot::label(const model::Node& node) {
    if (node.kind == model::NodeKind::Scene) return node.category;
    return fmt::format("{}#{}", node.category, node.id);
}

std::string SceneSnapshot::path(Slot slot) const {
    std::vector<Slot> chain;
    for (std::optional<Slot> s = slot; s; s = slotOf(nodes_[*s].parent)) {
        chain.push_back(*s);
        if (chain.size() > nodes_.size()) break;  // a corrupt parent cycle must not hang a query
    }
    std::string out;
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
        if (!out.empty()) out += " / ";
        out += label(nodes_[*it]);
    }
    return out;
}

}  // namespace smql::exec
