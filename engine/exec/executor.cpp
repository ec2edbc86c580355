#include "engine/exec/executor.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "engine/binder/singular.hpp"
#include "model/error.hpp"
#include "relations/viewer.hpp"

namespace smql::exec {

using binder::NodeSet;
using model::Node;

namespace {

model::Vec2 centre2(const Node& n) { return {n.box.center.x, n.box.center.y}; }

bool queryable(const Node& n) { return !n.hidden && n.kind != model::NodeKind::Scene; }

}  // namespace

Executor::Executor(const storage::ReadTransaction& txn, catalog::Session& session, const planner::Plan& plan,
                   const std::atomic<bool>* interrupt, storage::Database* db)
    : txn_(txn),
      session_(session),
      plan_(plan),
      interrupt_(interrupt),
      db_(db),
      thresholds_(session.thresholds),
      resolved_(plan.statement->setCount),
      membership_(plan.statement->setCount),
      sweeps_(plan.statement->setCount) {}

void Executor::interrupted() {
    throw Error(ErrorKind::Interrupted, "the statement was interrupted", std::nullopt, "nothing was changed");
}

void checkRowLimit(const catalog::Session& session, std::size_t rows) {
    if (static_cast<std::int64_t>(rows) <= session.limits.maxRows) return;
    throw Error(ErrorKind::Limit, fmt::format("the answer has {} rows; the limit is {}", rows, session.limits.maxRows),
                std::nullopt, "add a LIMIT or a WHERE, or raise it: SET max_rows = N");
}

void Executor::checkRows(std::size_t rows) const { checkRowLimit(session_, rows); }

ResultSet Executor::run() {
    ResultSet rs = std::visit([&](const auto& body) { return run(body); }, plan_.statement->body);
    const std::string& note = plan_.statement->note;
    if (!note.empty()) rs.message += (rs.message.empty() ? "" : "\n") + note;
    return rs;
}

const std::vector<catalog::Slot>& Executor::slots(const NodeSet& set, const relations::Frame& frame) {
    if (set.source == NodeSet::Source::Nodes) return set.nodes();
    auto& resolved = resolved_[set.id];
    if (resolved) return *resolved;
    if (set.source == NodeSet::Source::Side) return resolveSide(set, frame);
    // A sub-query runs once, in the statement's read transaction, the first time its nodes are needed.
    std::vector<catalog::Slot> out;
    for (const auto& hit : find(*plan_.subqueries[set.id])) out.push_back(hit.slot);
    std::sort(out.begin(), out.end());
    if (!set.singleFor.empty()) requireOne(scene(), set, out);
    resolved = std::move(out);
    return *resolved;
}

const std::vector<catalog::Slot>& Executor::resolveSide(const NodeSet& set, const relations::Frame& frame) {
    std::vector<catalog::Slot> candidates;
    std::vector<model::Vec2> centres;
    for (catalog::Slot s : set.nodes()) {
        const Node& n = scene().node(s);
        if (n.geometry == model::GeometryKind::None || n.hidden) continue;
        candidates.push_back(s);
        centres.push_back(centre2(n));
    }
    const std::optional<std::size_t> chosen = relations::farthestOnSide(frame, set.side, centres);
    if (!chosen)
        throw Error(ErrorKind::Binding,
                    fmt::format("no {} on the {} side of the viewpoint in scene '{}'",
                                set.description.substr(0, set.description.find('.')), set.side, scene().info().name),
                    std::nullopt, "SHOW SCENES gives the default viewpoint; VIEW FROM x FACING y sets another");
    resolved_[set.id] = std::vector<catalog::Slot>{candidates[*chosen]};
    return *resolved_[set.id];
}

const std::vector<char>& Executor::membership(const NodeSet& set, const relations::Frame& frame) {
    auto& member = membership_[set.id];
    if (member.empty()) {
        member.assign(scene().size(), 0);
        for (catalog::Slot s : slots(set, frame)) member[s] = 1;
    }
    return member;
}

const Executor::ReferenceSweep& Executor::sweepOf(const NodeSet& set, const relations::Frame& frame) {
    auto& sweep = sweeps_[set.id];
    if (!sweep) {
        const auto& nodes = slots(set, frame);
        std::vector<catalog::Slot> order;
        order.reserve(nodes.size());
        for (catalog::Slot s : nodes) {
            const model::Aabb& b = scene().bounds(s);
            if (!std::isnan(b.min.x) && !std::isnan(b.max.x)) order.push_back(s);
        }
        std::sort(order.begin(), order.end(),
                  [&](catalog::Slot a, catalog::Slot b) { return scene().bounds(a).min.x < scene().bounds(b).min.x; });
        sweep.emplace();
        sweep->slots = std::move(order);
        sweep->bounds.reserve(sweep->slots.size());
        for (catalog::Slot s : sweep->slots) {
            sweep->bounds.push_back(scene().bounds(s));
            sweep->widest = std::max(sweep->widest, sweep->bounds.back().max.x - sweep->bounds.back().min.x);
        }
    }
    return *sweep;
}

relations::Frame Executor::defaultFrame() const { return relations::viewFrame(scene().info().viewpoint); }

relations::Frame Executor::frame(const binder::BoundView& view) {
    relations::Frame standard = defaultFrame();
    if (!view.from) return standard;
    const auto& from = slots(*view.from, standard);
    if (from.empty())
        throw Error(ErrorKind::Binding, fmt::format("VIEW FROM {} names no node", view.from->description));
    const Node& origin = scene().node(from.front());
    model::Vec2 towards;
    if (view.facing) {
        const auto& facing = slots(*view.facing, standard);
        if (facing.empty())
            throw Error(ErrorKind::Binding, fmt::format("FACING {} names no node", view.facing->description));
        towards = centre2(scene().node(facing.front()));
    } else {
        // Without FACING the viewer looks into the room: towards the middle of the visible boxes.
        std::vector<model::Vec2> centres;
        for (const auto& node : scene().nodes())
            if (queryable(node) && node.geometry != model::GeometryKind::None) centres.push_back(centre2(node));
        towards = relations::middleOf(centres, origin.box.center);
    }
    const std::optional<model::Viewpoint> viewpoint = relations::lookingAt(origin.box.center, towards);
    if (!viewpoint)
        throw Error(ErrorKind::Binding,
                    fmt::format("VIEW {}: the viewer and what it faces are at the same place", view.description));
    relations::Frame viewer = relations::viewFrame(*viewpoint);
    viewer.headingGiven = view.facing.has_value();
    return viewer;
}

ResultSet Executor::run(const binder::BoundExplain& explain) {
    ResultSet rs;
    rs.columns = {{"plan", ValueType::Text}};
    for (auto& line : plan_.explained->explain()) rs.rows.push_back({std::move(line)});
    if (explain.fromShape)
        rs.rows.push_back(
            {std::string("Parse skipped: a cached statement shape, this text's literals bound as values")});
    return rs;
}

}  // namespace smql::exec
