#include "engine/guide/route_steps.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "model/geometry.hpp"

namespace smql::guide {

namespace {

using model::Node;
using model::NodeKind;

double wrap(double a) {
    while (a > M_PI) a -= 2 * M_PI;
    while (a <= -M_PI) a += 2 * M_PI;
    return a;
}

double degrees(double radians) { return radians / model::kDegree; }

// Legs shorter than this (metres) are not steps of their own.
constexpr double kShortestStep = 0.4;

// "Bear left. " / "Turn left. " / "Turn right. " / "Turn around. " / "" for a change of heading.
std::string turn(double change) {
    double d = degrees(wrap(change));
    if (std::abs(d) <= kStraightDegrees) return "";
    if (std::abs(d) >= 180 - kStraightDegrees) return "Turn around. ";
    if (std::abs(d) < kBearDegrees) return d > 0 ? "Bear left. " : "Bear right. ";
    return d > 0 ? "Turn left. " : "Turn right. ";
}

std::string howFar(double metres) {
    if (metres < 0.75) return "a few steps";
    if (metres < 1.5) return "about 1 m";
    return fmt::format("about {:.0f} m", metres);
}

// A walker's eye looks out below this height above the floor (metres): a thing wholly above it
// (a ceiling light, a vent) is not a landmark anyone walking uses.
constexpr double kEyeLevel = 1.8;

// What a person sees as a landmark: doors, windows and furniture-sized things at eye level, not
// what lies flat on the floor (a rug is walked over, not walked toward).
bool landmarkLike(const Node& n, const Footing& footing) {
    if (n.hidden || n.geometry == model::GeometryKind::None) return false;
    if (n.kind == NodeKind::Anchor) return n.category == "door" || n.category == "window";
    return n.kind == NodeKind::Object && n.box.size.x * n.box.size.y >= 0.3 &&
           model::bottom(n.box) - footing.floor() < kEyeLevel && !footing.walkedOver(n);
}

// What no model named is stored as "object": a landmark only where no named thing is near.
bool unnamed(const Node& n) { return n.category == "object"; }

// A landmark is within this of the end of the leg it names (metres).
constexpr double kLandmarkReach = 1.5;

// The landmark nearest the end of a leg (within kLandmarkReach of it), none of `skipped` (the goal, the thing the walk
// starts beside, the one named last); a thing with a name before one without ("toward the sofa", not "toward
// the object" beside it).
const Node* landmarkAt(const std::vector<Node>& nodes, const Footing& footing, Point p,
                       std::initializer_list<model::NodeId> skipped) {
    const Node* best = nullptr;
    double bestGap = kLandmarkReach;
    for (const Node& n : nodes) {
        if (std::find(skipped.begin(), skipped.end(), n.id) != skipped.end() || !landmarkLike(n, footing)) continue;
        double gap = model::footprintGap(n.box, {p.x, p.y});
        const bool better = !best || (unnamed(*best) && !unnamed(n)) || (unnamed(*best) == unnamed(n) && gap < bestGap);
        if (gap < kLandmarkReach && better) {
            bestGap = gap;
            best = &n;
        }
    }
    return best;
}

// How a step names its landmark: "the sofa"; a thing no model named by its size and colour, as the
// memory keeps them ("the large white thing").
std::string landmarkWords(const Node& n) {
    if (!unnamed(n)) return "the " + n.category;
    std::string words = "the ";
    for (const char* attribute : {"size", "color"})
        if (const std::string* value = n.attribute(attribute)) words += *value + " ";
    return words + "thing";
}

// "the red mug on the desk", "the lamp by the wall"
std::string thingWithSupport(const std::vector<Node>& nodes, const Node& goal) {
    std::string out = "the ";
    if (const std::string* colour = goal.attribute("color")) out += *colour + " ";
    out += goal.category;
    for (const Node& n : nodes)
        if (n.id == goal.parent) {
            if (n.kind == NodeKind::Object) out += " on the " + n.category;
            if (n.kind == NodeKind::Anchor) out += " by the " + n.category;
        }
    return out;
}

}  // namespace

std::vector<Step> describeRoute(const Route& route, const std::vector<Node>& nodes, const Node& goal,
                                std::optional<double> startHeading, const FreeSpace* space, model::NodeId startThing) {
    // Legs, with nearly straight runs merged: a decision is a turn, not every graph node.
    struct Leg {
        Point from, to;
        double heading, length;
    };
    std::vector<Leg> legs;
    for (std::size_t i = 1; i < route.waypoints.size(); ++i) {
        Point a = route.waypoints[i - 1], b = route.waypoints[i];
        double length = std::hypot(b.x - a.x, b.y - a.y);
        if (length < 1e-6) continue;
        double heading = std::atan2(b.y - a.y, b.x - a.x);
        // A step of less than a stride, or nearly straight on, continues the leg before it, unless
        // the one line of both would cut a corner through blocked floor (a walk that ends against it).
        bool shortStep = length < kShortestStep;
        if (!legs.empty() &&
            (shortStep || std::abs(degrees(wrap(heading - legs.back().heading))) <= kStraightDegrees / 2) &&
            (!space || space->clear(legs.back().from, b))) {
            Leg& last = legs.back();
            last.to = b;
            last.length += length;
            last.heading = std::atan2(b.y - last.from.y, b.x - last.from.x);
            continue;
        }
        legs.push_back({a, b, heading, length});
    }

    std::vector<Step> steps;
    std::optional<double> heading = startHeading;
    const Footing footing(nodes, GraphOptions{});
    // A landmark the last step named says nothing new, and the thing the walk starts beside is where the walker
    // stands: a leg along a long sofa is not walked "toward the sofa".
    model::NodeId namedLast = model::kNoNode;
    for (const Leg& leg : legs) {
        Step step;
        step.instruction = heading ? turn(leg.heading - *heading) : "";
        const Node* landmark = landmarkAt(nodes, footing, leg.to, {goal.id, startThing, namedLast});
        namedLast = landmark ? landmark->id : model::kNoNode;
        step.instruction +=
            fmt::format("Walk {}{}.", howFar(leg.length), landmark ? " toward " + landmarkWords(*landmark) : "");
        if (landmark) step.landmark = landmark->id;
        step.at = leg.to;
        step.distance = leg.length;
        steps.push_back(std::move(step));
        heading = leg.heading;
    }

    // Where the goal is from the last point, as the walker faces.
    Point end = route.waypoints.back();
    double dx = goal.box.center.x - end.x, dy = goal.box.center.y - end.y;
    double away = std::hypot(dx, dy);
    std::string where = "right here";
    if (away > 0.05 && heading) {
        double d = degrees(wrap(std::atan2(dy, dx) - *heading));
        where = std::abs(d) <= 45    ? "ahead"
                : std::abs(d) >= 135 ? "behind you"
                : d > 0              ? "on your left"
                                     : "on your right";
    }
    std::string sentence = thingWithSupport(nodes, goal);
    sentence[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(sentence[0])));
    Step last;
    last.instruction =
        fmt::format("{} is {}{}.", sentence, where == "right here" ? "" : fmt::format("{:.1f} m ", away), where);
    last.landmark = goal.id;
    last.at = {goal.box.center.x, goal.box.center.y};
    steps.push_back(std::move(last));
    return steps;
}

}  // namespace smql::guide
