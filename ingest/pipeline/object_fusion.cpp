#include "ingest/pipeline/object_fusion.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "ingest/capture/detections.hpp"
#include "ingest/geometry/clusters.hpp"
#include "ingest/geometry/instance_map.hpp"
#include "ingest/geometry/typical_sizes.hpp"

namespace smql::ingest {

namespace {

// A view's region in the aligned frame, colours as RGB.
ViewRegion alignedRegion(const Observation& view, const Alignment& alignment) {
    ViewRegion region;
    region.points.reserve(view.region.size());
    for (const auto& r : view.region) {
        region.points.push(alignment.apply(r.position()), {r.bgr[2], r.bgr[1], r.bgr[0]}, view.frame);
        region.grid.push_back({r.column, r.row});
    }
    region.pitch = view.regionPitch * alignment.scale;
    return region;
}

// The instance's points that its views agree on: cells seen by two views, when it has three or more.
PointCloud instancePoints(const Instance& instance) { return instance.points(instance.sources.size() >= 3 ? 2 : 1); }

// How many of the cameras held the instance in view: at least half of up to 16 of its points project
// into the image, between 0.2 m and kMaxDepthReading in front (occlusion aside: an upper bound).
std::size_t framesInView(const PointCloud& points, const std::vector<FusionCamera>& cameras) {
    std::vector<model::Vec3> sample;
    const std::size_t step = std::max<std::size_t>(1, points.size() / 16);
    for (std::size_t i = 0; i < points.size(); i += step) sample.push_back(points.points[i]);
    std::size_t seen = 0;
    for (const auto& camera : cameras) {
        std::size_t inside = 0;
        for (const auto& p : sample) {
            auto at = projectToCamera(p, camera.pose, camera.intrinsics);
            inside += at && at->z > 0.2 && at->z < kMaxDepthReading && at->x >= 0 && at->y >= 0 &&
                      at->x < camera.intrinsics.width && at->y < camera.intrinsics.height;
        }
        seen += 2 * inside >= sample.size();
    }
    return seen;
}

// Whether a name suits a box: its largest side within [kNameFitLow, kNameFitHigh] x the largest
// side things of that kind commonly have (typical_sizes.hpp); kinds the table lacks suit any box.
constexpr double kNameFitLow = 0.25, kNameFitHigh = 1.5;
bool nameSuits(const std::string& category, const model::Box& box) {
    auto usual = typicalExtent(category);
    const double largest = std::max({box.size.x, box.size.y, box.size.z});
    return !usual || (largest >= kNameFitLow * *usual && largest <= kNameFitHigh * *usual);
}

// The instance's name: of the names its views gave that suit its box, the one with the largest sum
// of scores (a bed a detector called "suitcase" in more views is still a bed); when none suits, the
// best voted, which the objects stage keeps only as detected_as.
std::string nameOf(const Instance& instance, const model::Box& box) {
    std::string best;
    double bestVotes = -1;
    for (const auto& [label, votes] : instance.tally())
        if (nameSuits(label, box) && votes > bestVotes) best = label, bestVotes = votes;
    return best.empty() ? instance.category() : best;
}

}  // namespace

std::vector<ObjectTrack> fuseTracks(std::vector<ObjectTrack> tracks, const Alignment& alignment,
                                    const RoomSurfaces& room, const std::vector<FusionCamera>& cameras,
                                    const FusionOptions& options, StageProgress& progress) {
    // Every view, in frame order, with the track it came from (for its evidence crop).
    std::vector<Observation> views;
    std::vector<std::size_t> trackOf;
    for (std::size_t t = 0; t < tracks.size(); ++t)
        for (auto& v : tracks[t].views) {
            views.push_back(std::move(v));
            trackOf.push_back(t);
        }
    std::vector<std::size_t> order(views.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return views[a].frame < views[b].frame; });

    InstanceMapOptions mapOptions;
    mapOptions.voteLabels = options.voteLabels;
    InstanceMap map(mapOptions);
    std::size_t segmented = 0;
    for (std::size_t i = 0; i < order.size();) {
        progress.stopIfCancelled();
        std::vector<InstanceView> frame;
        const std::uint32_t at = views[order[i]].frame;
        for (; i < order.size() && views[order[i]].frame == at; ++i) {
            const Observation& view = views[order[i]];
            const bool onSurface = usualSupport(view.label) == Support::Surface;
            PointCloud thing = thingInView(alignedRegion(view, alignment), room, onSurface);
            if (thing.empty()) continue;
            ++segmented;
            frame.push_back({view.frame, view.label, view.score, view.alsoSeenAs, std::move(thing), order[i]});
        }
        map.integrate(std::move(frame));
    }
    const std::size_t before = map.instances().size();
    map.consolidate();
    const std::size_t merged = before - map.instances().size();

    std::vector<ObjectTrack> out;
    std::size_t slivers = 0, guesses = 0;
    for (const Instance& instance : map.instances()) {
        PointCloud points = instancePoints(instance);
        if (points.size() < 3) continue;
        const model::Box box = uprightBox(points.points);
        const std::string category = nameOf(instance, box);
        const double thinnest = std::min({box.size.x, box.size.y, box.size.z});
        const auto usual = typicalExtent(category);
        if (box.size.z < options.minHeight || std::max({box.size.x, box.size.y, box.size.z}) < options.minLargest ||
            (usual && thinnest < options.thinShare * *usual)) {
            ++slivers;
            continue;
        }
        const auto inView = static_cast<double>(framesInView(points, cameras));
        const auto needed = std::clamp(static_cast<int>(std::ceil(options.minViewShare * inView)), 1, options.viewsEnough);
        if (static_cast<int>(instance.frames.size()) < needed) {
            ++guesses;
            continue;
        }
        ObjectTrack track;
        track.category = category;
        track.kind = detectionKind(track.category);
        std::map<std::size_t, std::size_t> fromTrack;  // views each frame-pass track gave
        std::vector<std::size_t> sources = instance.sources;
        std::sort(sources.begin(), sources.end(), [&](auto a, auto b) { return views[a].frame < views[b].frame; });
        for (auto s : sources) {
            ++fromTrack[trackOf[s]];
            track.views.push_back(std::move(views[s]));
        }
        auto most = std::max_element(fromTrack.begin(), fromTrack.end(),
                                     [](const auto& a, const auto& b) { return a.second < b.second; });
        track.evidence = tracks[most->first].evidence;
        track.material = tracks[most->first].material;
        for (std::size_t p = 0; p < points.size(); ++p) {
            track.fused.push_back(points.points[p]);
            const auto& c = points.colors[p];
            track.fusedColors.push_back(cv::Vec3b(c[2], c[1], c[0]));
        }
        out.push_back(std::move(track));
    }
    progress.note(fmt::format("objects: {} of {} views showed a thing apart from the floor and walls; fused into {} "
                              "instances ({} pieces merged into the things they belong to, {} slivers and {} things "
                              "seen in too few of the frames that held them dropped)",
                              segmented, views.size(), out.size(), merged, slivers, guesses));
    return out;
}

}  // namespace smql::ingest
