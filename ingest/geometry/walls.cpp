#include "ingest/geometry/walls.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <Eigen/Core>

#include "ingest/geometry/pcl_ops.hpp"
#include "ingest/geometry/robust.hpp"
#include "model/geometry.hpp"

namespace smql::ingest {

namespace {

using model::kDegree;

struct Candidate {
    Eigen::Vector2d normal;
    double offset = 0;
    std::vector<std::size_t> inliers;
};

double alongOf(const Eigen::Vector2d& normal, const model::Vec3& p) { return -normal.y() * p.x + normal.x() * p.y; }

double offsetOf(const Eigen::Vector2d& normal, const PointCloud& cloud, const std::vector<std::size_t>& inliers) {
    std::vector<double> offsets;
    offsets.reserve(inliers.size());
    for (auto i : inliers) offsets.push_back(-(normal.x() * cloud.points[i].x + normal.y() * cloud.points[i].y));
    return detail::median(std::move(offsets));
}

// Least-squares vertical plane through the inliers: the smallest principal axis of their footprint.
void refit(Candidate& c, const PointCloud& cloud) {
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (auto i : c.inliers) mean += Eigen::Vector2d(cloud.points[i].x, cloud.points[i].y);
    mean /= static_cast<double>(c.inliers.size());
    Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
    for (auto i : c.inliers) {
        Eigen::Vector2d d = Eigen::Vector2d(cloud.points[i].x, cloud.points[i].y) - mean;
        covariance += d * d.transpose();
    }
    // The footprint's principal axis is at angle theta; the normal is perpendicular to it.
    double theta = 0.5 * std::atan2(2 * covariance(0, 1), covariance(0, 0) - covariance(1, 1));
    Eigen::Vector2d n(-std::sin(theta), std::cos(theta));
    if (n.dot(c.normal) < 0) n = -n;
    c.normal = n;
    c.offset = offsetOf(n, cloud, c.inliers);
}

std::pair<double, double> alongSpan(const Candidate& c, const PointCloud& cloud) {
    std::vector<double> along;
    along.reserve(c.inliers.size());
    for (auto i : c.inliers) along.push_back(alongOf(c.normal, cloud.points[i]));
    return detail::robustRange(std::move(along));
}

// Splits a plane's inliers where they leave a gap wider than maxGap along the plane.
std::vector<Candidate> splitAtGaps(const Candidate& plane, const PointCloud& cloud, double maxGap) {
    std::vector<std::pair<double, std::size_t>> order;
    order.reserve(plane.inliers.size());
    for (auto i : plane.inliers) order.emplace_back(alongOf(plane.normal, cloud.points[i]), i);
    std::sort(order.begin(), order.end());
    std::vector<Candidate> runs;
    for (std::size_t k = 0; k < order.size(); ++k) {
        if (k == 0 || order[k].first - order[k - 1].first > maxGap) runs.push_back({plane.normal, plane.offset, {}});
        runs.back().inliers.push_back(order[k].second);
    }
    return runs;
}

}  // namespace

model::Box WallSegment::box() const {
    model::Vec3 d = direction();
    double a = (along0 + along1) / 2;
    model::Box b;
    b.center = {-offset * normal.x + a * d.x, -offset * normal.y + a * d.y, (z0 + z1) / 2};
    b.size = {along1 - along0, thickness, z1 - z0};
    b.yaw = std::atan2(d.y, d.x);
    return b;
}

const WallSegment* wallAgainst(const model::Box& box, const std::vector<WallSegment>& walls, double within,
                               bool longSide) {
    const WallSegment* nearest = nullptr;
    double least = within;
    for (const auto& wall : walls) {
        const model::Vec3 d = wall.direction();
        const double wallYaw = std::atan2(d.y, d.x);
        if (std::abs(std::remainder(box.yaw - wallYaw, M_PI / 2)) > kSquareToWall * model::kDegree) continue;
        // Which of the box's axes runs along the wall: its x within 45 degrees of the wall's direction, or its y.
        const bool xAlong = std::abs(std::remainder(box.yaw - wallYaw, M_PI)) < M_PI / 4;
        const double along = xAlong ? box.size.x : box.size.y, across = xAlong ? box.size.y : box.size.x;
        const double t = d.x * box.center.x + d.y * box.center.y;
        if ((longSide && along < across) || t < wall.along0 || t > wall.along1) continue;
        const double gap = std::abs(std::abs(wall.signedDistance(box.center)) - across / 2);
        if (gap <= least) least = gap, nearest = &wall;
    }
    return nearest;
}

namespace {

// Iterated RANSAC: take the strongest vertical plane, remove its inliers, repeat; each plane split
// where its points leave a gap.
std::vector<Candidate> verticalPlanes(const PointCloud& aligned, const std::vector<std::size_t>& above,
                                      const WallOptions& options) {
    std::vector<Candidate> candidates;
    std::vector<std::size_t> remaining = above;
    pcl_ops::PlaneSearch search;
    search.axis = {0, 0, 1};
    search.constraint = pcl_ops::PlaneConstraint::NormalAcrossAxis;
    search.epsAngle = options.verticalTolerance * kDegree;
    search.distance = options.distance;
    std::vector<char> taken(aligned.size(), 0);
    for (int k = 0; k < options.maxPlanes && remaining.size() >= options.minInliers; ++k) {
        auto found = pcl_ops::segmentPlane(aligned.points, remaining, search);
        if (!found || found->inliers.size() < options.minInliers) break;
        for (auto i : found->inliers) taken[i] = 1;
        std::erase_if(remaining, [&](std::size_t i) { return taken[i] != 0; });
        Eigen::Vector2d n(found->normal.x, found->normal.y);
        if (n.norm() < 1e-6) continue;
        Candidate plane{n.normalized(), 0, std::move(found->inliers)};
        plane.offset = offsetOf(plane.normal, aligned, plane.inliers);
        for (auto& run : splitAtGaps(plane, aligned, options.maxGap))
            if (run.inliers.size() >= options.minInliers / 4) candidates.push_back(std::move(run));
    }
    return candidates;
}

// Point the normals into the room: towards most cameras, else towards most of the cloud.
void faceIntoRoom(std::vector<Candidate>& candidates, const PointCloud& aligned, const std::vector<std::size_t>& above,
                  const std::vector<model::Vec3>& cameras, const WallOptions& options) {
    for (auto& c : candidates) {
        std::size_t front = 0, back = 0;
        for (const auto& p : cameras) {
            double s = c.normal.x() * p.x + c.normal.y() * p.y + c.offset;
            if (s > 0)
                ++front;
            else if (s < 0)
                ++back;
        }
        if (front != back) {
            if (back > front) c.normal = -c.normal, c.offset = -c.offset;
            continue;
        }
        for (auto i : above) {
            double s = c.normal.x() * aligned.points[i].x + c.normal.y() * aligned.points[i].y + c.offset;
            if (s > options.distance)
                ++front;
            else if (s < -options.distance)
                ++back;
        }
        if (back > front) c.normal = -c.normal, c.offset = -c.offset;
    }
}

// Merge near-duplicates: parallel, same side, close offsets, touching extents.
void mergeDuplicates(std::vector<Candidate>& candidates, const PointCloud& aligned, const WallOptions& options) {
    const double mergeCos = std::cos(options.mergeAngle * kDegree);
    for (bool merged = true; merged;) {
        merged = false;
        for (std::size_t i = 0; i < candidates.size() && !merged; ++i) {
            for (std::size_t j = i + 1; j < candidates.size() && !merged; ++j) {
                auto& a = candidates[i];
                auto& b = candidates[j];
                if (a.normal.dot(b.normal) < mergeCos || std::abs(a.offset - b.offset) > options.mergeOffset) continue;
                auto [a0, a1] = alongSpan(a, aligned);
                auto [b0, b1] = alongSpan(b, aligned);
                if (std::max(a0, b0) - std::min(a1, b1) > options.maxGap) continue;
                if (b.inliers.size() > a.inliers.size()) std::swap(a, b);  // keep the stronger one's orientation
                a.inliers.insert(a.inliers.end(), b.inliers.begin(), b.inliers.end());
                refit(a, aligned);
                candidates.erase(candidates.begin() + static_cast<std::ptrdiff_t>(j));
                merged = true;
            }
        }
    }
}

// The segment a candidate plane makes: its extent, thickness and the frames that saw it.
WallSegment segmentOf(const Candidate& c, const PointCloud& aligned, const WallOptions& options) {
    WallSegment wall;
    wall.normal = {c.normal.x(), c.normal.y(), 0};
    wall.offset = c.offset;
    wall.inliers = c.inliers.size();
    std::tie(wall.along0, wall.along1) = alongSpan(c, aligned);
    std::vector<double> heights, residuals;
    std::map<std::uint32_t, std::size_t> perFrame;
    for (auto i : c.inliers) {
        heights.push_back(aligned.points[i].z);
        residuals.push_back(std::abs(wall.signedDistance(aligned.points[i])));
        ++perFrame[aligned.frames[i]];
    }
    std::tie(wall.z0, wall.z1) = detail::robustRange(std::move(heights));
    wall.thickness = std::max(0.02, 2 * detail::quantile(std::move(residuals), 0.9));
    const double frameFloor = std::max(3.0, options.frameShare * static_cast<double>(c.inliers.size()));
    for (const auto& [frame, count] : perFrame)
        if (static_cast<double>(count) >= frameFloor) ++wall.frames;
    return wall;
}

// A wall is a surface, not a few lines: its inliers fill much of its extent. A vertical plane through
// a strip of ceiling and the fronts of some furniture spans the room's height but leaves most cells
// of its extent empty.
bool coversItsExtent(const WallSegment& wall, const Candidate& c, const PointCloud& aligned,
                     const WallOptions& options) {
    const double cell = options.coverageCell;
    auto columns = static_cast<std::size_t>(std::ceil(wall.length() / cell));
    auto rows = static_cast<std::size_t>(std::ceil((wall.z1 - wall.z0) / cell));
    std::vector<char> filled(std::max<std::size_t>(1, columns * rows), 0);
    for (auto i : c.inliers) {
        const auto& p = aligned.points[i];
        double a = alongOf(c.normal, p);
        if (a < wall.along0 || a > wall.along1 || p.z < wall.z0 || p.z > wall.z1) continue;
        auto col = std::min(columns - 1, static_cast<std::size_t>((a - wall.along0) / cell));
        auto row = std::min(rows - 1, static_cast<std::size_t>((p.z - wall.z0) / cell));
        filled[row * columns + col] = 1;
    }
    double coverage = static_cast<double>(std::count(filled.begin(), filled.end(), 1)) / filled.size();
    return coverage >= options.minCoverage;
}

// Walls bound the room: few points lie behind them (doorways and windows let some through). A
// free-standing cabinet has the far wall behind it. Judged against the room in front, and against
// the segment's own surface: a tall shelf's face has a busy room in front of it, but a whole wall's
// worth of points behind.
bool boundsTheRoom(const WallSegment& wall, const Candidate& c, const PointCloud& aligned,
                   const std::vector<std::size_t>& above, const WallOptions& options) {
    std::size_t front = 0, behind = 0;
    for (auto i : above) {
        const auto& p = aligned.points[i];
        double a = alongOf(c.normal, p);
        if (a < wall.along0 || a > wall.along1 || p.z < wall.z0 || p.z > wall.z1) continue;
        double s = wall.signedDistance(p);
        if (s > options.behindDistance)
            ++front;
        else if (s < -options.behindDistance)
            ++behind;
    }
    if (front + behind > 0 &&
        static_cast<double>(behind) > options.maxBehindShare * static_cast<double>(front + behind))
        return false;
    return static_cast<double>(behind) <= options.maxBehindOfSurface * static_cast<double>(wall.inliers);
}

// How much of `front`'s length lies within `wall`'s extent at a signed distance from `wall`'s plane (into the
// room) between `nearest` and `farthest`: distances are measured along the length of `front`, which may turn
// from `wall` a little.
double lengthAhead(const WallSegment& front, const WallSegment& wall, double nearest, double farthest) {
    // `front`'s line p(t) = base + t * direction, t from along0 to along1; on it, `wall`'s signed distance and
    // its position along `wall` are linear in t.
    const model::Vec3 base{-front.offset * front.normal.x, -front.offset * front.normal.y, 0};
    const model::Vec3 dir = front.direction();
    const Eigen::Vector2d wallNormal{wall.normal.x, wall.normal.y};
    double lo = front.along0, hi = front.along1;
    // Keeps the t where a + b * t lies in [low, high].
    auto clip = [&](double a, double b, double low, double high) {
        if (std::abs(b) < 1e-12) {
            if (a < low || a > high) hi = lo;
            return;
        }
        double t0 = (low - a) / b, t1 = (high - a) / b;
        if (t0 > t1) std::swap(t0, t1);
        lo = std::max(lo, t0), hi = std::min(hi, t1);
    };
    clip(alongOf(wallNormal, base), alongOf(wallNormal, dir), wall.along0, wall.along1);
    clip(wall.signedDistance(base), wall.normal.x * dir.x + wall.normal.y * dir.y, nearest, farthest);
    return std::max(0.0, hi - lo);
}

// Furniture standing against a wall (a cabinet front, a sideboard) makes a plane just inside it: parallel,
// or turned a little where the fronts of several things in a row make it (ScanNet's bathroom: its vanity's,
// toilet's and bathtub's fronts and the shower curtain made a 3.3 m plane 12 degrees from the wall behind
// them, which cut the toilet and the vanity to slivers). Of two segments within layerAngle of each other, one
// that lies in front of the other (by mergeOffset to layerDistance) for more than half the shorter one's
// length is not the wall; one that lies on the other (within mergeOffset) for as much is the same wall seen
// twice, and the weaker goes. Strongest first.
std::vector<WallSegment> outermost(const std::vector<WallSegment>& walls, const WallOptions& options) {
    const double layerCos = std::cos(options.layerAngle * kDegree);
    std::vector<char> inner(walls.size(), 0);
    for (std::size_t i = 0; i < walls.size(); ++i) {
        for (std::size_t j = 0; j < walls.size(); ++j) {
            const auto& a = walls[i];
            const auto& b = walls[j];
            if (i == j || a.normal.x * b.normal.x + a.normal.y * b.normal.y < layerCos) continue;
            const double half = 0.5 * std::min(a.length(), b.length());
            const bool weaker = a.inliers < b.inliers || (a.inliers == b.inliers && i > j);
            if (lengthAhead(a, b, options.mergeOffset, options.layerDistance) > half ||
                (weaker && lengthAhead(a, b, -options.mergeOffset, options.mergeOffset) > half))
                inner[i] = 1;
        }
    }
    std::vector<WallSegment> outer;
    for (std::size_t i = 0; i < walls.size(); ++i)
        if (!inner[i]) outer.push_back(walls[i]);
    std::sort(outer.begin(), outer.end(), [](const auto& a, const auto& b) { return a.inliers > b.inliers; });
    return outer;
}

}  // namespace

std::vector<WallSegment> findWalls(const PointCloud& aligned, const std::vector<model::Vec3>& cameras,
                                   const WallOptions& options) {
    std::vector<std::size_t> above;
    for (std::size_t i = 0; i < aligned.size(); ++i)
        if (aligned.points[i].z > options.minPointHeight) above.push_back(i);
    const std::size_t views = std::set<std::uint32_t>(aligned.frames.begin(), aligned.frames.end()).size();
    const std::size_t minFrames = std::min(options.minFrames, std::max<std::size_t>(views, 1));

    std::vector<Candidate> candidates = verticalPlanes(aligned, above, options);
    faceIntoRoom(candidates, aligned, above, cameras, options);
    mergeDuplicates(candidates, aligned, options);

    std::vector<WallSegment> walls;
    for (const auto& c : candidates) {
        if (c.inliers.size() < options.minInliers) continue;
        WallSegment wall = segmentOf(c, aligned, options);
        if (wall.frames < minFrames || wall.z1 - wall.z0 < options.minHeight || wall.length() < options.minLength)
            continue;
        if (!coversItsExtent(wall, c, aligned, options) || !boundsTheRoom(wall, c, aligned, above, options)) continue;
        double support = std::min(1.0, static_cast<double>(wall.inliers) / (4.0 * options.minInliers));
        double seen = std::min(1.0, static_cast<double>(wall.frames) / 3.0);
        wall.confidence = 0.5 * support + 0.5 * seen;
        walls.push_back(wall);
    }
    return outermost(walls, options);
}

std::vector<std::size_t> nonStructuralPoints(const PointCloud& aligned, const std::vector<WallSegment>& walls,
                                             const StructureOptions& options) {
    std::vector<std::size_t> kept;
    for (std::size_t i = 0; i < aligned.size(); ++i) {
        const auto& p = aligned.points[i];
        if (p.z < options.floorMargin) continue;
        if (options.ceilingHeight && p.z > *options.ceilingHeight - options.ceilingMargin) continue;
        bool onWall = false;
        for (const auto& wall : walls) {
            double a = wall.direction().x * p.x + wall.direction().y * p.y;
            const double margin = std::max(options.wallMargin, wall.surfaceBand());
            if (std::abs(wall.signedDistance(p)) <= margin && a >= wall.along0 - margin && a <= wall.along1 + margin) {
                onWall = true;
                break;
            }
        }
        if (!onWall) kept.push_back(i);
    }
    return kept;
}

}  // namespace smql::ingest
