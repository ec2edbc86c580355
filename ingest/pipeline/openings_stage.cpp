#include "ingest/pipeline/openings_stage.hpp"
#include "ingest/capture/detections.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <fmt/format.h>

#include "ingest/pipeline/scene_nodes.hpp"

namespace smql::ingest {

using model::GeometryKind;
using model::NodeKind;

std::vector<WallOpening> OpeningsStage::run(StageProgress& progress) {
    if (!depth || walls.empty()) return {};
    std::unordered_map<std::uint32_t, model::Vec3> cameras;
    for (const auto& [frame, centre] : cameraCentres) cameras.emplace(static_cast<std::uint32_t>(frame), centre);
    // Doors and windows the object source gave stand: an opening where one of them is, is that one.
    std::vector<model::Box> given;
    for (const auto& n : scene.nodes)
        if (n.kind == NodeKind::Anchor && isOpening(n.category)) given.push_back(n.box);
    std::vector<WallOpening> added;
    for (const WallOpening& o : findOpenings(aligned.cloud, cameras, walls)) {
        model::Box box = o.box(walls[o.wall]);
        bool known = std::any_of(given.begin(), given.end(), [&](const model::Box& g) {
            double reach = (std::max(g.size.x, g.size.y) + box.size.x) / 2;
            return std::hypot(g.center.x - box.center.x, g.center.y - box.center.y) < reach;
        });
        if (known) continue;
        model::Node& node = addNode(scene, NodeKind::Anchor, o.category, GeometryKind::Plane, box);
        node.confidence = static_cast<float>(std::min(1.0, 0.5 + 0.01 * static_cast<double>(o.through)));
        node.attributes.push_back({"source", "opening"});
        progress.note(
            fmt::format("{} {:.2f} m wide and {:.2f} m tall{}, an opening in a wall: {} depth readings "
                        "seen through it",
                        o.category, box.size.x, box.size.z,
                        o.category == "window" ? fmt::format(", {:.2f} m above the floor", o.z0) : "", o.through));
        added.push_back(o);
    }
    return added;
}

std::string OpeningsStage::summary(const std::vector<WallOpening>& added) const {
    if (!depth) return "none looked for: openings need depth";
    auto doors = std::count_if(added.begin(), added.end(), [](const WallOpening& o) { return o.category == "door"; });
    return fmt::format("{} doors, {} windows", doors, added.size() - static_cast<std::size_t>(doors));
}

}  // namespace smql::ingest
