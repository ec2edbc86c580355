// EXPLAIN's text: the plan's operators, root first, each indented under its parent.
#include <fmt/format.h>

#include "engine/planner/planner.hpp"
#include "engine/similar/embedding_index.hpp"

namespace smql::planner {

using binder::BoundExpr;

namespace {

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

// NEAREST TO x leaves x out of its answer; HERE is no node to leave out.
const char* withoutItself(const binder::BoundFind& f) {
    return f.nearest && f.distanceTo->source != binder::NodeSet::Source::Here ? ", without itself" : "";
}

// What SIMILAR TO compares with: "'couch'" or "the bound vector (384 dimensions)".
std::string similarQuery(const binder::BoundSimilarTo& similarTo) {
    return similarTo.stored() ? fmt::format("the bound vector ({} dimensions)", similarTo.vector.size())
                              : fmt::format("'{}'", similarTo.text);
}

// Which vectors it searches: the built-in text embedder's or those stored on the nodes at ingest.
std::string_view similarSpace(const binder::BoundSimilarTo& similarTo) {
    return similarTo.stored() ? "the space of the nodes' stored embeddings" : "the built-in text embedder's space";
}

// Operators from the root down; `indent` nests each under the one before.
struct Lines {
    std::vector<std::string> out;
    std::size_t depth = 0;
    void add(std::string line) { out.push_back(std::string(2 * depth++, ' ') + std::move(line)); }
    void note(std::string line) { out.push_back(std::string(2 * depth, ' ') + std::move(line)); }
};

void explainFind(const FindPlan& plan, Lines& lines) {
    const auto& f = *plan.find;
    if (f.countOnly) {
        lines.add("Count");
    } else {
        std::string columns;
        for (const auto& column : f.columns) columns += (columns.empty() ? "" : ", ") + column;
        if (columns.empty()) {
            columns = "id, category, source_id, box";
            if (f.distanceTo) columns += ", distance";
            if (f.similarTo) columns += ", similarity";
        }
        if (f.path) columns += ", path";
        lines.add("Project " + columns);
        if (f.limit) lines.add(fmt::format("Limit {}", *f.limit));
    }
    std::string keep = f.target.nodes.description;
    switch (plan.access) {
        case Access::NearestFirst:
            lines.add(
                fmt::format("Top {} nearest to {}{}: R-tree nearest-first search, widened until no box "
                            "outside can beat the last answer",
                            *f.limit, f.distanceTo->description, withoutItself(f)));
            if (f.where) lines.add("Filter " + describe(*f.where));
            lines.add("Keep " + keep);
            break;
        case Access::SimilarFirst:
            lines.add(
                fmt::format("Top {} most similar to {} in {}: search of the embedding index's distinct vectors "
                            "(HNSW from {} of them), widened until {} pass",
                            *f.limit, similarQuery(*f.similarTo), similarSpace(*f.similarTo),
                            similar::EmbeddingIndex::kIndexedFrom, *f.limit));
            lines.add("Keep " + keep);
            break;
        case Access::RTreeProbe:
        case Access::Scan:
            if (f.distanceTo)
                lines.add(fmt::format("Sort by distance to {}{}{}", f.distanceTo->description,
                                      f.descending ? " descending" : "", withoutItself(f)));
            if (f.similarTo)
                lines.add(fmt::format("{} by similarity to {} in {}: exact, each candidate's vector, {}",
                                      plan.topK ? fmt::format("Top {}", *f.limit) : std::string("Sort"),
                                      similarQuery(*f.similarTo), similarSpace(*f.similarTo),
                                      f.similarTo->stored() ? std::string("nodes without one left out")
                                                            : fmt::format("none below {}", similar::kLeastSimilarity)));
            if (!f.orderAttribute.empty() && plan.topK)
                lines.add(fmt::format("Top {} by {}{}: partial sort, nodes without it last", *f.limit, f.orderAttribute,
                                      f.descending ? " descending" : ""));
            else if (!f.orderAttribute.empty())
                lines.add(fmt::format("Sort by {}{}, nodes without it last", f.orderAttribute,
                                      f.descending ? " descending" : ""));
            if (f.where) lines.add("Filter " + describe(*f.where));
            if (plan.access == Access::RTreeProbe)
                lines.add(fmt::format("R-tree probe for {} around each reference node, keep {}",
                                      describe(plan.probeTerm()), keep));
            else
                lines.add("Scan " + keep);
            break;
    }
    lines.note("(view: " + f.view.description + ")");
}

struct StatementLines {
    const Plan& plan;
    Lines& lines;

    void operator()(const binder::BoundFind&) const { explainFind(*plan.find, lines); }
    void operator()(const binder::BoundCatalogFind& f) const {
        if (f.countOnly) {
            lines.add(fmt::format("Count '{}' in every scene from the label index's counts", f.category));
            return;
        }
        lines.add("Project id, category, scene, source_id, box");
        if (f.limit) lines.add(fmt::format("Limit {}", *f.limit));
        lines.add(fmt::format(
            "Label index scan of '{}' across all scenes, its entries holding the columns (no node record read)",
            f.category));
    }
    void operator()(const binder::BoundRelate& r) const {
        lines.add(
            fmt::format("Relate each node of {} to each node of {}", r.subject.description, r.object.description));
        lines.note("(view: " + r.view.description + ")");
    }
    void operator()(const binder::BoundCheck& c) const {
        std::string args;
        for (const auto& a : c.args) args += (args.empty() ? "" : " and ") + a.description;
        lines.add(fmt::format("Check {} {} {}{}", c.subject.description, relations::toString(c.predicate), args,
                              c.nearDistance ? fmt::format(" within {} m", *c.nearDistance) : std::string()));
        lines.note("(view: " + c.view.description + ")");
    }
    void operator()(const binder::BoundShowCategories& s) const {
        lines.add(s.allScenes ? std::string("Count each category of each scene from the label index")
                              : std::string("Count the nodes of each category of the current scene"));
    }
    void operator()(const binder::BoundShowAttributes&) const {
        lines.add("List the built-in attributes and those stored in the current scene");
    }
    void operator()(const binder::BoundDescribe& d) const {
        lines.add(fmt::format("Describe {}, with evidence from the blob table", d.nodes.description));
    }
    void operator()(const binder::BoundShowScenes&) const { lines.add("Read the scene table"); }
    void operator()(const binder::BoundShowSettings&) const { lines.add("List the settings of this session"); }
    void operator()(const binder::BoundShowTree& t) const {
        lines.add("Walk the tree depth-first from " + (t.root ? t.root->description : std::string("the scene root")));
    }
    void operator()(const binder::BoundShowChanges& c) const {
        lines.add(fmt::format("Read the history of scene '{}'{}", c.scene,
                              c.since ? fmt::format(", updates at or after {}", *c.since) : std::string()));
    }
    void operator()(const binder::BoundShowGraph&) const {
        lines.add("Build the scene's decision-point graph over its free floor (kept with the scene's snapshot)");
    }
    void operator()(const binder::BoundGuide& g) const {
        std::string from = g.from    ? g.from->description
                           : g.point ? fmt::format("the point ({}, {})", g.point->first, g.point->second)
                                     : std::string("the scene's viewpoint");
        lines.add(
            fmt::format("Guide from {} to {}: shortest route on the decision-point graph (Dijkstra), "
                        "told as steps",
                        from, g.to.description));
    }
    void operator()(const binder::BoundDropScene& d) const {
        lines.add(
            fmt::format("Remove scene '{}' with its nodes, indexes and history, in one write transaction", d.scene));
    }
    void operator()(const binder::BoundRenameScene& r) const {
        lines.add(
            fmt::format("Rename scene '{}' to '{}' with its history, in one write transaction", r.scene, r.newName));
    }
    void operator()(const binder::BoundUse& u) const {
        lines.add(u.allScenes ? std::string("Switch the session to all scenes")
                              : fmt::format("Switch the session to scene '{}'", u.scene));
    }
    void operator()(const binder::BoundSet& s) const {
        if (s.setsTranslator)
            lines.add(fmt::format("Set translator = '{}' for this session", s.translatorUrl));
        else
            lines.add(fmt::format("Set {} = {} for this session", s.name(), s.value));
    }
    void operator()(const binder::BoundExplain&) const {
        for (auto& line : plan.explained->explain()) lines.out.push_back(std::move(line));
    }
    void operator()(const binder::BoundAsk& a) const {
        lines.add(fmt::format("Answer the question with {}{}", a.inner ? "" : "(not run) ", a.translation.smql));
        if (!plan.asked) return;
        for (auto& line : plan.asked->explain()) lines.out.push_back("  " + line);
    }
};

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
            if (expr.distanceTo)
                return fmt::format("distance({}) {} {} m", expr.distanceTo->description, ast::toString(expr.op),
                                   literalText(expr.literal));
            if (expr.op == ast::CompareOp::IsNull || expr.op == ast::CompareOp::IsNotNull)
                return fmt::format("{} {}", expr.attribute, ast::toString(expr.op));
            return fmt::format("{} {} {}", expr.attribute, ast::toString(expr.op), literalText(expr.literal));
    }
    return {};
}

std::vector<std::string> Plan::explain() const {
    Lines lines;
    std::visit(StatementLines{*this, lines}, statement->body);
    // Sub-queries run first, each once, when the statement first needs their nodes.
    for (std::size_t id = 0; id < subqueries.size(); ++id) {
        if (!subqueries[id]) continue;
        lines.depth = 0;
        lines.add(fmt::format("Sub-query {}, run once before its first use:", id));
        explainFind(*subqueries[id], lines);
    }
    return lines.out;
}

}  // namespace smql::planner
