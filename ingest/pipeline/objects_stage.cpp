#include "ingest/pipeline/objects_stage.hpp"
#include "ingest/capture/detections.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include <fmt/format.h>
#include <opencv2/core.hpp>

#include "ingest/geometry/clusters.hpp"
#include "ingest/geometry/robust.hpp"
#include "ingest/geometry/typical_sizes.hpp"
#include "ingest/pipeline/colors.hpp"
#include "ingest/pipeline/objects_from_clusters.hpp"
#include "ingest/pipeline/plausibility.hpp"
#include "ingest/pipeline/scene_nodes.hpp"
#include "model/category.hpp"
#include "model/embedding.hpp"
#include "model/geometry.hpp"
#include "relations/predicates.hpp"

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

// Turns the box by quarter turns so that its front (+x) points most nearly along `way`, swapping its sides with each
// quarter; none where `lengthwise` and that front would not run along its longer side. Whether it faces so now.
bool turnToFace(model::Box& box, const model::Vec3& way, bool lengthwise) {
    int best = 0;
    double most = -2;
    for (int k = 0; k < 4; ++k) {
        const double yaw = box.yaw + k * M_PI / 2;
        if (const double ahead = std::cos(yaw) * way.x + std::sin(yaw) * way.y; ahead > most) most = ahead, best = k;
    }
    const bool swapped = best % 2 == 1;
    const double length = swapped ? box.size.y : box.size.x, width = swapped ? box.size.x : box.size.y;
    if (lengthwise && length < width) return false;
    box.yaw = std::remainder(box.yaw + best * M_PI / 2, 2 * M_PI);
    if (swapped) std::swap(box.size.x, box.size.y);
    return true;
}

// A thing with a front (relations::hasFront: a sofa, a tv, a fridge, a bed) that stands against a wall (wallAgainst)
// faces away from it: the box's +x axis, its front, is turned to point into the room. A box's axes come from its
// points and say nothing of which side is its front; of the RGB-D memories' fronted things against a wall, ScanNet's
// apartment's fridge, oven and desk faced along their wall and a chair faced it. A bed's front is its foot, so a bed
// turns only where a short side is against the wall.
bool faceAwayFromWall(model::Box& box, const std::string& category, const std::vector<WallSegment>& walls) {
    const WallSegment* against = wallAgainst(box, walls);
    if (!against) return false;
    const double side = against->signedDistance(box.center) >= 0 ? 1.0 : -1.0;
    return turnToFace(box, {side * against->normal.x, side * against->normal.y, 0}, category == "bed");
}

// A chair within kAtTable of a table or a desk, and against no wall, stands at the nearest of them (tableAt): people
// sit at tables. Wider than FusionOptions::chairAtDesk (0.4 m), which names a desk by the chair pushed in at it:
// ScanNet's lounge's armchairs stand 0.3-0.5 m from their low table.
constexpr double kAtTable = 0.5;  // m, between the footprints
const model::Box* tableAt(const model::Box& box, const std::vector<const model::Box*>& tables) {
    const model::Box* nearest = nullptr;
    double gap = kAtTable;
    for (const model::Box* table : tables)
        if (const double g = model::horizontalGap(box, *table); g <= gap) gap = g, nearest = table;
    return nearest;
}

// A chair at a table faces its centre. Of the chairs at one in the RGB-D memories of ScanNet's apartment, lounge and
// bathroom, TUM fr1/rpy and the dining frames, 7 of 14 faced it by their boxes' axes.
bool faceTable(model::Box& box, const model::Box& table) {
    const double dx = table.center.x - box.center.x, dy = table.center.y - box.center.y;
    const double length = std::hypot(dx, dy);
    return length > 0 && turnToFace(box, {dx / length, dy / length, 0}, false);
}

// m: no chair is wider (ARKitScenes' 235 labelled chairs in ../shared/data/real-layouts: the widest 1.02 m).
constexpr double kWidestChair = 1.0;

// A chair's box that holds its back alone: shallower than any chair of its width (shallowestFootprint), at most half
// as deep as it is wide, and no wider than kWidestChair. That depth, or nullopt when the box is no such slab. The
// dining frames' wingback armchair, seen from behind, was a 0.74 x 0.36 m slab, 1.21 m tall: deeper than the
// shallowest chairs, yet half as deep as a chair so wide is.
std::optional<double> backAlone(const model::Box& box, std::string_view category) {
    const double thin = std::min(box.size.x, box.size.y), wide = std::max(box.size.x, box.size.y);
    const auto shallowest = shallowestFootprint(category, wide);
    if (!shallowest || wide > kWidestChair || 2 * thin > wide || thin >= *shallowest) return std::nullopt;
    return shallowest;
}

// The back's slab turned to face `yaw` and reaching `depth` deep ahead of the back, where the seat is.
void seatAhead(model::Box& box, double yaw, double depth) {
    const double thin = std::min(box.size.x, box.size.y), wide = std::max(box.size.x, box.size.y);
    box.yaw = yaw;
    box.size = {depth, wide, box.size.z};
    box.center.x += std::cos(yaw) * (depth - thin) / 2;
    box.center.y += std::sin(yaw) * (depth - thin) / 2;
}

// A chair pushed in at a table shows the cameras its back alone, its seat under the table's top: its box is a slab
// (backAlone). The dining frames' four chairs at the table were 0.11-0.19 m deep, their slabs' axes turned up to 30
// degrees from the table's. Such a chair stands square to the table's nearest side and faces it, its back along that
// side where it was seen, and reaches as deep as the shallowest chairs of its width towards the table. Whether it was
// one.
bool pushInAt(model::Box& box, std::string_view category, const model::Box& table) {
    const auto shallowest = backAlone(box, category);
    if (!shallowest) return false;
    // The chair's centre in the table's own axes: the side it stands beyond the most is the one it is at.
    const double c = std::cos(table.yaw), s = std::sin(table.yaw);
    const double ox = box.center.x - table.center.x, oy = box.center.y - table.center.y;
    const double u = c * ox + s * oy, v = -s * ox + c * oy;
    const bool endOn = std::abs(u) - table.size.x / 2 >= std::abs(v) - table.size.y / 2;
    // Towards the table: against the table's x axis beyond its +x end, and so on.
    const double sign = (endOn ? u : v) >= 0 ? -1.0 : 1.0;
    seatAhead(box, endOn ? std::atan2(sign * s, sign * c) : std::atan2(sign * c, -sign * s), *shallowest);
    return true;
}

// A chair at no table whose back alone was seen (backAlone) was seen from behind: a chair seen from before or
// from a side shows its seat. It faces away from the cameras that saw it (`seenFrom`, their mean centre), across its
// back, and reaches as deep as the shallowest chairs of its width ahead of it. The dining frames' slat-backed chair 1 m
// beyond the table's end, seen in three frames, was a 0.51 x 0.17 m slab facing the wall beside it. Whether it was one.
bool seatAwayFrom(model::Box& box, std::string_view category, const model::Vec3& seenFrom) {
    const auto shallowest = backAlone(box, category);
    if (!shallowest) return false;
    // Across the back: the box's thinner horizontal axis, turned to point away from the cameras.
    const double yaw = box.size.x <= box.size.y ? box.yaw : box.yaw + M_PI / 2;
    const double away = std::cos(yaw) * (box.center.x - seenFrom.x) + std::sin(yaw) * (box.center.y - seenFrom.y);
    seatAhead(box, std::remainder(away >= 0 ? yaw : yaw + M_PI, 2 * M_PI), *shallowest);
    return true;
}

}  // namespace

std::pair<std::size_t, std::size_t> seatChairs(std::vector<PlacedTrack>& placed,
                                               const std::vector<ObjectTrack>& tracks) {
    const auto kindOf = [&](const PlacedTrack& p, std::initializer_list<std::string_view> kinds) {
        return std::find(kinds.begin(), kinds.end(), tracks[p.track].category) != kinds.end();
    };
    std::vector<const model::Box*> tables;
    for (const auto& p : placed)
        if (kindOf(p, {"table", "desk"})) tables.push_back(&p.box);
    std::size_t pushedIn = 0, turned = 0;
    for (auto& p : placed) {
        if (p.againstWall || !kindOf(p, {"chair", "armchair", "office-chair"})) continue;
        const model::Box* table = tableAt(p.box, tables);
        if (!table) {
            turned += seatAwayFrom(p.box, tracks[p.track].category, p.seenFrom);
            continue;
        }
        p.pushedIn = pushInAt(p.box, tracks[p.track].category, *table);
        if (p.pushedIn)
            ++pushedIn;
        else
            faceTable(p.box, *table);
    }
    return {pushedIn, turned};
}

namespace {

// Nothing stands below the floor or above the ceiling: a hull carved from views that all look
// down at a thing reaches under the floor, and the floor and ceiling bound it (a little slack for
// the planes' own noise). So does a floor placed a table's height under a table top: no floor node is
// stored then, but the memory's heights are measured from it, and the desk whose top placed it reached
// 0.13 m under it in TUM's desk photos.
bool withinRoom(const model::Vec3& p, const Alignment& alignment) {
    constexpr double kSlack = 0.02;  // m
    if ((alignment.floorFound || alignment.tableTopHeight) && p.z < -kSlack) return false;
    return !alignment.ceilingHeight || p.z <= *alignment.ceilingHeight + kSlack;
}

// The pedestal's column: each band of kPedestalBand m from kPedestalFrom over the floor to kPedestalGap under the
// thing (a sink's bowl) holds kPedestalPoints points or more under its footprint, whose middle 80 % lie within
// kPedestalWidth of the thing's longer side along it and across it; kPedestalShare of the bands do. The walls' points
// are theirs (nonStructuralPoints). A vanity's front under a basin fills the footprint from side to side. ScanNet's
// apartment's pedestal sink: 0.27-0.41 m in the bands of its 0.70 m basin, 0.08-0.14 m in those of its 0.34 m one from
// every third frame; its bathroom's vanity from every third frame 0.40 m along a 0.51 m basin; its bathroom's towel
// stand under the towels' 0.34 m box, 0.01-0.15 m.
constexpr double kPedestalBand = 0.1, kPedestalFrom = 0.1, kPedestalGap = 0.05;
constexpr double kPedestalShare = 0.75, kPedestalWidth = 0.5;
// m: a sink's bowl is fitted short of its basin (the apartment's 0.67 m basin 0.34-0.47 m from every second and every
// third frame), so under a sink a column this wide is narrow whatever the bowl measured: the apartment's pedestal from
// every second frame, 0.24-0.30 m across in a band or two. A vanity's front is wider (the bathroom's 0.40 m). Under
// other things the thing's own size is the measure: books on a shelf no model named, 0.21 x 0.16 m.
constexpr double kBowlPedestal = 0.3;
constexpr std::size_t kPedestalPoints = 3;

}  // namespace

std::vector<std::size_t> pedestalUnder(const model::Box& top, const PointCloud& cloud,
                                       const std::vector<std::size_t>& roomPoints,
                                       const std::vector<model::Box>& others, double narrowest) {
    const double under = model::bottom(top) - kPedestalGap;
    const int bands = static_cast<int>(std::floor((under - kPedestalFrom) / kPedestalBand));
    if (bands < 2) return {};
    const double c = std::cos(top.yaw), s = std::sin(top.yaw);
    std::vector<std::size_t> points;
    std::vector<std::vector<double>> along(static_cast<std::size_t>(bands)), across(static_cast<std::size_t>(bands));
    for (const std::size_t i : roomPoints) {
        const model::Vec3& p = cloud.points[i];
        if (p.z < kPedestalFrom || p.z >= kPedestalFrom + bands * kPedestalBand) continue;
        if (!model::footprintContains(top, {p.x, p.y})) continue;
        if (std::any_of(others.begin(), others.end(), [&](const model::Box& other) {
                return model::footprintContains(other, {p.x, p.y}) && p.z >= model::bottom(other) &&
                       p.z <= model::top(other);
            }))
            continue;
        const double dx = p.x - top.center.x, dy = p.y - top.center.y;
        const auto band = static_cast<std::size_t>((p.z - kPedestalFrom) / kPedestalBand);
        along[band].push_back(c * dx + s * dy);
        across[band].push_back(-s * dx + c * dy);
        points.push_back(i);
    }
    const double narrow = std::max(kPedestalWidth * std::max(top.size.x, top.size.y), narrowest);
    const auto spread = [](const std::vector<double>& values) { return detail::quantileSpread(values, 0.1, 0.9); };
    int column = 0;
    for (std::size_t b = 0; b < along.size(); ++b)
        column += along[b].size() >= kPedestalPoints && spread(along[b]) <= narrow && spread(across[b]) <= narrow;
    if (column < kPedestalShare * bands) return {};
    return points;
}

Pedestals standOnPedestals(std::vector<PlacedTrack>& placed, const std::vector<ObjectTrack>& tracks,
                           const PointCloud& cloud, const std::vector<WallSegment>& walls) {
    Pedestals found;
    const std::vector<std::size_t> roomPoints = nonStructuralPoints(cloud, walls);
    for (auto& thing : placed) {
        const std::string& category = tracks[thing.track].category;
        const bool basin = role(category) == Role::Basin;
        if (!basin && relations::usualSupport(category) == relations::Support::Floor) continue;
        std::vector<model::Box> others;
        for (const auto& other : placed)
            if (&other != &thing) others.push_back(other.box);
        const std::vector<std::size_t> column =
            pedestalUnder(thing.box, cloud, roomPoints, others, basin ? kBowlPedestal : 0.0);
        if (column.empty()) continue;
        const double bottom = model::bottom(thing.box);
        if (basin) {
            const double top = model::top(thing.box);
            // No counter lies around a pedestal sink's bowl: its rim is its own edge, and the basin all its points,
            // square to the wall it stands against (its bowl is often fitted short of it and turned off it).
            if (const auto& points = tracks[thing.track].fused; !points.empty())
                thing.box = wallAlignedBox(points, FusionOptions{}.squareSlack);
            thing.box.center.z = top / 2, thing.box.size.z = top;
            ++found.sinks;
            continue;
        }
        Stand stand{thing.box, column};
        stand.box.center.z = bottom / 2, stand.box.size.z = bottom;
        found.stands.push_back(std::move(stand));
    }
    return found;
}

namespace {

// The centres of the cameras that saw a track, in the aligned frame.
std::vector<model::Vec3> camerasOf(const ObjectTrack& track, const Capture& capture, const Alignment& alignment) {
    std::vector<model::Vec3> cameras;
    for (const auto& v : track.views)
        if (const auto& pose = capture.frames[v.frame].pose) cameras.push_back(alignment.apply(pose->translation));
    return cameras;
}

// Their mean: where the track was seen from (the origin when no camera has a pose).
model::Vec3 meanOf(const std::vector<model::Vec3>& points) {
    model::Vec3 sum{0, 0, 0};
    for (const auto& p : points) sum = {sum.x + p.x, sum.y + p.y, sum.z + p.z};
    const double n = static_cast<double>(std::max<std::size_t>(points.size(), 1));
    return {sum.x / n, sum.y / n, sum.z / n};
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

// m a table's box may reach over the table top a floor was placed under: the top's own thickness and noise.
constexpr double kOverTableTop = 0.03;

// The height under which 95 % of a thing's surface points lie: its top, less the highest twentieth,
// which may be what stands on it.
double surfaceTop(const std::vector<model::Vec3>& surface) {
    std::vector<double> heights;
    for (const auto& p : surface) heights.push_back(p.z);
    const auto high = heights.begin() + static_cast<std::ptrdiff_t>(0.95 * (heights.size() - 1));
    std::nth_element(heights.begin(), high, heights.end());
    return *high;
}

// A thing widest at its top (a table, a desk, a counter) has its top where its own surfaces were seen
// most (the cloth, the fruit bowl, the papers): the cells its surface points fill in the band under
// `top`, and a cell around them, bound its footprint, in the frame of those cells' own rectangle (the
// hull's, which reaches past the thing along the views, was turned 25 degrees from a table's edges in one
// run). Views along a table cannot carve away the chairs at its sides; this does. Returns the hull's points
// within those bounds (all of them when the band holds too few cells to say).
std::vector<model::Vec3> underTop(std::vector<model::Vec3> hull, const std::vector<model::Vec3>& surface, double top) {
    constexpr double kBand = 0.15;  // m under the top
    constexpr double kCell = 0.05;  // m
    constexpr std::size_t kMinCells = 20;
    std::set<std::pair<long, long>> cells;
    for (const auto& p : surface)
        if (p.z <= top && p.z >= top - kBand)
            cells.insert({static_cast<long>(std::floor(p.x / kCell)), static_cast<long>(std::floor(p.y / kCell))});
    if (cells.size() < kMinCells) return hull;
    std::vector<model::Vec3> centres;
    for (const auto& [i, j] : cells) centres.push_back({(i + 0.5) * kCell, (j + 0.5) * kCell, top});
    const model::Box box = uprightBox(centres);
    const model::BoxFrame frame(box);
    double u0 = 1e18, u1 = -1e18, v0 = 1e18, v1 = -1e18;
    for (const auto& p : centres) {
        const model::Vec2 at = frame.local({p.x, p.y});
        u0 = std::min(u0, at.x), u1 = std::max(u1, at.x), v0 = std::min(v0, at.y), v1 = std::max(v1, at.y);
    }
    std::vector<model::Vec3> kept;
    for (const auto& p : hull) {
        const model::Vec2 at = frame.local({p.x, p.y});
        if (at.x >= u0 - kCell && at.x <= u1 + kCell && at.y >= v0 - kCell && at.y <= v1 + kCell) kept.push_back(p);
    }
    return kept.size() >= 3 ? kept : hull;
}

}  // namespace

// A hull carved without depth from a narrow range of directions stays long along the view. Along the
// views' mean direction it is held to where the thing's own surfaces were seen (its sparse points),
// widened at each end by half its width across the view: a thing reaches past what showed of it, not
// without bound. Its kind's usual size is never the answer (a 2.97 m table stays 2.97 m). Its top is
// held to its surfaces too (below), and so is the footprint of a thing `widestAtTop` (underTop).
// Returns the hull's points within those bounds (all of them when nothing says where to cut).
std::vector<model::Vec3> holdToSurface(const std::vector<model::Vec3>& hull, const std::vector<model::Vec3>& surface,
                                       const std::vector<model::Vec3>& cameras, bool widestAtTop,
                                       std::optional<double> tableTop) {
    if (hull.empty() || surface.empty() || cameras.empty()) return hull;
    model::Vec3 centre{0, 0, 0};
    for (const auto& p : hull) centre = {centre.x + p.x, centre.y + p.y, 0};
    centre = {centre.x / hull.size(), centre.y / hull.size(), 0};
    double dx = 0, dy = 0;
    for (const auto& c : cameras) {
        const double ex = centre.x - c.x, ey = centre.y - c.y, length = std::hypot(ex, ey);
        if (length > 1e-6) dx += ex / length, dy += ey / length;
    }
    const double length = std::hypot(dx, dy);
    if (length < 1e-6) return hull;
    dx /= length, dy /= length;
    auto along = [&](const model::Vec3& p) { return dx * p.x + dy * p.y; };
    auto across = [&](const model::Vec3& p) { return -dy * p.x + dx * p.y; };
    double a0 = 1e18, a1 = -1e18, w0 = 1e18, w1 = -1e18;
    for (const auto& p : surface) a0 = std::min(a0, along(p)), a1 = std::max(a1, along(p));
    for (const auto& p : hull) w0 = std::min(w0, across(p)), w1 = std::max(w1, across(p));
    const double reach = (w1 - w0) / 2;
    // Views that all look down carve nothing above a thing's top: the space over a table projects into
    // the table's outline in every one of them. Its top is held to where its surfaces were seen
    // (surfaceTop), raised by a tenth of its height.
    double high = surfaceTop(surface);
    double bottom = 1e18;
    for (const auto& p : hull) bottom = std::min(bottom, p.z);
    double top = high + 0.1 * std::max(0.0, high - bottom);
    // Where the floor was placed under a table top, a table whose hull reaches past that top has it for its
    // own: what its surfaces show above it (a monitor, a laptop) stands on it.
    if (widestAtTop && tableTop && bottom < *tableTop && *tableTop < high) {
        high = *tableTop;
        top = *tableTop + kOverTableTop;
    }
    std::vector<model::Vec3> kept;
    for (const auto& p : hull)
        if (along(p) >= a0 - reach && along(p) <= a1 + reach && p.z <= top) kept.push_back(p);
    if (kept.size() < 3) return hull;
    return widestAtTop ? underTop(std::move(kept), surface, high) : kept;
}

namespace {

// `box` grown in its own axes to take in `other`'s footprint and heights.
void takeIn(model::Box& box, const model::Box& other) {
    const double bottom = std::min(model::bottom(box), model::bottom(other));
    const double top = std::max(model::top(box), model::top(other));
    model::takeInFootprint(box, other);
    box.center.z = (bottom + top) / 2;
    box.size.z = top - bottom;
}

}  // namespace

std::size_t mergeStoredTwice(std::vector<PlacedTrack>& placed, std::vector<ObjectTrack>& tracks) {
    std::stable_sort(placed.begin(), placed.end(), [](const PlacedTrack& a, const PlacedTrack& b) {
        return model::volume(a.box) > model::volume(b.box);
    });
    std::size_t merged = 0;
    for (std::size_t small = placed.size(); small-- > 0;) {
        ObjectTrack& smaller = tracks[placed[small].track];
        const bool unnamed = smaller.category == model::kUnnamedCategory;
        if (!(smaller.carved || placed[small].pushedIn || unnamed) || isOpening(smaller.category)) continue;
        for (std::size_t large = 0; large < small; ++large) {
            ObjectTrack& larger = tracks[placed[large].track];
            const bool alike = placed[small].pushedIn ? placed[large].pushedIn : smaller.carved && larger.carved;
            const bool sameKind = alike && kindName(larger.category) == kindName(smaller.category);
            const bool holdsSink =
                unnamed && role(larger.category) == Role::Basin && model::bottom(placed[large].box) <= kStandingReach;
            if (!(sameKind || holdsSink) || !storedTwice(placed[small].box, placed[large].box)) continue;
            if (placed[small].pushedIn) takeIn(placed[large].box, placed[small].box);
            larger.views.insert(larger.views.end(), std::make_move_iterator(smaller.views.begin()),
                                std::make_move_iterator(smaller.views.end()));
            if (!placed[small].colors.empty()) placed[large].colors.push_back(placed[small].colors);
            placed.erase(placed.begin() + static_cast<std::ptrdiff_t>(small));
            ++merged;
            break;
        }
    }
    std::sort(placed.begin(), placed.end(),
              [](const PlacedTrack& a, const PlacedTrack& b) { return a.track < b.track; });
    return merged;
}

namespace {

// What a note says of a name its box does not fit (nameFit), the name kept as detected_as.
std::string misnamedNote(NameFit fit, const std::string& category, const model::Box& box) {
    const std::string stored = fmt::format("stored as 'object' with detected_as = {}", category);
    switch (fit) {
        case NameFit::TooLarge:
            return fmt::format("a {:.2f} m thing was detected as '{}', which is never that large: {}",
                               std::max({box.size.x, box.size.y, box.size.z}), category, stored);
        case NameFit::TooDeep:
            return fmt::format(
                "a {:.2f} x {:.2f} m footprint was detected as '{}', which is never deeper than "
                "{:.2f} m: {}",
                box.size.x, box.size.y, category, deepestFootprint(category).value_or(0), stored);
        case NameFit::TooSmall:
        case NameFit::TooSlender:
            return fmt::format("a {:.2f} x {:.2f} x {:.2f} m thing was detected as '{}', which is never that {}: {}",
                               box.size.x, box.size.y, box.size.z, category,
                               fit == NameFit::TooSmall ? "small" : "slender", stored);
        case NameFit::TooTall: {
            const auto usual = typicalHeight(category);
            return fmt::format("a {:.2f} m tall thing was detected as '{}', which stands {} {:.2f} m: {}", box.size.z,
                               category, usual ? "about" : "at most",
                               usual ? *usual : tallestHeight(category).value_or(0), stored);
        }
        case NameFit::TooLow:
            return fmt::format(
                "a thing detected as '{}' has its top {:.2f} m over the floor, where things of the kind "
                "reach {:.2f} m or more: {}",
                category, model::top(box), lowestTop(category).value_or(0), stored);
        case NameFit::Fits:
            break;
    }
    return {};
}

// With depth, a thing of a kind that always stands on the floor (those with a typical height: a fridge, a
// bed, a chair, a table) whose box hangs in the air with nothing under it is something else a detector gave
// that name: ScanNet's bathroom had a 13 cm deep shelf 0.78 m up on the wall stored as a "fridge". Kinds that
// also hang or stand on counters (cabinets, shelves, ovens) are left to the plausibility warning.
void renameFloating(model::SceneData& scene, StageProgress& progress) {
    std::vector<const model::Node*> things;
    for (const auto& n : scene.nodes)
        if (n.kind == NodeKind::Object && n.geometry == GeometryKind::Box) things.push_back(&n);
    std::vector<model::Node*> floating;
    for (auto& n : scene.nodes)
        if (n.kind == NodeKind::Object && typicalHeight(n.category) && floatsOverNothing(n, things))
            floating.push_back(&n);
    for (model::Node* n : floating) {
        progress.note(
            fmt::format("a {:.2f} x {:.2f} x {:.2f} m thing detected as '{}' hangs {:.2f} m above the floor "
                        "with nothing under it, where things of the kind stand on the floor: stored as "
                        "'object' with detected_as = {}",
                        n->box.size.x, n->box.size.y, n->box.size.z, n->category, model::bottom(n->box), n->category));
        n->attributes.push_back({"detected_as", n->category});
        std::sort(n->attributes.begin(), n->attributes.end(),
                  [](const auto& a, const auto& b) { return a.name < b.name; });
        n->category = model::kUnnamedCategory;
        n->confidence *= 0.5f;
    }
}

// The stands standOnPedestals found, as tables no model named (as a cluster under a sink is its cabinet).
void addStands(const std::vector<Stand>& stands, const PointCloud& cloud, const Capture& capture,
               model::SceneData& scene, StageProgress& progress) {
    for (const Stand& stand : stands) addUnnamedThing(scene, "table", stand.box, cloud, stand.points, capture);
    if (!stands.empty())
        progress.note(
            fmt::format("objects: {} thing(s) held up by a column no model named: the column stored as a "
                        "'table' from the floor up to the thing",
                        stands.size()));
}

}  // namespace

std::vector<TrackedNode> ObjectsStage::run(StageProgress& progress) {
    std::vector<TrackedNode> made;
    const std::size_t steps = this->steps();
    tracks = finder.fuse(std::move(tracks), aligned, walls, progress);
    // Each track's points and box first, then its node: hulls carved without depth are judged against each other
    // before any is stored.
    std::vector<PlacedTrack> placed;
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
        const std::vector<model::Vec3> cameras = camerasOf(track, capture, aligned.alignment);
        if (track.carved) {
            std::vector<model::Vec3> surface;
            for (const auto& p : track.surface) surface.push_back(aligned.alignment.apply(p));
            PointCloud held;
            const bool widestAtTop = holdsThings(category) && !hasUprightEnds(category);
            for (const auto& p :
                 holdToSurface(cloud.points, surface, cameras, widestAtTop, aligned.alignment.tableTopHeight))
                held.push(p, {0, 0, 0}, 0);
            cloud = std::move(held);
        }
        model::Box box = track.fusedBox ? *track.fusedBox : uprightBox(cloud.points);
        if (opening && !walls.empty()) setInWall(box, cloud, walls);
        const bool againstWall = !opening && relations::hasFront(category) && faceAwayFromWall(box, category, walls);
        placed.push_back({t, std::move(colors), box, againstWall, false, meanOf(cameras)});
    }
    // Depth and a floor found: heights of things measured from the floor the views showed.
    const bool measuredFloor = framesHaveDepth(capture) && aligned.alignment.floorFound;
    const Pedestals pedestals = measuredFloor ? standOnPedestals(placed, tracks, aligned.cloud, walls) : Pedestals{};
    if (pedestals.sinks)
        progress.note(fmt::format("objects: {} sink(s) on a pedestal: from the floor up to the bowl", pedestals.sinks));
    const auto [pushedIn, turned] = seatChairs(placed, tracks);
    if (pushedIn)
        progress.note(
            fmt::format("objects: {} chair(s) at a table seen by their backs alone: square to it, reaching "
                        "under it as deep as the shallowest chairs of their width",
                        pushedIn));
    if (turned)
        progress.note(
            fmt::format("objects: {} chair(s) at no table seen by their backs alone: facing away from the "
                        "cameras, as deep as the shallowest chairs of their width",
                        turned));
    if (const std::size_t merged = mergeStoredTwice(placed, tracks))
        progress.note(
            fmt::format("objects: {} thing(s) stored twice, merged into the one they lie mostly inside (hulls "
                        "without depth or chairs pushed in, of one kind; what holds a sink on its pedestal)",
                        merged));

    for (auto& [t, colors, box, againstWall, pushedIn, seenFrom] : placed) {
        auto& track = tracks[t];
        const auto& category = track.category;
        const bool opening = isOpening(category);
        // A name far too small for its box (a detector's 1.8 m "cake") or too large for it (a 16 cm slab of a
        // "bed"), or, for a hull whose top was held to its surfaces, of a kind that stands far lower than the hull
        // (a counter's hull named "table"), is kept only as a guess, as is one fusion did not keep (a toilet in a
        // kitchen; a suitcase among seats, a low table).
        const BoxMeasure measure = !track.carved           ? BoxMeasure::Depth
                                   : track.surface.empty() ? BoxMeasure::HullFromBoxes
                                                           : BoxMeasure::HullHeldToSurface;
        const NameFit fit = opening ? NameFit::Fits : nameFit(category, box, measure);
        const bool misnamed = fit != NameFit::Fits;
        const std::string detectedAs = misnamed ? category : track.detectedAs;
        const std::string stored = misnamed ? std::string(model::kUnnamedCategory) : category;
        if (misnamed)
            progress.note(misnamedNote(fit, category, box));
        else if (!detectedAs.empty())
            progress.note(fmt::format("a thing detected as '{}' {}: stored as '{}' with detected_as = {}", detectedAs,
                                      track.renamedWhy, stored, detectedAs));
        model::Node& node = addNode(scene, opening ? NodeKind::Anchor : NodeKind::Object, stored,
                                    opening ? GeometryKind::Plane : GeometryKind::Box, box);
        if (!detectedAs.empty()) node.attributes.push_back({"detected_as", detectedAs});
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
        node.confidence =
            static_cast<float>(std::min(1.0, 0.5 + 0.1 * track.views.size()) * (detectedAs.empty() ? 1.0 : 0.5));
        std::sort(node.attributes.begin(), node.attributes.end(),
                  [](const auto& a, const auto& b) { return a.name < b.name; });
        if (!track.evidence.jpeg.empty())
            scene.blobs.push_back({node.id,
                                   fmt::format("evidence-frame{}.jpg", capture.frames[track.evidence.frame].index),
                                   "image/jpeg", std::move(track.evidence.jpeg)});
        if (auto embedding = meanEmbedding(track.views); !embedding.empty())
            scene.blobs.push_back(model::embeddingBlob(node.id, embedding));
        made.push_back({node.id, std::move(track.views), !track.fused.empty()});
    }
    addStands(pedestals.stands, aligned.cloud, capture, scene, progress);
    finder.addStructureObjects(aligned, walls, scene, progress);
    if (measuredFloor) renameFloating(scene, progress);
    return made;
}

std::string ObjectsStage::summary(const std::vector<TrackedNode>&) const {
    auto count = std::count_if(scene.nodes.begin(), scene.nodes.end(),
                               [](const model::Node& n) { return n.kind == NodeKind::Object; });
    return fmt::format("{} objects", count);
}

}  // namespace smql::ingest
