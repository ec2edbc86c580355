// Runs bound, planned statements over one scene snapshot.
#pragma once

#include <optional>
#include <unordered_map>
#include <vector>

#include "engine/binder/bound.hpp"
#include "engine/planner/planner.hpp"
#include "engine/result.hpp"

namespace smql::exec {

struct Hit {
    Slot slot;
    double distance = 0;  // to the ORDER BY / NEAREST TO reference, when there is one
};

class Executor {
public:
    Executor(const SceneSnapshot& scene, const relations::Thresholds& thresholds)
        : scene_(scene), thresholds_(thresholds) {}

    std::vector<Hit> find(const planner::FindPlan& plan) const;
    ResultSet findRows(const planner::FindPlan& plan) const;
    ResultSet relate(const binder::BoundRelate& relate) const;
    ResultSet describe(const binder::NodeSet& nodes) const;
    ResultSet tree(std::optional<Slot> root) const;

private:
    bool matches(const binder::BoundExpr& expr, Slot slot, const relations::Frame& frame) const;
    bool holdsForSome(const binder::BoundExpr& expr, Slot slot, const relations::Frame& frame) const;
    const std::vector<char>& membership(const binder::NodeSet& set) const;
    // NEAREST TO / ORDER BY distance(x) LIMIT k around one node: the R-tree's
    // nearest boxes, widened until no box outside can beat the k-th answer.
    std::optional<std::vector<Hit>> nearestFirst(const planner::FindPlan& plan) const;
    bool compare(const binder::BoundExpr& expr, const model::Node& node) const;
    bool inTarget(const binder::Target& target, Slot slot) const;

    const SceneSnapshot& scene_;
    const relations::Thresholds& thresholds_;
    // Per query: which slots a large reference set holds, for R-tree lookups of references.
    mutable std::unordered_map<const binder::NodeSet*, std::vector<char>> membership_;
};

}  // namespace smql::exec
