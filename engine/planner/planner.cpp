#include "engine/planner/planner.hpp"

#include <limits>

#include <fmt/format.h>

namespace smql::planner {

using binder::BoundExpr;
using relations::Predicate;

namespace {

// Predicates that hold only near the reference node, so an R-tree probe can find their candidates.
bool isLocal(Predicate p) {
    return p == Predicate::On || p == Predicate::In || p == Predicate::Above || p == Predicate::Below ||
           p == Predicate::Near || p == Predicate::Attached;
}

std::string literalText(const ast::Literal& literal) {
    return std::visit(
        [](const auto& v) -> std::string {
            if constexpr (std::is_same_v<std::decay_t<decltype(v)>, std::string>)
                return fmt::format("'{}'", v);
            else
                return fmt::format("{}", v);
        },
        literal);
}

std::string_view opText(ast::CompareOp op) {
    switch (op) {
        case ast::CompareOp::Eq: return "=";
        case ast::CompareOp::Ne: return "!=";
        case ast::CompareOp::Lt: return "<";
        case ast::CompareOp::Le: return "<=";
        case ast::CompareOp::Gt: return ">";
        case ast::CompareOp::Ge: return ">=";
        case ast::CompareOp::Like: return "LIKE";
    }
    return "?";
}

}  // namespace

std::string describe(const BoundExpr& expr) {
    switch (expr.kind) {
        case BoundExpr::Kind::And:
        case BoundExpr::Kind::Or: {
            std::string out;
            for (const auto& c : expr.children) {
                if (!out.empty()) out += expr.kind == BoundExpr::Kind::And ? " AND " : " OR ";
                bool group = c.kind == BoundExpr::Kind::And || c.kind == BoundExpr::Kind::Or;
                out += group ? "(" + describe(c) + ")" : describe(c);
            }
            return out;
        }
        case BoundExpr::Kind::Not:
            return "NOT " + describe(expr.children.front());
        case BoundExpr::Kind::Predicate: {
            std::string out = std::string(relations::toString(expr.predicate)) + "(";
            for (std::size_t i = 0; i < expr.args.size(); ++i) out += (i ? ", " : "") + expr.args[i].description;
            if (expr.nearDistance) out += fmt::format(", {} m", *expr.nearDistance);
            return out + ")";
        }
        case BoundExpr::Kind::Compare:
            return fmt::format("{} {} {}", expr.attribute, opText(expr.op), literalText(expr.literal));
    }
    return {};
}

FindPlan planFind(const binder::BoundFind& find, const exec::SceneSnapshot& scene, const relations::Thresholds& t) {
    FindPlan plan;
    plan.find = &find;
    if (!find.where) return plan;

    // Only top-level conjuncts may drive a probe: each must hold for every row.
    std::vector<const BoundExpr*> conjuncts;
    if (find.where->kind == BoundExpr::Kind::And)
        for (const auto& c : find.where->children) conjuncts.push_back(&c);
    else
        conjuncts.push_back(&*find.where);

    const BoundExpr* best = nullptr;
    for (const BoundExpr* c : conjuncts) {
        if (c->kind != BoundExpr::Kind::Predicate || c->args.size() != 1) continue;
        if (!isLocal(c->predicate)) continue;
        if (!best || c->args[0].slots.size() < best->args[0].slots.size()) best = c;
    }
    // A probe costs a tree descent per reference node; a scan costs a test per target node.
    if (!best || best->args[0].slots.size() * 4 >= find.target.nodes.slots.size()) return plan;

    RTreeProbe probe;
    double nearDistance = best->nearDistance.value_or(t.nearDistance);
    for (auto slot : best->args[0].slots)
        probe.regions.push_back(*relations::candidateRegion(best->predicate, scene.bounds(slot), nearDistance, t));
    probe.description = describe(*best);
    plan.probe = std::move(probe);
    return plan;
}

std::vector<std::string> FindPlan::explain() const {
    std::vector<std::string> lines;
    const auto& f = *find;
    if (f.countOnly) {
        lines.push_back("Count");
    } else {
        std::string columns = "id, category, source_id, box";
        if (f.distanceTo) columns += ", distance";
        if (f.path) columns += ", path";
        lines.push_back("Project " + columns);
        if (f.limit) lines.push_back(fmt::format("Limit {}", *f.limit));
        if (f.distanceTo)
            lines.push_back(fmt::format("Sort by distance to {}{}{}", f.distanceTo->description,
                                        f.descending ? " descending" : "", f.nearest ? ", without itself" : ""));
    }
    if (f.where) lines.push_back("Filter " + describe(*f.where));
    if (probe) {
        lines.push_back(fmt::format("R-tree probe for {}: {} region{}, keep {}", probe->description,
                                    probe->regions.size(), probe->regions.size() == 1 ? "" : "s",
                                    f.target.description));
    } else {
        lines.push_back("Scan " + f.target.description);
    }
    for (std::size_t i = 0; i < lines.size(); ++i) lines[i] = std::string(2 * i, ' ') + lines[i];
    lines.push_back(std::string(2 * lines.size(), ' ') + "(view: " + f.viewDescription + ")");
    return lines;
}

}  // namespace smql::planner
