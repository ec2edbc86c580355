// Class-agnostic objects (--objects cluster, the fallback): Euclidean clusters
// of the aligned structure cloud's points that are not floor, ceiling or wall
// become objects of category `object`, named by the colour of their points.
#include <fmt/format.h>
#include <opencv2/core.hpp>

#include "ingest/geometry/clusters.hpp"
#include "ingest/pipeline/colors.hpp"
#include "ingest/pipeline/object_finder.hpp"
#include "ingest/pipeline/scene_nodes.hpp"

namespace smql::ingest {

namespace {

class ClusterFinder : public ObjectFinder {
public:
    // Clusters come from the aligned structure, which the frame pass builds anyway.
    void observe(const PosedFrame&) override {}
    std::vector<ObjectTrack> takeTracks() override { return {}; }

    void addStructureObjects(const AlignedCapture& aligned, const std::vector<WallSegment>& walls,
                             model::SceneData& scene, StageProgress& progress) override {
        StructureOptions structureOptions;
        structureOptions.ceilingHeight = aligned.alignment.ceilingHeight;
        const PointCloud& cloud = aligned.cloud;
        auto rest = nonStructuralPoints(cloud, walls, structureOptions);
        auto clusters = euclideanClusters(cloud, rest, 0.08, 30, 200000);
        for (const auto& cluster : clusters) {
            std::vector<model::Vec3> points;
            cv::Mat colors;
            for (auto i : cluster) {
                points.push_back(cloud.points[i]);
                const auto& c = cloud.colors[i];
                colors.push_back(cv::Vec3b(c[2], c[1], c[0]));
            }
            model::Box box = uprightBox(points);
            if (box.size.x < 0.05 || box.size.y < 0.03 || box.size.z < 0.03) continue;  // specks
            model::Node& node = addNode(scene, model::NodeKind::Object, "object", model::GeometryKind::Box, box);
            node.attributes.push_back({"color", nameColor(colors).name});
            node.attributes.push_back({"size", sizeWord(box)});
            node.attributes.push_back({"points", std::to_string(cluster.size())});
            node.confidence = 0.5f;
        }
        progress.note(
            fmt::format("objects by 3D clustering (no masks): {} clusters, category 'object'", clusters.size()));
    }
};

}  // namespace

bool clustersUsable(const Capture&, const IngestOptions&) { return true; }

std::unique_ptr<ObjectFinder> makeClusterFinder(const Capture&, const IngestOptions&) {
    return std::make_unique<ClusterFinder>();
}

extern const ObjectSourceSpec kClusterSource{"cluster", "clusters of the points off the walls and floor",
                                             clustersUsable, makeClusterFinder};

}  // namespace smql::ingest
