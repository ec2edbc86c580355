#include "ingest/import/floor.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "ingest/import/common.hpp"
#include "model/error.hpp"
#include "model/floor.hpp"
#include "model/geometry.hpp"

namespace smql::import::detail {

namespace {

// Bottoms within this of each other (metres) belong to one level: a scan's boxes of things that
// stand on one floor differ by a few centimetres, and more where a box leans.
constexpr double kLevelSpread = 0.25;
// The floor's cluster holds at least this share of the boxes (and at least one, at most three of
// them): one box poking below the floor, a scan's stray fit, is not the floor.
constexpr double kFloorShare = 0.2;
constexpr std::size_t kFloorMostNeeded = 3;

bool placed(const model::Node& n) {
    return !n.hidden && n.geometry != model::GeometryKind::None &&
           (n.kind == model::NodeKind::Anchor || n.kind == model::NodeKind::Object);
}

}  // namespace

std::optional<FloorFound> findFloor(const std::vector<model::Node>& nodes) {
    if (const model::Node* labelled = model::labelledFloor(nodes))
        return FloorFound{model::top(labelled->box), "the labelled floor's top"};

    std::vector<double> bottoms;
    for (const model::Node& n : nodes)
        if (placed(n) && n.category != "ceiling") bottoms.push_back(model::bottom(n.box));
    if (bottoms.empty()) return std::nullopt;
    std::sort(bottoms.begin(), bottoms.end());
    const std::size_t needed =
        std::clamp<std::size_t>(static_cast<std::size_t>(std::ceil(kFloorShare * bottoms.size())), 1, kFloorMostNeeded);
    for (std::size_t i = 0; i < bottoms.size(); ++i) {
        std::size_t end = i;
        while (end < bottoms.size() && bottoms[end] <= bottoms[i] + kLevelSpread) ++end;
        if (end - i >= needed) return FloorFound{bottoms[i + (end - i) / 2], "the bottoms the lowest things share"};
    }
    return FloorFound{bottoms.front(), "the lowest box's bottom"};
}

std::optional<FloorFound> standOnFloor(model::SceneData& scene) {
    auto floor = findFloor(scene.nodes);
    if (!floor || std::abs(floor->height) <= kFloorTolerance) return floor;
    const double dz = floor->height;
    for (model::Node& n : scene.nodes) {
        if (n.geometry == model::GeometryKind::None) continue;
        n.box.center.z -= dz;
        if (std::abs(n.box.center.z) > kMaxCoordinate)
            throw Error(
                ErrorKind::Input,
                fmt::format("{}: standing on its floor ({} m, {}), {} #{} is {} m up: more than {} m",
                            scene.info.source, floor->height, floor->how, n.category,
                            n.sourceId ? *n.sourceId : static_cast<std::int64_t>(n.id), n.box.center.z, kMaxCoordinate),
                std::nullopt, "a scene spans at most that much in height: check the file's units");
    }
    scene.info.viewpoint.position.z -= dz;
    // aligned = T(0, 0, -dz) * A: the row of z loses dz times the homogeneous row (row-major 4x4).
    auto& a = scene.info.alignment;
    for (std::size_t column = 0; column < 4; ++column) a[8 + column] -= dz * a[12 + column];
    return floor;
}

}  // namespace smql::import::detail
