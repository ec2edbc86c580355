#include "ingest/pipeline/anchors_stage.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "ingest/pipeline/scene_nodes.hpp"

namespace smql::ingest {

using model::GeometryKind;
using model::NodeKind;

namespace {

// Points outside this share at either end of x or y are strays (sparse points triangulated through a
// window or from a bad match, kilometres away), not the room: they must not stretch the floor.
constexpr double kStrayShare = 0.01;

// The value `share` of the way through `values` (sorted in place).
double quantile(std::vector<double>& values, double share) {
    auto at = values.begin() + static_cast<std::ptrdiff_t>(share * static_cast<double>(values.size() - 1));
    std::nth_element(values.begin(), at, values.end());
    return *at;
}

}  // namespace

std::vector<WallSegment> AnchorsStage::run(StageProgress&) {
    const Alignment& alignment = aligned.alignment;
    std::vector<double> xs, ys;
    for (const auto& p : aligned.cloud.points) xs.push_back(p.x), ys.push_back(p.y);
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    if (!xs.empty()) {
        x0 = quantile(xs, kStrayShare), x1 = quantile(xs, 1 - kStrayShare);
        y0 = quantile(ys, kStrayShare), y1 = quantile(ys, 1 - kStrayShare);
    }
    if (alignment.floorFound && !aligned.cloud.empty()) {
        model::Node& floor = addNode(scene, NodeKind::Anchor, "floor", GeometryKind::Plane,
                                     {{(x0 + x1) / 2, (y0 + y1) / 2, -0.01}, {x1 - x0, y1 - y0, 0.02}, 0});
        floor.confidence = 1.0f;
    }
    if (alignment.ceilingHeight)
        addNode(scene, NodeKind::Anchor, "ceiling", GeometryKind::Plane,
                {{(x0 + x1) / 2, (y0 + y1) / 2, *alignment.ceilingHeight + 0.01}, {x1 - x0, y1 - y0, 0.02}, 0});
    std::vector<WallSegment> walls = findWalls(aligned.cloud, aligned.cameraCentres);
    for (const auto& w : walls) {
        model::Node& wall = addNode(scene, NodeKind::Anchor, "wall", GeometryKind::Plane, w.box());
        wall.confidence = static_cast<float>(w.confidence);
        wall.attributes.push_back({"views", std::to_string(w.frames)});
    }
    return walls;
}

std::string AnchorsStage::summary(const std::vector<WallSegment>& walls) const {
    return fmt::format("{} walls{}{}", walls.size(), aligned.alignment.floorFound ? ", floor" : "",
                       aligned.alignment.ceilingHeight ? ", ceiling" : "");
}

}  // namespace smql::ingest
