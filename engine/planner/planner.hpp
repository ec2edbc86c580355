// Bound statement -> plan. The choices that matter at this size are made here
// and nowhere else, so EXPLAIN prints the plan that runs:
//  - a local spatial predicate (on, in, above, below, near, attached) over few
//    reference nodes is pushed into the R-tree: only boxes around those nodes
//    are visited instead of every node of the target;
//  - NEAREST TO / ORDER BY distance(x) LIMIT k around one node is a top-k
//    nearest-first search of the R-tree;
//  - ORDER BY an attribute with a LIMIT keeps the top k (a partial sort), without one sorts all;
//  - SIMILAR TO ... LIMIT k without WHERE over a target of hundreds of nodes asks the embedding
//    index for the top k; otherwise each candidate's similarity is computed;
//  - under USE SCENE '*', FIND and COUNT read the label index of every scene;
//  - every sub-query gets a plan of its own, run before the statement needs it.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/binder/bound.hpp"

namespace smql::planner {

// How FIND gathers its candidates.
enum class Access {
    Scan,          // every node of the target
    RTreeProbe,    // the boxes around the reference nodes of one local conjunct
    NearestFirst,  // top k by distance to one node: the R-tree's nearest boxes, widened until exact
    SimilarFirst,  // top k by similarity (SIMILAR TO) over a large target: the embedding index's
                   // search, widened until k candidates pass the target
};

struct FindPlan {
    std::shared_ptr<const binder::BoundFind> find;
    Access access = Access::Scan;
    std::size_t probeConjunct = 0;  // RTreeProbe: the top-level conjunct that drives the probe
    bool topK = false;              // ORDER BY an attribute LIMIT k: only the first k are sorted

    // The conjunct an R-tree probe is built from.
    const binder::BoundExpr& probeTerm() const;
};

struct Plan {
    std::shared_ptr<const binder::BoundStatement> statement;  // the plan shares what it runs
    std::optional<FindPlan> find;                             // FIND / COUNT in one scene
    std::vector<std::shared_ptr<const FindPlan>> subqueries;  // by NodeSet id; null where none
    std::shared_ptr<const Plan> explained;                    // EXPLAIN: the inner statement's plan
    std::shared_ptr<const Plan> asked;                        // ASK: the plan of the question's SMQL

    // The plan as EXPLAIN prints it, one operator per line, root first.
    std::vector<std::string> explain() const;
};

Plan plan(std::shared_ptr<const binder::BoundStatement> statement);
// The access path for one FIND; plan() uses it for the statement and each sub-query.
FindPlan planFind(std::shared_ptr<const binder::BoundFind> find);

// The references an R-tree probe can gather candidates around: those of a local predicate with one
// reference (on, near, ...) or of `distance(x) < d`; null for a conjunct that cannot drive a probe.
const binder::NodeSet* probeReferences(const binder::BoundExpr& term);

// The WHERE clause as EXPLAIN and errors print it.
std::string describe(const binder::BoundExpr& expr);
// The top-level conjuncts of a WHERE clause: each must hold for every row.
std::vector<const binder::BoundExpr*> conjuncts(const binder::BoundExpr& where);

}  // namespace smql::planner
