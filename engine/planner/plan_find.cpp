// FIND / COUNT in one scene: the access path.
#include "engine/planner/planner.hpp"

namespace smql::planner {

using binder::BoundExpr;
using binder::NodeSet;

std::vector<const BoundExpr*> conjuncts(const BoundExpr& where) {
    std::vector<const BoundExpr*> out;
    if (where.kind == BoundExpr::Kind::And)
        for (const auto& c : where.children) out.push_back(&c);
    else
        out.push_back(&where);
    return out;
}

const BoundExpr& FindPlan::probeTerm() const { return *conjuncts(*find->where)[probeConjunct]; }

const NodeSet* probeReferences(const BoundExpr& term) {
    if (term.kind == BoundExpr::Kind::Predicate && term.args.size() == 1 && relations::spec(term.predicate).local())
        return &term.args[0];
    // distance(x) < d: within d of x's boxes, so within d of their bounds on every axis.
    const bool upperBound = term.op == ast::CompareOp::Lt || term.op == ast::CompareOp::Le;
    if (term.kind == BoundExpr::Kind::Compare && term.distanceTo && upperBound) return &*term.distanceTo;
    return nullptr;
}

namespace {

// The smallest local conjunct with one reference, if a probe around its references beats a scan.
std::optional<std::size_t> probeConjunct(const binder::BoundFind& find) {
    if (!find.where) return std::nullopt;
    auto terms = conjuncts(*find.where);
    std::optional<std::size_t> best;
    for (std::size_t i = 0; i < terms.size(); ++i) {
        const NodeSet* around = probeReferences(*terms[i]);
        if (around && (!best || around->estimate() < probeReferences(*terms[*best])->estimate())) best = i;
    }
    // A probe costs a tree descent per reference node; a scan costs a test per target node.
    if (!best || probeReferences(*terms[*best])->estimate() * 4 >= find.target.nodes.estimate()) return std::nullopt;
    return best;
}

// From this many target nodes, SIMILAR TO ... LIMIT k without WHERE asks the embedding index
// (one dot product per distinct vector, or HNSW) rather than computing every candidate's similarity:
// a room's few hundred objects share a few dozen vectors.
constexpr std::size_t kSimilarFirstFrom = 256;

// Exactly one reference, known before the statement runs: a name, id or side, or HERE.
bool oneReference(const NodeSet& set) {
    return (set.source == NodeSet::Source::Nodes && set.nodes().size() == 1) || set.source == NodeSet::Source::Side ||
           set.source == NodeSet::Source::Here;
}

}  // namespace

FindPlan planFind(std::shared_ptr<const binder::BoundFind> find) {
    FindPlan plan;
    plan.find = std::move(find);
    const auto& f = *plan.find;
    if (auto probe = probeConjunct(f)) {
        plan.access = Access::RTreeProbe;
        plan.probeConjunct = *probe;
    } else if (f.distanceTo && oneReference(*f.distanceTo) && f.limit && !f.descending) {
        plan.access = Access::NearestFirst;
    } else if (f.similarTo && f.limit && !f.where && f.target.nodes.estimate() >= kSimilarFirstFrom) {
        plan.access = Access::SimilarFirst;
    }
    plan.topK = (!f.orderAttribute.empty() || f.similarTo) && f.limit.has_value();
    return plan;
}

}  // namespace smql::planner
