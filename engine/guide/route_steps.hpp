// A route in words: each leg a step that names a landmark, the turn relative to the walker's
// heading and the distance; the last step says where the goal is (docs/guidance.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "engine/guide/route_graph.hpp"
#include "model/types.hpp"

namespace smql::guide {

struct Step {
    std::string instruction;                  // "Turn right. Walk about 2 m toward the sofa."
    model::NodeId landmark = model::kNoNode;  // the thing the step names, if any
    Point at;                                 // where the step ends
    double distance = 0;                      // metres walked in it
};

// Turns within this angle are "go straight"; beyond 180 minus it, "turn around" (degrees).
inline constexpr double kStraightDegrees = 30;
// Turns within this angle (and beyond kStraightDegrees) are "bear left" or "bear right": three such turns in a row
// said as "turn right" sound like a walk in a circle, where the way only swings around a stool (degrees).
inline constexpr double kBearDegrees = 60;

// `nodes` are the scene's (for landmarks and the goal's support); `goal` the thing sought;
// `startHeading` the walker's heading at the start (radians about +z), when known; `space` the free
// floor the route was found on, when given: two legs merge only where their one line stays on it;
// `startThing` the thing the walk starts beside, when it does (the start step names it already).
std::vector<Step> describeRoute(const Route& route, const std::vector<model::Node>& nodes, const model::Node& goal,
                                std::optional<double> startHeading, const FreeSpace* space = nullptr,
                                model::NodeId startThing = model::kNoNode);

}  // namespace smql::guide
