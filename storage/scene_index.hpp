// A scene's table of contents, stored with the scene (table scene_index, docs/storage.md): for
// every node in id order its kind, geometry kind, hidden flag, category and world-aligned bounds
// (in single precision, rounded outward).
// It is what a scene's first query needs to find its way (the category lists, the spatial
// index's boxes) without decoding every node record; the nodes it then visits are read one by one.
#pragma once

#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "model/geometry.hpp"
#include "model/types.hpp"

namespace smql::storage {

// World-aligned bounds in single precision, each minimum rounded down and each maximum up, so that
// they hold the exact bounds: a search over them rules out only what the exact bounds rule out,
// and reads 24 bytes a box where doubles take 48 (a scene's first query reads every box's). A NaN
// coordinate stays NaN.
struct IndexBounds {
    float minX, minY, minZ, maxX, maxY, maxZ;

    static IndexBounds around(const model::Aabb& exact);
    // The same bounds in double precision (each float exactly).
    model::Aabb aabb() const { return {{minX, minY, minZ}, {maxX, maxY, maxZ}}; }
};

// One node's line, fixed size so the stored array is copied out of the memory map in one piece.
struct SceneIndexEntry {
    IndexBounds bounds;      // IndexBounds::around(model::worldAabb(node.box)) of the record
    std::uint32_t category;  // a position in SceneIndex::categories
    model::NodeKind kind;
    model::GeometryKind geometry;
    std::uint8_t hidden;  // 0 or 1
    std::uint8_t reserved;
};
static_assert(std::is_trivially_copyable_v<SceneIndexEntry> && sizeof(SceneIndexEntry) == 32,
              "the stored array is these bytes");

struct SceneIndex {
    // The scene version it describes (model::SceneInfo::version): one made before a write that
    // changed the scene is not believed.
    std::uint64_t version = 0;
    std::vector<std::string> categories;   // distinct, in order of first use
    std::vector<SceneIndexEntry> entries;  // by slot: the scene node first, then its nodes in id order
    // The slots of the nodes with geometry (the scene node left out) in an order that keeps near
    // boxes together (sort-tile-recursive, as an R-tree is packed), and the bounds of each run of
    // kBlock of them: a spatial query tests the blocks, then the boxes of the blocks it meets.
    static constexpr std::size_t kBlock = 16;
    std::vector<std::uint32_t> spatialOrder;
    std::vector<IndexBounds> blockBounds;

    // The index of a scene's nodes (the scene node first, then the rest in id order).
    static SceneIndex of(const std::vector<model::Node>& nodes, std::uint64_t version);
    // The spatial order and the blocks packed from the entries (of() does this last).
    void pack();
    // Byte for byte, so a stored index equals the one its records give (NaN bounds included).
    friend bool operator==(const SceneIndex& a, const SceneIndex& b);
};

// Sort-tile-recursive packing, as an R-tree is bulk-loaded, in the floor plane (rooms are flat):
// `order` (positions into `bounds`) sorted by x into vertical slices of whole runs of
// SceneIndex::kBlock, each slice by y, so that a run's members lie close together. Returns the bounds
// of each run. The scene index packs its boxes into blocks so; a snapshot packs the blocks into the
// levels above them (engine/catalog/scene_snapshot.hpp).
std::vector<model::Aabb> packTiles(const std::vector<model::Aabb>& bounds, std::vector<std::uint32_t>& order);

}  // namespace smql::storage
