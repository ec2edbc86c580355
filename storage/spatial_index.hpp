// A packed R-tree over the world-aligned bounds of a scene's boxes
// (Boost.Geometry, bulk-loaded), built in memory once a scene's spatial queries
// have run often enough to pay for it (engine/catalog/scene_snapshot.hpp).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "model/geometry.hpp"

namespace smql::storage {

class SpatialIndex {
public:
    struct Entry {
        model::Aabb bounds;
        std::uint32_t slot;  // the caller's handle (a position in its node array)
    };

    SpatialIndex();
    explicit SpatialIndex(const std::vector<Entry>& entries);  // packs (bulk-loads) the tree
    SpatialIndex(SpatialIndex&&) noexcept;
    SpatialIndex& operator=(SpatialIndex&&) noexcept;
    ~SpatialIndex();

    // Slots whose bounds intersect `region` (unordered).
    void intersecting(const model::Aabb& region, std::vector<std::uint32_t>& out) const;

private:
    struct Tree;
    std::unique_ptr<Tree> tree_;
};

}  // namespace smql::storage
