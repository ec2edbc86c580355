// One scene as the executor sees it: every node decoded once, with the
// category, source-id and children lookups and the R-tree. Built from a read
// transaction the first time a scene is queried and reused until the scene's
// version changes, so a query touches LMDB only to check that version.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "engine/guide/route_graph.hpp"
#include "engine/similar/embedding_index.hpp"
#include "model/types.hpp"
#include "relations/predicates.hpp"
#include "storage/spatial_index.hpp"

namespace smql::storage {
class ReadTransaction;
}

namespace smql::catalog {

using Slot = std::uint32_t;  // a node's position in SceneSnapshot::nodes

class SceneSnapshot {
public:
    static std::shared_ptr<const SceneSnapshot> load(const storage::ReadTransaction& txn, const model::SceneInfo& info);
    // A superseded version from the scene's history (AS OF), with the ids it had then.
    static std::shared_ptr<const SceneSnapshot> fromVersion(const model::SceneVersion& version);

    const model::SceneInfo& info() const { return info_; }
    // Made from a superseded version (AS OF) rather than the stored scene.
    bool historical() const { return historical_; }
    const std::vector<model::Node>& nodes() const { return nodes_; }
    const model::Node& node(Slot slot) const { return nodes_[slot]; }
    // World-aligned bounds of a node's box (empty-looking for nodes without geometry).
    const model::Aabb& bounds(Slot slot) const { return bounds_[slot]; }
    std::optional<Slot> slotOf(model::NodeId id) const;
    std::optional<Slot> slotOfSource(std::int64_t sourceId) const;
    // Slots of a category (visible and hidden), in id order; empty when the scene has none.
    const std::vector<Slot>& withCategory(std::string_view category) const;
    const std::vector<Slot>& children(Slot slot) const;
    const std::vector<Slot>& slotsOfKind(model::NodeKind kind) const;
    // What a kind word (`object`) or `node` names, in id order: the nodes that are not hidden,
    // the scene's root left out. Made once with the snapshot, since most statements name one.
    const std::vector<Slot>& shownOfKind(model::NodeKind kind) const;
    const std::vector<Slot>& shownNodes() const { return shownNodes_; }
    std::vector<std::string> categories() const;
    // Names of the attributes any node of the scene carries (color, material ...), sorted.
    const std::vector<std::string>& attributeNames() const;
    const storage::SpatialIndex& spatialIndex() const { return rtree_; }
    const std::vector<model::Relation>& storedRelations() const { return relations_; }

    // Where a person can walk and the decision points of guidance: built the first time GUIDE or
    // SHOW GRAPH asks, then kept as long as the snapshot (a new version of the scene is a new one).
    struct Guidance {
        guide::FreeSpace space;
        guide::RouteGraph graph;
        guide::GraphOptions options;
    };
    const Guidance& guidance() const;
    // The nodes' vectors for SIMILAR TO, by slot (docs/similarity.md): embedded the first time a
    // query asks, then kept as long as the snapshot.
    const similar::EmbeddingIndex& embeddings() const;
    // The vectors an external model gave the nodes (their `embedding` blobs, model/embedding.hpp),
    // scaled to unit length, by slot; null when no node has one. Read through `txn` (a transaction
    // that sees this snapshot's version) the first time a query asks, then kept as long as the
    // snapshot. A version from the history has none: a superseded version keeps no blobs.
    const similar::EmbeddingIndex* storedEmbeddings(const storage::ReadTransaction& txn) const;

    // "room0 / wall#3 / sofa#12 / cushion#40"
    std::string path(Slot slot) const;
    static std::string label(const model::Node& node);  // "sofa#12"

private:
    void buildLinks() const;
    static std::shared_ptr<const SceneSnapshot> build(model::SceneInfo info, std::vector<model::Node> nodes,
                                                      std::vector<model::Relation> relations, bool historical);

    model::SceneInfo info_;
    std::vector<model::Node> nodes_;
    std::vector<model::Aabb> bounds_;
    // A stored scene's ids are one block in slot order (storage gives a scene's nodes consecutive
    // ids), so a slot is its id less the first; a scene rebuilt from its history may not be, and
    // maps its ids.
    bool idsInOneBlock_ = false;
    model::NodeId firstId_ = 0;
    std::unordered_map<model::NodeId, Slot> slotById_;
    // The tree's links and the source ids, made the first time a statement asks (PATH, SHOW TREE,
    // DESCRIBE, src#id): most statements need neither, and a scene's first statement pays the load.
    mutable std::once_flag linksBuilt_;
    mutable std::unordered_map<std::int64_t, Slot> slotBySource_;
    std::unordered_map<std::string, std::vector<Slot>> slotsByCategory_;
    mutable std::vector<std::vector<Slot>> children_;
    std::vector<std::vector<Slot>> slotsByKind_;
    std::vector<std::vector<Slot>> shownByKind_;
    std::vector<Slot> shownNodes_;
    mutable std::once_flag attributeNamesFound_;  // the names are gathered when a statement first asks
    mutable std::vector<std::string> attributeNames_;
    storage::SpatialIndex rtree_;
    std::vector<model::Relation> relations_;
    mutable std::once_flag guidanceBuilt_;
    mutable std::once_flag embeddingsBuilt_;
    mutable std::unique_ptr<const similar::EmbeddingIndex> embeddings_;
    bool historical_ = false;
    mutable std::once_flag storedEmbeddingsRead_;
    mutable std::unique_ptr<const similar::EmbeddingIndex> storedEmbeddings_;
    mutable std::unique_ptr<const Guidance> guidance_;
};

// The snapshot's boxes as what may stand between two nodes (visible_from, near): the R-tree names
// the boxes in a region; hidden nodes and nodes without geometry never stand in the way.
class SceneObstacles final : public relations::Obstacles {
public:
    explicit SceneObstacles(const SceneSnapshot& scene) : scene_(scene) {}
    void within(const model::Aabb& region, std::vector<const model::Node*>& out) const override;
    void wallsWithin(const model::Aabb& region, std::vector<const model::Node*>& out) const override;

private:
    const SceneSnapshot& scene_;
};

}  // namespace smql::catalog
