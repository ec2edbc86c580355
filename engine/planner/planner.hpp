// Bound FIND/COUNT -> physical plan. The one optimisation that matters at
// this size: push a local spatial predicate (on, in, above, below, near,
// attached) into the R-tree, so only boxes around the reference nodes are
// visited instead of every node of the target.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "engine/binder/bound.hpp"
#include "engine/model/geometry.hpp"

namespace smql::planner {

struct RTreeProbe {
    std::vector<model::Aabb> regions;  // one per reference node
    std::string description;           // "on(sofa (2 nodes))"
};

struct FindPlan {
    const binder::BoundFind* find = nullptr;
    std::optional<RTreeProbe> probe;  // absent: scan the target's nodes

    // The plan as EXPLAIN prints it, one operator per line, root first.
    std::vector<std::string> explain() const;
};

FindPlan planFind(const binder::BoundFind& find, const exec::SceneSnapshot& scene,
                  const relations::Thresholds& thresholds);

std::string describe(const binder::BoundExpr& expr);

}  // namespace smql::planner
