#include "ingest/pipeline/objects_stage.hpp"
#include "ingest/capture/detections.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <opencv2/core.hpp>

#include "ingest/geometry/clusters.hpp"
#include "ingest/pipeline/colors.hpp"
#include "ingest/pipeline/plausibility.hpp"
#include "ingest/pipeline/scene_nodes.hpp"
#include "model/embedding.hpp"

namespace smql::ingest {

using model::GeometryKind;
using model::NodeKind;

namespace {

// A door or window lies in its wall: the nearest wall's direction, the extent
// of the points along it, and a thin depth.
void setInWall(model::Box& box, const PointCloud& cloud, const std::vector<WallSegment>& walls) {
    const WallSegment* nearest = &walls.front();
    for (const auto& w : walls)
        if (std::abs(w.signedDistance(box.center)) < std::abs(nearest->signedDistance(box.center))) nearest = &w;
    model::Vec3 d = nearest->direction();
    box.yaw = std::atan2(d.y, d.x);
    double along0 = 1e9, along1 = -1e9;
    for (const auto& p : cloud.points) {
        double a = p.x * d.x + p.y * d.y;
        along0 = std::min(along0, a), along1 = std::max(along1, a);
    }
    box.size = {along1 - along0, 0.05, box.size.z};
}

// Nothing stands below the floor or above the ceiling: a hull carved from views that all look
// down at a thing reaches under the floor, and the floor and ceiling bound it (a little slack for
// the planes' own noise).
bool withinRoom(const model::Vec3& p, const Alignment& alignment) {
    constexpr double kSlack = 0.02;  // m
    if (alignment.floorFound && p.z < -kSlack) return false;
    return !alignment.ceilingHeight || p.z <= *alignment.ceilingHeight + kSlack;
}

// A hull carved without depth from a narrow range of directions stays long along the view. Along
// its longer side it is held to where the thing's own surfaces were seen (its sparse points,
// aligned), widened by its shorter side at each end: a thing reaches past what showed of it, not
// without bound. Its kind's usual size is never the answer (a 2.97 m table stays 2.97 m).
void holdToSurface(model::Box& box, const std::vector<model::Vec3>& surface, const Alignment& alignment) {
    if (surface.empty() || box.size.x <= box.size.y) return;
    const double c = std::cos(box.yaw), s = std::sin(box.yaw);
    double lo = 1e18, hi = -1e18;
    for (const auto& raw : surface) {
        const model::Vec3 p = alignment.apply(raw);
        const double along = c * (p.x - box.center.x) + s * (p.y - box.center.y);
        lo = std::min(lo, along), hi = std::max(hi, along);
    }
    const double from = std::max(-box.size.x / 2, lo - box.size.y), to = std::min(box.size.x / 2, hi + box.size.y);
    if (!(to > from)) return;
    const double middle = (from + to) / 2;
    box.center = {box.center.x + c * middle, box.center.y + s * middle, box.center.z};
    box.size.x = to - from;
}

// What the views' embeddings agree on: the mean of their unit vectors, at unit length. Empty when
// no view has one, or when they cancel out (views pointing opposite ways say nothing).
std::vector<float> meanEmbedding(const std::vector<Observation>& views) {
    std::vector<double> sum;
    for (const auto& view : views) {
        if (view.embedding.empty()) continue;
        if (sum.empty()) sum.assign(view.embedding.size(), 0.0);
        double norm = 0;
        for (float x : view.embedding) norm += static_cast<double>(x) * x;
        norm = std::sqrt(norm);
        for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += view.embedding[i] / norm;
    }
    double norm = 0;
    for (double x : sum) norm += x * x;
    norm = std::sqrt(norm);
    if (!(norm > 1e-6)) return {};
    std::vector<float> mean;
    mean.reserve(sum.size());
    for (double x : sum) mean.push_back(static_cast<float>(x / norm));
    return mean;
}

}  // namespace

std::vector<TrackedNode> ObjectsStage::run(StageProgress& progress) {
    std::vector<TrackedNode> made;
    const std::size_t steps = this->steps();
    tracks = finder.fuse(std::move(tracks), aligned, walls, progress);
    for (std::size_t t = 0; t < tracks.size(); ++t) {
        auto& track = tracks[t];
        progress.advanced((t + 1) * steps / tracks.size());
        const auto& category = track.category;
        bool opening = isOpening(category);
        if (track.kind == NodeKind::Anchor && !opening) continue;  // walls, floor, ceiling: geometry's job
        if (static_cast<int>(track.views.size()) < options.minObjectViews) continue;

        PointCloud cloud;
        cv::Mat colors;
        if (!track.fused.empty()) {
            // Already in the aligned frame, and already thinned to the map's cells.
            for (const auto& p : track.fused) cloud.push(p, {0, 0, 0}, 0);
            colors = track.fusedColors;
        } else {
            for (const auto& v : track.views)
                for (const auto& p : v.points)
                    if (auto q = aligned.alignment.apply(p); withinRoom(q, aligned.alignment))
                        cloud.push(q, {0, 0, 0}, v.frame);
            if (cloud.size() < 10) continue;
            cloud = voxelDownsample(cloud, options.objectVoxel);
            for (const auto& v : track.views) colors.push_back(v.colors);
        }
        if (cloud.empty()) continue;
        model::Box box = track.fusedBox ? *track.fusedBox : uprightBox(cloud.points);
        if (track.carved) holdToSurface(box, track.surface, aligned.alignment);
        if (opening && !walls.empty()) setInWall(box, cloud, walls);
        // A name far too small for its box (a detector's 1.8 m "cake") is kept only as a guess.
        const bool misnamed = !opening && !nameFitsBox(category, box);
        if (misnamed)
            progress.note(
                fmt::format("a {:.2f} m thing was detected as '{}', which is never that large: stored as "
                            "'object' with detected_as = {}",
                            std::max({box.size.x, box.size.y, box.size.z}), category, category));
        model::Node& node =
            addNode(scene, opening ? NodeKind::Anchor : NodeKind::Object, misnamed ? std::string("object") : category,
                    opening ? GeometryKind::Plane : GeometryKind::Box, box);
        if (misnamed) node.attributes.push_back({"detected_as", category});
        if (!opening) {
            if (auto color = nameColor(colors).name; !color.empty()) node.attributes.push_back({"color", color});
            node.attributes.push_back({"size", sizeWord(box)});
            if (!track.material.empty()) node.attributes.push_back({"material", track.material});
        }
        auto [first, last] = std::minmax_element(track.views.begin(), track.views.end(),
                                                 [](const auto& a, const auto& b) { return a.frame < b.frame; });
        node.attributes.push_back({"first_seen", std::to_string(capture.frames[first->frame].index)});
        node.attributes.push_back({"last_seen", std::to_string(capture.frames[last->frame].index)});
        node.attributes.push_back({"views", std::to_string(track.views.size())});
        node.confidence = static_cast<float>(std::min(1.0, 0.5 + 0.1 * track.views.size()) * (misnamed ? 0.5 : 1.0));
        std::sort(node.attributes.begin(), node.attributes.end(),
                  [](const auto& a, const auto& b) { return a.name < b.name; });
        if (!track.evidence.jpeg.empty())
            scene.blobs.push_back({node.id,
                                   fmt::format("evidence-frame{}.jpg", capture.frames[track.evidence.frame].index),
                                   "image/jpeg", std::move(track.evidence.jpeg)});
        if (auto embedding = meanEmbedding(track.views); !embedding.empty())
            scene.blobs.push_back(model::embeddingBlob(node.id, embedding));
        made.push_back({node.id, std::move(track.views)});
    }
    finder.addStructureObjects(aligned, walls, scene, progress);
    return made;
}

std::string ObjectsStage::summary(const std::vector<TrackedNode>&) const {
    auto count = std::count_if(scene.nodes.begin(), scene.nodes.end(),
                               [](const model::Node& n) { return n.kind == NodeKind::Object; });
    return fmt::format("{} objects", count);
}

}  // namespace smql::ingest
