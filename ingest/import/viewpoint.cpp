#include "ingest/import/viewpoint.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "ingest/import/common.hpp"
#include "ingest/import/floor.hpp"
#include "ingest/import/wall_faces.hpp"
#include "model/floor.hpp"
#include "model/geometry.hpp"

namespace smql::import::detail {

namespace {

using model::Node;

bool isAnchor(const Node& node, std::string_view category) {
    return node.kind == model::NodeKind::Anchor && node.category == category && !node.hidden &&
           node.geometry != model::GeometryKind::None;
}

std::string label(const Node& node) {
    return fmt::format("{} #{}", node.category, node.sourceId ? *node.sourceId : static_cast<std::int64_t>(node.id));
}

// A wall's face: the product of its two largest extents (its thickness is the smallest).
double faceArea(const model::Box& box) {
    double s[3] = {box.size.x, box.size.y, box.size.z};
    std::sort(s, s + 3);
    return s[1] * s[2];
}

// The direction `yaw` turned to the nearest of the four directions parallel
// or perpendicular to `axis`.
double snapToAxes(double yaw, double axis) {
    constexpr double quarter = std::numbers::pi / 2;
    return normaliseYaw(axis + std::round((yaw - axis) / quarter) * quarter);
}

template <typename Score>
const Node* best(const std::vector<const Node*>& nodes, Score score) {
    const Node* found = nullptr;
    double bestScore = -std::numeric_limits<double>::infinity();
    for (const Node* n : nodes)
        if (double s = score(*n); s > bestScore) {
            bestScore = s;
            found = n;
        }
    return found;
}

}  // namespace

ViewpointChoice defaultViewpoint(const std::vector<Node>& nodes) {
    std::vector<const Node*> boxes, walls, doors;
    for (const Node& n : nodes) {
        if (n.geometry == model::GeometryKind::None || n.hidden) continue;
        boxes.push_back(&n);
        if (isAnchor(n, "wall")) walls.push_back(&n);
        if (isAnchor(n, "door")) doors.push_back(&n);
    }
    // A scene of hidden parts only still needs a viewpoint: use them all.
    if (boxes.empty())
        for (const Node& n : nodes)
            if (n.geometry != model::GeometryKind::None) boxes.push_back(&n);
    assert(!boxes.empty());

    const Node* floor = model::labelledFloor(nodes);
    const Node* wall = best(walls, [](const Node& n) { return faceArea(n.box); });

    model::Vec2 centre;
    double base = 0;
    std::string centreText, baseText;
    if (floor) {
        centre = {floor->box.center.x, floor->box.center.y};
        base = model::top(floor->box);
        centreText = "the centre of " + label(*floor);
        baseText = "the floor's top";
    } else {
        model::Aabb all = model::worldAabb(boxes.front()->box);
        for (const Node* n : boxes) {
            model::Aabb a = model::worldAabb(n->box);
            all.min = {std::min(all.min.x, a.min.x), std::min(all.min.y, a.min.y), std::min(all.min.z, a.min.z)};
            all.max = {std::max(all.max.x, a.max.x), std::max(all.max.y, a.max.y), std::max(all.max.z, a.max.z)};
        }
        centre = {(all.min.x + all.max.x) / 2, (all.min.y + all.max.y) / 2};
        centreText = "the centre of all boxes";
        const auto& bottoms = walls.empty() ? boxes : walls;
        base = std::numeric_limits<double>::infinity();
        for (const Node* n : bottoms) base = std::min(base, model::bottom(n->box));
        baseText = walls.empty() ? "the lowest box bottom" : "the lowest wall bottom";
    }

    auto distanceToCentre = [&](const Node& n) {
        return std::hypot(n.box.center.x - centre.x, n.box.center.y - centre.y);
    };
    const Node* door = best(doors, [&](const Node& n) { return -distanceToCentre(n); });

    ViewpointChoice choice;
    choice.viewpoint.position.z = base + kEyeHeight;
    if (door && distanceToCentre(*door) > 1e-6) {
        double dx = centre.x - door->box.center.x, dy = centre.y - door->box.center.y;
        double length = std::hypot(dx, dy);
        double step = std::min(kStepInside, length);
        double axis = wall ? wall->box.yaw : 0.0;
        choice.viewpoint.position.x = door->box.center.x + dx / length * step;
        choice.viewpoint.position.y = door->box.center.y + dy / length * step;
        choice.viewpoint.facingYaw = snapToAxes(std::atan2(dy, dx), axis);
        choice.note = fmt::format(
            "just inside the main door ({}, the door closest to {}): {} m from its centre towards that centre, "
            "eye height {} m above {}, facing from the door towards that centre snapped to the nearest "
            "right angle of {}",
            label(*door), centreText, kStepInside, kEyeHeight, baseText,
            wall ? "the largest wall (" + label(*wall) + ")" : std::string("the world axes (no wall)"));
    } else {
        choice.viewpoint.position.x = centre.x;
        choice.viewpoint.position.y = centre.y;
        choice.viewpoint.facingYaw = std::numbers::pi / 2;
        choice.note = fmt::format("at {}, eye height {} m above {}, facing +y ({})", centreText, kEyeHeight, baseText,
                                  door ? "the door stands at that centre" : "no door");
    }
    return choice;
}

void finishScene(model::SceneData& scene, const std::string& name, std::string source) {
    scene.info.name = name;
    scene.info.source = std::move(source);
    standOnFloor(scene);
    splitWallOutlines(scene);
    scene.info.nodeCount = scene.nodes.size();
    ViewpointChoice view = defaultViewpoint(scene.nodes);
    scene.info.viewpoint = view.viewpoint;
    scene.info.viewpointNote = std::move(view.note);
}

}  // namespace smql::import::detail
