// Bound statements: names resolved to node sets of one scene, units to
// metres, the viewpoint to a frame. What the planner consumes.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "engine/exec/scene_snapshot.hpp"
#include "engine/parser/ast.hpp"
#include "engine/relations/predicates.hpp"

namespace smql::binder {

using exec::Slot;

// The nodes a reference stands for, and how to say it ("sofa (2 nodes)").
struct NodeSet {
    std::vector<Slot> slots;
    std::string description;
};

// What FIND / COUNT range over: a category, a kind of node, or given nodes.
struct Target {
    enum class Kind { Category, NodeKind, AnyNode, Nodes };
    Kind kind = Kind::AnyNode;
    std::string category;
    model::NodeKind nodeKind = model::NodeKind::Object;
    NodeSet nodes;  // the candidates, in id order (for every kind)
    std::string description;
};

struct BoundExpr {
    enum class Kind { And, Or, Not, Predicate, Compare };
    Kind kind = Kind::Predicate;
    std::vector<BoundExpr> children;

    relations::Predicate predicate = relations::Predicate::Near;
    std::vector<NodeSet> args;
    std::optional<double> nearDistance;

    // Compare: a built-in field or a stored attribute against a literal.
    std::string attribute;
    ast::CompareOp op = ast::CompareOp::Eq;
    ast::Literal literal;
};

struct BoundFind {
    Target target;
    relations::Frame frame;
    std::string viewDescription;
    std::optional<BoundExpr> where;
    std::optional<NodeSet> distanceTo;  // ORDER BY distance(x) / NEAREST TO x
    bool nearest = false;               // NEAREST TO: the reference nodes themselves are left out
    bool descending = false;
    std::optional<std::int64_t> limit;
    bool path = false;
    bool countOnly = false;
};

struct BoundRelate {
    NodeSet subject;
    NodeSet object;
    relations::Frame frame;
    std::string viewDescription;
};

}  // namespace smql::binder
