#include "ingest/pipeline/ray_tracks.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <queue>
#include <unordered_map>

#include <opencv2/core.hpp>

#include "ingest/capture/detections.hpp"
#include "model/geometry.hpp"

namespace smql::ingest {

namespace {

using Vec = cv::Vec3d;

Vec vec(const model::Vec3& p) { return {p.x, p.y, p.z}; }
model::Vec3 point(const Vec& v) { return {v[0], v[1], v[2]}; }

struct Ray {
    Vec origin, direction;  // unit direction
};

// A view with what placing it needs: its camera, its box's centre and size, and the ray through
// the centre.
struct BoxView {
    const MaskView* camera = nullptr;
    cv::Point2d centre;
    cv::Size2d size;
    Ray ray;
};

BoxView boxView(const Observation& view, const MaskView& camera) {
    const cv::Rect& b = view.bounds;
    // Box edges are pixel edges: its centre, in pixel-centre coordinates, is half a pixel back.
    cv::Point2d centre(b.x + b.width / 2.0 - 0.5, b.y + b.height / 2.0 - 0.5);
    const auto& K = camera.intrinsics;
    const auto& R = camera.pose.rotation;
    Vec c{(centre.x - K.cx) / K.fx, (centre.y - K.cy) / K.fy, 1};
    Vec d{R[0] * c[0] + R[1] * c[1] + R[2] * c[2], R[3] * c[0] + R[4] * c[1] + R[5] * c[2],
          R[6] * c[0] + R[7] * c[1] + R[8] * c[2]};
    return {&camera,
            centre,
            cv::Size2d(std::max(b.width, 1), std::max(b.height, 1)),
            {vec(camera.pose.translation), cv::normalize(d)}};
}

// Where `x` falls in the view's image, and how deep: nothing behind the camera.
std::optional<cv::Point3d> project(const Vec& x, const MaskView& camera) {
    return projectToCamera(point(x), camera.pose, camera.intrinsics);
}

// How far `x` falls from the box's centre, in box widths or heights (the larger); nothing behind
// the camera.
std::optional<double> offCentre(const Vec& x, const BoxView& box) {
    auto p = project(x, *box.camera);
    if (!p) return std::nullopt;
    return std::max(std::abs(p->x - box.centre.x) / box.size.width, std::abs(p->y - box.centre.y) / box.size.height);
}

// The midpoint of the shortest segment between two rays, when they are at least kMinRayAngle apart
// (nearer to parallel, depth is ill-posed) and it lies in front of both.
std::optional<Vec> closestApproach(const Ray& a, const Ray& b) {
    double cosine = a.direction.dot(b.direction);
    if (cosine > std::cos(kMinRayAngle * model::kDegree)) return std::nullopt;
    Vec w = a.origin - b.origin;
    double d = a.direction.dot(w), e = b.direction.dot(w), denominator = 1 - cosine * cosine;
    double s = (cosine * e - d) / denominator, t = (e - cosine * d) / denominator;
    if (!(s > 0 && t > 0)) return std::nullopt;
    return (a.origin + s * a.direction + b.origin + t * b.direction) * 0.5;
}

// The point nearest to every ray in the least-squares sense: sum (I - d d^T) x = sum (I - d d^T) o.
std::optional<Vec> nearestToRays(const std::vector<const Ray*>& rays) {
    cv::Matx33d a = cv::Matx33d::zeros();
    Vec b(0, 0, 0);
    for (const Ray* r : rays) {
        cv::Matx33d m = cv::Matx33d::eye() - r->direction * r->direction.t();
        a += m;
        b += m * r->origin;
    }
    Vec x;
    if (!cv::solve(a, b, x, cv::DECOMP_SVD)) return std::nullopt;
    return x;
}

class RayGrouper {
public:
    RayGrouper(const std::vector<UnplacedView>& unplaced, const std::vector<MaskView>& cameras) : unplaced_(unplaced) {
        std::unordered_map<std::uint32_t, const MaskView*> byFrame;
        for (const auto& m : cameras) byFrame.emplace(m.frame, &m);
        for (std::size_t i = 0; i < unplaced.size(); ++i) {
            auto it = byFrame.find(unplaced[i].view.frame);
            if (it == byFrame.end()) continue;
            boxes_.emplace(i, boxView(unplaced[i].view, *it->second));
            byCategory_[unplaced[i].category].push_back(i);
        }
        used_.assign(unplaced.size(), false);
    }

    const std::map<std::string, std::vector<std::size_t>>& byCategory() const { return byCategory_; }
    const BoxView* box(std::size_t i) const {
        auto it = boxes_.find(i);
        return it == boxes_.end() ? nullptr : &it->second;
    }
    bool used(std::size_t i) const { return used_[i]; }
    void use(std::size_t i) { used_[i] = true; }

    // The unused views of `category` whose box centre `x` falls near, the nearest one per frame, with
    // the sum of their offsets.
    std::pair<std::vector<std::size_t>, double> groupAt(const Vec& x, const std::string& category) const {
        std::map<std::uint32_t, std::pair<double, std::size_t>> best;  // frame -> (offset, view)
        for (auto i : byCategory_.at(category)) {
            if (used_[i]) continue;
            auto off = offCentre(x, boxes_.at(i));
            if (!off || *off > kCentreShare) continue;
            auto [it, added] = best.try_emplace(unplaced_[i].view.frame, *off, i);
            if (!added && *off < it->second.first) it->second = {*off, i};
        }
        std::vector<std::size_t> group;
        double sum = 0;
        for (const auto& [frame, entry] : best) group.push_back(entry.second), sum += entry.first;
        return {group, sum};
    }

private:
    const std::vector<UnplacedView>& unplaced_;
    std::unordered_map<std::size_t, BoxView> boxes_;
    std::map<std::string, std::vector<std::size_t>> byCategory_;
    std::vector<bool> used_;
};

// The region a group's hull is carved in: a cube around its centre, as wide as the largest box
// spans at the centre's depth, with room to spare.
HullRegion regionAround(const Vec& centre, const std::vector<const BoxView*>& boxes) {
    double half = 0;
    for (const BoxView* b : boxes) {
        auto p = project(centre, *b->camera);
        if (!p) continue;
        const auto& K = b->camera->intrinsics;
        half = std::max(half, 0.75 * p->z * std::max(b->size.width / K.fx, b->size.height / K.fy));
    }
    return {{centre[0] - half, centre[1] - half, centre[2] - half},
            {centre[0] + half, centre[1] + half, centre[2] + half}};
}

// The mean of a placed track's points: its hull's centre once carved.
std::optional<Vec> trackCentre(const ObjectTrack& track) {
    Vec sum(0, 0, 0);
    std::size_t count = 0;
    for (const auto& v : track.views)
        for (const auto& p : v.points) sum += vec(p), ++count;
    if (count == 0) return std::nullopt;
    return sum / static_cast<double>(count);
}

// Views that show a placed track where its own views' points fell short: each joins the track of
// its category, not yet seen in its frame, whose centre falls nearest its box's centre.
std::size_t joinPlaced(RayGrouper& grouper, const std::vector<UnplacedView>& unplaced,
                       std::vector<ObjectTrack>& placed) {
    std::size_t joined = 0;
    for (auto& track : placed) {
        auto centre = trackCentre(track);
        auto it = grouper.byCategory().find(track.category);
        if (!centre || it == grouper.byCategory().end()) continue;
        auto [group, sum] = grouper.groupAt(*centre, track.category);
        for (auto i : group) {
            bool seen = std::any_of(track.views.begin(), track.views.end(),
                                    [&](const Observation& v) { return v.frame == unplaced[i].view.frame; });
            if (seen) continue;
            track.views.push_back(unplaced[i].view);
            track.views.back().points.clear();  // the track's hull stands for it
            if (unplaced[i].evidence.pixels > track.evidence.pixels) track.evidence = unplaced[i].evidence;
            grouper.use(i);
            ++joined;
        }
    }
    return joined;
}

// The bounds of a track's points: its hull's, once carved.
HullRegion hullBounds(const ObjectTrack& track) {
    HullRegion b{{1e18, 1e18, 1e18}, {-1e18, -1e18, -1e18}};
    for (const auto& v : track.views)
        for (const auto& p : v.points) b = b.united({p, p});
    return b;
}

// One thing split into two carved tracks (its views associated apart): two tracks of a category
// that never share a frame, one's centre inside the other's hull bounds, become one, carved from all
// their views in both regions: a track whose views carved little reaches far past the thing, so its
// centre may lie outside the other's bounds while the other's lies inside its own.
void mergeSplitTracks(std::vector<ObjectTrack>& tracks, const std::vector<MaskView>& cameras) {
    for (std::size_t a = 0; a < tracks.size(); ++a) {
        ObjectTrack& one = tracks[a];
        if (!one.carved) continue;
        // One's bounds and centre, again only when a merge changes them.
        HullRegion first = hullBounds(one);
        auto c1 = trackCentre(one);
        for (std::size_t b = a + 1; b < tracks.size() && c1; ++b) {
            ObjectTrack& other = tracks[b];
            if (!other.carved || other.category != one.category || other.views.empty()) continue;
            HullRegion second = hullBounds(other);
            auto c2 = trackCentre(other);
            if (!c2 || (!second.holds(point(*c1)) && !first.holds(point(*c2)))) continue;
            bool shareFrame = std::any_of(one.views.begin(), one.views.end(), [&](const Observation& v) {
                return std::any_of(other.views.begin(), other.views.end(),
                                   [&](const Observation& w) { return w.frame == v.frame; });
            });
            if (shareFrame) continue;
            std::vector<Observation> views = one.views;
            views.insert(views.end(), other.views.begin(), other.views.end());
            auto hull = carveRegion(first.united(second), views, cameras, 1.0);
            if (hull.size() < 10) continue;
            for (auto& v : views) v.points.clear();
            views.front().points = std::move(hull);
            one.views = std::move(views);
            if (other.evidence.pixels > one.evidence.pixels) one.evidence = std::move(other.evidence);
            one.surface.insert(one.surface.end(), other.surface.begin(), other.surface.end());
            other.views.clear();
            first = hullBounds(one);
            c1 = trackCentre(one);
        }
    }
    std::erase_if(tracks, [](const ObjectTrack& t) { return t.views.empty(); });
}

struct Candidate {
    Vec centre;
    std::string category;
    std::size_t size = 0;  // views in its group when last counted
    double offset = 0;     // their summed offsets from their boxes' centres
    bool operator<(const Candidate& other) const {
        return size != other.size ? size < other.size : offset > other.offset;
    }
};

}  // namespace

std::size_t placeByRays(std::vector<UnplacedView> unplaced, const std::vector<MaskView>& cameras,
                        std::vector<ObjectTrack>& placed, int minViews) {
    RayGrouper grouper(unplaced, cameras);
    std::size_t used = joinPlaced(grouper, unplaced, placed);
    const auto enough = static_cast<std::size_t>(std::max(minViews, 2));

    std::priority_queue<Candidate> candidates;
    for (const auto& [category, views] : grouper.byCategory())
        for (std::size_t a = 0; a < views.size(); ++a)
            for (std::size_t b = a + 1; b < views.size(); ++b) {
                std::size_t i = views[a], j = views[b];
                if (grouper.used(i) || grouper.used(j) || unplaced[i].view.frame == unplaced[j].view.frame) continue;
                auto x = closestApproach(grouper.box(i)->ray, grouper.box(j)->ray);
                if (!x) continue;
                auto [group, offset] = grouper.groupAt(*x, category);
                if (group.size() >= enough) candidates.push({*x, category, group.size(), offset});
            }

    // Greedy, the largest group first; a group shrinks as its views join others, so each is
    // counted again before it is taken.
    while (!candidates.empty()) {
        Candidate top = candidates.top();
        candidates.pop();
        auto [group, offset] = grouper.groupAt(top.centre, top.category);
        if (group.size() < enough) continue;
        if (group.size() < top.size && !candidates.empty()) {
            candidates.push({top.centre, top.category, group.size(), offset});
            continue;
        }
        // The centre from all the group's rays, when that keeps at least as many views.
        std::vector<const Ray*> rays;
        for (auto i : group) rays.push_back(&grouper.box(i)->ray);
        Vec centre = top.centre;
        if (auto refined = nearestToRays(rays)) {
            auto again = grouper.groupAt(*refined, top.category);
            if (again.first.size() >= group.size()) centre = *refined, group = std::move(again.first);
        }
        std::vector<const BoxView*> boxes;
        std::vector<Observation> views;
        for (auto i : group) boxes.push_back(grouper.box(i)), views.push_back(unplaced[i].view);
        auto hull = carveRegion(regionAround(centre, boxes), views, cameras, 1.0);
        if (hull.size() < 10) continue;
        // A view whose box the hull does not fill is of something else: the group is carved again
        // without such views, once.
        std::vector<std::size_t> filled;
        for (auto i : group)
            if (hullFillsBox(hull, unplaced[i].view.bounds, *grouper.box(i)->camera)) filled.push_back(i);
        if (filled.size() < group.size()) {
            if (filled.size() < enough) continue;
            group = std::move(filled);
            views.clear();
            for (auto i : group) views.push_back(unplaced[i].view);
            hull = carveRegion(regionAround(centre, boxes), views, cameras, 1.0);
            if (hull.size() < 10) continue;
        }

        ObjectTrack track;
        track.category = top.category;
        track.kind = detectionKind(top.category);
        for (auto i : group) {
            if (unplaced[i].evidence.pixels > track.evidence.pixels) track.evidence = std::move(unplaced[i].evidence);
            track.views.push_back(std::move(unplaced[i].view));
            track.views.back().points.clear();
            grouper.use(i);
        }
        track.views.front().points = std::move(hull);
        track.carved = true;
        used += group.size();
        placed.push_back(std::move(track));
    }
    mergeSplitTracks(placed, cameras);
    return used;
}

}  // namespace smql::ingest
