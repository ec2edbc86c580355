#include "ingest/capture/observations.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <opencv2/imgproc.hpp>

#include "ingest/capture/media.hpp"

namespace smql::ingest {

namespace {

// The pixel a projection (projectToImage) falls in.
cv::Point pixelOf(const cv::Point2d& at) {
    return {static_cast<int>(std::floor(at.x + 0.5)), static_cast<int>(std::floor(at.y + 0.5))};
}

}  // namespace

std::vector<Observation> observeInstances(const FrameImages& images, const Pose& pose, std::uint32_t frame, int stride,
                                          int minPixels) {
    std::vector<Observation> out;
    if (images.instances.empty()) return out;
    const auto& K = images.intrinsics;
    const auto& R = pose.rotation;
    const auto& t = pose.translation;

    // One sweep over the mask: areas, bounds and centroids of every instance.
    struct Extent {
        int pixels = 0;
        int x0 = INT32_MAX, y0 = INT32_MAX, x1 = -1, y1 = -1;
        double sumX = 0;
    };
    std::unordered_map<std::uint16_t, Extent> extents;
    for (int y = 0; y < images.instances.rows; ++y) {
        const auto* row = images.instances.ptr<std::uint16_t>(y);
        for (int x = 0; x < images.instances.cols; ++x) {
            if (!row[x]) continue;
            auto& e = extents[row[x]];
            ++e.pixels;
            e.sumX += x;
            e.x0 = std::min(e.x0, x), e.y0 = std::min(e.y0, y), e.x1 = std::max(e.x1, x), e.y1 = std::max(e.y1, y);
        }
    }
    std::unordered_map<std::uint16_t, std::size_t> slot;
    for (const auto& [id, e] : extents) {
        if (e.pixels < minPixels) continue;
        Observation o;
        o.frame = frame;
        o.instance = id;
        o.pixels = e.pixels;
        o.bounds = cv::Rect(e.x0, e.y0, e.x1 - e.x0 + 1, e.y1 - e.y0 + 1);
        o.centreX = e.sumX / e.pixels / images.instances.cols;
        slot.emplace(id, out.size());
        out.push_back(std::move(o));
    }

    std::vector<std::vector<cv::Vec3b>> samples(out.size());
    for (int y = 0; y < images.instances.rows; y += stride) {
        const auto* ids = images.instances.ptr<std::uint16_t>(y);
        const auto* bgr = images.color.ptr<cv::Vec3b>(y);
        const float* depth = images.depth.empty() ? nullptr : images.depth.ptr<float>(y);
        for (int x = 0; x < images.instances.cols; x += stride) {
            auto it = slot.find(ids[x]);
            if (it == slot.end()) continue;
            Observation& o = out[it->second];
            samples[it->second].push_back(bgr[x]);
            if (!depth || !(depth[x] > 0)) continue;
            double z = depth[x];
            double cx = (x - K.cx) / K.fx * z, cy = (y - K.cy) / K.fy * z;
            o.points.push_back({R[0] * cx + R[1] * cy + R[2] * z + t.x, R[3] * cx + R[4] * cy + R[5] * z + t.y,
                                R[6] * cx + R[7] * cy + R[8] * z + t.z});
        }
    }
    for (std::size_t i = 0; i < out.size(); ++i) cv::Mat(samples[i], true).copyTo(out[i].colors);
    return out;
}

void liftSparsePoints(std::vector<Observation>& observations, const FrameImages& images, const Pose& pose,
                      const std::vector<SparsePoint>& points, std::vector<std::uint32_t>& inView, double depthBand) {
    if (images.instances.empty() || observations.empty()) return;
    std::unordered_map<std::uint16_t, std::size_t> slot;
    for (std::size_t i = 0; i < observations.size(); ++i) slot.emplace(observations[i].instance, i);
    std::vector<std::vector<std::pair<double, std::uint32_t>>> hits(observations.size());  // (depth, point)
    inView.resize(points.size(), 0);
    for (std::uint32_t index = 0; index < points.size(); ++index) {
        auto at = projectToCamera(points[index].position, pose, images.intrinsics);
        if (!at) continue;
        int u = static_cast<int>(std::lround(at->x)), v = static_cast<int>(std::lround(at->y));
        if (u < 0 || v < 0 || u >= images.instances.cols || v >= images.instances.rows) continue;
        ++inView[index];
        auto it = slot.find(images.instances.at<std::uint16_t>(v, u));
        if (it == slot.end()) continue;
        hits[it->second].push_back({at->z, index});
    }
    for (std::size_t i = 0; i < observations.size(); ++i) {
        auto& h = hits[i];
        if (h.empty()) continue;
        std::sort(h.begin(), h.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        double median = h[h.size() / 2].first;
        double nearest = h[h.size() / 10].first;  // robust to a stray point in front
        double band = depthBand * median;
        for (const auto& [z, p] : h)
            if (z >= nearest - band && z <= nearest + band) observations[i].sparse.push_back(p);
    }
}

void keepConsistentSparsePoints(std::vector<ObjectTrack*>& tracks, const std::vector<SparsePoint>& points,
                                const std::vector<std::uint32_t>& inView, int minVotes, double minShare) {
    // votes[track][point]: frames where the point fell on that track's instance.
    std::vector<std::unordered_map<std::uint32_t, int>> votes(tracks.size());
    for (std::size_t t = 0; t < tracks.size(); ++t)
        for (const auto& v : tracks[t]->views)
            for (auto p : v.sparse) ++votes[t][p];
    for (std::size_t t = 0; t < tracks.size(); ++t)
        for (auto& v : tracks[t]->views)
            for (auto p : v.sparse) {
                int n = votes[t][p];
                if (n >= minVotes && n >= minShare * inView[p]) v.points.push_back(points[p].position);
            }
}

std::vector<model::Vec3> carveRegion(const HullRegion& region, const std::vector<Observation>& views,
                                     const std::vector<MaskView>& masks, double minShare, int grid) {
    std::unordered_map<std::uint32_t, const MaskView*> byFrame;
    for (const auto& m : masks) byFrame.emplace(m.frame, &m);
    // Each view's own silhouette: its mask value (a mask keeps one per instance, detections
    // number theirs per frame), or its box where the view keeps no mask.
    struct Silhouette {
        const MaskView* view;
        std::uint16_t instance;
        cv::Rect box;
        const cv::Mat1b* outline;
    };
    std::vector<Silhouette> silhouettes;
    for (const auto& v : views)
        if (auto it = byFrame.find(v.frame); it != byFrame.end())
            silhouettes.push_back({it->second, v.instance, v.bounds, &v.outline});
    // Neighbouring frames see much alike: tried in an order that spreads them (the golden-ratio
    // sequence), a voxel outside the hull misses a silhouette sooner.
    std::vector<std::pair<double, std::size_t>> order;
    for (std::size_t i = 0; i < silhouettes.size(); ++i)
        order.emplace_back(std::fmod(static_cast<double>(i) * 0.6180339887498949, 1.0), i);
    std::sort(order.begin(), order.end());
    std::vector<Silhouette> spread;
    for (const auto& entry : order) spread.push_back(silhouettes[entry.second]);
    const auto& [lo, hi] = region;
    std::vector<model::Vec3> hull;
    for (int i = 0; i < grid; ++i)
        for (int j = 0; j < grid; ++j)
            for (int k = 0; k < grid; ++k) {
                model::Vec3 p{lo.x + (i + 0.5) * (hi.x - lo.x) / grid, lo.y + (j + 0.5) * (hi.y - lo.y) / grid,
                              lo.z + (k + 0.5) * (hi.z - lo.z) / grid};
                int seen = 0, inside = 0, left = static_cast<int>(spread.size());
                for (const auto& [m, instance, box, outline] : spread) {
                    // Stop once even the views left, all inside, could not reach the share.
                    if (inside + left < minShare * (seen + left)) break;
                    --left;
                    auto at = projectToImage(p, m->pose, m->intrinsics);
                    if (!at) continue;
                    ++seen;
                    if (m->instances.empty()) {
                        // The detection's outline, or its box; the pixel `at` falls in, from the box's corner.
                        cv::Point pixel = pixelOf(*at) - box.tl();
                        bool inBox = pixel.x >= 0 && pixel.y >= 0 && pixel.x < box.width && pixel.y < box.height;
                        inside += inBox && (outline->empty() || (*outline)(pixel) != 0);
                    } else {
                        inside += m->instances.at<std::uint16_t>(pixelOf(*at)) == instance;
                    }
                }
                if (seen >= 2 && inside >= minShare * seen) hull.push_back(p);
            }
    return hull;
}

void carveVisualHulls(std::vector<ObjectTrack*>& tracks, const std::vector<MaskView>& masks, double minShare,
                      int grid) {
    std::unordered_map<std::uint32_t, const MaskView*> byFrame;
    for (const auto& m : masks) byFrame.emplace(m.frame, &m);
    for (ObjectTrack* track : tracks) {
        std::vector<model::Vec3> seed;
        for (const auto& v : track->views) seed.insert(seed.end(), v.points.begin(), v.points.end());
        if (seed.size() < 10 || track->views.empty()) continue;
        double lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
            std::vector<double> c;
            for (const auto& p : seed) c.push_back(a == 0 ? p.x : a == 1 ? p.y : p.z);
            std::sort(c.begin(), c.end());
            lo[a] = c[c.size() / 20];
            hi[a] = c[c.size() - 1 - c.size() / 20];
        }
        double grow = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
        for (int a = 0; a < 3; ++a) lo[a] -= grow / 2, hi[a] += grow / 2;
        const HullRegion region{{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}};
        auto hull = carveRegion(region, track->views, masks, minShare, grid);
        if (hull.size() < 10) continue;
        // Views of boxes the hull does not fill are of something else: carved again without them, once.
        auto unfilled = [&](const Observation& v) {
            auto m = byFrame.find(v.frame);
            return m != byFrame.end() && m->second->instances.empty() && !hullFillsBox(hull, v.bounds, *m->second);
        };
        if (std::any_of(track->views.begin(), track->views.end(), unfilled)) {
            std::vector<Observation> kept;
            for (auto& v : track->views)
                if (!unfilled(v)) kept.push_back(std::move(v));
            if (kept.size() < 2) continue;
            track->views = std::move(kept);
            hull = carveRegion(region, track->views, masks, minShare, grid);
            if (hull.size() < 10) continue;
        }
        track->surface = std::move(seed);
        track->carved = true;
        for (auto& v : track->views) v.points.clear();
        track->views.front().points = std::move(hull);
    }
}

bool hullFillsBox(const std::vector<model::Vec3>& hull, const cv::Rect& bounds, const MaskView& camera) {
    double x0 = 1e18, y0 = 1e18, x1 = -1e18, y1 = -1e18;
    for (const auto& p : hull)
        if (auto at = projectToCamera(p, camera.pose, camera.intrinsics))
            x0 = std::min(x0, at->x), y0 = std::min(y0, at->y), x1 = std::max(x1, at->x), y1 = std::max(y1, at->y);
    // Pixel centres to pixel edges.
    double across = std::min(x1 + 0.5, double(bounds.x + bounds.width)) - std::max(x0 + 0.5, double(bounds.x));
    double down = std::min(y1 + 0.5, double(bounds.y + bounds.height)) - std::max(y0 + 0.5, double(bounds.y));
    return across >= kMinFill * bounds.width && down >= kMinFill * bounds.height;
}

MaskView maskView(std::uint32_t frame, const cv::Mat& instances, const Intrinsics& K, const Pose& pose) {
    MaskView m;
    m.frame = frame;
    cv::resize(instances, m.instances, cv::Size(), 0.25, 0.25, cv::INTER_NEAREST);
    double sx = double(m.instances.cols) / instances.cols, sy = double(m.instances.rows) / instances.rows;
    m.intrinsics = {m.instances.cols, m.instances.rows,        K.fx * sx,
                    K.fy * sy,        (K.cx + 0.5) * sx - 0.5, (K.cy + 0.5) * sy - 0.5};
    m.pose = pose;
    return m;
}

std::string encodeCrop(const cv::Mat& color, const cv::Rect& bounds, int size) {
    int padX = bounds.width / 10, padY = bounds.height / 10;
    cv::Rect padded(bounds.x - padX, bounds.y - padY, bounds.width + 2 * padX, bounds.height + 2 * padY);
    padded &= cv::Rect(0, 0, color.cols, color.rows);
    cv::Mat crop = color(padded);
    double scale = double(size) / std::max(crop.cols, crop.rows);
    // At least a pixel a side: a view one pixel wide and tall would scale to nothing.
    auto scaled = [&](int side) { return std::max(1, static_cast<int>(std::lround(side * scale))); };
    if (scale < 1) cv::resize(crop, crop, cv::Size(scaled(crop.cols), scaled(crop.rows)), 0, 0, cv::INTER_AREA);
    return media::encodeJpeg(crop, 85);
}

void keepLargestEvidence(EvidenceCrop& evidence, const Observation& view, const cv::Mat& color, int size) {
    if (view.pixels > evidence.pixels) evidence = {view.pixels, view.frame, encodeCrop(color, view.bounds, size)};
}

}  // namespace smql::ingest
