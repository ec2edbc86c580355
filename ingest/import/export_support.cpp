#include "ingest/import/export_support.hpp"

#include <array>

#include "model/geometry.hpp"

namespace smql::import::detail {

bool isDrawn(const model::Node& node) {
    bool placed = node.kind == model::NodeKind::Anchor || node.kind == model::NodeKind::Object;
    return placed && !node.hidden && node.geometry != model::GeometryKind::None && node.category != "ceiling";
}

std::array<model::Vec3, 8> boxCorners(const model::Box& box) {
    std::array<model::Vec2, 4> footprint = model::footprint(box);
    std::array<model::Vec3, 8> corners;
    for (std::size_t i = 0; i < 4; ++i) {
        corners[i] = {footprint[i].x, footprint[i].y, model::bottom(box)};
        corners[i + 4] = {footprint[i].x, footprint[i].y, model::top(box)};
    }
    return corners;
}

}  // namespace smql::import::detail
