#include "engine/binder/binder.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "engine/error.hpp"
#include "engine/model/geometry.hpp"
#include "engine/model/names.hpp"

namespace smql::binder {

using model::Node;
using model::NodeKind;

namespace {

// Kind words name every node of a kind; plurals are accepted.
std::optional<NodeKind> kindWord(const std::string& name) {
    static const std::pair<std::string_view, NodeKind> words[] = {
        {"object", NodeKind::Object}, {"objects", NodeKind::Object}, {"anchor", NodeKind::Anchor},
        {"anchors", NodeKind::Anchor}, {"room", NodeKind::Room},     {"rooms", NodeKind::Room},
        {"frame", NodeKind::Frame},   {"frames", NodeKind::Frame},   {"description", NodeKind::Description},
        {"descriptions", NodeKind::Description}};
    for (const auto& [word, kind] : words)
        if (name == word) return kind;
    return std::nullopt;
}

bool anyNodeWord(const std::string& name) { return name == "node" || name == "nodes" || name == "thing" || name == "things"; }

bool queryable(const Node& n) { return !n.hidden && n.kind != NodeKind::Scene; }

std::string describeSet(const std::string& name, std::size_t count) {
    return fmt::format("{} ({} node{})", name, count, count == 1 ? "" : "s");
}

model::Vec2 centre2(const Node& n) { return {n.box.center.x, n.box.center.y}; }

}  // namespace

std::string Binder::resolveCategory(const ast::Ref& ref) const {
    const auto& name = ref.name;
    if (!ctx_.scene.withCategory(name).empty()) return name;
    // Plurals of known categories ("cushions", "boxes").
    for (std::string_view suffix : {"es", "s"}) {
        if (name.size() > suffix.size() + 1 && name.ends_with(suffix)) {
            std::string singular = name.substr(0, name.size() - suffix.size());
            if (!ctx_.scene.withCategory(singular).empty()) return singular;
        }
    }
    if (ctx_.categoryExistsElsewhere && ctx_.categoryExistsElsewhere(name)) return name;
    auto known = ctx_.scene.categories();
    auto close = model::nearestNames(name, known);
    std::string hint = close.empty()
                           ? fmt::format("this scene has: {}", model::joinAlternatives(known))
                           : fmt::format("did you mean {}?", model::joinAlternatives(close));
    throw Error(ErrorKind::Binding, fmt::format("unknown category '{}' in scene '{}'", name, ctx_.scene.info().name),
                ref.where, hint);
}

NodeSet Binder::bindName(const ast::Ref& ref) const {
    NodeSet set;
    if (auto kind = kindWord(ref.name)) {
        for (Slot s : ctx_.scene.slotsOfKind(*kind))
            if (queryable(ctx_.scene.node(s))) set.slots.push_back(s);
        set.description = describeSet(ref.name, set.slots.size());
        return set;
    }
    if (anyNodeWord(ref.name)) {
        for (Slot s = 0; s < ctx_.scene.nodes().size(); ++s)
            if (queryable(ctx_.scene.node(s))) set.slots.push_back(s);
        set.description = describeSet(ref.name, set.slots.size());
        return set;
    }
    std::string category = resolveCategory(ref);
    // Naming a category asks for its nodes, hidden ones included (`undefined`).
    set.slots = ctx_.scene.withCategory(category);
    set.description = describeSet(category, set.slots.size());
    return set;
}

NodeSet Binder::bindSide(const ast::Ref& ref, const relations::Frame& frame) const {
    NodeSet all = bindName(ast::Ref{ast::Ref::Kind::Name, ref.name, {}, 0, nullptr, ref.where});
    // Each candidate's centre in the viewer's frame: `lateral` to the right, `depth` ahead.
    std::optional<Slot> best;
    double bestScore = -std::numeric_limits<double>::infinity();
    bool bestInSector = false;
    for (Slot s : all.slots) {
        const Node& n = ctx_.scene.node(s);
        if (n.geometry == model::GeometryKind::None || n.hidden) continue;
        model::Vec2 c = centre2(n);
        double dx = c.x - frame.position.x, dy = c.y - frame.position.y;
        double lateral = dx * frame.right.x + dy * frame.right.y;
        double depth = dx * frame.forward.x + dy * frame.forward.y;
        double along = ref.side == "left" ? -lateral : ref.side == "right" ? lateral : ref.side == "front" ? depth : -depth;
        double across = ref.side == "left" || ref.side == "right" ? depth : lateral;
        // Prefer candidates inside the 90-degree sector around that side, then the farthest out.
        bool inSector = along > 0 && along >= std::abs(across);
        if (!best || (inSector && !bestInSector) || (inSector == bestInSector && along > bestScore)) {
            best = s, bestScore = along, bestInSector = inSector;
        }
    }
    if (!best || bestScore <= 0)
        throw Error(ErrorKind::Binding,
                    fmt::format("no {} on the {} side of the viewpoint in scene '{}'", ref.name, ref.side,
                                ctx_.scene.info().name),
                    ref.where, "SHOW SCENES gives the default viewpoint; VIEW FROM x FACING y sets another");
    return NodeSet{{*best}, fmt::format("{}.{} = {}", ref.name, ref.side, exec::SceneSnapshot::label(ctx_.scene.node(*best)))};
}

NodeSet Binder::bindRef(const ast::Ref& ref, const relations::Frame& frame) const {
    switch (ref.kind) {
        case ast::Ref::Kind::Name:
            return bindName(ref);
        case ast::Ref::Kind::Side:
            return bindSide(ref, frame);
        case ast::Ref::Kind::NodeId: {
            auto slot = ctx_.scene.slotOf(static_cast<model::NodeId>(ref.number));
            if (!slot)
                throw Error(ErrorKind::Binding,
                            fmt::format("no node #{} in scene '{}'", ref.number, ctx_.scene.info().name), ref.where,
                            "ids are global; SHOW TREE lists this scene's nodes, USE SCENE switches scenes");
            return NodeSet{{*slot}, exec::SceneSnapshot::label(ctx_.scene.node(*slot))};
        }
        case ast::Ref::Kind::SourceId: {
            auto slot = ctx_.scene.slotOfSource(ref.number);
            if (!slot)
                throw Error(ErrorKind::Binding,
                            fmt::format("no node with source id {} in scene '{}'", ref.number, ctx_.scene.info().name),
                            ref.where, "source ids are the ids of the imported file; they resolve in the current scene");
            return NodeSet{{*slot}, fmt::format("src#{} = {}", ref.number,
                                                exec::SceneSnapshot::label(ctx_.scene.node(*slot)))};
        }
        case ast::Ref::Kind::SubQuery: {
            auto slots = ctx_.runSubquery(*ref.subquery);
            return NodeSet{slots, describeSet("sub-query", slots.size())};
        }
    }
    return {};
}

relations::Frame Binder::bindView(const std::optional<ast::View>& view, std::string& description) const {
    const auto& info = ctx_.scene.info();
    if (!view) {
        description = "default viewpoint of scene '" + info.name + "'";
        return relations::viewFrame(info.viewpoint);
    }
    relations::Frame defaultFrame = relations::viewFrame(info.viewpoint);
    NodeSet from = bindRef(view->from, defaultFrame);
    if (from.slots.empty())
        throw Error(ErrorKind::Binding, "VIEW FROM names no node", view->from.where);
    const Node& origin = ctx_.scene.node(from.slots.front());
    model::Vec2 position = centre2(origin);
    model::Vec2 towards;
    if (view->facing) {
        NodeSet facing = bindRef(*view->facing, defaultFrame);
        if (facing.slots.empty()) throw Error(ErrorKind::Binding, "FACING names no node", view->facing->where);
        towards = centre2(ctx_.scene.node(facing.slots.front()));
        description = fmt::format("from {} facing {}", exec::SceneSnapshot::label(origin),
                                  exec::SceneSnapshot::label(ctx_.scene.node(facing.slots.front())));
    } else {
        // Without FACING the viewer looks into the room: towards the centre of all visible boxes.
        double sx = 0, sy = 0;
        std::size_t n = 0;
        for (const auto& node : ctx_.scene.nodes())
            if (queryable(node) && node.geometry != model::GeometryKind::None) sx += node.box.center.x, sy += node.box.center.y, ++n;
        towards = n ? model::Vec2{sx / n, sy / n} : model::Vec2{position.x, position.y + 1};
        description = fmt::format("from {} facing the middle of the scene", exec::SceneSnapshot::label(origin));
    }
    double dx = towards.x - position.x, dy = towards.y - position.y;
    if (std::hypot(dx, dy) < 1e-6)
        throw Error(ErrorKind::Binding, "VIEW FROM and FACING are at the same place", view->where);
    model::Viewpoint vp{{position.x, position.y, origin.box.center.z}, std::atan2(dy, dx)};
    return relations::viewFrame(vp);
}

Target Binder::bindTarget(const ast::Ref& ref, const relations::Frame& frame) const {
    Target t;
    if (ref.kind == ast::Ref::Kind::Name) {
        if (auto kind = kindWord(ref.name)) {
            t.kind = Target::Kind::NodeKind, t.nodeKind = *kind;
        } else if (anyNodeWord(ref.name)) {
            t.kind = Target::Kind::AnyNode;
        } else {
            t.kind = Target::Kind::Category;
            t.category = resolveCategory(ref);
        }
    } else {
        t.kind = Target::Kind::Nodes;
    }
    t.nodes = bindRef(ref, frame);
    t.description = t.nodes.description;
    return t;
}

BoundExpr Binder::bindExpr(const ast::Expr& expr, const relations::Frame& frame) const {
    BoundExpr out;
    switch (expr.kind) {
        case ast::Expr::Kind::And: out.kind = BoundExpr::Kind::And; break;
        case ast::Expr::Kind::Or: out.kind = BoundExpr::Kind::Or; break;
        case ast::Expr::Kind::Not: out.kind = BoundExpr::Kind::Not; break;
        case ast::Expr::Kind::Predicate: {
            out.kind = BoundExpr::Kind::Predicate;
            auto p = relations::predicateFromName(expr.predicate);
            if (!p) {
                std::vector<std::string> names = {"on", "in", "inside", "above", "below", "under", "near", "attached",
                                                  "left_of", "right_of", "in_front_of", "behind", "between"};
                auto close = model::nearestNames(expr.predicate, names);
                throw Error(ErrorKind::Binding, fmt::format("unknown predicate '{}'", expr.predicate), expr.where,
                            close.empty() ? "predicates: " + model::joinAlternatives(names)
                                          : "did you mean " + model::joinAlternatives(close) + "?");
            }
            out.predicate = *p;
            int want = relations::arity(*p);
            if (static_cast<int>(expr.args.size()) != want)
                throw Error(ErrorKind::Binding,
                            fmt::format("{}() takes {} reference{}, got {}", expr.predicate, want, want == 1 ? "" : "s",
                                        expr.args.size()),
                            expr.where,
                            *p == relations::Predicate::Between ? "between(lamp, sofa): the target lies between the two"
                                                                : fmt::format("{}(desk)", expr.predicate));
            if (expr.threshold) {
                if (*p != relations::Predicate::Near)
                    throw Error(ErrorKind::Binding, fmt::format("only near() takes a distance, not {}()", expr.predicate),
                                expr.threshold->where, "SET changes the other thresholds; SHOW SETTINGS lists them");
                out.nearDistance = expr.threshold->metres;
            }
            for (const auto& arg : expr.args) out.args.push_back(bindRef(arg, frame));
            return out;
        }
        case ast::Expr::Kind::Compare:
            out.kind = BoundExpr::Kind::Compare;
            out.attribute = expr.attribute;
            out.op = expr.op;
            out.literal = expr.literal;
            return out;
    }
    for (const auto& child : expr.children) out.children.push_back(bindExpr(child, frame));
    return out;
}

BoundFind Binder::bindFind(const ast::FindStmt& find) const {
    BoundFind out;
    out.frame = bindView(find.view, out.viewDescription);
    out.target = bindTarget(find.target, out.frame);
    if (find.where) out.where = bindExpr(*find.where, out.frame);
    if (find.nearestTo && find.orderBy)
        throw Error(ErrorKind::Binding, "NEAREST TO and ORDER BY both set an order", find.orderBy->where,
                    "keep one: NEAREST TO x is ORDER BY distance(x) without x itself");
    if (find.nearestTo) {
        out.distanceTo = bindRef(*find.nearestTo, out.frame);
        out.nearest = true;
    } else if (find.orderBy) {
        out.distanceTo = bindRef(find.orderBy->distanceTo, out.frame);
        out.descending = find.orderBy->descending;
    }
    out.limit = find.limit;
    out.path = find.path;
    return out;
}

// COUNT is a FIND without order, limit or path that returns only how many.
BoundFind Binder::bindCount(const ast::CountStmt& count) const {
    ast::FindStmt find;
    find.target = count.target;
    find.view = count.view;
    find.where = count.where;
    BoundFind out = bindFind(find);
    out.countOnly = true;
    return out;
}

BoundRelate Binder::bindRelate(const ast::RelateStmt& relate) const {
    BoundRelate out;
    out.frame = bindView(relate.view, out.viewDescription);
    out.subject = bindRef(relate.subject, out.frame);
    out.object = bindRef(relate.object, out.frame);
    return out;
}

}  // namespace smql::binder
