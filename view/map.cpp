#include "view/map.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <unordered_map>

#include <fmt/format.h>

#include "engine/guide/route_graph.hpp"
#include "model/geometry.hpp"
#include "model/presentation.hpp"

namespace smql::view {

namespace {

constexpr double kPixelsPerMetre = 80;
constexpr double kMargin = 40;
constexpr double kLegendWidth = 200;
constexpr double kBottomBand = 44;       // under the drawing: the scale bar
constexpr double kCeilingFixture = 1.8;  // m above the floor: a thing whose bottom is higher hangs from the ceiling
constexpr double kWallFixture = 0.1;     // m: a thing this thin that hangs on a wall, door or window

const Rgb kWall{90, 90, 90}, kDoor{60, 160, 60}, kWindow{40, 140, 200}, kFloor{245, 245, 245}, kBlocked{240, 215, 215},
    kPocket{250, 230, 170}, kGraph{170, 205, 225}, kRoute{220, 40, 40}, kText{40, 40, 40};

// The category's colour, as the exports and the view's page give it.
Rgb categoryColour(const model::Palette& palette, const std::string& category) {
    const model::Rgb c = palette(category);
    return {c.r, c.g, c.b};
}

Rgb lighter(const Rgb& c, double towardsWhite) {
    Rgb out;
    for (int i = 0; i < 3; ++i) out[i] = static_cast<unsigned char>(c[i] + (255 - c[i]) * towardsWhite);
    return out;
}

// Scene metres to pixels: x to the right, y up (the picture's rows run down).
class Frame {
public:
    explicit Frame(const model::SceneData& scene) {
        bounds_ = {{1e300, 1e300, 0}, {-1e300, -1e300, 0}};
        for (const auto& n : scene.nodes) {
            if (n.geometry == model::GeometryKind::None || n.hidden || n.kind == model::NodeKind::Scene) continue;
            auto b = model::worldAabb(n.box);
            bounds_.min.x = std::min(bounds_.min.x, b.min.x), bounds_.min.y = std::min(bounds_.min.y, b.min.y);
            bounds_.max.x = std::max(bounds_.max.x, b.max.x), bounds_.max.y = std::max(bounds_.max.y, b.max.y);
        }
        if (bounds_.min.x > bounds_.max.x) bounds_ = {{0, 0, 0}, {1, 1, 0}};
    }
    double width() const { return (bounds_.max.x - bounds_.min.x) * kPixelsPerMetre + 2 * kMargin; }
    double height() const { return (bounds_.max.y - bounds_.min.y) * kPixelsPerMetre + 2 * kMargin; }
    MapPlan::Point at(double x, double y) const {
        return {kMargin + (x - bounds_.min.x) * kPixelsPerMetre, kMargin + (bounds_.max.y - y) * kPixelsPerMetre};
    }
    std::vector<MapPlan::Point> footprint(const model::Box& box) const {
        const double c = std::cos(box.yaw), s = std::sin(box.yaw);
        std::vector<MapPlan::Point> corners;
        for (auto [u, v] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
            const double dx = u * box.size.x / 2, dy = v * box.size.y / 2;
            corners.push_back(at(box.center.x + c * dx - s * dy, box.center.y + s * dx + c * dy));
        }
        return corners;
    }

private:
    model::Aabb bounds_;
};

// Ceiling lights and what hangs on a wall (switches, plugs, pictures): left out unless asked, as
// they crowd a plan of what stands in the room.
bool isFixture(const model::Node& n, const std::unordered_map<model::NodeId, const model::Node*>& byId, double floor) {
    if (model::bottom(n.box) - floor >= kCeilingFixture) return true;
    auto parent = byId.find(n.parent);
    if (parent == byId.end() || parent->second->kind != model::NodeKind::Anchor) return false;
    const std::string& on = parent->second->category;
    return (on == "wall" || on == "door" || on == "window") && std::min(n.box.size.x, n.box.size.y) <= kWallFixture;
}

// Places labels so that none overlaps another: at the thing, else around it at growing distances
// (with a leader line), else a number at or around the thing, named in the key.
class LabelPlacer {
public:
    LabelPlacer(MapPlan& plan, Rect area) : plan_(plan), area_(area) {}

    void fixed(MapPlan::Label label) {
        taken_.push_back(label.box);
        plan_.labels.push_back(std::move(label));
    }

    void place(const std::string& text, MapPlan::Point at, const Rgb& colour) {
        const double width = text.size() * kMapCharWidth + 4, height = kMapTextHeight + 4;
        if (auto box = free(at, width, height, 0)) return add(text, at, *box, false, colour);
        const double marker = kMapTextHeight + 6;
        std::string number = std::to_string(plan_.key.size() + 1);
        if (auto box = free(at, marker, marker, 0)) return numbered(number, text, at, *box, colour);
        for (double radius : {14.0, 26.0, 40.0, 60.0})
            if (auto box = free(at, width, height, radius)) return add(text, at, *box, true, colour);
        for (double radius : {14.0, 26.0, 40.0, 60.0, 90.0})
            if (auto box = free(at, marker, marker, radius)) return numbered(number, text, at, *box, colour);
        numbered(number, text, at, Rect{at.x - marker / 2, at.y - marker / 2, marker, marker}, colour);
    }

private:
    std::optional<Rect> free(MapPlan::Point at, double width, double height, double radius) const {
        const int directions = radius == 0 ? 1 : 8;
        for (int d = 0; d < directions; ++d) {
            const double angle = d * M_PI / 4;
            Rect box{at.x + radius * std::cos(angle) - width / 2, at.y - radius * std::sin(angle) - height / 2, width,
                     height};
            const bool inside = box.left >= area_.left && box.top >= area_.top &&
                                box.left + box.width <= area_.left + area_.width &&
                                box.top + box.height <= area_.top + area_.height;
            if (inside && std::none_of(taken_.begin(), taken_.end(), [&](const Rect& t) { return t.overlaps(box); }))
                return box;
        }
        return std::nullopt;
    }
    void add(const std::string& text, MapPlan::Point at, const Rect& box, bool leader, const Rgb& colour) {
        taken_.push_back(box);
        plan_.labels.push_back({text, box, at, leader, false, colour});
        if (leader) {
            const MapPlan::Point end{std::clamp(at.x, box.left, box.left + box.width),
                                     std::clamp(at.y, box.top, box.top + box.height)};
            plan_.segments.push_back({at, end, colour, 0.8});
        }
    }
    void numbered(const std::string& number, const std::string& text, MapPlan::Point at, const Rect& box,
                  const Rgb& colour) {
        taken_.push_back(box);
        const bool away =
            std::abs(box.left + box.width / 2 - at.x) > 1 || std::abs(box.top + box.height / 2 - at.y) > 1;
        plan_.labels.push_back({number, box, at, away, true, colour});
        if (away) plan_.segments.push_back({at, {box.left + box.width / 2, box.top + box.height / 2}, colour, 0.8});
        plan_.key.push_back(number + "  " + text);
    }

    MapPlan& plan_;
    Rect area_;
    std::vector<Rect> taken_;
};

void addFloorAndSpace(MapPlan& plan, const Frame& frame, const Engine::SceneMap& map) {
    for (const auto& n : map.scene.nodes)
        if (n.kind == model::NodeKind::Anchor && n.category == "floor" && !n.hidden)
            plan.shapes.push_back({frame.footprint(n.box), kFloor, kFloor, true});
    // The floor as guidance sees it: blocked (within a body's radius of what stands on it) and cut off.
    const auto& space = map.space;
    for (int j = 0; j < space.height(); ++j)
        for (int i = 0; i < space.width(); ++i) {
            if (space.openCell(i, j)) continue;
            const double x = space.minX() + i * space.cell(), y = space.minY() + j * space.cell(), c = space.cell();
            const Rgb colour = space.freeCell(i, j) ? kPocket : kBlocked;
            plan.shapes.push_back({{frame.at(x, y), frame.at(x + c, y), frame.at(x + c, y + c), frame.at(x, y + c)},
                                   colour,
                                   colour,
                                   true});
        }
}

void addScaleBar(MapPlan& plan, double drawingWidth, double drawingHeight) {
    double metres = 0.5;
    for (double candidate : {1.0, 2.0, 5.0, 10.0, 20.0})
        if (candidate * kPixelsPerMetre <= (drawingWidth - 2 * kMargin) / 3) metres = candidate;
    plan.scale = {{kMargin, drawingHeight + kBottomBand / 2},
                  metres * kPixelsPerMetre,
                  metres < 1 ? fmt::format("{:g} cm", metres * 100) : fmt::format("{:g} m", metres)};
}

}  // namespace

MapPlan planMap(const Engine::SceneMap& map, const std::vector<RouteMark>& route, const MapOptions& options) {
    MapPlan plan;
    plan.scene = map.scene.info.name;
    const Frame frame(map.scene);
    const double drawingWidth = frame.width(), drawingHeight = frame.height();
    std::unordered_map<model::NodeId, const model::Node*> byId;
    for (const auto& n : map.scene.nodes) byId.emplace(n.id, &n);
    const double floor = guide::floorHeight(map.scene.nodes);

    addFloorAndSpace(plan, frame, map);
    for (const auto& [category, colour] : {std::pair{"wall", kWall}, {"door", kDoor}, {"window", kWindow}})
        for (const auto& n : map.scene.nodes)
            if (n.kind == model::NodeKind::Anchor && n.category == category && !n.hidden &&
                n.geometry != model::GeometryKind::None)
                plan.shapes.push_back({frame.footprint(n.box), colour, colour, true});
    if (options.graph) {
        for (const auto& e : map.graph.edges)
            plan.segments.push_back({frame.at(map.graph.points[e.a].at.x, map.graph.points[e.a].at.y),
                                     frame.at(map.graph.points[e.b].at.x, map.graph.points[e.b].at.y), kGraph, 1});
    }

    // Objects, largest first, so that small ones are drawn over them.
    std::vector<const model::Node*> objects;
    for (const auto& n : map.scene.nodes) {
        if (n.geometry == model::GeometryKind::None || n.hidden || n.kind != model::NodeKind::Object) continue;
        if (!options.fixtures && isFixture(n, byId, floor)) {
            ++plan.fixturesLeftOut;
            continue;
        }
        objects.push_back(&n);
    }
    std::sort(objects.begin(), objects.end(), [](const model::Node* a, const model::Node* b) {
        return model::footprintArea(a->box) > model::footprintArea(b->box);
    });
    const model::Palette palette(map.scene.nodes);
    std::vector<std::string> categories;
    for (const auto* n : objects) {
        const Rgb colour = categoryColour(palette, n->category);
        plan.shapes.push_back({frame.footprint(n->box), lighter(colour, 0.7), colour, true});
        if (std::find(categories.begin(), categories.end(), n->category) == categories.end())
            categories.push_back(n->category);
    }

    LabelPlacer labels(plan, {0, 0, drawingWidth, drawingHeight});
    for (std::size_t i = 1; i < route.size(); ++i)
        plan.segments.push_back(
            {frame.at(route[i - 1].x, route[i - 1].y), frame.at(route[i].x, route[i].y), kRoute, 2.5});
    for (const auto& step : route) {
        const auto at = frame.at(step.x, step.y);
        const double size = kMapTextHeight + 8;
        labels.fixed(
            {std::to_string(step.step), {at.x - size / 2, at.y - size / 2, size, size}, at, false, true, kRoute});
    }
    // Small things first: they have one place, the large ones have room around them.
    for (auto it = objects.rbegin(); it != objects.rend(); ++it) {
        const auto& n = **it;
        labels.place(fmt::format("{}#{}", n.category, n.id), frame.at(n.box.center.x, n.box.center.y), kText);
    }

    std::sort(categories.begin(), categories.end());
    plan.legend = {{"wall", kWall}, {"door", kDoor}, {"window", kWindow}};
    for (const auto& c : categories) plan.legend.push_back({c, categoryColour(palette, c)});
    plan.legend.push_back({"floor blocked for walking", kBlocked});
    plan.legend.push_back({"floor cut off from the room", kPocket});
    if (options.graph) plan.legend.push_back({"guidance graph", kGraph});
    if (!route.empty()) plan.legend.push_back({"route, steps numbered", kRoute});

    const double line = kMapTextHeight + 6;
    plan.legendBox = {drawingWidth, kMargin, kLegendWidth, (plan.legend.size() + 1) * line};
    plan.keyBox = {drawingWidth, plan.legendBox.top + plan.legendBox.height + line, kLegendWidth,
                   (plan.key.size() + (plan.key.empty() ? 0 : 1)) * line};
    addScaleBar(plan, drawingWidth, drawingHeight);
    plan.width = static_cast<int>(std::ceil(drawingWidth + kLegendWidth));
    plan.height = static_cast<int>(
        std::ceil(std::max(drawingHeight + kBottomBand, plan.keyBox.top + plan.keyBox.height + kMargin)));
    return plan;
}

}  // namespace smql::view
