#include "ingest/pipeline/anchors_stage.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "ingest/geometry/robust.hpp"
#include "ingest/pipeline/scene_nodes.hpp"

namespace smql::ingest {

using model::GeometryKind;
using model::NodeKind;

std::vector<WallSegment> AnchorsStage::run(StageProgress&) {
    const Alignment& alignment = aligned.alignment;
    // A few stray points (sparse points triangulated through a window, kilometres away) must not stretch
    // the floor: its extent is the cloud's without outliers.
    std::vector<double> xs, ys;
    for (const auto& p : aligned.cloud.points) xs.push_back(p.x), ys.push_back(p.y);
    auto [x0, x1] = detail::robustRange(std::move(xs));
    auto [y0, y1] = detail::robustRange(std::move(ys));
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
