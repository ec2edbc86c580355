// Guidance: where a person can walk in a scene, as a graph of decision points, and the shortest
// route between two places on it (docs/guidance.md). Built from the floor-projected free space:
// the floor minus walls and floor-standing things, grown by a body radius; doors open the walls;
// where a capture's camera went counts as free. Pure functions over model types.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "model/types.hpp"

namespace smql::guide {

struct Point {
    double x = 0, y = 0;
};

struct GraphOptions {
    double bodyRadius = 0.25;  // metres kept from every obstacle
    double cell = 0.1;         // the free-space grid's resolution (m)
    double lattice = 1.0;      // spacing of the junction points laid over the free space (m)
    double maxEdge = 4.0;      // the longest straight segment an edge may be (m)
    // Things whose bottom is this close to the floor stand on it and block the way; higher ones
    // (a mug on a table, a picture on a wall) do not.
    double standingHeight = 0.3;
};

enum class PointKind : std::uint8_t { Door, Approach, Junction, Camera };
std::string_view toString(PointKind kind);

struct DecisionPoint {
    Point at;
    PointKind kind = PointKind::Junction;
    model::NodeId node = model::kNoNode;  // the door, or the thing approached
};

struct Edge {
    std::size_t a = 0, b = 0;
    double length = 0;
};

// The free space of a scene as a grid of cells over its floor rectangle.
class FreeSpace {
public:
    FreeSpace(const std::vector<model::Node>& nodes, const GraphOptions& options);
    bool free(Point p) const;
    // Free and part of the largest connected stretch of free floor: the room people walk in, not a
    // pocket between a bed and a wall.
    bool open(Point p) const;
    // Every cell the straight segment crosses is free.
    bool clear(Point a, Point b) const;
    // The open cell centre nearest to p within `radius` metres, else the nearest free one (in a
    // pocket of its own), if any.
    std::optional<Point> nearestFree(Point p, double radius) const;
    double minX() const { return minX_; }
    double minY() const { return minY_; }
    int width() const { return width_; }
    int height() const { return height_; }
    double cell() const { return cell_; }
    bool freeCell(int i, int j) const { return cells_[static_cast<std::size_t>(j) * width_ + i] != 0; }

private:
    double cell_, minX_ = 0, minY_ = 0;
    int width_ = 0, height_ = 0;
    std::vector<std::uint8_t> cells_;  // 1 = free
    std::vector<int> component_;       // per cell: its connected stretch of free floor, -1 when blocked
    int mainComponent_ = -1;
};

struct RouteGraph {
    std::vector<DecisionPoint> points;
    std::vector<Edge> edges;
};

// The decision points (each door from both sides, an approach point beside each object, junctions
// on a lattice over the free space, the capture's camera positions) and the edges between those
// that see each other within options.maxEdge.
RouteGraph buildGraph(const std::vector<model::Node>& nodes, const FreeSpace& space, const GraphOptions& options);

struct Route {
    std::vector<Point> waypoints;  // from the start to the goal
    double length = 0;
};

// The shortest way from `from` to `to` (Dijkstra on the graph, each end joined to the decision
// points it sees); nullopt when none exists. The ends need not be decision points.
std::optional<Route> shortestRoute(const RouteGraph& graph, const FreeSpace& space, Point from, Point to,
                                   const GraphOptions& options);

}  // namespace smql::guide
