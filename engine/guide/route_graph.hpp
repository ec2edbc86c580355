// Guidance: where a person can walk in a scene, as a graph of decision points, and the shortest
// route between two places on it (docs/guidance.md). Built from the floor-projected free space:
// the floor minus walls and the footprints of what stands on the floor, grown by a body radius;
// flat things (rugs) are walked over, things lying on furniture leave the floor to it; doors open
// the walls at their width less a body; where a capture's camera went counts as free. Pure
// functions over model types.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "model/seating.hpp"
#include "model/types.hpp"

namespace smql::guide {

struct Point {
    double x = 0, y = 0;
};

struct GraphOptions {
    double bodyRadius = model::kBodyRadius;  // metres kept from every obstacle
    double cell = 0.05;                      // the free-space grid's resolution (m)
    double lattice = 1.0;                    // spacing of the junction points laid over the free space (m)
    double maxEdge = 4.0;                    // the longest straight segment an edge may be (m)
    // Things whose bottom is this close to the floor stand on it and block the way; higher ones
    // (a mug on a table, a picture on a wall) do not.
    double standingHeight = 0.3;
    // Things whose top is at most this above the floor (rugs, mats, carpets) are walked over.
    double walkOverHeight = 0.05;
    // The crowded room's free floor (docs/guidance.md, "What guidance assumes"): what a person moves
    // with a hand or a foot (chairs, stools, bags, bins) is pushed aside, and a table's or a desk's box,
    // a bound of its top and not a solid, blocks the floor it covers but not a body's radius around it.
    bool pushAside = false;
};

// What a person pushes aside to pass: a chair, a stool, a bag, a bin.
bool movable(const model::Node& n);
// Furniture on legs whose box bounds its top (a table, a desk): the floor under its edge is free.
bool onLegs(const model::Node& n);

// The floor's height: the top of the largest floor box, else 0 (scenes are stored in the upright
// floor frame: docs/formats.md).
double floorHeight(const std::vector<model::Node>& nodes);

// How guidance sees each thing of a scene: what blocks the floor, and which floor-standing thing
// carries what rests on furniture. Built once per scene over its nodes (which it must outlive).
class Footing {
public:
    Footing(const std::vector<model::Node>& nodes, const GraphOptions& options);
    double floor() const { return floor_; }
    // Flat on the floor: walked over.
    bool walkedOver(const model::Node& n) const;
    // It stands on the floor: a wall, a pillar, a thing standing on the floor that does not rest on
    // furniture (a blanket over a bed's side leaves that floor to the bed).
    bool stands(const model::Node& n) const;
    // Its floor footprint closes the floor: it stands there and is not pushed aside (pushAside).
    bool blocks(const model::Node& n) const;
    // The floor-standing thing under n, following the tree through the furniture it rests on (the
    // bed under the pillow, the table under the plant in its pot); n itself when it rests on none.
    const model::Node& support(const model::Node& n) const;
    // The floor a thing takes: its box, or, for a box that is a loose bound (it overlaps another
    // thing standing on the floor, which the thing itself cannot) turned against the room's walls,
    // the rectangle square to the walls whose bounds the box is: a semantic mesh's box fitted in a
    // frame that is not the thing's (docs/guidance.md, "What guidance assumes").
    const model::Box& footprint(const model::Node& n) const;

private:
    const model::Node* parentThing(const model::Node& n) const;
    const std::vector<model::Node>& nodes_;
    GraphOptions options_;
    double floor_ = 0;
    std::unordered_map<model::NodeId, const model::Node*> byId_;
    std::unordered_map<model::NodeId, model::Box> squared_;
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
    // Whether p and q lie in one connected stretch of free floor.
    bool connected(Point p, Point q) const;
    // What closes off the free stretch around p from the rest of the floor: the things whose
    // blocked cells border it, the longest border first, at most `most`; the stretch's size (m^2).
    std::vector<model::NodeId> enclosedBy(Point p, std::size_t most, double& area) const;
    // The one thing of `candidates` whose removal alone would join p's stretch of free floor to
    // q's (a cabinet in a doorway, a wall box that spans a door), the first such in their order.
    std::optional<model::NodeId> closing(Point p, Point q, const std::vector<model::NodeId>& candidates) const;
    // The thing (or wall) that blocks a cell; kNoNode for a free cell or one outside the floor.
    model::NodeId blocker(int i, int j) const { return blockers_[static_cast<std::size_t>(j) * width_ + i]; }
    double minX() const { return minX_; }
    double minY() const { return minY_; }
    int width() const { return width_; }
    int height() const { return height_; }
    double cell() const { return cell_; }
    bool freeCell(int i, int j) const { return cells_[static_cast<std::size_t>(j) * width_ + i] != 0; }
    // Free and part of the largest connected stretch (see open()).
    bool openCell(int i, int j) const {
        return mainComponent_ >= 0 && component_[static_cast<std::size_t>(j) * width_ + i] == mainComponent_;
    }

private:
    double cell_, minX_ = 0, minY_ = 0;
    int width_ = 0, height_ = 0;
    int componentAt(Point p) const;
    std::vector<std::uint8_t> cells_;      // 1 = free
    std::vector<model::NodeId> blockers_;  // per blocked cell: what blocks it (kNoNode where free)
    std::vector<int> component_;           // per cell: its connected stretch of free floor, -1 when blocked
    std::vector<std::size_t> componentSizes_;
    int mainComponent_ = -1;
};

struct RouteGraph {
    std::vector<DecisionPoint> points;
    std::vector<Edge> edges;
};

// The decision points (each door from both sides, an approach point beside each object — beside
// its floor-standing support when it rests on furniture, nearest to it — junctions on a lattice
// over the free space, the capture's camera positions) and the edges between those that see each
// other within options.maxEdge.
RouteGraph buildGraph(const std::vector<model::Node>& nodes, const FreeSpace& space, const GraphOptions& options);

struct Route {
    std::vector<Point> waypoints;  // from the start to the goal
    double length = 0;
};

// The shortest way from `from` to `to` (Dijkstra on the graph, each end joined to the decision
// points it sees); nullopt when none exists. The ends need not be decision points.
std::optional<Route> shortestRoute(const RouteGraph& graph, const FreeSpace& space, Point from, Point to,
                                   const GraphOptions& options);
// The shortest way from `from` to whichever of `to` (none empty) it reaches first: a walker goes to the side of a
// thing they come from. Where the graph joins none, the way over the free cells to the first.
std::optional<Route> shortestRoute(const RouteGraph& graph, const FreeSpace& space, Point from,
                                   const std::vector<Point>& to, const GraphOptions& options);

// Where a walker may stand to reach `goal`, which stands on the floor: on open floor every 0.2 m around its
// footprint, a body's radius and a little more from it (the decision point beside it, buildGraph's, is the one
// nearest the middle of the room). Empty for a thing that rests on furniture (its one point is beside the thing)
// and for an anchor (a door, a window: its decision points).
std::vector<Point> sidesOf(const std::vector<model::Node>& nodes, const model::Node& goal, const FreeSpace& space,
                           const GraphOptions& options);

}  // namespace smql::guide
