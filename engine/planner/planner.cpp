#include "engine/planner/planner.hpp"

namespace smql::planner {

using binder::BoundExpr;
using binder::BoundFind;
using binder::NodeSet;

namespace {

// Every sub-query a statement holds, at any depth, gets its plan under its set's id.
struct SubqueryPlanner {
    std::vector<std::shared_ptr<const FindPlan>>& plans;

    void set(const NodeSet& s) {
        if (s.source != NodeSet::Source::SubQuery) return;
        find(*s.subquery);
        plans[s.id] = std::make_shared<const FindPlan>(planFind(s.subquery));
    }
    void set(const std::optional<NodeSet>& s) {
        if (s) set(*s);
    }
    void view(const binder::BoundView& v) {
        set(v.from);
        set(v.facing);
    }
    void expr(const BoundExpr& e) {
        for (const auto& c : e.children) expr(c);
        for (const auto& a : e.args) set(a);
        set(e.distanceTo);
    }
    void find(const BoundFind& f) {
        view(f.view);
        set(f.target.nodes);
        if (f.where) expr(*f.where);
        set(f.distanceTo);
    }

    void body(const BoundFind& f) { find(f); }
    void body(const binder::BoundRelate& r) {
        view(r.view);
        set(r.subject);
        set(r.object);
    }
    void body(const binder::BoundDescribe& d) { set(d.nodes); }
    void body(const binder::BoundCheck& c) {
        view(c.view);
        set(c.subject);
        for (const auto& a : c.args) set(a);
    }
    void body(const binder::BoundShowTree& t) { set(t.root); }
    void body(const binder::BoundGuide& g) {
        set(g.from);
        set(g.to);
    }
    void body(const auto&) {}
};

}  // namespace

Plan plan(std::shared_ptr<const binder::BoundStatement> statement) {
    Plan out;
    out.statement = statement;
    out.subqueries.resize(statement->setCount);
    SubqueryPlanner subqueries{out.subqueries};
    std::visit([&](const auto& body) { subqueries.body(body); }, statement->body);
    if (const auto* find = std::get_if<BoundFind>(&statement->body))
        out.find = planFind(std::shared_ptr<const BoundFind>(statement, find));
    if (const auto* explain = std::get_if<binder::BoundExplain>(&statement->body))
        out.explained = std::make_shared<const Plan>(plan(explain->inner));
    if (const auto* ask = std::get_if<binder::BoundAsk>(&statement->body); ask && ask->inner)
        out.asked = std::make_shared<const Plan>(plan(ask->inner));
    return out;
}

}  // namespace smql::planner
