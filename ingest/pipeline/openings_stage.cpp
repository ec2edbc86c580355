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

// Every door and window the scene holds, those the objects' detections gave included, so that the
// stage lines add up to the anchors the ingest reports.
std::string OpeningsStage::summary(const std::vector<WallOpening>& added) const {
    auto count = [&](std::string_view category) {
        return std::count_if(scene.nodes.begin(), scene.nodes.end(), [&](const model::Node& n) {
            return n.kind == NodeKind::Anchor && n.category == category;
        });
    };
    return fmt::format("{} doors, {} windows ({} from gaps in the walls{})", count("door"), count("window"),
                       added.size(), depth ? "" : ": none looked for, openings need depth");
}

}  // namespace smql::ingest
