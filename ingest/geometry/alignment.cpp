#include "ingest/geometry/alignment.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "ingest/geometry/floor_evidence.hpp"
#include "ingest/geometry/pcl_ops.hpp"
#include "ingest/geometry/robust.hpp"
#include "model/geometry.hpp"

namespace smql::ingest {

using detail::fromEigen;
using detail::rotationOf;
using detail::toEigen;

namespace {

using model::kDegree;
// Typical distance from a hand-held camera to the surfaces it sees indoors:
// turns metre thresholds into the units of a scale-free cloud before its scale is known.
constexpr double kTypicalViewingDistance = 2.5;
// Where no level surface is seen, the cameras' up is all there is besides the photos' vertical edges, and a
// person pitches a camera down at what they look at: the edges are looked for this many degrees around it
// (the dining photos pitch 16 degrees, TUM's desk video 39; the default cone, for a floor's normal, is 10).
constexpr double kFloorlessSearch = 40;

std::string fixed(double value, int digits = 2) {
    std::ostringstream out;
    out.setf(std::ios::fixed);
    out.precision(digits);
    out << value;
    return out.str();
}

// The smallest rotation taking unit vector `from` to unit vector `to` (Rodrigues). Written out because
// Eigen's Quaternion::FromTwoVectors drags in JacobiSVD, which costs ~10 s of compile time.
Eigen::Matrix3d rotationTaking(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
    Eigen::Vector3d axis = from.cross(to);
    double sine = axis.norm(), cosine = from.dot(to);
    if (sine < 1e-12) {
        if (cosine > 0) return Eigen::Matrix3d::Identity();
        // Opposite: half a turn about any axis perpendicular to `from`.
        Eigen::Vector3d other = std::abs(from.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
        Eigen::Vector3d k = from.cross(other).normalized();
        return 2 * k * k.transpose() - Eigen::Matrix3d::Identity();
    }
    Eigen::Vector3d k = axis / sine;
    Eigen::Matrix3d cross;
    cross << 0, -k.z(), k.y(), k.z(), 0, -k.x(), -k.y(), k.x(), 0;
    return Eigen::Matrix3d::Identity() + sine * cross + (1 - cosine) * cross * cross;
}

// Cloud units per metre, before the scale is known.
double unitEstimate(const PointCloud& world, const std::vector<Pose>& cameras, const AlignOptions& options,
                    std::vector<std::string>& notes) {
    if (options.scale) return 1.0 / *options.scale;
    if (options.metric) return 1.0;
    std::vector<double> distances;
    const std::size_t step = std::max<std::size_t>(1, world.size() / 20000);
    for (std::size_t i = 0; i < world.size(); i += step) {
        Eigen::Vector3d p = toEigen(world.points[i]);
        double best = std::numeric_limits<double>::max();
        if (world.frames[i] < cameras.size()) {
            best = (p - toEigen(cameras[world.frames[i]].translation)).norm();
        } else {
            for (const auto& camera : cameras) best = std::min(best, (p - toEigen(camera.translation)).norm());
        }
        if (best < std::numeric_limits<double>::max()) distances.push_back(best);
    }
    if (distances.empty()) {
        notes.push_back("scale-free capture without cameras: thresholds taken in cloud units");
        return 1.0;
    }
    double unit = detail::median(distances) / kTypicalViewingDistance;
    return unit > 0 ? unit : 1.0;
}

struct HorizontalPlane {
    Plane plane;
    double height = 0;  // -offset: the plane's height along its (up-pointing) normal
    double level = 0;   // median height of its inliers along a common reference normal: comparable between planes
    std::vector<std::size_t> inliers;
};

// Least-squares plane through the points (smallest principal axis), normal along `up`; its level is
// measured along `reference`.
HorizontalPlane fitHorizontal(const PointCloud& world, std::vector<std::size_t> inliers, const Eigen::Vector3d& up,
                              const Eigen::Vector3d& reference) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (auto i : inliers) mean += toEigen(world.points[i]);
    mean /= static_cast<double>(inliers.size());
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    for (auto i : inliers) {
        Eigen::Vector3d d = toEigen(world.points[i]) - mean;
        covariance += d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
    Eigen::Vector3d n = solver.eigenvectors().col(0).normalized();
    if (n.dot(up) < 0) n = -n;
    std::vector<double> heights, levels;
    for (auto i : inliers) {
        heights.push_back(n.dot(toEigen(world.points[i])));
        levels.push_back(reference.dot(toEigen(world.points[i])));
    }
    HorizontalPlane out;
    out.height = detail::median(std::move(heights));
    out.level = detail::median(std::move(levels));
    out.plane = {fromEigen(n), -out.height, inliers.size()};
    out.inliers = std::move(inliers);
    return out;
}

// Heading: the dominant direction, modulo 90 degrees, of the horizontal normals of flat vertical surfaces,
// in the levelled frame. Returns radians in [-pi/4, pi/4) or nullopt with too few votes.
std::optional<double> manhattanHeading(const PointCloud& world, const Eigen::Matrix3d& level, double unit,
                                       const AlignOptions& options, std::size_t& votes) {
    auto normals = pcl_ops::estimateNormals(world.points, options.normalRadius * unit, 5);
    const double maxVertical = std::sin(options.verticalSurfaceTolerance * kDegree);
    constexpr int kBins = 90;  // one degree each
    std::vector<double> histogram(kBins, 0.0);
    std::vector<double> angles;  // theta mod 90 deg, in [0, 90) degrees
    for (const auto& n : normals) {
        if (n.curvature > options.maxCurvature) continue;
        Eigen::Vector3d v = level * toEigen(n.normal);
        if (v.squaredNorm() < 0.5 || std::abs(v.z()) > maxVertical) continue;
        double degrees = std::atan2(v.y(), v.x()) / kDegree;
        degrees = std::fmod(std::fmod(degrees, 90.0) + 90.0, 90.0);
        angles.push_back(degrees);
        histogram[static_cast<int>(degrees) % kBins] += 1;
    }
    votes = angles.size();
    if (votes < options.minHeadingVotes) return std::nullopt;
    int peak = 0;
    double best = -1;
    for (int b = 0; b < kBins; ++b) {
        double smoothed = 0;
        for (int w = -2; w <= 2; ++w) smoothed += histogram[(b + w + kBins) % kBins] * (3 - std::abs(w));
        if (smoothed > best) best = smoothed, peak = b;
    }
    // Refine: circular mean (period 90 deg, so on 4 theta) of the votes within 5 degrees of the peak.
    double peakDegrees = peak + 0.5, sumCos = 0, sumSin = 0;
    for (double a : angles) {
        double gap = std::fmod(a - peakDegrees + 135.0, 90.0) - 45.0;
        if (std::abs(gap) > 5.0) continue;
        sumCos += std::cos(4 * a * kDegree);
        sumSin += std::sin(4 * a * kDegree);
    }
    double heading = std::atan2(sumSin, sumCos) / 4;  // (-45, 45] degrees
    if (heading >= std::numbers::pi / 4) heading -= std::numbers::pi / 2;
    return heading;
}

}  // namespace

double Plane::signedDistance(const model::Vec3& p) const {
    return normal.x * p.x + normal.y * p.y + normal.z * p.z + offset;
}

model::Vec3 Alignment::apply(const model::Vec3& p) const {
    const auto& m = transform;
    return {m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3], m[4] * p.x + m[5] * p.y + m[6] * p.z + m[7],
            m[8] * p.x + m[9] * p.y + m[10] * p.z + m[11]};
}

model::Vec3 Alignment::unapply(const model::Vec3& q) const {
    const auto& m = transform;
    const model::Vec3 d{q.x - m[3], q.y - m[7], q.z - m[11]};
    const double s2 = scale * scale;  // the rows of scale * R: R's transpose, over the scale once more
    return {(m[0] * d.x + m[4] * d.y + m[8] * d.z) / s2, (m[1] * d.x + m[5] * d.y + m[9] * d.z) / s2,
            (m[2] * d.x + m[6] * d.y + m[10] * d.z) / s2};
}

std::array<double, 9> Alignment::rotation() const {
    std::array<double, 9> r{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) r[i * 3 + j] = transform[i * 4 + j] / scale;
    return r;
}

namespace {

// Up prior: cameras are held roughly upright, and a camera's y axis points down.
Eigen::Vector3d upPrior(const std::vector<Pose>& cameras, const AlignOptions& options,
                        std::vector<std::string>& notes) {
    Eigen::Vector3d prior = Eigen::Vector3d::Zero();
    for (const auto& camera : cameras) prior -= rotationOf(camera).col(1);
    if (prior.norm() < 1e-9) {
        prior = options.upPrior ? toEigen(*options.upPrior) : Eigen::Vector3d::UnitZ();
        notes.push_back(cameras.empty() ? "up prior: no cameras, " + std::string(options.upPrior ? "given" : "+z")
                                        : "up prior: cameras disagree, +z");
    }
    return prior.normalized();
}

// Whether a plane tilted further from the up prior than `horizontalTolerance` may still be the
// floor or a table: it lies below every camera and the cameras look down at it. Cameras pitched
// down at a desk all tilt their up prior towards where they look, by as much as they pitch; walls
// in front of them face the way they look instead.
bool seenFromAbove(const HorizontalPlane& plane, const std::vector<Pose>& cameras, const AlignOptions& options) {
    if (cameras.empty()) return false;
    const Eigen::Vector3d n = toEigen(plane.plane.normal);
    std::vector<double> towards;
    for (const auto& camera : cameras) {
        if (n.dot(toEigen(camera.translation)) <= plane.height) return false;
        towards.push_back(rotationOf(camera).col(2).dot(n));
    }
    return detail::median(std::move(towards)) < -std::sin(options.lookDownPitch * kDegree);
}

// Horizontal planes by iterated RANSAC around the prior (within `steepTolerance`, of which those
// beyond `horizontalTolerance` only when seenFromAbove), each with its level along the strongest
// plane's normal (the prior may be tens of degrees off); planes at the same level become one (depth
// noise and small registration errors make a floor seen from several views a few centimetres
// thick). Lowest first.
std::vector<HorizontalPlane> horizontalPlanes(const PointCloud& world, const std::vector<Pose>& cameras,
                                              const Eigen::Vector3d& prior, double unit, const AlignOptions& options) {
    std::vector<std::size_t> remaining(world.size());
    for (std::size_t i = 0; i < remaining.size(); ++i) remaining[i] = i;
    const std::size_t minPlane =
        std::max(options.minPlanePoints, static_cast<std::size_t>(options.minPlaneShare * world.size()));
    pcl_ops::PlaneSearch search;
    search.axis = fromEigen(prior);
    search.constraint = pcl_ops::PlaneConstraint::NormalAlongAxis;
    search.epsAngle = (cameras.empty() ? options.horizontalTolerance : options.steepTolerance) * kDegree;
    search.distance = options.planeDistance * unit;
    std::vector<HorizontalPlane> extracted;
    // Planes passed over (walls, mostly) do not count against the limit, up to as many again.
    for (int k = 0; static_cast<int>(extracted.size()) < options.maxHorizontalPlanes &&
                    k < 2 * options.maxHorizontalPlanes && remaining.size() >= minPlane;
         ++k) {
        auto found = pcl_ops::segmentPlane(world.points, remaining, search);
        if (!found || found->inliers.size() < minPlane) break;
        std::vector<char> taken(world.size(), 0);
        for (auto i : found->inliers) taken[i] = 1;
        std::erase_if(remaining, [&](std::size_t i) { return taken[i] != 0; });
        HorizontalPlane plane = fitHorizontal(world, std::move(found->inliers), prior, prior);
        const double tilt = std::acos(std::clamp(toEigen(plane.plane.normal).dot(prior), -1.0, 1.0)) / kDegree;
        if (tilt <= options.horizontalTolerance || seenFromAbove(plane, cameras, options))
            extracted.push_back(std::move(plane));
    }
    Eigen::Vector3d reference = prior;
    std::size_t strongest = 0;
    for (const auto& p : extracted)
        if (p.inliers.size() > strongest) strongest = p.inliers.size(), reference = toEigen(p.plane.normal);
    for (auto& p : extracted) {
        std::vector<double> levels;
        for (auto i : p.inliers) levels.push_back(reference.dot(toEigen(world.points[i])));
        p.level = detail::median(std::move(levels));
    }
    std::sort(extracted.begin(), extracted.end(), [](const auto& a, const auto& b) { return a.level < b.level; });
    std::vector<HorizontalPlane> planes;
    for (auto& p : extracted) {
        if (!planes.empty() && p.level - planes.back().level <= options.sameLevel * unit &&
            toEigen(p.plane.normal).dot(toEigen(planes.back().plane.normal)) >=
                std::cos(options.sameLevelAngle * kDegree)) {
            auto merged = std::move(planes.back().inliers);
            merged.insert(merged.end(), p.inliers.begin(), p.inliers.end());
            planes.back() = fitHorizontal(world, std::move(merged), prior, reference);
        } else {
            planes.push_back(std::move(p));
        }
    }
    return planes;
}

std::vector<double> cameraHeights(const std::vector<Pose>& cameras, const Eigen::Vector3d& n) {
    std::vector<double> heights;
    for (const auto& camera : cameras) heights.push_back(n.dot(toEigen(camera.translation)));
    return heights;
}

struct FloorChoice {
    const HorizontalPlane* floor = nullptr;
    SurfaceEvidence floorEvidence;
    const HorizontalPlane* tableTop = nullptr;  // the lowest plane passed over as a table top
    SurfaceEvidence tableEvidence;
};

// Floor: the lowest large horizontal plane below every camera that is not a table top (what stands
// on it says so: floor_evidence.hpp); "large" among the planes that are not table tops, so that the
// floor seen in a few photos under a table that fills the others still counts.
FloorChoice findFloor(const std::vector<HorizontalPlane>& planes, const std::vector<Pose>& cameras,
                      const PointCloud& world, const std::vector<NamedThing>& things, double unit,
                      const AlignOptions& options) {
    const double clearance = options.cameraClearance * unit;
    const std::vector<model::Vec3> measured(
        world.points.begin(), world.points.begin() + static_cast<long>(std::min(options.evidencePoints, world.size())));
    FloorChoice out;
    std::vector<std::pair<const HorizontalPlane*, SurfaceEvidence>> candidates;
    for (const auto& p : planes) {
        auto heights = cameraHeights(cameras, toEigen(p.plane.normal));
        if (!heights.empty() && p.height >= *std::min_element(heights.begin(), heights.end()) - clearance) continue;
        SurfaceEvidence evidence = weighSurface({p.plane.normal, p.height}, things, measured, unit);
        if (!evidence.tableTop()) {
            candidates.emplace_back(&p, std::move(evidence));
        } else if (!out.tableTop || p.level < out.tableTop->level) {
            out.tableTop = &p;
            out.tableEvidence = std::move(evidence);
        }
    }
    // Floors lie below tables.
    if (out.tableTop) std::erase_if(candidates, [&](const auto& c) { return c.first->level >= out.tableTop->level; });
    std::size_t biggest = 0;
    for (const auto& [p, evidence] : candidates) biggest = std::max(biggest, p->plane.inliers);
    for (auto& [p, evidence] : candidates) {
        if (static_cast<double>(p->plane.inliers) < options.largePlaneShare * static_cast<double>(biggest)) continue;
        if (!out.floor || p->level < out.floor->level) {
            out.floor = p;
            out.floorEvidence = evidence;
        }
    }
    return out;
}

// The surface chosen (the floor, or the table top the floor is placed under) where the photos' vertical edges are
// measured against it: photos without depth that have edges. Else nothing.
const HorizontalPlane* edgedSurface(const FloorChoice& choice, const LinePlanes& lines, const AlignOptions& options) {
    if (options.metric || lines.normals.empty()) return nullptr;
    return choice.floor ? choice.floor : choice.tableTop;
}

// Up among the photos' vertical edges, looked for in their narrow cone (LineOptions::search) around the surface.
std::optional<Vertical> surfaceVertical(const FloorChoice& choice, const LinePlanes& lines,
                                        const AlignOptions& options) {
    const HorizontalPlane* surface = edgedSurface(choice, lines, options);
    return surface ? verticalFromLines(lines, surface->plane.normal, options.lines) : std::nullopt;
}

// A level surface of the room stands within the edges' narrow cone of their vertical (surfaceVertical). One of
// photos without depth that the edges find no up near, but find one in a wider cone of, leans from it and is not
// level: in one COLMAP run of two, the five dining photos' points gave a 107-point "floor" 35 deg from the cameras'
// up and 20.5 deg from the vertical of 112 edges in all five photos, and the room was stored 23 deg askew at 0.55
// times its size. Returns that vertical, for the level surfaces to be looked for around it.
std::optional<Vertical> leaningFromEdges(const FloorChoice& choice, const LinePlanes& lines,
                                         const AlignOptions& options) {
    const HorizontalPlane* surface = edgedSurface(choice, lines, options);
    if (!surface) return std::nullopt;
    LineOptions wide = options.lines;
    wide.search = kFloorlessSearch;
    return verticalFromLines(lines, surface->plane.normal, wide);
}

// Ceiling: the largest horizontal plane above every camera, parallel to the floor.
const HorizontalPlane* findCeiling(const std::vector<HorizontalPlane>& planes, const std::vector<Pose>& cameras,
                                   const Eigen::Vector3d& up, double clearance, const AlignOptions& options) {
    const HorizontalPlane* ceiling = nullptr;
    for (const auto& p : planes) {
        auto heights = cameraHeights(cameras, toEigen(p.plane.normal));
        double angle = std::acos(std::clamp(toEigen(p.plane.normal).dot(up), -1.0, 1.0));
        if (p.height > *std::max_element(heights.begin(), heights.end()) + clearance &&
            angle <= options.ceilingParallel * kDegree && (!ceiling || p.plane.inliers > ceiling->plane.inliers))
            ceiling = &p;
    }
    return ceiling;
}

// Where the floor is: the plane chosen; else, under a table top, a table's height below it (with no
// scale to give that height in the capture's units, as far below it as the cameras are above it,
// which the camera-height prior then reads as a table's height); else, along the photos' vertical edges
// where they agree on one (`lines`) or the cameras' up, a person's camera height under the cameras when
// the unit is known, or under the lowest points when it is not. Returns the floor's normal.
Eigen::Vector3d placeFloor(Alignment& out, const FloorChoice& choice, const PointCloud& world,
                           const Eigen::Vector3d& prior, const std::vector<Pose>& cameras, const LinePlanes& lines,
                           const AlignOptions& options) {
    auto& notes = out.notes;
    if (const HorizontalPlane* floor = choice.floor) {
        const Eigen::Vector3d up = toEigen(floor->plane.normal);
        out.floorHeight = floor->height;
        out.floorFound = true;
        out.floorInliers = floor->plane.inliers;
        notes.push_back("floor: plane with " + std::to_string(floor->plane.inliers) + " of " +
                        std::to_string(world.size()) + " points, " +
                        fixed(std::acos(std::clamp(up.dot(prior), -1.0, 1.0)) / kDegree, 1) +
                        " deg from the cameras' up; " + choice.floorEvidence.describe());
        if (choice.tableTop && choice.tableTop->level > floor->level)
            notes.push_back("floor: a table top above it passed over: " + choice.tableEvidence.describe());
        return up;
    }
    if (const HorizontalPlane* top = choice.tableTop) {
        const Eigen::Vector3d up = toEigen(top->plane.normal);
        const double tableHeight = *typicalHeight("table");  // the size table has a table's height
        double below = tableHeight;                          // metres, then capture units
        if (options.scale) {
            below /= *options.scale;
        } else if (!options.metric) {
            auto heights = cameraHeights(cameras, up);
            const double above = heights.empty() ? 0 : detail::median(heights) - top->height;
            below = above > 0 ? above * tableHeight / (options.cameraHeight - tableHeight) : 0;
        }
        out.floorHeight = top->height - below;
        out.floorNotSeen =
            "the lowest horizontal surface below the cameras is a table top: " + choice.tableEvidence.describe();
        out.floorPlaced = "a table's usual height (" + fixed(tableHeight) + " m) below the table top";
        notes.push_back("floor: not seen; " + out.floorNotSeen + "; the floor taken " + out.floorPlaced);
        return up;
    }
    Eigen::Vector3d up = prior;
    LineOptions floorless = options.lines;
    floorless.search = kFloorlessSearch;
    const auto vertical = verticalFromLines(lines, fromEigen(prior), floorless);
    if (vertical) {
        up = toEigen(vertical->up);
        notes.push_back(
            fmt::format("up: no level surface; {} vertical edges in {} of {} photos, {:.1f} deg from the cameras' up",
                        vertical->segments, vertical->photos, lines.photos, vertical->degreesFromNear));
    }
    const char* along = vertical ? "the photos' vertical edges" : "the cameras' up";
    std::vector<double> heights;
    for (const auto& p : world.points) heights.push_back(up.dot(toEigen(p)));
    out.floorNotSeen =
        fmt::format("no horizontal surface was found below the cameras among the {} points", world.size());
    const std::optional<double> metresPerUnit = options.metric ? std::optional(1.0) : options.scale;
    if (metresPerUnit && !cameras.empty()) {
        // With the unit known, the floor is a person's camera height under the cameras: the points a capture
        // without a level surface has under them are not the floor's. The five dining photos without their depth,
        // levelled by their edges, have a fifth of their points more than 1.47 m under the cameras (stray matches)
        // and a tenth more than 1.72, where the depth's floor is 1.40 m under them; their lowest 2 % lay 2.8-7.4 m
        // under.
        out.floorHeight = detail::median(cameraHeights(cameras, up)) - options.cameraHeight / *metresPerUnit;
        const auto lower = std::count_if(heights.begin(), heights.end(), [&](double h) { return h < out.floorHeight; });
        out.floorPlaced = fmt::format(
            "{:.2f} m under the cameras, as a person holds one, along {} ({:.0f}% of the points lie lower)",
            options.cameraHeight, along,
            heights.empty() ? 0.0 : 100.0 * static_cast<double>(lower) / static_cast<double>(heights.size()));
    } else {
        out.floorHeight = detail::quantile(heights, 0.02);
        out.floorPlaced = fmt::format("under the lowest 2% of the points, level with {}", along);
    }
    notes.push_back("floor: not measured; " + out.floorNotSeen + "; the floor taken " + out.floorPlaced);
    return up;
}

// A scale-free capture's up: the floor's (or table top's) normal, or its photos' vertical edges, which stand
// upright on it in a room (docs/ingest.md, "Up from the photos' lines"). How far apart the two stand goes in
// a note. A floor that holds a fifth of the points or more levels the room, and the angle is kept
// (Alignment::edgesFromFloor): a floor seen well stands upright to its edges unless the reconstruction is bent.
// ScanNet's lounge (58 %) and bathroom (29 %) were level within 0.8 degrees of the truth by their floors, 2.0
// and 2.2 by the edges. A smaller one is seen at the photos' edges, grazed, and its plane leans: TUM's office
// photos' (9-15 %) by 3.9-7.6 degrees from TUM's up, 7-Scenes' red kitchen's (7 %) by 2.5; the edges level
// those, and the floor's height is measured again along them. `vertical`: the edges' up near the surface
// (surfaceVertical), looked for once.
Eigen::Vector3d upByLines(Alignment& out, const FloorChoice& choice, const PointCloud& world, const Eigen::Vector3d& up,
                          const std::optional<Vertical>& vertical, const LinePlanes& lines,
                          const AlignOptions& options) {
    const HorizontalPlane* surface = edgedSurface(choice, lines, options);
    if (!surface) return up;
    const char* what = choice.floor ? "floor" : "table top";
    if (!vertical) {
        out.notes.push_back(
            fmt::format("up: the {}'s normal; the {} straight edges of {} photos agree on no "
                        "vertical within {:g} deg of it",
                        what, lines.normals.size(), lines.photos, options.lines.search));
        return up;
    }
    const std::string edges =
        fmt::format("{} vertical edges in {} of {} photos stand {:.1f} deg from the {}'s normal", vertical->segments,
                    vertical->photos, lines.photos, vertical->degreesFromNear, what);
    const double share = static_cast<double>(surface->inliers.size()) / static_cast<double>(world.size());
    if (share >= options.levellingShare) {
        out.edgesFromFloor = vertical->degreesFromNear;
        out.notes.push_back(
            fmt::format("up: the {}'s normal, which holds {:.0f}% of the points; {}", what, 100 * share, edges));
        return up;
    }
    const Eigen::Vector3d levelled = toEigen(vertical->up);
    std::vector<double> before, after;
    for (auto i : surface->inliers) {
        const Eigen::Vector3d p = toEigen(world.points[i]);
        before.push_back(up.dot(p));
        after.push_back(levelled.dot(p));
    }
    out.floorHeight += detail::median(std::move(after)) - detail::median(std::move(before));
    out.notes.push_back(
        fmt::format("up: levelled by the photos' edges: {}, which holds {:.0f}% of the points", edges, 100 * share));
    return levelled;
}

// Why a floor that a scale-free capture's scale rests on (`priors` measured) may not be the floor; empty when
// nothing says so. A desk that fills the photos, its floor unseen and nothing named under it, is a plane below
// the cameras like a floor: only what stands on it, or a second prior, tells them apart (TUM's desk video was
// stored 2.17x too large in one run of several). And no floor has much of the cloud under it: the photos'
// floors that were stored right had none (TUM's office photos, ScanNet's lounge: 0 %), where the planes taken
// for floors that were not had 5-8 % (TUM's ten desk photos) and 6-33 % (the dining photos), a chair rising
// from some of them.
std::string floorDoubt(const SurfaceEvidence& evidence, std::size_t priors) {
    if (priors == 1 && evidence.standing.empty())
        return "nothing that stands on floors rises from the lowest horizontal surface and no ceiling shows, so "
               "it may be a table top: " +
               evidence.describe();
    if (evidence.muchBelow())
        return "more of the points lie below the lowest horizontal surface than below any floor, so it may be a "
               "table top or a seat: " +
               evidence.describe();
    return {};
}

// Scale: as given, 1 for a metric capture, else the priors that apply (floor to ceiling, the
// cameras' height, the heights of named things above the floor, or above the table top the floor was placed
// under: `tableTop`, its height along `up`) combined. Returns how many priors were measured.
std::size_t chooseScale(Alignment& out, const AlignOptions& options, double unit, double ceilingAbove, bool floorFound,
                        std::optional<double> tableTop, const std::vector<Pose>& cameras, const Eigen::Vector3d& up,
                        const std::vector<NamedThing>& things) {
    auto& notes = out.notes;
    if (options.scale) {
        out.scale = *options.scale;
        notes.push_back("scale: " + fixed(out.scale, 4) + " as given");
        return 0;
    }
    if (options.metric) {
        out.scale = 1;
        notes.push_back(options.cameraHeightGiven ? "scale: 1 (metric capture: the cameras' height given, " +
                                                        fixed(options.cameraHeight) + " m, is not needed)"
                                                  : std::string("scale: 1 (metric capture)"));
        return 0;
    }
    std::vector<ScaleEstimate> estimates;
    if (ceilingAbove > 0)
        estimates.push_back(
            {"floor-to-ceiling taken as " + fixed(options.ceilingHeight) + " m", options.ceilingHeight / ceilingAbove});
    std::optional<ScaleEstimate> byCameras;
    if (!cameras.empty()) {
        std::vector<double> heights = cameraHeights(cameras, up);
        for (auto& h : heights) h -= out.floorHeight;
        double medianHeight = detail::median(heights);
        if (medianHeight > 0)
            byCameras =
                ScaleEstimate{fmt::format("median camera height {} as {} m",
                                          options.cameraHeightGiven ? "given" : "taken", fixed(options.cameraHeight)),
                              options.cameraHeight / medianHeight, options.cameraHeightGiven};
    }
    if (byCameras && !options.cameraHeightGiven) estimates.push_back(*byCameras);
    if (floorFound) {
        auto heights = scaleFromHeights(things, fromEigen(up), out.floorHeight, unit, options.thingsOnDepth);
        if (!heights) {
            out.scaleThingsLeftOut =
                heightsLeftOut(things, fromEigen(up), out.floorHeight, unit, options.thingsOnDepth);
        } else if (!heights->heldTogether) {
            notes.push_back("scale: " + heights->prior);
            out.scaleThingsApart = heights->things;
        } else {
            estimates.insert(heights->leads ? estimates.begin() : estimates.end(), *heights);
        }
    } else if (tableTop) {
        if (auto onTop = scaleFromHeightsOnTop(things, fromEigen(up), *tableTop, unit))
            estimates.insert(onTop->leads ? estimates.begin() : estimates.end(), *onTop);
    }
    // A height given is measured: it leads, the things' heights and the ceiling's only checking it.
    if (byCameras && options.cameraHeightGiven) estimates.insert(estimates.begin(), *byCameras);
    if (estimates.empty()) {
        notes.push_back("scale: no camera above the floor, no ceiling and no things of a typical height; left at 1");
        return 0;
    }
    ScaleChoice choice = combineScales(estimates);
    out.scale = choice.scale;
    out.scaleSpread = choice.spread;
    out.scaleSplit = choice.split;
    notes.push_back(choice.note);
    return estimates.size();
}

}  // namespace

Alignment alignCapture(const PointCloud& world, const std::vector<Pose>& cameras, const AlignOptions& options,
                       const std::vector<NamedThing>& things, const LinePlanes& lines) {
    Alignment out;
    auto& notes = out.notes;
    const Eigen::Vector3d prior = upPrior(cameras, options, notes);
    const double unit = unitEstimate(world, cameras, options, notes);
    std::vector<HorizontalPlane> planes = horizontalPlanes(world, cameras, prior, unit, options);
    const double clearance = options.cameraClearance * unit;

    FloorChoice choice = findFloor(planes, cameras, world, things, unit, options);
    std::optional<Vertical> vertical = surfaceVertical(choice, lines, options);
    std::optional<Vertical> leaning;  // the edges' vertical the first surface leaned from, when it did
    if (const auto edges = vertical ? std::nullopt : leaningFromEdges(choice, lines, options)) {
        leaning = edges;
        notes.push_back(fmt::format(
            "floor: the {} found leans {:.1f} deg from {} vertical edges in {} of {} photos; level surfaces looked "
            "for again within {:g} deg of their vertical",
            choice.floor ? "plane" : "table top", edges->degreesFromNear, edges->segments, edges->photos, lines.photos,
            options.lines.search));
        AlignOptions level = options;
        level.horizontalTolerance = level.steepTolerance = options.lines.search;
        planes = horizontalPlanes(world, cameras, toEigen(edges->up), unit, level);
        choice = findFloor(planes, cameras, world, things, unit, options);
        vertical = surfaceVertical(choice, lines, options);
    }
    const HorizontalPlane* floor = choice.floor;
    // The floor of that second look still leans from the edges it was looked for along when they find no up near
    // it either: the five dining photos' points gave a 116-point plane 9.2 deg from the vertical of 112 edges in
    // all five, and the room was stored 1.13 times its size with the cameras 27 cm too high.
    const std::string leansFromEdges =
        floor && leaning && !vertical
            ? fmt::format(
                  "the plane found on a second look, level surfaces sought along the vertical of {} edges "
                  "in {} of {} photos, still stands {:.1f} deg from it, where a room's floor is level with "
                  "its upright edges",
                  leaning->segments, leaning->photos, lines.photos,
                  std::acos(std::clamp(toEigen(floor->plane.normal).dot(toEigen(leaning->up)), -1.0, 1.0)) / kDegree)
            : std::string();
    const Eigen::Vector3d up = upByLines(
        out, choice, world, placeFloor(out, choice, world, prior, cameras, lines, options), vertical, lines, options);
    out.up = fromEigen(up);

    // The ceiling's height above the floor, measured along the floor's normal.
    const HorizontalPlane* ceiling =
        floor && !cameras.empty() ? findCeiling(planes, cameras, up, clearance, options) : nullptr;
    double ceilingAbove = 0;
    if (ceiling) {
        std::vector<double> heights;
        for (auto i : ceiling->inliers) heights.push_back(up.dot(toEigen(world.points[i])));
        ceilingAbove = detail::median(std::move(heights)) - out.floorHeight;
    }

    // Level: floor normal -> +z. Then heading about +z.
    Eigen::Matrix3d level = rotationTaking(up, Eigen::Vector3d::UnitZ());
    std::size_t votes = 0;
    auto heading = manhattanHeading(world, level, unit, options, votes);
    if (heading) {
        out.heading = -*heading;
        notes.push_back("heading: walls at " + fixed(*heading / kDegree, 1) + " deg (mod 90) from " +
                        std::to_string(votes) + " vertical-surface normals, turned to the x/y axes");
    } else {
        notes.push_back("heading: only " + std::to_string(votes) + " vertical-surface normals; left unchanged");
    }
    Eigen::Matrix3d turn;
    turn << std::cos(out.heading), -std::sin(out.heading), 0, std::sin(out.heading), std::cos(out.heading), 0, 0, 0, 1;
    Eigen::Matrix3d rotation = turn * level;

    // The table top the floor was placed under, measured along the up its placement ended with (the edges' where they
    // levelled the room, as the floor's height is).
    std::optional<double> tableTopAlong;
    if (!floor && choice.tableTop) {
        std::vector<double> heights;
        for (auto i : choice.tableTop->inliers) heights.push_back(up.dot(toEigen(world.points[i])));
        tableTopAlong = detail::median(std::move(heights));
    }
    const std::size_t priors = out.scalePriors = chooseScale(out, options, unit, ceiling ? ceilingAbove : 0,
                                                             floor != nullptr, tableTopAlong, cameras, up, things);
    if (floor && priors > 0) {
        out.floorUnconfirmed = leansFromEdges.empty() ? floorDoubt(choice.floorEvidence, priors) : leansFromEdges;
        if (!out.floorUnconfirmed.empty()) notes.push_back("floor: not confirmed; " + out.floorUnconfirmed);
    }
    if (tableTopAlong) out.tableTopHeight = out.scale * (*tableTopAlong - out.floorHeight);
    if (ceiling) {
        out.ceilingHeight = out.scale * ceilingAbove;
        notes.push_back("ceiling: plane with " + std::to_string(ceiling->plane.inliers) + " points, " +
                        fixed(*out.ceilingHeight) + " m above the floor");
    }

    Eigen::Matrix3d scaled = out.scale * rotation;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) out.transform[i * 4 + j] = scaled(i, j);
    out.transform[3] = 0;
    out.transform[7] = 0;
    out.transform[11] = -out.scale * out.floorHeight;  // (R p).z = up . p, the floor's height
    out.transform[12] = out.transform[13] = out.transform[14] = 0;
    out.transform[15] = 1;
    return out;
}

PointCloud transformed(const PointCloud& cloud, const Alignment& alignment) {
    PointCloud out = cloud;
    for (auto& p : out.points) p = alignment.apply(p);
    return out;
}

Pose transformed(const Pose& pose, const Alignment& alignment) {
    Pose out;
    Eigen::Matrix3d r = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(alignment.rotation().data());
    Eigen::Matrix<double, 3, 3, Eigen::RowMajor> rotated = r * rotationOf(pose);
    std::copy(rotated.data(), rotated.data() + 9, out.rotation.begin());
    out.translation = alignment.apply(pose.translation);
    return out;
}

}  // namespace smql::ingest
