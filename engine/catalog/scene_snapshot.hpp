// One scene as the executor sees it: what its first statement needs to find its way (each node's
// kind, category and bounds, the category and kind lists) from the scene's stored index, the nodes
// themselves decoded the first time a statement asks for them, and the spatial queries answered by
// an R-tree whose leaves are the index's stored blocks. Built the first
// time a scene is queried and reused until the scene's version changes, so a query touches LMDB
// only to check that version and to read the nodes it visits for the first time.
#pragma once

#include <atomic>
#include <cstdint>
#include <deque>
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
#include "storage/scene_index.hpp"

namespace smql::storage {
class ReadTransaction;
}

namespace smql::catalog {

using Slot = std::uint32_t;  // a node's position in SceneSnapshot::nodes

class SceneSnapshot {
public:
    // The scene as `txn` holds it: from its stored index when it has one (nodes decoded when first
    // asked for, through the transaction readThrough names), else every node decoded now.
    static std::shared_ptr<const SceneSnapshot> load(const storage::ReadTransaction& txn, const model::SceneInfo& info);
    // A superseded version from the scene's history (AS OF), with the ids it had then.
    static std::shared_ptr<const SceneSnapshot> fromVersion(const model::SceneVersion& version);

    // The transaction the nodes and relations not read yet are read through: any that sees the
    // scene at this snapshot's version holds the same records, but a snapshot outlives each one, so
    // whoever hands the snapshot to a statement names the statement's transaction, and null after.
    void readThrough(const storage::ReadTransaction* txn) const;

    const model::SceneInfo& info() const { return info_; }
    // Made from a superseded version (AS OF) rather than the stored scene.
    bool historical() const { return historical_; }
    std::size_t size() const { return index_.entries.size(); }
    // Every node, decoded (the export, guidance, ASK's vocabulary, the embeddings need them all).
    const std::vector<model::Node>& nodes() const;
    const model::Node& node(Slot slot) const {
        const Decoded* decoded = decoded_[slot].load(std::memory_order_acquire);
        return decoded ? *decoded->node : decode(slot);
    }
    // What the index knows of a node without decoding it.
    model::NodeKind kind(Slot slot) const { return index_.entries[slot].kind; }
    bool hidden(Slot slot) const { return index_.entries[slot].hidden != 0; }
    model::GeometryKind geometry(Slot slot) const { return index_.entries[slot].geometry; }
    const std::string& category(Slot slot) const { return index_.categories[index_.entries[slot].category]; }
    // World-aligned bounds of a node's box (empty-looking for nodes without geometry), as the index
    // holds them: rounded outward to floats, so they hold the box. What they rule out, the exact
    // bounds rule out too; a test that must be exact takes decodedBounds.
    model::Aabb bounds(Slot slot) const { return index_.entries[slot].bounds.aabb(); }
    // The exact bounds (model::worldAabb) of `node` when it is this scene's record as node() gave it
    // (not a copy that kept its id), else null: the predicates' pair tests ask for a node's bounds
    // per pair, and these are worked out once, when the node is decoded.
    const model::Aabb* decodedBounds(const model::Node& node) const {
        if (!idsInOneBlock_ || node.id < firstId_ || node.id - firstId_ >= size()) return nullptr;
        const Decoded* decoded = decoded_[node.id - firstId_].load(std::memory_order_acquire);
        return decoded && decoded->node == &node ? &decoded->bounds : nullptr;
    }
    std::optional<Slot> slotOf(model::NodeId id) const;
    std::optional<Slot> slotOfSource(std::int64_t sourceId) const;
    // Slots of a category (visible and hidden), in id order; empty when the scene has none. The name
    // may be written any way model::categoryName folds ("Trash Cans" is trash-can).
    const std::vector<Slot>& withCategory(std::string_view category) const;
    // withCategory(relations::kWall), looked up once: near asks for the walls of every pair it tests.
    const std::vector<Slot>& walls() const { return *walls_; }
    const std::vector<Slot>& children(Slot slot) const;
    // What a kind word (`object`) names, in id order: the nodes that are not hidden, the scene's
    // root left out. Made once with the snapshot, since most statements name one.
    const std::vector<Slot>& shownOfKind(model::NodeKind kind) const;
    // What `node` names, the same nodes of every kind: made the first time a statement asks, as few do.
    const std::vector<Slot>& shownNodes() const;
    std::vector<std::string> categories() const;
    // Names of the attributes any node of the scene carries (color, material ...), sorted.
    const std::vector<std::string>& attributeNames() const;
    // The spatial index over the boxes of the nodes with geometry (the scene node left out):
    // slots whose bounds() intersect `region` (unordered): every box that meets it, and perhaps one
    // that misses it by less than a float's rounding, so callers test what they take exactly. It is
    // an R-tree packed when the scene was stored: the stored blocks are its leaves, and the levels
    // above them are packed from the blocks' bounds once a scene's first queries have scanned the blocks 32 times (3 us
    // for 2,000 boxes: no query waits long for a tree).
    void intersecting(const model::Aabb& region, std::vector<Slot>& out) const;
    // The same boxes by the (squared) gap between their bounds and a region, nearest first, one at
    // a time (which of equal gaps comes first is free): the stored blocks best first, a block's boxes
    // taken in once it is the nearest left. A box is never nearer than its block, so what a caller
    // stops at has not cost the rest; NEAREST's few answers cost a gap per block and a few blocks.
    class NearestWalk {
    public:
        std::optional<Slot> next();

    private:
        friend class SceneSnapshot;
        NearestWalk(const SceneSnapshot& scene, const model::Aabb& region);
        const SceneSnapshot& scene_;
        model::Aabb region_;
        std::vector<std::pair<double, std::uint32_t>> blocks_;  // by gap, a heap with the nearest on top
        std::vector<std::pair<double, Slot>> boxes_;            // taken in, a heap with the nearest on top
    };
    NearestWalk walkNearest(const model::Aabb& region) const { return NearestWalk(*this, region); }
    std::size_t spatialSize() const { return index_.spatialOrder.size(); }
    const std::vector<model::Relation>& storedRelations() const;

    // Where a person can walk and the decision points of guidance: built the first time GUIDE or
    // SHOW GRAPH asks, then kept as long as the snapshot (a new version of the scene is a new one).
    struct Guidance {
        guide::FreeSpace space;
        guide::RouteGraph graph;
        guide::GraphOptions options;
    };
    const Guidance& guidance() const;
    // The same for a crowded room, where a person pushes chairs aside and squeezes past a table's
    // edge (GraphOptions::pushAside): GUIDE's second try when the free floor has no way.
    const Guidance& crowdedGuidance() const;
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
    SceneSnapshot(model::SceneInfo info, storage::SceneIndex index, bool historical);
    // Decoded nodes of a scene loaded whole (no stored index, or a version from the history).
    void holdAll(std::vector<model::Node> nodes);
    const model::Node& decode(Slot slot) const;
    void buildLinks() const;
    // Whether the levels above the stored blocks are made (intersecting): once enough scans of the
    // blocks have run, this makes them. And the walk down them from a node of `level` (0: a block;
    // n: a run of levels_[n - 1]).
    bool levelsBuilt() const;
    void collect(std::size_t level, std::size_t node, const model::Aabb& region, const storage::IndexBounds& rounded,
                 std::vector<Slot>& out) const;

    model::SceneInfo info_;
    storage::SceneIndex index_;
    bool historical_ = false;
    // A stored scene's ids are one block in slot order (storage gives a scene's nodes consecutive
    // ids), so a slot is its id less the first; a scene rebuilt from its history may not be, and
    // maps its ids.
    bool idsInOneBlock_ = false;
    model::NodeId firstId_ = 0;
    std::unordered_map<model::NodeId, Slot> slotById_;

    // The nodes by slot, null until decoded, each with its exact bounds. The nodes decoded one by
    // one live in decodedNodes_ (a deque, so they never move), those of a scene loaded whole in
    // allNodes_; a Decoded lives in decodedLines_.
    struct Decoded {
        const model::Node* node;
        model::Aabb bounds;
    };
    std::unique_ptr<std::atomic<const Decoded*>[]> decoded_;
    mutable std::mutex readMutex_;  // guards what the reads below fill in
    mutable const storage::ReadTransaction* reader_ = nullptr;
    mutable std::deque<model::Node> decodedNodes_;
    mutable std::deque<Decoded> decodedLines_;
    mutable std::once_flag allDecoded_;
    mutable std::vector<model::Node> allNodes_;
    mutable std::optional<std::vector<model::Relation>> relations_;

    // Keyed by views of index_'s category names, which live as long as the snapshot.
    std::unordered_map<std::string_view, std::vector<Slot>> slotsByCategory_;
    const std::vector<Slot>* walls_ = nullptr;
    std::vector<std::vector<Slot>> shownByKind_;
    mutable std::once_flag shownNodesMade_;
    mutable std::vector<Slot> shownNodes_;
    // The tree's links and the source ids, made the first time a statement asks (PATH, SHOW TREE,
    // DESCRIBE, src#id): most statements need neither.
    mutable std::once_flag linksBuilt_;
    mutable std::unordered_map<std::int64_t, Slot> slotBySource_;
    mutable std::vector<std::vector<Slot>> children_;
    mutable std::once_flag attributeNamesFound_;  // the names are gathered when a statement first asks
    mutable std::vector<std::string> attributeNames_;
    // The stored blocks' bounds in double precision, for the levels packed over them and the gaps a
    // walk nearest first measures (125 blocks for 2,000 boxes: converted once, with the snapshot).
    std::vector<model::Aabb> blocks_;
    // The levels above the stored blocks, bottom first, each packed over the one below as the blocks
    // are over the boxes (storage::packTiles): `order` the positions of the level below in runs of
    // SceneIndex::kBlock, `bounds` each run's; up to a level of at most kBlock nodes, none when the
    // blocks are that few.
    struct Level {
        std::vector<std::uint32_t> order;
        std::vector<model::Aabb> bounds;
    };
    mutable std::vector<Level> levels_;
    mutable std::atomic<std::size_t> scans_{0};
    mutable std::atomic<bool> levelsBuilt_{false};
    mutable std::once_flag levelsBuilding_;
    mutable std::once_flag guidanceBuilt_, crowdedBuilt_;
    mutable std::once_flag embeddingsBuilt_;
    mutable std::unique_ptr<const similar::EmbeddingIndex> embeddings_;
    mutable std::once_flag storedEmbeddingsRead_;
    mutable std::unique_ptr<const similar::EmbeddingIndex> storedEmbeddings_;
    mutable std::unique_ptr<const Guidance> guidance_, crowded_;
};

// The snapshot's boxes as what may stand between two nodes (visible_from, near): the R-tree names
// the boxes in a region; hidden nodes and nodes without geometry never stand in the way.
class SceneObstacles final : public relations::Obstacles {
public:
    explicit SceneObstacles(const SceneSnapshot& scene) : scene_(scene) {}
    void within(const model::Aabb& region, std::vector<const model::Node*>& out) const override;
    void wallsWithin(const model::Aabb& region, std::vector<const model::Node*>& out) const override;
    model::Aabb bounds(const model::Node& node) const override;

private:
    const SceneSnapshot& scene_;
};

}  // namespace smql::catalog
