#include "engine/catalog/scene_snapshot.hpp"

#include <algorithm>
#include <limits>

#include <fmt/format.h>

#include "model/embedding.hpp"
#include "model/error.hpp"
#include "storage/database.hpp"

namespace smql::catalog {

std::shared_ptr<const SceneSnapshot> SceneSnapshot::load(const storage::ReadTransaction& txn,
                                                         const model::SceneInfo& info) {
    std::vector<model::Node> nodes;
    nodes.reserve(info.nodeCount + 1);
    txn.forEachNodeInScene(info.id, [&](const model::Node& n) { nodes.push_back(n); });
    std::vector<model::Relation> relations;
    txn.forEachRelationInScene(info.id, [&](const model::Relation& r) { relations.push_back(r); });
    return build(info, std::move(nodes), std::move(relations), /*historical=*/false);
}

std::shared_ptr<const SceneSnapshot> SceneSnapshot::fromVersion(const model::SceneVersion& version) {
    return build(version.info, version.nodes, version.relations, /*historical=*/true);
}

std::shared_ptr<const SceneSnapshot> SceneSnapshot::build(model::SceneInfo info, std::vector<model::Node> nodes,
                                                          std::vector<model::Relation> relations, bool historical) {
    auto snap = std::make_shared<SceneSnapshot>();
    snap->info_ = std::move(info);
    snap->historical_ = historical;
    snap->nodes_ = std::move(nodes);

    const auto count = static_cast<Slot>(snap->nodes_.size());
    snap->slotsByKind_.resize(6);
    snap->shownByKind_.resize(6);
    snap->bounds_.resize(count);
    std::vector<storage::SpatialIndex::Entry> entries;
    entries.reserve(count);
    snap->firstId_ = count > 0 ? snap->nodes_.front().id : model::kNoNode;
    snap->idsInOneBlock_ = true;
    for (Slot s = 0; s < count; ++s)
        snap->idsInOneBlock_ = snap->idsInOneBlock_ && snap->nodes_[s].id == snap->firstId_ + s;
    if (!snap->idsInOneBlock_) snap->slotById_.reserve(count);
    for (Slot s = 0; s < count; ++s) {
        const auto& n = snap->nodes_[s];
        if (!snap->idsInOneBlock_) snap->slotById_.emplace(n.id, s);
        snap->slotsByCategory_[n.category].push_back(s);
        snap->slotsByKind_[static_cast<std::size_t>(n.kind)].push_back(s);
        if (!n.hidden && n.kind != model::NodeKind::Scene) {
            snap->shownByKind_[static_cast<std::size_t>(n.kind)].push_back(s);
            snap->shownNodes_.push_back(s);
        }
        snap->bounds_[s] = model::worldAabb(n.box);
        if (n.geometry != model::GeometryKind::None && n.kind != model::NodeKind::Scene)
            entries.push_back({snap->bounds_[s], s});
    }
    snap->rtree_ = storage::SpatialIndex(entries);
    snap->relations_ = std::move(relations);
    return snap;
}

const SceneSnapshot::Guidance& SceneSnapshot::guidance() const {
    std::call_once(guidanceBuilt_, [&] {
        guide::GraphOptions options;
        guide::FreeSpace space(nodes_, options);
        guide::RouteGraph graph = guide::buildGraph(nodes_, space, options);
        guidance_ = std::make_unique<const Guidance>(Guidance{std::move(space), std::move(graph), options});
    });
    return *guidance_;
}

const similar::EmbeddingIndex& SceneSnapshot::embeddings() const {
    std::call_once(embeddingsBuilt_, [&] {
        std::vector<similar::Vector> vectors;
        vectors.reserve(nodes_.size());
        for (const auto& node : nodes_) vectors.push_back(similar::embedNode(node));
        embeddings_ = std::make_unique<const similar::EmbeddingIndex>(std::move(vectors));
    });
    return *embeddings_;
}

const similar::EmbeddingIndex* SceneSnapshot::storedEmbeddings(const storage::ReadTransaction& txn) const {
    std::call_once(storedEmbeddingsRead_, [&] {
        if (historical_) return;
        std::vector<float> vectors;
        std::size_t dimensions = 0;
        for (std::size_t s = 0; s < nodes_.size(); ++s) {
            auto blob = txn.blob(nodes_[s].id, model::kEmbeddingBlob);
            if (!blob) continue;
            std::vector<float> vector;
            try {
                vector = model::readEmbedding(*blob);
            } catch (const Error& e) {
                throw Error(ErrorKind::Storage, fmt::format("the embedding of {}: {}", label(nodes_[s]), e.message()),
                            std::nullopt, "smql check DB verifies the database");
            }
            if (dimensions == 0) {
                dimensions = vector.size();
                vectors.resize(nodes_.size() * dimensions);
            }
            // Storage refuses a scene whose embeddings differ in length.
            if (vector.size() != dimensions)
                throw Error(ErrorKind::Storage,
                            fmt::format("the embedding of {} has {} dimensions, others in scene '{}' have {}",
                                        label(nodes_[s]), vector.size(), info_.name, dimensions),
                            std::nullopt, "smql check DB verifies the database");
            const std::vector<float> unit = similar::unitVector(vector);
            std::copy(unit.begin(), unit.end(), vectors.begin() + static_cast<std::ptrdiff_t>(s * dimensions));
        }
        if (dimensions == 0) return;
        // An external model's cosine has no floor that means "unrelated": every node with a vector ranks.
        storedEmbeddings_ =
            std::make_unique<const similar::EmbeddingIndex>(dimensions, vectors, std::numeric_limits<float>::lowest());
    });
    return storedEmbeddings_.get();
}

std::optional<Slot> SceneSnapshot::slotOf(model::NodeId id) const {
    if (idsInOneBlock_) {
        if (id < firstId_ || id - firstId_ >= nodes_.size()) return std::nullopt;
        return static_cast<Slot>(id - firstId_);
    }
    auto it = slotById_.find(id);
    if (it == slotById_.end()) return std::nullopt;
    return it->second;
}

void SceneSnapshot::buildLinks() const {
    std::call_once(linksBuilt_, [&] {
        const auto count = static_cast<Slot>(nodes_.size());
        children_.resize(count);
        slotBySource_.reserve(count);
        for (Slot s = 0; s < count; ++s) {
            if (nodes_[s].sourceId) slotBySource_.emplace(*nodes_[s].sourceId, s);
            if (std::optional<Slot> parent = slotOf(nodes_[s].parent)) children_[*parent].push_back(s);
        }
    });
}

const std::vector<std::string>& SceneSnapshot::attributeNames() const {
    std::call_once(attributeNamesFound_, [&] {
        // A scene has a handful of attribute names over thousands of nodes: each is looked for
        // among those found so far, rather than every node's names sorted.
        for (const auto& n : nodes_)
            for (const auto& a : n.attributes)
                if (std::find(attributeNames_.begin(), attributeNames_.end(), a.name) == attributeNames_.end())
                    attributeNames_.push_back(a.name);
        std::sort(attributeNames_.begin(), attributeNames_.end());
    });
    return attributeNames_;
}

std::optional<Slot> SceneSnapshot::slotOfSource(std::int64_t sourceId) const {
    buildLinks();
    auto it = slotBySource_.find(sourceId);
    if (it == slotBySource_.end()) return std::nullopt;
    return it->second;
}

const std::vector<Slot>& SceneSnapshot::withCategory(std::string_view category) const {
    static const std::vector<Slot> none;
    auto it = slotsByCategory_.find(std::string(category));
    return it == slotsByCategory_.end() ? none : it->second;
}

const std::vector<Slot>& SceneSnapshot::children(Slot slot) const {
    buildLinks();
    return children_[slot];
}

const std::vector<Slot>& SceneSnapshot::slotsOfKind(model::NodeKind kind) const {
    return slotsByKind_[static_cast<std::size_t>(kind)];
}

const std::vector<Slot>& SceneSnapshot::shownOfKind(model::NodeKind kind) const {
    return shownByKind_[static_cast<std::size_t>(kind)];
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
    return node.category + '#' + std::to_string(node.id);
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

void SceneObstacles::within(const model::Aabb& region, std::vector<const model::Node*>& out) const {
    std::vector<Slot> slots;
    scene_.spatialIndex().intersecting(region, slots);
    for (Slot s : slots) {
        const model::Node& n = scene_.node(s);
        if (!n.hidden && n.geometry != model::GeometryKind::None && n.kind != model::NodeKind::Scene) out.push_back(&n);
    }
}

void SceneObstacles::wallsWithin(const model::Aabb& region, std::vector<const model::Node*>& out) const {
    for (Slot s : scene_.withCategory(relations::kWall)) {
        const model::Node& n = scene_.node(s);
        if (!n.hidden && n.geometry != model::GeometryKind::None && relations::intersects(scene_.bounds(s), region))
            out.push_back(&n);
    }
}

}  // namespace smql::catalog
