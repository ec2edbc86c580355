#include "engine/guide/route_graph.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <boost/geometry.hpp>
#include <boost/geometry/geometries/multi_point.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/dijkstra_shortest_paths.hpp>

#include "model/floor.hpp"
#include "model/geometry.hpp"

namespace smql::guide {

namespace {

using model::Node;
using model::NodeKind;

bool solid(const Node& n) { return !n.hidden && n.geometry != model::GeometryKind::None; }

double distance(Point a, Point b) { return std::hypot(a.x - b.x, a.y - b.y); }

// The rectangle people walk in: the floor's boxes, else the walls', else every box's.
model::Aabb floorRectangle(const std::vector<Node>& nodes) {
    model::Aabb out{{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(), 0},
                    {-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(), 0}};
    for (const char* category : {"floor", "wall", ""}) {
        for (const Node& n : nodes) {
            if (!solid(n) || (*category && n.category != category)) continue;
            if (!*category && n.kind != NodeKind::Anchor && n.kind != NodeKind::Object) continue;
            model::Aabb box = model::worldAabb(n.box);
            out.min.x = std::min(out.min.x, box.min.x);
            out.min.y = std::min(out.min.y, box.min.y);
            out.max.x = std::max(out.max.x, box.max.x);
            out.max.y = std::max(out.max.y, box.max.y);
        }
        if (out.min.x <= out.max.x) break;
    }
    if (!(out.min.x <= out.max.x)) out = {{0, 0, 0}, {0, 0, 0}};
    return out;
}

namespace bg = boost::geometry;
using Outline = bg::model::polygon<bg::model::d2::point_xy<double>>;

// A layout of things without a floor or walls (a scan's boxes): the room is the convex hull of
// their footprints, not the axis-aligned rectangle around them, which for a room at an angle
// holds as much floor outside it as in it.
std::optional<Outline> thingsOutline(const std::vector<Node>& nodes) {
    bg::model::multi_point<bg::model::d2::point_xy<double>> corners;
    for (const Node& n : nodes) {
        if (!solid(n)) continue;
        if (n.kind == NodeKind::Anchor && (n.category == "floor" || n.category == "wall")) return std::nullopt;
        if (n.kind == NodeKind::Anchor || n.kind == NodeKind::Object)
            for (model::Vec2 c : model::footprint(n.box))
                bg::append(corners, bg::model::d2::point_xy<double>(c.x, c.y));
    }
    if (corners.size() < 3) return std::nullopt;
    Outline hull;
    bg::convex_hull(corners, hull);
    return hull;
}

// The direction of the room's walls, modulo a right angle (radians): the mean of their long
// sides' directions weighted by length, taken on a circle of a quarter turn. None without walls.
std::optional<double> wallDirection(const std::vector<Node>& nodes) {
    double x = 0, y = 0;
    for (const Node& n : nodes) {
        if (n.kind != NodeKind::Anchor || n.category != "wall" || !solid(n)) continue;
        const double length = std::max(n.box.size.x, n.box.size.y);
        const double along = n.box.yaw + (n.box.size.x < n.box.size.y ? M_PI / 2 : 0.0);
        x += length * std::cos(4 * along);
        y += length * std::sin(4 * along);
    }
    if (std::hypot(x, y) < 1e-9) return std::nullopt;
    return std::atan2(y, x) / 4;
}

// The rectangle square to the walls (at `walls`, modulo a right angle) whose bounds in the box's own
// axes are the box: sides a and b turned by t from those axes span a|cos t| + b|sin t| along the
// first and a|sin t| + b|cos t| along the second. None for a box within 10 degrees of the walls
// (its own fit), near 45 degrees (where the bounds hardly tell the sides apart), or whose sizes no
// rectangle at that turn has as bounds.
std::optional<model::Box> squareTo(const model::Box& box, double walls) {
    constexpr double kOwnFit = 10 * model::kDegree, kLeastConditioning = 0.15;
    const double turn = std::remainder(walls - box.yaw, M_PI / 2);
    const double c = std::cos(turn), s = std::abs(std::sin(turn)), conditioning = c * c - s * s;
    if (std::abs(turn) < kOwnFit || conditioning < kLeastConditioning) return std::nullopt;
    const double a = (box.size.x * c - box.size.y * s) / conditioning;
    const double b = (box.size.y * c - box.size.x * s) / conditioning;
    if (a <= 0 || b <= 0) return std::nullopt;
    model::Box squared = box;
    squared.yaw = box.yaw + turn;
    squared.size.x = a;
    squared.size.y = b;
    return squared;
}

bool isDoor(const Node& n) { return n.kind == NodeKind::Anchor && n.category == "door" && solid(n); }

// A door's two sides: unit normal of its face (its thinner horizontal axis).
Point doorNormal(const model::Box& box) {
    bool thinAlongX = box.size.x < box.size.y;
    double angle = box.yaw + (thinAlongX ? 0.0 : M_PI / 2);
    return {std::cos(angle), std::sin(angle)};
}

}  // namespace

std::string_view toString(PointKind kind) {
    switch (kind) {
        case PointKind::Door:
            return "door";
        case PointKind::Approach:
            return "approach";
        case PointKind::Junction:
            return "junction";
        case PointKind::Camera:
            return "camera";
    }
    return "?";
}

double floorHeight(const std::vector<Node>& nodes) {
    const Node* floor = model::labelledFloor(nodes);
    return floor ? model::top(floor->box) : 0.0;
}

Footing::Footing(const std::vector<Node>& nodes, const GraphOptions& options)
    : nodes_(nodes), options_(options), floor_(floorHeight(nodes)) {
    for (const Node& n : nodes) byId_.emplace(n.id, &n);
    const auto walls = wallDirection(nodes);
    if (!walls) return;
    // Two things standing where the other stands: the larger box is the loose bound (the bed's over
    // its nightstands; a nightstand's small box does not hold a bed). A quarter of the smaller
    // footprint, so that boxes that touch or graze do not count. Furniture on legs holds what is
    // pushed under its top by right (a chair, a nested table); what a person moves stands turned
    // any way and is left its box.
    constexpr double kShared = 0.25;
    auto loose = [&](const Node& a, const Node& b) {
        const double other = model::footprintArea(b.box);
        return model::footprintArea(a.box) > other && !movable(a) && !(onLegs(a) && (onLegs(b) || movable(b))) &&
               model::footprintOverlap(a.box, b.box) >= kShared * other;
    };
    // Only boxes whose bounds meet can share floor: swept along x.
    std::vector<std::pair<model::Aabb, const Node*>> standing;
    for (const Node& n : nodes)
        if (n.kind == NodeKind::Object && stands(n)) standing.push_back({model::worldAabb(n.box), &n});
    std::sort(standing.begin(), standing.end(),
              [](const auto& p, const auto& q) { return p.first.min.x < q.first.min.x; });
    for (std::size_t i = 0; i < standing.size(); ++i)
        for (std::size_t j = i + 1; j < standing.size() && standing[j].first.min.x <= standing[i].first.max.x; ++j) {
            const auto& [ai, a] = standing[i];
            const auto& [bj, b] = standing[j];
            if (bj.min.y > ai.max.y || ai.min.y > bj.max.y) continue;
            for (auto [bound, held] : {std::pair{a, b}, std::pair{b, a}})
                if (!squared_.count(bound->id) && loose(*bound, *held))
                    if (auto squared = squareTo(bound->box, *walls)) squared_.emplace(bound->id, *squared);
        }
}

const model::Box& Footing::footprint(const Node& n) const {
    auto it = squared_.find(n.id);
    return it == squared_.end() ? n.box : it->second;
}

bool Footing::walkedOver(const Node& n) const {
    return n.kind == NodeKind::Object && model::top(n.box) - floor_ <= options_.walkOverHeight;
}

const Node* Footing::parentThing(const Node& n) const {
    auto it = byId_.find(n.parent);
    if (it == byId_.end() || it->second->kind != NodeKind::Object || !solid(*it->second) || walkedOver(*it->second))
        return nullptr;
    return it->second;
}

bool Footing::stands(const Node& n) const {
    if (!solid(n)) return false;
    const bool standing = model::bottom(n.box) - floor_ < options_.standingHeight;
    if (n.kind == NodeKind::Anchor) return n.category == "wall" || (standing && n.geometry == model::GeometryKind::Box);
    return n.kind == NodeKind::Object && standing && !walkedOver(n) && !parentThing(n);
}

bool Footing::blocks(const Node& n) const { return stands(n) && !(options_.pushAside && movable(n)); }

namespace {

bool named(const Node& n, std::initializer_list<std::string_view> categories) {
    return n.kind == NodeKind::Object &&
           std::any_of(categories.begin(), categories.end(), [&](std::string_view c) { return n.category == c; });
}

}  // namespace

bool movable(const Node& n) {
    return named(n, {"chair", "office-chair", "folding-chair", "stool", "bar-stool", "ottoman", "backpack", "bag",
                     "trash-bin", "trash-can", "wastebasket", "bin", "basket"});
}

bool onLegs(const Node& n) {
    return named(n, {"table", "desk", "coffee-table", "dining-table", "side-table", "end-table", "kitchen-table"});
}

const Node& Footing::support(const Node& n) const {
    const Node* at = &n;
    // A tree has no cycles; the bound only guards against a damaged one.
    for (std::size_t depth = 0; depth < nodes_.size(); ++depth) {
        const Node* up = parentThing(*at);
        if (!up) break;
        at = up;
    }
    return *at;
}

FreeSpace::FreeSpace(const std::vector<Node>& nodes, const GraphOptions& options) : cell_(options.cell) {
    const Footing footing(nodes, options);
    model::Aabb floor = floorRectangle(nodes);
    minX_ = floor.min.x;
    minY_ = floor.min.y;
    width_ = std::max(1, static_cast<int>(std::ceil((floor.max.x - floor.min.x) / cell_)));
    height_ = std::max(1, static_cast<int>(std::ceil((floor.max.y - floor.min.y) / cell_)));
    cells_.assign(static_cast<std::size_t>(width_) * height_, 1);
    blockers_.assign(cells_.size(), model::kNoNode);
    if (auto outline = thingsOutline(nodes))
        for (int j = 0; j < height_; ++j)
            for (int i = 0; i < width_; ++i)
                if (!bg::covered_by(
                        bg::model::d2::point_xy<double>(minX_ + (i + 0.5) * cell_, minY_ + (j + 0.5) * cell_),
                        *outline))
                    cells_[static_cast<std::size_t>(j) * width_ + i] = 0;

    // Marks the cells whose centres lie within `grow` of the box's footprint: blocked by `by`, or
    // free again when `by` is kNoNode.
    auto mark = [&](const model::Box& box, double grow, model::NodeId by) {
        model::Aabb b = model::worldAabb(box);
        const model::BoxFrame frame(box);
        int i0 = std::max(0, static_cast<int>(std::floor((b.min.x - grow - minX_) / cell_)));
        int i1 = std::min(width_ - 1, static_cast<int>(std::floor((b.max.x + grow - minX_) / cell_)));
        int j0 = std::max(0, static_cast<int>(std::floor((b.min.y - grow - minY_) / cell_)));
        int j1 = std::min(height_ - 1, static_cast<int>(std::floor((b.max.y + grow - minY_) / cell_)));
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i)
                if (frame.gap({minX_ + (i + 0.5) * cell_, minY_ + (j + 0.5) * cell_}) <= grow) {
                    const std::size_t c = static_cast<std::size_t>(j) * width_ + i;
                    cells_[c] = by == model::kNoNode;
                    blockers_[c] = by;
                }
    };
    for (const Node& n : nodes)
        if (footing.blocks(n))
            mark(footing.footprint(n), options.pushAside && onLegs(n) ? 0.0 : options.bodyRadius, n.id);
    // Doors open the walls they stand in: through the wall and a body's radius beyond, as wide as a
    // body's centre can pass (the door's width less a body's radius at each jamb).
    for (const Node& n : nodes) {
        if (!isDoor(n)) continue;
        model::Box passage = n.box;
        bool thinAlongX = passage.size.x < passage.size.y;
        (thinAlongX ? passage.size.x : passage.size.y) += 2 * (options.bodyRadius + cell_);
        double& width = thinAlongX ? passage.size.y : passage.size.x;
        width = std::max(cell_, width - 2 * options.bodyRadius);
        mark(passage, 0, model::kNoNode);
    }
    // Where a capture's camera stood, someone walked.
    for (const Node& n : nodes)
        if (n.kind == NodeKind::Frame && n.geometry != model::GeometryKind::None)
            mark({n.box.center, {0, 0, 0}, 0}, options.cell, model::kNoNode);

    // Connected stretches of free floor (4-neighbours), and the largest of them.
    component_.assign(cells_.size(), -1);
    std::vector<std::size_t> sizes, stack;
    for (std::size_t start = 0; start < cells_.size(); ++start) {
        if (!cells_[start] || component_[start] >= 0) continue;
        const int label = static_cast<int>(sizes.size());
        sizes.push_back(0);
        stack.assign(1, start);
        component_[start] = label;
        while (!stack.empty()) {
            std::size_t c = stack.back();
            stack.pop_back();
            ++sizes.back();
            const int i = static_cast<int>(c % width_), j = static_cast<int>(c / width_);
            for (auto [di, dj] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
                int ni = i + di, nj = j + dj;
                if (ni < 0 || nj < 0 || ni >= width_ || nj >= height_) continue;
                std::size_t n = static_cast<std::size_t>(nj) * width_ + ni;
                if (cells_[n] && component_[n] < 0) {
                    component_[n] = label;
                    stack.push_back(n);
                }
            }
        }
    }
    if (!sizes.empty()) mainComponent_ = static_cast<int>(std::max_element(sizes.begin(), sizes.end()) - sizes.begin());
    componentSizes_ = std::move(sizes);
}

int FreeSpace::componentAt(Point p) const {
    int i = static_cast<int>(std::floor((p.x - minX_) / cell_)),
        j = static_cast<int>(std::floor((p.y - minY_) / cell_));
    if (i < 0 || j < 0 || i >= width_ || j >= height_) return -1;
    return component_[static_cast<std::size_t>(j) * width_ + i];
}

bool FreeSpace::connected(Point p, Point q) const {
    int a = componentAt(p);
    return a >= 0 && a == componentAt(q);
}

std::vector<model::NodeId> FreeSpace::enclosedBy(Point p, std::size_t most, double& area) const {
    const int label = componentAt(p);
    area = label >= 0 ? static_cast<double>(componentSizes_[label]) * cell_ * cell_ : 0;
    std::map<model::NodeId, std::size_t> border;
    for (int j = 0; j < height_ && label >= 0; ++j)
        for (int i = 0; i < width_; ++i) {
            if (component_[static_cast<std::size_t>(j) * width_ + i] != label) continue;
            for (auto [di, dj] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
                int ni = i + di, nj = j + dj;
                if (ni < 0 || nj < 0 || ni >= width_ || nj >= height_) continue;
                if (model::NodeId by = blocker(ni, nj); by != model::kNoNode) ++border[by];
            }
        }
    std::vector<std::pair<std::size_t, model::NodeId>> ranked;
    for (auto [id, cells] : border) ranked.push_back({cells, id});
    std::sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) {
        return a.first != b.first ? a.first > b.first : a.second < b.second;
    });
    std::vector<model::NodeId> out;
    for (std::size_t k = 0; k < ranked.size() && k < most; ++k) out.push_back(ranked[k].second);
    return out;
}

std::optional<model::NodeId> FreeSpace::closing(Point p, Point q, const std::vector<model::NodeId>& candidates) const {
    auto cellOf = [&](Point at) -> std::optional<std::size_t> {
        int i = static_cast<int>(std::floor((at.x - minX_) / cell_)),
            j = static_cast<int>(std::floor((at.y - minY_) / cell_));
        if (i < 0 || j < 0 || i >= width_ || j >= height_) return std::nullopt;
        return static_cast<std::size_t>(j) * width_ + i;
    };
    const auto from = cellOf(p), to = cellOf(q);
    if (!from || !to) return std::nullopt;
    // A flood over the free cells and those `without` blocks, from p's cell: does it reach q's?
    std::vector<std::uint8_t> seen(cells_.size());
    std::vector<std::size_t> frontier;
    for (model::NodeId without : candidates) {
        std::fill(seen.begin(), seen.end(), 0);
        frontier.assign(1, *from);
        seen[*from] = 1;
        while (!frontier.empty()) {
            const std::size_t at = frontier.back();
            frontier.pop_back();
            if (at == *to) return without;
            const int i = static_cast<int>(at % width_), j = static_cast<int>(at / width_);
            for (auto [di, dj] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
                const int ni = i + di, nj = j + dj;
                if (ni < 0 || nj < 0 || ni >= width_ || nj >= height_) continue;
                const std::size_t next = static_cast<std::size_t>(nj) * width_ + ni;
                if (seen[next] || (cells_[next] == 0 && blockers_[next] != without)) continue;
                seen[next] = 1;
                frontier.push_back(next);
            }
        }
    }
    return std::nullopt;
}

bool FreeSpace::open(Point p) const { return mainComponent_ >= 0 && componentAt(p) == mainComponent_; }

bool FreeSpace::free(Point p) const {
    int i = static_cast<int>(std::floor((p.x - minX_) / cell_)),
        j = static_cast<int>(std::floor((p.y - minY_) / cell_));
    if (i < 0 || j < 0 || i >= width_ || j >= height_) return false;
    return freeCell(i, j);
}

bool FreeSpace::clear(Point a, Point b) const {
    const double length = distance(a, b);
    const int steps = std::max(1, static_cast<int>(std::ceil(length / (cell_ / 2))));
    for (int k = 0; k <= steps; ++k) {
        double t = static_cast<double>(k) / steps;
        if (!free({a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t})) return false;
    }
    return true;
}

std::optional<Point> FreeSpace::nearestFree(Point p, double radius) const {
    std::optional<Point> best, bestOpen;
    double bestDistance = radius, bestOpenDistance = radius;
    const int reach = static_cast<int>(std::ceil(radius / cell_));
    const int ci = static_cast<int>(std::floor((p.x - minX_) / cell_));
    const int cj = static_cast<int>(std::floor((p.y - minY_) / cell_));
    for (int j = std::max(0, cj - reach); j <= std::min(height_ - 1, cj + reach); ++j)
        for (int i = std::max(0, ci - reach); i <= std::min(width_ - 1, ci + reach); ++i) {
            if (!freeCell(i, j)) continue;
            Point c{minX_ + (i + 0.5) * cell_, minY_ + (j + 0.5) * cell_};
            double d = distance(p, c);
            if (d <= bestDistance) bestDistance = d, best = c;
            if (d <= bestOpenDistance && component_[static_cast<std::size_t>(j) * width_ + i] == mainComponent_)
                bestOpenDistance = d, bestOpen = c;
        }
    return bestOpen ? bestOpen : best;
}

namespace {

// Where a walker stands to reach `goal`: on open floor beside its floor-standing support, a body's
// radius and a little more from the support's footprint, at points every 0.2 m around it. Beside a
// thing on the floor, the point nearest the middle of the room (its most open side); beside the
// furniture a thing rests on, the point nearest the thing, or the open cell nearer to it where what
// stands beside the support (a nightstand at a bed's head, the chairs at a desk) takes the outline
// there. Else the nearest free cell.
// The open points every 0.2 m around a floor-standing thing's footprint, a body's radius and a little more from it:
// the rectangle's outline, walked side by side from corner to corner.
std::vector<Point> outlinePoints(const model::Box& box, const FreeSpace& space, const GraphOptions& options) {
    constexpr double kSpacing = 0.2;
    const double away = options.bodyRadius + 0.1;
    const double hx = box.size.x / 2 + away, hy = box.size.y / 2 + away;
    const model::BoxFrame frame(box);
    std::vector<Point> out;
    const std::pair<double, double> corners[] = {{hx, hy}, {-hx, hy}, {-hx, -hy}, {hx, -hy}, {hx, hy}};
    for (std::size_t k = 0; k + 1 < std::size(corners); ++k) {
        auto [u0, v0] = corners[k];
        auto [u1, v1] = corners[k + 1];
        const int steps = std::max(1, static_cast<int>(std::ceil(std::hypot(u1 - u0, v1 - v0) / kSpacing)));
        for (int t = 0; t < steps; ++t) {
            double u = u0 + (u1 - u0) * t / steps, v = v0 + (v1 - v0) * t / steps;
            const model::Vec2 at = frame.world({u, v});
            const Point p{at.x, at.y};
            if (space.open(p)) out.push_back(p);
        }
    }
    return out;
}

std::optional<Point> approach(const Node& goal, const Node& support, const Footing& footing, const FreeSpace& space,
                              Point centre, const GraphOptions& options) {
    const model::Box& box = footing.footprint(support);
    const Point goalAt{goal.box.center.x, goal.box.center.y};
    const Point target = &goal == &support ? centre : goalAt;
    std::optional<Point> best;
    for (const Point& p : outlinePoints(box, space, options))
        if (!best || distance(p, target) < distance(*best, target)) best = p;
    const double away = options.bodyRadius + 0.1;
    const double reach = std::max(1.5, std::hypot(box.size.x / 2 + away, box.size.y / 2 + away));
    if (best && &goal == &support) return best;
    if (auto nearest = space.nearestFree(goalAt, reach);
        nearest && space.open(*nearest) && (!best || distance(*nearest, goalAt) < distance(*best, goalAt)))
        return nearest;
    if (best) return best;
    return space.nearestFree(goalAt, reach);
}

}  // namespace

std::vector<Point> sidesOf(const std::vector<Node>& nodes, const Node& goal, const FreeSpace& space,
                           const GraphOptions& options) {
    // A door or a window is walked to at its decision point, not along the wall beside it.
    if (goal.kind != NodeKind::Object) return {};
    const Footing footing(nodes, options);
    if (&footing.support(goal) != &goal || footing.walkedOver(goal)) return {};
    return outlinePoints(footing.footprint(goal), space, options);
}

RouteGraph buildGraph(const std::vector<Node>& nodes, const FreeSpace& space, const GraphOptions& options) {
    const Footing footing(nodes, options);
    RouteGraph graph;
    const Point centre{space.minX() + space.width() * space.cell() / 2,
                       space.minY() + space.height() * space.cell() / 2};
    for (const Node& n : nodes) {
        if (!solid(n)) continue;
        if (isDoor(n)) {
            Point normal = doorNormal(n.box);
            double out = std::min(n.box.size.x, n.box.size.y) / 2 + options.bodyRadius + 0.3;
            for (double side : {1.0, -1.0}) {
                Point p{n.box.center.x + side * normal.x * out, n.box.center.y + side * normal.y * out};
                if (auto snapped = space.nearestFree(p, 1.0)) graph.points.push_back({*snapped, PointKind::Door, n.id});
            }
        } else if (n.kind == NodeKind::Object && !footing.walkedOver(n)) {
            if (auto p = approach(n, footing.support(n), footing, space, centre, options))
                graph.points.push_back({*p, PointKind::Approach, n.id});
        } else if (n.kind == NodeKind::Frame && space.free({n.box.center.x, n.box.center.y})) {
            graph.points.push_back({{n.box.center.x, n.box.center.y}, PointKind::Camera, n.id});
        }
    }
    for (double y = space.minY() + options.lattice / 2; y < space.minY() + space.height() * space.cell();
         y += options.lattice)
        for (double x = space.minX() + options.lattice / 2; x < space.minX() + space.width() * space.cell();
             x += options.lattice)
            if (space.free({x, y})) graph.points.push_back({{x, y}, PointKind::Junction, model::kNoNode});

    // Edges between points that see each other: only pairs in neighbouring buckets of maxEdge.
    std::map<std::pair<long, long>, std::vector<std::size_t>> buckets;
    auto bucketOf = [&](Point p) {
        return std::pair<long, long>{static_cast<long>(std::floor(p.x / options.maxEdge)),
                                     static_cast<long>(std::floor(p.y / options.maxEdge))};
    };
    for (std::size_t i = 0; i < graph.points.size(); ++i) buckets[bucketOf(graph.points[i].at)].push_back(i);
    for (std::size_t i = 0; i < graph.points.size(); ++i) {
        auto [bx, by] = bucketOf(graph.points[i].at);
        for (long dx = -1; dx <= 1; ++dx)
            for (long dy = -1; dy <= 1; ++dy) {
                auto bucket = buckets.find({bx + dx, by + dy});
                if (bucket == buckets.end()) continue;
                for (std::size_t j : bucket->second) {
                    if (j <= i) continue;
                    double d = distance(graph.points[i].at, graph.points[j].at);
                    if (d <= options.maxEdge && space.clear(graph.points[i].at, graph.points[j].at))
                        graph.edges.push_back({i, j, d});
                }
            }
    }
    return graph;
}

namespace {

using WeightedGraph = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS, boost::no_property,
                                            boost::property<boost::edge_weight_t, double>>;

// Vertices from `start` to `goal` along Dijkstra's predecessors; empty when goal was not reached.
std::vector<std::size_t> shortestPath(const WeightedGraph& g, std::size_t start, std::size_t goal) {
    std::vector<std::size_t> previous(boost::num_vertices(g));
    std::vector<double> distances(previous.size(), std::numeric_limits<double>::infinity());
    boost::dijkstra_shortest_paths(g, start, boost::predecessor_map(previous.data()).distance_map(distances.data()));
    // Dijkstra leaves an unreached vertex its own predecessor (and the largest double as distance).
    if (previous[goal] == goal && goal != start) return {};
    std::vector<std::size_t> path;
    for (std::size_t v = goal; v != start; v = previous[v]) path.push_back(v);
    path.push_back(start);
    std::reverse(path.begin(), path.end());
    return path;
}

// Straightened: from each waypoint, on to the farthest later one in plain view. The lattice's and
// the grid's zigzags are not decisions a walker makes.
Route straightened(const std::vector<Point>& path, const FreeSpace& space) {
    Route route;
    route.waypoints.push_back(path.front());
    for (std::size_t i = 0; i + 1 < path.size();) {
        std::size_t next = path.size() - 1;
        while (next > i + 1 && !space.clear(path[i], path[next])) --next;
        route.length += distance(path[i], path[next]);
        route.waypoints.push_back(path[next]);
        i = next;
    }
    return route;
}

// The way over the free cells themselves (8 neighbours, no corner cut), for two places the free
// floor joins where the decision points do not see each other: a winding way between chairs.
std::optional<Route> cellRoute(const FreeSpace& space, Point from, Point to) {
    auto cellOf = [&](Point p) {
        return std::pair{static_cast<int>(std::floor((p.x - space.minX()) / space.cell())),
                         static_cast<int>(std::floor((p.y - space.minY()) / space.cell()))};
    };
    const int w = space.width(), h = space.height();
    auto index = [&](int i, int j) { return static_cast<std::size_t>(j) * w + i; };
    auto freeAt = [&](int i, int j) { return i >= 0 && j >= 0 && i < w && j < h && space.freeCell(i, j); };
    auto [si, sj] = cellOf(from);
    auto [gi, gj] = cellOf(to);
    if (!freeAt(si, sj) || !freeAt(gi, gj)) return std::nullopt;
    WeightedGraph g(static_cast<std::size_t>(w) * h);
    const double step = space.cell(), diagonal = space.cell() * std::sqrt(2.0);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            if (!freeAt(i, j)) continue;
            if (freeAt(i + 1, j)) boost::add_edge(index(i, j), index(i + 1, j), step, g);
            if (freeAt(i, j + 1)) boost::add_edge(index(i, j), index(i, j + 1), step, g);
            if (freeAt(i + 1, j + 1) && freeAt(i + 1, j) && freeAt(i, j + 1))
                boost::add_edge(index(i, j), index(i + 1, j + 1), diagonal, g);
            if (freeAt(i - 1, j + 1) && freeAt(i - 1, j) && freeAt(i, j + 1))
                boost::add_edge(index(i, j), index(i - 1, j + 1), diagonal, g);
        }
    auto cells = shortestPath(g, index(si, sj), index(gi, gj));
    if (cells.empty()) return std::nullopt;
    // The cells where the way turns, between the two ends.
    std::vector<Point> path{from};
    for (std::size_t k = 1; k + 1 < cells.size(); ++k) {
        const long before = static_cast<long>(cells[k]) - static_cast<long>(cells[k - 1]);
        const long after = static_cast<long>(cells[k + 1]) - static_cast<long>(cells[k]);
        if (before == after) continue;
        const int i = static_cast<int>(cells[k] % w), j = static_cast<int>(cells[k] / w);
        path.push_back({space.minX() + (i + 0.5) * space.cell(), space.minY() + (j + 0.5) * space.cell()});
    }
    path.push_back(to);
    return straightened(path, space);
}

}  // namespace

std::optional<Route> shortestRoute(const RouteGraph& graph, const FreeSpace& space, Point from, Point to,
                                   const GraphOptions& options) {
    return shortestRoute(graph, space, from, std::vector<Point>{to}, options);
}

std::optional<Route> shortestRoute(const RouteGraph& graph, const FreeSpace& space, Point from,
                                   const std::vector<Point>& to, const GraphOptions& options) {
    // The decision points, the start, each end, and one vertex past every end that Dijkstra goes to.
    const std::size_t n = graph.points.size(), start = n, firstEnd = n + 1, sink = n + 1 + to.size();
    WeightedGraph g(sink + 1);
    for (const Edge& e : graph.edges) boost::add_edge(e.a, e.b, e.length, g);
    // The start and the ends join every decision point they see, and the start each end it sees.
    for (std::size_t i = 0; i < n; ++i) {
        Point p = graph.points[i].at;
        if (distance(from, p) <= options.maxEdge && space.clear(from, p))
            boost::add_edge(start, i, distance(from, p), g);
        for (std::size_t k = 0; k < to.size(); ++k)
            if (distance(to[k], p) <= options.maxEdge && space.clear(to[k], p))
                boost::add_edge(firstEnd + k, i, distance(to[k], p), g);
    }
    for (std::size_t k = 0; k < to.size(); ++k) {
        if (space.clear(from, to[k])) boost::add_edge(start, firstEnd + k, distance(from, to[k]), g);
        boost::add_edge(firstEnd + k, sink, 0.0, g);
    }

    auto vertices = shortestPath(g, start, sink);
    if (vertices.empty()) return space.connected(from, to.front()) ? cellRoute(space, from, to.front()) : std::nullopt;
    vertices.pop_back();  // the sink
    std::vector<Point> path;
    for (std::size_t v : vertices)
        path.push_back(v == start ? from : v >= firstEnd ? to[v - firstEnd] : graph.points[v].at);
    return straightened(path, space);
}

}  // namespace smql::guide
