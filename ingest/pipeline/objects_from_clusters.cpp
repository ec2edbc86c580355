// Class-agnostic objects: Euclidean clusters of the aligned structure cloud's points that are not
// floor, ceiling or wall become objects of category `object` (one right under a sink: `cabinet`, the cabinet
// it is set in), named by the colour of their points.
// The fallback source (--objects cluster) keeps every cluster but specks; beside detections, only the
// large things no detector named (a bed, a cabinet: PASCAL's and COCO's classes lack them) are kept.
#include "ingest/pipeline/objects_from_clusters.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>
#include <opencv2/core.hpp>

#include "ingest/geometry/clusters.hpp"
#include "ingest/geometry/typical_sizes.hpp"
#include "ingest/geometry/view_segment.hpp"
#include "ingest/pipeline/colors.hpp"
#include "ingest/pipeline/geometry_stage.hpp"
#include "ingest/pipeline/object_finder.hpp"
#include "ingest/pipeline/scene_nodes.hpp"
#include "model/category.hpp"
#include "model/geometry.hpp"

namespace smql::ingest {

namespace {

// Whether a point lies in (or within `margin` of) the box of an object the scene already holds.
bool inKnownThing(const model::Vec3& p, const model::SceneData& scene, double margin) {
    for (const auto& n : scene.nodes) {
        if (n.kind != model::NodeKind::Object || n.geometry != model::GeometryKind::Box) continue;
        if (model::footprintContains(n.box, {p.x, p.y}, margin) &&
            std::abs(p.z - n.box.center.z) <= n.box.size.z / 2 + margin)
            return true;
    }
    return false;
}

class ClusterFinder : public ObjectFinder {
public:
    explicit ClusterFinder(const Capture& capture) : capture_(capture) {}
    // Clusters come from the aligned structure, which the frame pass builds anyway.
    void observe(const PosedFrame&) override {}
    std::vector<ObjectTrack> takeTracks() override { return {}; }

    void addStructureObjects(const AlignedCapture& aligned, const std::vector<WallSegment>& walls,
                             model::SceneData& scene, StageProgress& progress) override {
        const ClusterCounts counts = addClusterObjects(aligned, walls, scene, {}, capture_);
        progress.note(fmt::format("objects by 3D clustering (no masks): {} clusters, category 'object'{}", counts.added,
                                  counts.cabinets + counts.wallCabinets > 0
                                      ? fmt::format(" ({} under a sink or hung on a wall as 'cabinet')",
                                                    counts.cabinets + counts.wallCabinets)
                                      : ""));
    }

private:
    const Capture& capture_;
};

}  // namespace

bool hungOnWall(const model::Box& box, const std::vector<WallSegment>& walls) {
    return model::bottom(box) >= kWallCabinetBottom && std::any_of(walls.begin(), walls.end(), [&](const auto& wall) {
               return model::horizontalGap(box, wall.box()) <= kAgainstWall;
           });
}

model::Node& addUnnamedThing(model::SceneData& scene, std::string category, const model::Box& box,
                             const PointCloud& cloud, const std::vector<std::size_t>& indices, const Capture& capture) {
    cv::Mat colors;  // BGR, as nameColor takes them
    for (const auto i : indices) {
        const auto& c = cloud.colors[i];
        colors.push_back(cv::Vec3b(c[2], c[1], c[0]));
    }
    model::Node& node = addNode(scene, model::NodeKind::Object, std::move(category), model::GeometryKind::Box, box);
    node.attributes.push_back({"color", nameColor(colors).name});
    node.attributes.push_back({"size", sizeWord(box)});
    node.attributes.push_back({"points", std::to_string(indices.size())});
    // A depth frame's points carry the frame they were seen in; photos' points (COLMAP's, the dense ones) carry none.
    if (!indices.empty() && framesHaveDepth(capture)) {
        const auto [first, last] =
            std::minmax_element(indices.begin(), indices.end(),
                                [&](std::size_t a, std::size_t b) { return cloud.frames[a] < cloud.frames[b]; });
        node.attributes.push_back({"first_seen", std::to_string(capture.frames[cloud.frames[*first]].index)});
        node.attributes.push_back({"last_seen", std::to_string(capture.frames[cloud.frames[*last]].index)});
    }
    std::sort(node.attributes.begin(), node.attributes.end(),
              [](const auto& a, const auto& b) { return a.name < b.name; });
    node.confidence = 0.5f;
    return node;
}

const model::Node* basinOver(const model::Box& cluster, const model::SceneData& scene, const FusionOptions& options) {
    for (const auto& n : scene.nodes)
        if (n.kind == model::NodeKind::Object && n.geometry == model::GeometryKind::Box &&
            role(n.category) == Role::Basin && cabinetOf(cluster, n.box, options))
            return &n;
    return nullptr;
}

ClusterCounts addClusterObjects(const AlignedCapture& aligned, const std::vector<WallSegment>& walls,
                                model::SceneData& scene, const ClusterObjects& options, const Capture& capture) {
    StructureOptions structureOptions;
    structureOptions.ceilingHeight = aligned.alignment.ceilingHeight;
    const PointCloud& cloud = aligned.cloud;
    const RoomSurfaces room = roomSurfaces(aligned.alignment, &walls);
    std::vector<std::size_t> rest;
    for (auto i : nonStructuralPoints(cloud, walls, structureOptions))
        if (!onRoomSurface(cloud.points[i], room) &&
            !(options.outsideKnown && inKnownThing(cloud.points[i], scene, options.knownMargin)))
            rest.push_back(i);
    auto clusters = euclideanClusters(cloud, rest, options.gap, options.minPoints, 200000);
    ClusterCounts counts;
    for (const auto& cluster : clusters) {
        std::vector<model::Vec3> points;
        std::set<std::uint32_t> frames;
        for (auto i : cluster) {
            points.push_back(cloud.points[i]);
            frames.insert(cloud.frames[i]);
        }
        model::Box box = uprightBox(points);
        if (box.size.x < options.minLonger || box.size.y < options.minShorter || box.size.z < options.minHeight ||
            box.size.x > options.maxLonger || frames.size() < options.minFrames)
            continue;
        const model::Node* basin = basinOver(box, scene);
        const bool wallCabinet = !basin && aligned.alignment.floorFound && hungOnWall(box, walls);
        const bool cabinet = basin != nullptr || wallCabinet;
        if (basin) reachUnder(box, basin->box);
        // Built in, as the kinds of a kitchen that stand on its floor are (typical_sizes.hpp: standsSquare): a few
        // points of the wall or of what stands under turned the apartment's wall cabinet 30 degrees off its wall.
        if (wallCabinet) box = wallAlignedBox(points, FusionOptions{}.squareSlack);
        counts.cabinets += basin != nullptr;
        counts.wallCabinets += wallCabinet;
        addUnnamedThing(scene, std::string(cabinet ? "cabinet" : model::kUnnamedCategory), box, cloud, cluster,
                        capture);
        ++counts.added;
    }
    return counts;
}

bool clustersUsable(const Capture&, const IngestOptions&) { return true; }

std::unique_ptr<ObjectFinder> makeClusterFinder(const Capture& capture, const IngestOptions&) {
    return std::make_unique<ClusterFinder>(capture);
}

extern const ObjectSourceSpec kClusterSource{"cluster", "clusters of the points off the walls and floor",
                                             clustersUsable, makeClusterFinder};

}  // namespace smql::ingest
