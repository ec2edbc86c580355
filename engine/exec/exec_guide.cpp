// GUIDE and SHOW GRAPH: routes on the scene's decision-point graph, told as steps (docs/guidance.md).
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "engine/exec/executor.hpp"
#include "engine/guide/route_steps.hpp"
#include "model/error.hpp"
#include "model/presentation.hpp"

namespace smql::exec {

namespace {

constexpr std::size_t kCandidatesShown = 8;

Value nodeLabel(const catalog::SceneSnapshot& scene, model::NodeId id) {
    auto slot = scene.slotOf(id);
    return slot ? Value(catalog::SceneSnapshot::label(scene.node(*slot))) : Value();
}

Value nodeId(model::NodeId id) { return id == model::kNoNode ? Value() : Value(static_cast<std::int64_t>(id)); }

// Where the walk to `goal` ends: its approach point, else the free floor nearest it.
std::optional<guide::Point> approachTo(const catalog::SceneSnapshot::Guidance& g, const model::Node& goal) {
    for (const auto& p : g.graph.points)
        if (p.kind == guide::PointKind::Approach && p.node == goal.id) return p.at;
    return g.space.nearestFree({goal.box.center.x, goal.box.center.y}, 1.5);
}

// Why no route joins two points: the smaller of their stretches of free floor, and what closes it.
Error noRoute(const catalog::SceneSnapshot& snap, const std::string& origin, const model::Node& goal,
              guide::Point start, guide::Point end) {
    const auto& g = snap.guidance();
    // Named: the three with the longest border; tried as the one thing that closes the way: twelve.
    constexpr std::size_t kBlockersNamed = 3, kBlockersTried = 12;
    double startArea = 0, endArea = 0;
    auto aroundStart = g.space.enclosedBy(start, kBlockersTried, startArea);
    auto aroundEnd = g.space.enclosedBy(end, kBlockersTried, endArea);
    const bool goalSide = endArea <= startArea;
    const auto& blockers = goalSide ? aroundEnd : aroundStart;
    auto label = [&](model::NodeId id) {
        auto slot = snap.slotOf(id);
        return slot ? catalog::SceneSnapshot::label(snap.node(*slot)) : fmt::format("#{}", id);
    };
    std::string named;
    const std::size_t shown = std::min(blockers.size(), kBlockersNamed);
    for (std::size_t i = 0; i < shown; ++i)
        named += fmt::format("{}{}", i == 0 ? "" : i + 1 == shown ? " and " : ", ", label(blockers[i]));
    // Things before walls: a cabinet in a doorway is what a person moves; a wall only when no thing
    // alone closes the way (a wall box that spans its door).
    std::vector<model::NodeId> tried = blockers;
    std::stable_partition(tried.begin(), tried.end(), [&](model::NodeId id) {
        auto slot = snap.slotOf(id);
        return slot && snap.node(*slot).kind == model::NodeKind::Object;
    });
    const std::optional<model::NodeId> alone = g.space.closing(start, end, tried);
    return Error(
        ErrorKind::Binding,
        fmt::format(
            "no route from {} to {}: the free floor {} ({:.1f} m^2) is closed off{} (a way must be "
            "{} m wide){}",
            origin, catalog::SceneSnapshot::label(goal),
            goalSide ? "beside " + catalog::SceneSnapshot::label(goal) : "at the start", goalSide ? endArea : startArea,
            named.empty() ? "" : " by " + named, 2 * g.options.bodyRadius,
            alone ? fmt::format("; {} alone closes the way: without it a route would pass", label(*alone)) : ""),
        std::nullopt, "smql map draws the free floor and what blocks it; SHOW GRAPH lists the decision points");
}

}  // namespace

catalog::Slot Executor::single(const binder::NodeSet& set, std::string_view role) {
    std::vector<catalog::Slot> candidates;
    for (catalog::Slot s : slots(set, defaultFrame())) {
        const model::Node& n = scene().node(s);
        if (!n.hidden && n.geometry != model::GeometryKind::None && n.kind != model::NodeKind::Scene)
            candidates.push_back(s);
    }
    if (candidates.size() == 1) return candidates.front();
    if (candidates.empty())
        throw Error(ErrorKind::Binding,
                    fmt::format("the {} names no node with a place in the scene ({})", role, set.description),
                    std::nullopt, "FIND shows what a reference names");
    std::vector<std::string> placed;
    for (auto id : candidates) {
        const model::Node& n = scene().node(id);
        placed.push_back(
            fmt::format("{} at ({:.1f}, {:.1f})", catalog::SceneSnapshot::label(n), n.box.center.x, n.box.center.y));
    }
    const std::string listed = model::listFirst(placed, kCandidatesShown);
    const model::Node& first = scene().node(candidates.front());
    throw Error(
        ErrorKind::Binding,
        fmt::format("the {} is ambiguous: {} names {} nodes: {}", role, set.description, candidates.size(), listed),
        std::nullopt,
        fmt::format("name one: {}, or (FIND {} NEAREST TO door LIMIT 1)", catalog::SceneSnapshot::label(first),
                    first.category));
}

ResultSet Executor::run(const binder::BoundShowGraph&) {
    const auto& g = scene().guidance();
    std::vector<std::size_t> degree(g.graph.points.size(), 0);
    for (const auto& e : g.graph.edges) ++degree[e.a], ++degree[e.b];
    ResultSet rs;
    rs.columns = {{"point", ValueType::Integer}, {"kind", ValueType::Text}, {"x", ValueType::Real},
                  {"y", ValueType::Real},        {"node", ValueType::Text}, {"node_id", ValueType::Integer},
                  {"edges", ValueType::Integer}};
    for (std::size_t i = 0; i < g.graph.points.size(); ++i) {
        poll();
        const auto& p = g.graph.points[i];
        rs.rows.push_back({static_cast<std::int64_t>(i), std::string(guide::toString(p.kind)), p.at.x, p.at.y,
                           nodeLabel(scene(), p.node), nodeId(p.node), static_cast<std::int64_t>(degree[i])});
    }
    checkRows(rs.rows.size());
    rs.message = fmt::format("{} decision points, {} edges over {:.1f} m x {:.1f} m of floor", g.graph.points.size(),
                             g.graph.edges.size(), g.space.width() * g.space.cell(), g.space.height() * g.space.cell());
    return rs;
}

namespace {

// A route planned on one of the scene's free floors, or the error that says why there is none.
struct Planned {
    guide::Point start;
    std::optional<double> heading;
    guide::Route route;
    const guide::FreeSpace* space = nullptr;  // the free floor it was found on
};

// What the route crosses of the room's free floor that only the crowded room frees: the chairs and
// bags pushed aside, the tables squeezed past, in the order walked.
std::vector<model::NodeId> pushedAside(const catalog::SceneSnapshot::Guidance& strict, const guide::Route& route) {
    std::vector<model::NodeId> out;
    const auto& space = strict.space;
    for (std::size_t k = 1; k < route.waypoints.size(); ++k) {
        const guide::Point a = route.waypoints[k - 1], b = route.waypoints[k];
        const double length = std::hypot(b.x - a.x, b.y - a.y);
        const int steps = std::max(1, static_cast<int>(std::ceil(length / (space.cell() / 2))));
        for (int t = 0; t <= steps; ++t) {
            const double x = a.x + (b.x - a.x) * t / steps, y = a.y + (b.y - a.y) * t / steps;
            const int i = static_cast<int>(std::floor((x - space.minX()) / space.cell())),
                      j = static_cast<int>(std::floor((y - space.minY()) / space.cell()));
            if (i < 0 || j < 0 || i >= space.width() || j >= space.height()) continue;
            const model::NodeId by = space.blocker(i, j);
            if (by != model::kNoNode && std::find(out.begin(), out.end(), by) == out.end()) out.push_back(by);
        }
    }
    return out;
}

}  // namespace

ResultSet Executor::run(const binder::BoundGuide& guide) {
    const catalog::SceneSnapshot& snap = scene();
    const model::Node& goal = snap.node(single(guide.to, "goal"));

    // The start and the walker's heading there, when the origin gives one.
    std::optional<double> heading;
    std::string origin, startWords;
    model::NodeId startNode = model::kNoNode;
    const model::Node* from = nullptr;
    guide::Point origin0;
    if (guide.point) {
        origin0 = {guide.point->first, guide.point->second};
        origin = fmt::format("({}, {})", guide.point->first, guide.point->second);
        startWords = fmt::format("Start at {}.", origin);
    } else if (!guide.from) {
        const auto& view = snap.info().viewpoint;
        origin0 = {view.position.x, view.position.y};
        heading = view.facingYaw;
        origin = "here (the scene's viewpoint)";
        startWords = "Start here, at the scene's viewpoint.";
    } else {
        from = &snap.node(single(*guide.from, "start"));
        origin = catalog::SceneSnapshot::label(*from);
        startNode = from->id;
        startWords = fmt::format("Start {} the {}.", from->category == "door" ? "at" : "beside", from->category);
        origin0 = {from->box.center.x, from->box.center.y};
    }

    // The route on one free floor; `fail` says why there is none (else nullopt is returned quietly).
    auto plan = [&](const catalog::SceneSnapshot::Guidance& g, bool fail) -> std::optional<Planned> {
        guide::Point start = origin0;
        std::optional<double> facing = heading;
        if (from) {
            // From a door: its side from which the goal's floor is reached, else nearest the goal,
            // facing away from the door. From anything else: the point beside it, as for a goal.
            const guide::Point goalAt{goal.box.center.x, goal.box.center.y};
            const auto goalEnd = approachTo(g, goal);
            auto better = [&](guide::Point p, guide::Point than) {
                const bool reaches = goalEnd && g.space.connected(p, *goalEnd);
                const bool thanReaches = goalEnd && g.space.connected(than, *goalEnd);
                if (reaches != thanReaches) return reaches;
                return std::hypot(p.x - goalAt.x, p.y - goalAt.y) < std::hypot(than.x - goalAt.x, than.y - goalAt.y);
            };
            std::optional<guide::Point> best;
            for (const auto& p : g.graph.points)
                if (p.node == from->id && (!best || better(p.at, *best))) best = p.at;
            if (best) {
                if (from->category == "door") facing = std::atan2(best->y - start.y, best->x - start.x);
                start = *best;
            }
        }
        auto onFloor = g.space.nearestFree(start, 1.0);
        if (!onFloor) {
            if (!fail) return std::nullopt;
            throw Error(ErrorKind::Binding,
                        fmt::format("the start {} is not on free floor: nothing in the scene is walkable within 1 m "
                                    "of ({:.1f}, {:.1f})",
                                    origin, start.x, start.y),
                        std::nullopt, "SHOW GRAPH lists the decision points; start from one of them, a door or HERE");
        }
        const auto end = approachTo(g, goal);
        if (!end) {
            if (!fail) return std::nullopt;
            throw Error(ErrorKind::Binding,
                        fmt::format("no route to {}: no free floor within 1.5 m of it is connected to the rest of "
                                    "the room",
                                    catalog::SceneSnapshot::label(goal)),
                        std::nullopt, "SHOW GRAPH lists where the graph reaches");
        }
        // The walk ends on whichever side of the goal it reaches first; its decision point (the side nearest the
        // middle of the room) is one of them.
        std::vector<guide::Point> ends{*end};
        for (const guide::Point& side : guide::sidesOf(snap.nodes(), goal, g.space, g.options)) ends.push_back(side);
        auto route = guide::shortestRoute(g.graph, g.space, *onFloor, ends, g.options);
        if (!route) {
            if (!fail) return std::nullopt;
            throw noRoute(snap, origin, goal, *onFloor, *end);
        }
        return Planned{*onFloor, facing, std::move(*route), &g.space};
    };

    // The room's free floor first; else the crowded room's, where chairs are pushed aside and
    // tables squeezed past; else the error says what closes the room's free floor.
    const auto& strict = snap.guidance();
    std::optional<Planned> planned = plan(strict, false);
    std::vector<model::NodeId> moved;
    if (!planned) {
        planned = plan(snap.crowdedGuidance(), false);
        if (planned) moved = pushedAside(strict, planned->route);
    }
    if (!planned) planned = plan(strict, true);
    const guide::Point onFloor = planned->start;
    const guide::Route& route = planned->route;

    std::string crowd;
    for (std::size_t i = 0; i < moved.size(); ++i) {
        auto slot = snap.slotOf(moved[i]);
        if (!slot) continue;
        crowd += fmt::format("{}{}", crowd.empty() ? "" : ", ", catalog::SceneSnapshot::label(snap.node(*slot)));
    }

    ResultSet rs;
    rs.columns = {{"step", ValueType::Integer},        {"instruction", ValueType::Text}, {"landmark", ValueType::Text},
                  {"landmark_id", ValueType::Integer}, {"x", ValueType::Real},           {"y", ValueType::Real},
                  {"distance", ValueType::Real}};
    // Step 0 is where the walk begins, so the rows hold the whole route.
    if (!crowd.empty()) startWords += fmt::format(" The way is crowded: push aside or squeeze past {}.", crowd);
    rs.rows.push_back(
        {std::int64_t{0}, startWords, nodeLabel(snap, startNode), nodeId(startNode), onFloor.x, onFloor.y, 0.0});
    auto steps = guide::describeRoute(route, snap.nodes(), goal, planned->heading, planned->space, startNode);
    for (std::size_t i = 0; i < steps.size(); ++i) {
        const auto& step = steps[i];
        rs.rows.push_back({static_cast<std::int64_t>(i + 1), step.instruction, nodeLabel(snap, step.landmark),
                           nodeId(step.landmark), step.at.x, step.at.y, step.distance});
    }
    rs.message =
        fmt::format("{:.1f} m from {} to {} in {} steps{}", route.length, origin, catalog::SceneSnapshot::label(goal),
                    steps.size(), crowd.empty() ? "" : fmt::format(" (crowded: past {})", crowd));
    return rs;
}

}  // namespace smql::exec
