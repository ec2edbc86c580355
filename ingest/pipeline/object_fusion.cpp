#include "ingest/pipeline/object_fusion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>

#include <fmt/format.h>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "ingest/capture/detections.hpp"
#include "ingest/geometry/clusters.hpp"
#include "ingest/geometry/instance_map.hpp"
#include "ingest/geometry/typical_sizes.hpp"
#include "ingest/pipeline/plausibility.hpp"
#include "model/category.hpp"
#include "model/geometry.hpp"
#include "relations/predicates.hpp"

namespace smql::ingest {

using relations::Support;
using relations::usualSupport;

namespace {

// A thing the instance map found: one or more of its instances (several when two were one thing
// stored twice), their points, the box fitted to them, their names' tally and the name chosen.
struct Thing {
    std::vector<const Instance*> instances;
    PointCloud points;
    model::Box box;
    std::map<std::string, double> tally;
    std::string category;
    std::optional<SeenTop> top;  // what a thing that holds things shows of its top, before it reaches the floor
};

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

// How many of the cameras held the points in view: at least half of up to 16 of them project into
// the image, between 0.2 m and kMaxDepthReading in front (occlusion aside: an upper bound).
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

// Whether a name suits a box: its largest side at least kNameFitLow x the largest side things of that kind
// commonly have, and the name fits the box as the objects stage judges it (plausibility.hpp: nameFit, the box
// neither far larger than things of the name nor smaller than any of them); kinds the table lacks suit any box.
constexpr double kNameFitLow = 0.25;
bool nameSuits(const std::string& category, const model::Box& box) {
    auto usual = typicalExtent(category);
    const double largest = std::max({box.size.x, box.size.y, box.size.z});
    return !usual || (largest >= kNameFitLow * *usual && nameFit(category, box) == NameFit::Fits);
}

// A thing's name: of the names its views gave that suit its box, the one with the largest tally (a
// bed a detector called "suitcase" in more views is still a bed); when none suits, the largest
// tally, which the objects stage keeps only as detected_as.
std::string nameOf(const std::map<std::string, double>& tally, const model::Box& box) {
    std::string best, anyBest;
    double bestVotes = -1, anyVotes = -1;
    for (const auto& [label, votes] : tally) {
        if (nameSuits(label, box) && votes > bestVotes) best = label, bestVotes = votes;
        if (votes > anyVotes) anyBest = label, anyVotes = votes;
    }
    return best.empty() ? anyBest : best;
}

// A thing's box: square to the walls when that costs at most FusionOptions::wallSlack more footprint
// (clusters.hpp: wallAlignedBox), else the minimum-area upright box.
model::Box boxOf(const PointCloud& points, const FusionOptions& options) {
    return wallAlignedBox(points.points, options.wallSlack);
}

void fit(Thing& thing, const FusionOptions& options) {
    thing.box = boxOf(thing.points, options);
    thing.category = nameOf(thing.tally, thing.box);
    // A kind that stands square to the walls takes their frame at more cost (a fridge between cabinets whose points
    // hold a piece of them).
    if (standsSquare(thing.category)) thing.box = wallAlignedBox(thing.points.points, options.squareSlack);
}

// The instances that are things: enough of their points agree (cells seen by two views, when it has
// three or more), and enough of the frames that held them in view saw them (a detector's one-off
// guess is no thing). Counts the guesses dropped.
std::vector<Thing> thingsOf(const InstanceMap& map, const std::vector<FusionCamera>& cameras,
                            const FusionOptions& options, std::size_t& guesses) {
    std::vector<Thing> out;
    for (const Instance& instance : map.instances()) {
        PointCloud points = instance.points(instance.sources.size() >= 3 ? 2 : 1);
        if (points.size() < 3) continue;
        const auto inView = static_cast<double>(framesInView(points, cameras));
        const int needed =
            std::clamp(static_cast<int>(std::ceil(options.minViewShare * inView)), 1, options.viewsEnough);
        if (static_cast<int>(instance.frames.size()) < needed) {
            ++guesses;
            continue;
        }
        Thing thing{{&instance}, std::move(points), {}, instance.tally(), {}, {}};
        fit(thing, options);
        out.push_back(std::move(thing));
    }
    return out;
}

// How many frames saw a thing: its instances' frames, each counted once.
std::size_t framesSeen(const Thing& thing) {
    std::vector<std::uint32_t> frames;
    for (const Instance* instance : thing.instances)
        frames.insert(frames.end(), instance->frames.begin(), instance->frames.end());
    std::sort(frames.begin(), frames.end());
    return static_cast<std::size_t>(std::unique(frames.begin(), frames.end()) - frames.begin());
}

// The whole with the part's instances and points added (its box and name are the caller's to fit).
Thing withPart(const Thing& whole, const Thing& part) {
    Thing both = whole;
    both.instances.insert(both.instances.end(), part.instances.begin(), part.instances.end());
    append(both.points, part.points);
    return both;
}

// The height of the top a thing that holds things shows (seenTop covering topCover of its footprint or more).
std::optional<double> topShown(const Thing& thing, const FusionOptions& options) {
    if (!holdsThings(thing.category) || hasUprightEnds(thing.category)) return std::nullopt;
    const SeenTop top = seenTop(thing.points.points, thing.box, options);
    return top.cover >= options.topCover ? std::optional(top.height) : std::nullopt;
}

// Pieces the map kept apart (pieceOf) merged, the smaller into the larger, when together they still suit the
// name their votes give (a glimpse's few votes barely count against the larger's). Returns how many were merged.
std::size_t mergePieces(std::vector<Thing>& things, const FusionOptions& options) {
    std::size_t merged = 0;
    for (bool changed = true; changed;) {
        changed = false;
        std::stable_sort(things.begin(), things.end(),
                         [](const Thing& a, const Thing& b) { return model::volume(a.box) > model::volume(b.box); });
        std::vector<SeenBox> seen;
        for (const auto& thing : things)
            seen.push_back({thing.box, thing.category, framesSeen(thing), topShown(thing, options)});
        for (std::size_t large = 0; large < things.size() && !changed; ++large)
            for (std::size_t small = large + 1; small < things.size(); ++small) {
                Thing& a = things[small];
                Thing& b = things[large];
                // Only a piece inside the larger's box can be a glimpse: the points are compared for those alone.
                const double touching = model::fractionInside(a.box, b.box) >= options.glimpseInside
                                            ? shareOfPointsNear(a.points, b.points, options.touchReach)
                                            : 0.0;
                if (!pieceOf(seen[small], seen[large], touching, options)) continue;
                Thing both = withPart(b, a);
                for (const auto& [label, votes] : a.tally) both.tally[label] += votes;
                fit(both, options);
                if (!nameSuits(both.category, both.box)) continue;
                b = std::move(both);
                things.erase(things.begin() + static_cast<std::ptrdiff_t>(small));
                ++merged;
                changed = true;
                break;
            }
    }
    return merged;
}

// A seat seen without its back: a thing of a seat's kind without upright ends in the kinds table (a chair), its top
// lower than FusionOptions::seatShare of its kind's usual height.
bool backlessSeat(const Thing& thing, const FusionOptions& options) {
    const auto usual = typicalHeight(thing.category);
    return role(thing.category) == Role::Seat && !hasUprightEnds(thing.category) && usual &&
           model::top(thing.box) < options.seatShare * *usual;
}

// A thing lying flatter than FusionOptions::minHeight (its kind made so: thinnestSide) on the top of one of `backs`,
// the boxes of seats that reach their backs (not backlessSeat), its centre over the seat: the back's edge, not a
// thing. A remote or a book left on a seat lies on its cushion, under its box's top. ScanNet's lounge: the top of an
// armchair's back, 0.74 m up, called a remote in three frames.
bool onSeatsBack(const model::Box& box, const std::vector<model::Box>& backs, const FusionOptions& options) {
    return box.size.z < options.minHeight && std::any_of(backs.begin(), backs.end(), [&](const model::Box& seat) {
               return std::abs(model::bottom(box) - model::top(seat)) <= options.restingGap &&
                      model::footprintContains(seat, {box.center.x, box.center.y}, 0);
           });
}

// Upright ends stored as things of their own joined to their bed or sofa: its box then reaches the
// headboard's top and the wall; and a chair's back, stored as a chair beside its seat, joined to the seat. The
// whole keeps its name and its votes. Returns how many were joined.
std::size_t joinUprightEnds(std::vector<Thing>& things, const FusionOptions& options) {
    std::size_t joined = 0;
    for (std::size_t w = 0; w < things.size(); ++w) {
        const bool seat = backlessSeat(things[w], options);
        if (!hasUprightEnds(things[w].category) && !seat) continue;
        for (std::size_t p = 0; p < things.size(); ++p) {
            // A thing named as one that holds others (a table, a counter) is a surface, not an upright end: the
            // counter behind a sofa. A chair's back rises to a chair's height: a seat as low as the seat is a
            // second seat (two stools side by side).
            if (p == w || hasUprightEnds(things[p].category) || holdsThings(things[p].category) ||
                (seat && backlessSeat(things[p], options)) || !uprightEndOf(things[p].box, things[w].box, options))
                continue;
            Thing both = withPart(things[w], things[p]);
            both.box = boxOf(both.points, options);
            if (!nameSuits(both.category, both.box)) continue;
            things[w] = std::move(both);
            things.erase(things.begin() + static_cast<std::ptrdiff_t>(p));
            if (p < w) --w;
            p = static_cast<std::size_t>(-1);  // the grown whole may reach another end: look again
            ++joined;
        }
    }
    return joined;
}

// Slivers: smaller than minLargest, or thinner than things of their kind are (typical_sizes.hpp: thinnestSide; a 6
// cm thin "table" is a table's edge), or flatter than minHeight unless their kind is made flatter (a remote lying
// on a table is 1.5 cm tall).
bool sliver(const Thing& thing, const FusionOptions& options) {
    const model::Box& box = thing.box;
    const double thinnest = std::min({box.size.x, box.size.y, box.size.z});
    const auto made = thinnestSide(thing.category);
    return box.size.z < (madeFlat(thing.category) ? std::min(options.minHeight, *made) : options.minHeight) ||
           std::max({box.size.x, box.size.y, box.size.z}) < options.minLargest || (made && thinnest < *made);
}

// A thing of a kind that stands on floors (a table, a chair, a bed) whose legs or base the views did
// not see (chairs in front, the table's own top): its bottom hangs in the air, below
// FusionOptions::groundReach or with its top no higher than such things' usual top
// (FusionOptions::topReach of it), and no other thing's top lies under its middle to carry it. It
// stands on the floor: its box reaches down to it. Returns whether the box was extended.
bool standOnFloor(SeenBox& thing, const std::vector<SeenBox>& all, const FusionOptions& options) {
    model::Box& box = thing.box;
    const double bottom = box.center.z - box.size.z / 2, top = box.center.z + box.size.z / 2;
    if (usualSupport(thing.category) != Support::Floor || bottom <= 0) return false;
    const auto usualTop = typicalHeight(thing.category);
    if (bottom > options.groundReach && !(usualTop && top <= options.topReach * *usualTop)) return false;
    for (const auto& other : all) {
        const model::Box& b = other.box;
        if (&other == &thing) continue;
        const double otherTop = b.center.z + b.size.z / 2;
        const bool under = model::footprintContains(b, {box.center.x, box.center.y});
        if (under && otherTop <= bottom + options.restingGap && otherTop > 0) return false;
    }
    box.center.z = top / 2;
    box.size.z = top;
    return true;
}

// Whether the lowest thing's bottom lies within FusionOptions::restingGap of z = 0: a floor the views did not show
// (placed a table's height below the lowest top, alignment.hpp: floorPlaced) that what stands lowest reaches down to
// is where things stand, and those whose legs were hidden reach down to it as to a floor seen.
bool lowestReachesFloor(const std::vector<SeenBox>& things, const FusionOptions& options) {
    if (things.empty()) return false;
    double lowest = 1e18;
    for (const auto& thing : things) lowest = std::min(lowest, thing.box.center.z - thing.box.size.z / 2);
    return std::abs(lowest) <= options.restingGap;
}

// Whether a table's box (a kind that holds things on a top, not a bed or sofa) holds the height of the table top
// a floor the views did not show was placed under (alignment.hpp: tableTopHeight): that floor was placed
// on the reading that this table stands on it, so what stands on floors stands there, as on a floor seen.
bool tableStandsOnPlacedFloor(const std::vector<SeenBox>& things, std::optional<double> tableTopHeight,
                              const FusionOptions& options) {
    if (!tableTopHeight) return false;
    return std::any_of(things.begin(), things.end(), [&](const SeenBox& thing) {
        return holdsThings(thing.category) && !hasUprightEnds(thing.category) &&
               model::bottom(thing.box) <= *tableTopHeight &&
               model::top(thing.box) >= *tableTopHeight - options.restingGap;
    });
}

}  // namespace

// Whether `part` is the upright end of `whole` (a bed's headboard, a sofa's back, named "tv" or "suitcase" by a
// detector that has no name for it): no deeper than FusionOptions::partDepth, standing at one of the whole's
// ends (its centre within partReach outside the footprint, or partDepth inside it, along one axis, and inside
// it along the other), as wide as partWidth of that end or more and at most a reach wider, parallel to it, its
// bottom no higher than the whole's top and its top above it.
bool uprightEndOf(const model::Box& p, const model::Box& w, const FusionOptions& options) {
    const double partBottom = p.center.z - p.size.z / 2, partTop = p.center.z + p.size.z / 2;
    const double wholeTop = w.center.z + w.size.z / 2;
    if (partBottom > wholeTop || partTop <= wholeTop) return false;
    const model::Vec2 at = model::BoxFrame(w).local({p.center.x, p.center.y});
    const double local[2] = {at.x, at.y};
    const double half[2] = {w.size.x / 2, w.size.y / 2};
    // The part's sides along the whole's axes (its yaw within 20 degrees of them, either way round).
    const double turn = std::remainder(p.yaw - w.yaw, M_PI);
    if (std::abs(std::remainder(turn, M_PI / 2)) > 20 * model::kDegree) return false;
    const bool swapped = std::abs(turn) > M_PI / 4;
    const double side[2] = {swapped ? p.size.y : p.size.x, swapped ? p.size.x : p.size.y};
    for (int along = 0; along < 2; ++along) {
        const int across = 1 - along;
        const double beyond = std::abs(local[along]) - half[along];
        if (side[along] > options.partDepth || beyond > options.partReach || beyond < -options.partDepth) continue;
        if (std::abs(local[across]) > half[across]) continue;
        const double end = 2 * half[across];
        if (side[across] >= options.partWidth * end && side[across] <= end + 2 * options.partReach) return true;
    }
    return false;
}

// A sink whose views took in the cabinet it is set in (its box reaching down to the floor, twice a basin's depth):
// the points within basinDepth of its top stay the sink, those under them become a thing of their own, which
// namedByUse names the sink's cabinet. Returns how many were parted.
std::size_t partBasins(std::vector<Thing>& things, const FusionOptions& options) {
    std::size_t parted = 0;
    const std::size_t count = things.size();
    for (std::size_t b = 0; b < count; ++b) {
        Thing& sink = things[b];
        if (role(sink.category) != Role::Basin || model::bottom(sink.box) > kStandingReach ||
            sink.box.size.z < 2 * options.basinDepth)
            continue;
        // Its box ends at its rim or counter (lowerToTop); what its views took in above that is no part of either.
        const double top = model::top(sink.box), cut = top - options.basinDepth;
        PointCloud basin, under;
        for (std::size_t i = 0; i < sink.points.size(); ++i) {
            const double z = sink.points.points[i].z;
            if (z > top) continue;
            (z >= cut ? basin : under).push(sink.points.points[i], sink.points.colors[i], sink.points.frames[i]);
        }
        if (basin.size() < 3 || under.size() < 3) continue;
        // The cabinet keeps the sink's footprint and turn (its points are mostly its front), up to the cut.
        Thing cabinet{sink.instances, std::move(under), sink.box, {}, "cabinet", {}};
        cabinet.box.size.z = cut - model::bottom(sink.box);
        cabinet.box.center.z = model::bottom(sink.box) + cabinet.box.size.z / 2;
        sink.points = std::move(basin);
        sink.box = boxOf(sink.points, options);
        things.push_back(std::move(cabinet));
        ++parted;
    }
    return parted;
}

// Whether `small` is a piece of `large` the map kept apart, judged by their boxes:
// - stored twice: one name (or two of one kind: a desk and a table, typical_sizes.hpp: kindName), a good share
//   of the smaller's box inside the larger's (a corner sofa's two arms, a sofa seen whole from afar and in parts
//   close up, their cells never close enough);
// - one place named twice: each box mostly inside the other (a side table seen as a "bed" in three frames and
//   as a "table" in two); for two kinds that stand on floors, each footprint mostly inside the other, since their
//   boxes reach down to the floor only later (ScanNet's apartment from every third frame: its bed named "sofa" in
//   12 frames, and "bed" in 5 whose box held its mattress and headboard alone, was stored twice), where one of
//   them was seen in two frames or more (two one-frame glimpses on a floor make no thing seen twice);
// - a glimpse: the smaller mostly inside the larger, most of its points touching the larger's, and seen in a
//   small share of the frames that saw the larger (a sofa's corner called "bed" in two frames of the forty that
//   saw the sofa); an ottoman standing free inside an L-shaped sofa's box touches none of it. Nothing is a
//   glimpse of a kind that holds things (a table, a bed: the chair tucked under a table, its back's top seen
//   over the table's edge, is a chair), and things that stand on tops are never glimpses, they are what the
//   larger carries;
// - its top: a thin thing of the same name lying on the larger's top, over its footprint (a table's top seen
//   a little high in one frame).
bool pieceOf(const SeenBox& small, const SeenBox& large, double touching, const FusionOptions& options) {
    const model::Box &a = small.box, &b = large.box;
    const bool sameName = kindName(small.category) == kindName(large.category);
    const double inside = model::fractionInside(a, b);
    const bool twoTops = small.top && large.top && std::abs(*small.top - *large.top) > options.oneTopSpread;
    if (sameName && inside >= options.storedTwiceShare && !twoTops) return true;
    if (inside >= options.namedTwiceShare && model::fractionInside(b, a) >= options.namedTwiceShare) return true;
    if (usualSupport(small.category) == Support::Floor && usualSupport(large.category) == Support::Floor &&
        model::verticalOverlap(a, b) > 0 && std::max(small.frames, large.frames) >= 2) {
        const double shared = model::footprintOverlap(a, b);
        if (shared >= options.namedTwiceShare * model::footprintArea(a) &&
            shared >= options.namedTwiceShare * model::footprintArea(b))
            return true;
    }
    if (inside >= options.glimpseInside && touching >= options.glimpseTouching && !holdsThings(large.category) &&
        usualSupport(small.category) != Support::Surface &&
        static_cast<double>(small.frames) <= options.glimpseShare * static_cast<double>(large.frames))
        return true;
    const double bottom = a.center.z - a.size.z / 2, top = b.center.z + b.size.z / 2;
    return sameName && a.size.z <= options.topSlab && std::abs(bottom - top) <= options.restingGap &&
           model::footprintContains(b, {a.center.x, a.center.y}, 0);
}

void reachUnder(model::Box& cabinet, const model::Box& basin) {
    model::takeInFootprint(cabinet, basin);
    const double bottom = model::bottom(cabinet), top = std::max(model::top(cabinet), model::bottom(basin));
    cabinet.size.z = top - bottom;
    cabinet.center.z = (top + bottom) / 2;
}

const SeenBox* seatAtTop(const model::Box& table, const std::vector<SeenBox>& things, const FusionOptions& options) {
    // Things put on tables resting on its top, over it: it is a table, whatever seat stands in it.
    const bool carriesThings = std::any_of(things.begin(), things.end(), [&](const SeenBox& other) {
        return usualSupport(other.category) == Support::Surface &&
               std::abs(model::bottom(other.box) - model::top(table)) <= options.restingGap &&
               model::footprintOverlap(other.box, table) >= 0.5 * model::footprintArea(other.box);
    });
    if (carriesThings) return nullptr;
    const auto seat = std::find_if(things.begin(), things.end(), [&](const SeenBox& other) {
        const std::optional<double> usual = typicalHeight(other.category);
        const bool stoolBeside = std::max(other.box.size.x, other.box.size.y) <= options.stoolSide &&
                                 model::horizontalGap(other.box, table) <= options.stoolBeside;
        return role(other.category) == Role::Seat &&
               std::abs(model::top(other.box) - model::top(table)) <= options.seatAtTop &&
               (!usual || model::top(other.box) <= *usual) &&
               (stoolBeside ||
                model::footprintOverlap(other.box, table) >= options.seatInside * model::footprintArea(other.box)) &&
               model::footprintArea(other.box) < model::footprintArea(table);
    });
    return seat == things.end() ? nullptr : &*seat;
}

namespace {

// The first of `things` but `thing` that `holds`, with `thing`'s centre over its footprint and `thing`'s bottom from
// `lowest` of its box up to FusionOptions::restingGap over its top; or null.
template <class Holds, class Lowest>
const SeenBox* thingUnder(const SeenBox& thing, const std::vector<SeenBox>& things, const FusionOptions& options,
                          Holds holds, Lowest lowest) {
    const double bottom = model::bottom(thing.box);
    const auto under = std::find_if(things.begin(), things.end(), [&](const SeenBox& other) {
        return &other != &thing && holds(other) && bottom >= lowest(other.box) &&
               bottom <= model::top(other.box) + options.restingGap &&
               model::footprintContains(other.box, {thing.box.center.x, thing.box.center.y});
    });
    return under == things.end() ? nullptr : &*under;
}

}  // namespace

const SeenBox* carrierUnder(const SeenBox& thing, const std::vector<SeenBox>& things, const FusionOptions& options) {
    const auto usual = typicalHeight(thing.category);
    if (usualSupport(thing.category) != Support::Floor || !usual || thing.box.size.z >= options.smallOnTop * *usual)
        return nullptr;
    return thingUnder(
        thing, things, options, [](const SeenBox& other) { return holdsThings(other.category); },
        [&](const model::Box& carrier) { return model::top(carrier) - options.restingGap; });
}

const SeenBox* seatUnder(const SeenBox& thing, const std::vector<SeenBox>& things, const FusionOptions& options) {
    const Role kind = role(thing.category);
    const bool neverOnSeats = kind == Role::Basin || (usualSupport(thing.category) == Support::Floor &&
                                                      kind != Role::Seat && kind != Role::Luggage);
    if (!neverOnSeats) return nullptr;
    return thingUnder(
        thing, things, options, [](const SeenBox& other) { return role(other.category) == Role::Seat; },
        [&](const model::Box& seat) { return model::bottom(seat) + options.restingGap; });
}

namespace {

// How far under a basin's bottom the top of a thing lies that stands under it, most of its footprint
// (FusionOptions::cabinetShare) under the basin's; nothing for a thing that does not.
std::optional<double> underBasin(const model::Box& under, const model::Box& basin, const FusionOptions& options) {
    if (model::footprintOverlap(under, basin) < options.cabinetShare * model::footprintArea(under)) return std::nullopt;
    return model::bottom(basin) - model::top(under);
}

}  // namespace

bool cabinetOf(const model::Box& under, const model::Box& basin, const FusionOptions& options) {
    const std::optional<double> below = underBasin(under, basin, options);
    return below && *below >= -options.cabinetAbove && *below <= options.cabinetBelow;
}

const SeenBox* sinkOverTable(const SeenBox& table, const std::vector<SeenBox>& things, const FusionOptions& options) {
    if (!holdsThings(table.category) || hasUprightEnds(table.category)) return nullptr;
    const auto sink = std::find_if(things.begin(), things.end(), [&](const SeenBox& other) {
        const std::optional<double> below = underBasin(table.box, other.box, options);
        return role(other.category) == Role::Basin && below && *below > options.cabinetBelow;
    });
    return sink == things.end() ? nullptr : &*sink;
}

std::size_t reachDownToFloor(std::vector<SeenBox>& things, bool floorFound, std::optional<double> tableTopHeight,
                             const FusionOptions& options) {
    if (!floorFound && !lowestReachesFloor(things, options) &&
        !tableStandsOnPlacedFloor(things, tableTopHeight, options))
        return 0;
    std::size_t grounded = 0;
    for (auto& thing : things) grounded += standOnFloor(thing, things, options);
    return grounded;
}

namespace {

// Whether a wall stands between two points of the floor plane: the segment joining them crosses the wall's.
bool wallBetween(const model::Vec3& a, const model::Vec3& b, const std::vector<WallSegment>& walls) {
    return std::any_of(walls.begin(), walls.end(), [&](const WallSegment& wall) {
        const double sa = wall.signedDistance(a), sb = wall.signedDistance(b);
        if ((sa > 0) == (sb > 0) || sa == sb) return false;
        const double k = sa / (sa - sb);
        const model::Vec3 along = wall.direction();
        const double t = along.x * (a.x + (b.x - a.x) * k) + along.y * (a.y + (b.y - a.y) * k);
        return t >= wall.along0 && t <= wall.along1;
    });
}

std::string_view roomName(RoomKind room) { return room == RoomKind::Kitchen ? "kitchen" : "bathroom"; }

}  // namespace

std::vector<std::string> outOfPlace(const std::vector<SeenBox>& things, const std::vector<WallSegment>& walls,
                                    const FusionOptions& options) {
    std::vector<std::string> doubts(things.size());
    for (std::size_t t = 0; t < things.size(); ++t) {
        const RoomKind own = roomKind(things[t].category);
        if (own == RoomKind::Any) continue;
        // The kinds of each room named there, counted by kind as the scale's priors count them (scale_priors.cpp:
        // namesInDoubt): one thing is often named twice, and a bathroom's tall white boxes are "fridges" in turn.
        std::map<RoomKind, std::set<std::string_view>> kinds;
        std::map<RoomKind, std::vector<std::string_view>> others;
        for (const auto& other : things) {
            const RoomKind room = roomKind(other.category);
            // A bed or a chair beside a toilet is no measure of the toilet's room: a toilet's name is the surer.
            if (!oneRoom(room) || model::distance(things[t].box, other.box) > options.roomReach ||
                wallBetween(things[t].box.center, other.box.center, walls))
                continue;
            kinds[room].insert(kindName(other.category));
            if (room != own) others[room].push_back(other.category);
        }
        const std::size_t ownKinds = kinds[own].size();
        // A kind that stands in any room but a bathroom is out of place beside one toilet; the others where
        // another room's kinds outweigh their own (roomOutweighs).
        for (const auto& [room, names] : others)
            if (own == RoomKind::Dry ? room == RoomKind::Bathroom
                                     : roomOutweighs(room, kinds[room].size(), own, ownKinds))
                doubts[t] = fmt::format("in a {} (beside {} within {:.1f} m)", roomName(room), fmt::join(names, ", "),
                                        options.roomReach);
    }
    return doubts;
}

namespace {

// The seats within FusionOptions::seatReach of a low table's box, if they give places for two or more, else "".
std::string seatsAround(const model::Box& box, const std::vector<SeenBox>& things, const FusionOptions& options) {
    std::size_t places = 0;
    std::vector<std::string_view> names;
    for (const auto& other : things) {
        if (role(other.category) != Role::Seat || model::horizontalGap(box, other.box) > options.seatReach) continue;
        const double longest = std::max(other.box.size.x, other.box.size.y);
        places += model::seatPlaces(longest, options.seatWidth);
        names.push_back(other.category);
    }
    return places >= 2 ? fmt::format("beside {} within {:.1f} m", fmt::join(names, ", "), options.seatReach) : "";
}

// The sink among `things` whose cabinet the box is (cabinetOf), or null.
const SeenBox* sinkOver(const model::Box& box, const std::vector<SeenBox>& things, const FusionOptions& options) {
    const auto sink = std::find_if(things.begin(), things.end(), [&](const SeenBox& other) {
        return role(other.category) == Role::Basin && cabinetOf(box, other.box, options);
    });
    return sink == things.end() ? nullptr : &*sink;
}

}  // namespace

std::vector<UseName> namedByUse(const std::vector<SeenBox>& things, const std::vector<WallSegment>& walls,
                                const FusionOptions& options) {
    std::vector<UseName> names(things.size());
    for (std::size_t t = 0; t < things.size(); ++t) {
        const model::Box& box = things[t].box;
        const double shorter = std::min(box.size.x, box.size.y);
        if (role(things[t].category) != Role::Basin && role(things[t].category) != Role::Seat &&
            things[t].category != "cabinet")
            if (const SeenBox* sink = sinkOver(box, things, options)) {
                names[t] = {"cabinet",
                            fmt::format("stands right under the {}, the cabinet it is set in", sink->category)};
                continue;
            }
        if (role(things[t].category) == Role::Luggage) {
            if (model::bottom(box) > options.restingGap || shorter < options.lowTableSide ||
                model::top(box) < options.lowTableTopMin || model::top(box) > options.lowTableTopMax)
                continue;
            if (std::string seats = seatsAround(box, things, options); !seats.empty())
                names[t] = {"table", "is a low table among seats (" + seats + ")"};
        } else if (things[t].category == "table") {
            const bool besideBed = std::any_of(things.begin(), things.end(), [&](const SeenBox& other) {
                return other.category == "bed" && model::horizontalGap(box, other.box) <= options.besideBed;
            });
            if (besideBed && std::max(box.size.x, box.size.y) <= options.nightstandSide &&
                model::top(box) <= options.nightstandTop) {
                names[t] = {"nightstand", fmt::format("stands beside a bed (within {:.1f} m), small and low, as a "
                                                      "nightstand does",
                                                      options.besideBed)};
                continue;
            }
            if (shorter > options.deskDepth || std::max(box.size.x, box.size.y) < options.deskSideMin ||
                model::top(box) < options.deskTopMin || !wallAgainst(box, walls, options.againstWall, true))
                continue;
            const auto chairs = std::count_if(things.begin(), things.end(), [&](const SeenBox& other) {
                return other.category == "chair" && model::horizontalGap(box, other.box) <= options.chairAtDesk;
            });
            if (chairs >= 1 && chairs <= options.deskChairsMax)
                names[t] = {"desk", fmt::format("stands against a wall with {} at it (within {:.1f} m), as a desk does",
                                                chairs == 1 ? "one chair" : fmt::format("{} chairs", chairs),
                                                options.chairAtDesk)};
        }
    }
    return names;
}

namespace {

// A box's footprint in square cells along its own axes, row x and column y: the cell a point falls in (those
// outside the footprint in the cell at its edge), and the cells' bounds in the box's frame.
struct FootprintGrid {
    FootprintGrid(const model::Box& box, double cell)
        : frame(box),
          cell(cell),
          halfX(box.size.x / 2),
          halfY(box.size.y / 2),
          nx(std::max(1, static_cast<int>(std::ceil(box.size.x / cell)))),
          ny(std::max(1, static_cast<int>(std::ceil(box.size.y / cell)))) {}
    std::pair<int, int> at(const model::Vec3& p) const {
        const model::Vec2 local = frame.local({p.x, p.y});
        return {std::clamp(static_cast<int>((local.x + halfX) / cell), 0, nx - 1),
                std::clamp(static_cast<int>((local.y + halfY) / cell), 0, ny - 1)};
    }
    model::BoxFrame frame;
    double cell, halfX, halfY;
    int nx, ny;
};

}  // namespace

SeenTop seenTop(const std::vector<model::Vec3>& points, const model::Box& box, const FusionOptions& options) {
    const FootprintGrid grid(box, options.topCell);
    const int nx = grid.nx, ny = grid.ny;
    // Each point's cell and height step; then every band of topBand above the box's lowest quarter, where a top is
    // (legs and the floor around them lie below it).
    const double bottom = model::bottom(box);
    const int steps = std::max(1, static_cast<int>(std::ceil(box.size.z / options.topCell)));
    const int band = std::max(1, static_cast<int>(std::lround(options.topBand / options.topCell)));
    struct Seen {
        int cell;
        double z;
    };
    std::vector<std::vector<Seen>> seenAt(static_cast<std::size_t>(steps));
    for (const auto& p : points) {
        const auto [ix, iy] = grid.at(p);
        const int iz = std::clamp(static_cast<int>((p.z - bottom) / options.topCell), 0, steps - 1);
        seenAt[static_cast<std::size_t>(iz)].push_back({ix * ny + iy, p.z});
    }
    SeenTop best{0, bottom};
    std::vector<char> held(static_cast<std::size_t>(nx * ny));
    for (int from = steps / 4; from < steps; ++from) {
        std::fill(held.begin(), held.end(), 0);
        std::size_t count = 0;
        double highest = bottom;
        for (int z = from; z < std::min(steps, from + band); ++z)
            for (const Seen& seen : seenAt[static_cast<std::size_t>(z)]) {
                count += !std::exchange(held[seen.cell], 1);
                highest = std::max(highest, seen.z);
            }
        const double cover = static_cast<double>(count) / (nx * ny);
        if (cover > best.cover) best = {cover, highest};
    }
    return best;
}

bool fitBasin(const std::vector<model::Vec3>& points, model::Box& box, const FusionOptions& options) {
    const FootprintGrid grid(box, options.topCell);
    cv::Mat highest(grid.nx, grid.ny, CV_64F, cv::Scalar(-std::numeric_limits<double>::infinity()));
    for (const auto& p : points) {
        const auto [ix, iy] = grid.at(p);
        double& h = highest.at<double>(ix, iy);
        h = std::max(h, p.z);
    }
    // The rim: the height most of the footprint's cells reach, the counter around the bowl (a backsplash or a tap
    // rising over it are a few cells).
    std::vector<double> seen;
    for (auto h = highest.begin<double>(); h != highest.end<double>(); ++h)
        if (std::isfinite(*h)) seen.push_back(*h);
    if (seen.empty()) return false;
    auto rimAt = seen.begin() + static_cast<std::ptrdiff_t>(0.9 * static_cast<double>(seen.size() - 1));
    std::nth_element(seen.begin(), rimAt, seen.end());
    // The bowl: the largest run of cells under the rim side by side (a counter's edge or a cabinet's side seen lower
    // down makes runs of its own; cells no point fell in are at minus infinity, under nothing).
    const cv::Mat bowl = (highest < *rimAt - options.basinDip) & (highest > -std::numeric_limits<double>::infinity());
    cv::Mat labels, stats, centroids;
    const int runs = cv::connectedComponentsWithStats(bowl, labels, stats, centroids, 4, CV_32S);
    int largest = 0;
    for (int r = 1; r < runs; ++r)
        if (largest == 0 || stats.at<int>(r, cv::CC_STAT_AREA) > stats.at<int>(largest, cv::CC_STAT_AREA)) largest = r;
    if (largest == 0 || stats.at<int>(largest, cv::CC_STAT_AREA) < 4) return false;
    // Rows run along the box's x axis, columns along its y axis.
    const int loX = stats.at<int>(largest, cv::CC_STAT_TOP), loY = stats.at<int>(largest, cv::CC_STAT_LEFT);
    const int hiX = loX + stats.at<int>(largest, cv::CC_STAT_HEIGHT),
              hiY = loY + stats.at<int>(largest, cv::CC_STAT_WIDTH);
    const double x0 = std::max(-grid.halfX, loX * grid.cell - grid.halfX - options.basinRim);
    const double x1 = std::min(grid.halfX, hiX * grid.cell - grid.halfX + options.basinRim);
    const double y0 = std::max(-grid.halfY, loY * grid.cell - grid.halfY - options.basinRim);
    const double y1 = std::min(grid.halfY, hiY * grid.cell - grid.halfY + options.basinRim);
    if ((x1 - x0) * (y1 - y0) > options.basinShare * box.size.x * box.size.y) return false;
    // The bowl's floor: the lowest of its cells' highest points.
    double floor = 0;
    cv::minMaxLoc(highest, &floor, nullptr, nullptr, nullptr, labels == largest);
    const model::Vec2 centre = grid.frame.world({(x0 + x1) / 2, (y0 + y1) / 2});
    box.center.x = centre.x, box.center.y = centre.y;
    box.size.x = x1 - x0, box.size.y = y1 - y0;
    // From the bowl's floor to the rim: what its views took in under the bowl is the cabinet's front.
    const double top = model::top(box), bottom = std::max(model::bottom(box), floor);
    box.size.z = top - bottom;
    box.center.z = (top + bottom) / 2;
    return true;
}

bool lowerToTop(model::Box& box, const SeenTop& top, const FusionOptions& options) {
    const double bottom = model::bottom(box);
    if (top.cover < options.topCover || model::top(box) <= top.height + options.overTop || top.height <= bottom)
        return false;
    box.center.z = (bottom + top.height) / 2;
    box.size.z = top.height - bottom;
    return true;
}

ObjectFusion::ObjectFusion(const Alignment& alignment, const RoomSurfaces& room, FusionOptions options)
    : alignment_(alignment),
      walls_(room.walls ? *room.walls : std::vector<WallSegment>{}),
      room_(room),
      options_(options),
      map_([&] {
          InstanceMapOptions mapOptions;
          mapOptions.voteLabels = options.voteLabels;
          return mapOptions;
      }()) {
    room_.walls = &walls_;
}

void ObjectFusion::addCamera(const FusionCamera& camera) { cameras_.push_back(camera); }

PointCloud ObjectFusion::segment(const Observation& view) const {
    const bool onSurface = usualSupport(view.label) == Support::Surface;
    return thingInView(alignedRegion(view, alignment_), room_, onSurface);
}

void ObjectFusion::addFrame(std::vector<Observation> frameViews) {
    std::vector<PointCloud> things;
    for (const auto& view : frameViews) things.push_back(segment(view));
    addSegmentedFrame(std::move(frameViews), std::move(things));
}

void ObjectFusion::addSegmentedFrame(std::vector<Observation> frameViews, std::vector<PointCloud> things) {
    std::vector<InstanceView> frame;
    for (std::size_t v = 0; v < frameViews.size(); ++v) {
        const std::size_t source = views_.size();
        views_.push_back(std::move(frameViews[v]));
        if (things[v].empty()) continue;
        ++segmented_;
        const Observation& added = views_.back();
        frame.push_back({added.frame, added.label, added.score, added.alsoSeenAs, std::move(things[v]), source});
    }
    map_.integrate(std::move(frame));
}

namespace {

// Why a thing's name is doubted, the first rule that holds, or nothing: a thing that holds things on its top (a table;
// not a bed, whose headboard rises over its top) that shows no top, or whose top is a seat's standing in it; a name
// out of place (outOfPlace: `misplaced`); a table standing under a sink's bowl (sinkOverTable); a kind that stands on
// floors resting on a table's top (carrierUnder), or one never put on seats resting in a seat (seatUnder).
std::string doubtOf(const Thing& thing, const SeenBox& seen, const std::vector<SeenBox>& named,
                    const std::string& misplaced, const FusionOptions& options) {
    if (thing.top && thing.top->cover < options.topCover)
        return fmt::format("shows no top (its points cover at most {:.0f} % of its footprint at one height)",
                           100 * thing.top->cover);
    if (thing.top)
        if (const SeenBox* seat = seatAtTop(seen.box, named, options))
            return fmt::format("holds a {} whose top is its top: the seat, seen as one with what stands around it",
                               seat->category);
    if (!misplaced.empty()) return "stands " + misplaced;
    if (const SeenBox* sink = sinkOverTable(seen, named, options))
        return fmt::format("stands under a {}'s bowl, {:.2f} m under it: what holds the {}, not a {}", sink->category,
                           model::bottom(sink->box) - model::top(seen.box), sink->category, seen.category);
    if (const SeenBox* carrier = carrierUnder(seen, named, options))
        return fmt::format("rests on a {}'s top, {:.2f} m tall where a {} stands about {:.2f} m on the floor",
                           carrier->category, seen.box.size.z, seen.category, typicalHeight(seen.category).value_or(0));
    if (const SeenBox* seat = seatUnder(seen, named, options))
        return fmt::format(
            "rests on a {}, where a {} {}", seat->category, seen.category,
            role(seen.category) == Role::Basin ? "is set in a counter or hung on a wall" : "stands on the floor");
    return {};
}

}  // namespace

std::vector<FusedThing> ObjectFusion::things(FusionCounts* counts) const {
    // The map keeps taking frames: its pieces are merged in a copy.
    InstanceMap map = map_;
    const std::size_t instances = map.instances().size();
    map.consolidate();
    FusionCounts made;
    made.segmented = segmented_;
    made.views = views_.size();
    made.mapMerged = instances - map.instances().size();

    std::vector<Thing> things = thingsOf(map, cameras_, options_, made.guesses);
    made.pieces = mergePieces(things, options_);
    made.ends = joinUprightEnds(things, options_);
    // A thing one frame saw, once its pieces are joined, where four or more held it in view: a closed-set
    // detector's one-off guess. Detections a user gives (detections.json) are taken as what was seen.
    if (options_.voteLabels)
        made.guesses += std::erase_if(things, [&](const Thing& t) {
            return framesSeen(t) < 2 &&
                   framesInView(t.points, cameras_) >= static_cast<std::size_t>(options_.oneViewOf);
        });
    // The tops of things that hold things, before their boxes reach down to the floor from them.
    for (auto& thing : things)
        if (holdsThings(thing.category) && !hasUprightEnds(thing.category)) {
            thing.top = seenTop(thing.points.points, thing.box, options_);
            made.lowered += lowerToTop(thing.box, *thing.top, options_);
        } else if (role(thing.category) == Role::Basin) {
            // A sink ends at its rim or counter too: what its views took in above it is what stands on the counter
            // or the wall behind where the walls stage took none (a short wall beside a vanity, a backsplash). Its
            // name is not doubted for a top not shown: a basin seen from the side shows its bowl, not its rim.
            made.lowered += lowerToTop(thing.box, seenTop(thing.points.points, thing.box, options_), options_);
        }
    std::vector<SeenBox> boxes;
    for (const auto& thing : things) boxes.push_back({thing.box, thing.category, 0, {}});
    made.grounded = reachDownToFloor(boxes, room_.floorFound, room_.tableTopHeight, options_);
    for (std::size_t t = 0; t < things.size(); ++t) things[t].box = boxes[t].box;
    made.basins = partBasins(things, options_);
    // Slivers after the floor: a table whose top alone was seen is a table, not a sliver.
    std::vector<model::Box> backs;
    for (const auto& thing : things)
        if (role(thing.category) == Role::Seat && typicalHeight(thing.category) && !backlessSeat(thing, options_))
            backs.push_back(thing.box);
    made.slivers = std::erase_if(
        things, [&](const Thing& t) { return sliver(t, options_) || onSeatsBack(t.box, backs, options_); });

    std::vector<SeenBox> named;
    for (const auto& thing : things) named.push_back({thing.box, thing.category, 0, {}});
    // Names doubted (doubtOf); a doubted thing is no seat, table or luggage to the rules after it, nor to namedByUse.
    std::vector<std::string> doubts(things.size());
    const std::vector<std::string> misplaced = outOfPlace(named, walls_, options_);
    for (std::size_t t = 0; t < things.size(); ++t) {
        doubts[t] = doubtOf(things[t], named[t], named, misplaced[t], options_);
        if (!doubts[t].empty()) named[t].category = model::kUnnamedCategory;
    }
    const std::vector<UseName> uses = namedByUse(named, walls_, options_);
    // A sink is its bowl, once its cabinet has been told by the box its views gave (cabinetOf).
    for (std::size_t t = 0; t < things.size(); ++t)
        if (doubts[t].empty() && uses[t].category.empty() && role(things[t].category) == Role::Basin)
            made.bowls += fitBasin(things[t].points.points, things[t].box, options_);

    std::vector<FusedThing> out;
    for (std::size_t t = 0; t < things.size(); ++t) {
        FusedThing fused{things[t].box, things[t].category, "", "", std::move(things[t].points), {}};
        // A sink's cabinet, named so or parted from it, holds the basin set in it: it reaches under the sink.
        if (doubts[t].empty() && (uses[t].category == "cabinet" || things[t].category == "cabinet"))
            if (const SeenBox* sink = sinkOver(named[t].box, named, options_))
                reachUnder(fused.box, things[static_cast<std::size_t>(sink - named.data())].box);
        if (!doubts[t].empty() || !uses[t].category.empty()) {
            fused.detectedAs = fused.category;
            fused.category = doubts[t].empty() ? uses[t].category : std::string(model::kUnnamedCategory);
            fused.renamedWhy = doubts[t].empty() ? uses[t].why : doubts[t];
        }
        for (const Instance* instance : things[t].instances)
            fused.views.insert(fused.views.end(), instance->sources.begin(), instance->sources.end());
        std::sort(fused.views.begin(), fused.views.end(),
                  [&](auto a, auto b) { return views_[a].frame < views_[b].frame; });
        out.push_back(std::move(fused));
    }
    if (counts) *counts = made;
    return out;
}

std::vector<ObjectTrack> fuseTracks(std::vector<ObjectTrack> tracks, const Alignment& alignment,
                                    const RoomSurfaces& room, const std::vector<FusionCamera>& cameras,
                                    const FusionOptions& options, StageProgress& progress) {
    ObjectFusion fusion(alignment, room, options);
    for (const auto& camera : cameras) fusion.addCamera(camera);
    // The frame pass's views, frame by frame in the order they were taken, each with the track it came from
    // (for its evidence crop).
    std::vector<std::pair<Observation, std::size_t>> all;
    for (std::size_t t = 0; t < tracks.size(); ++t)
        for (auto& v : tracks[t].views) all.emplace_back(std::move(v), t);
    std::stable_sort(all.begin(), all.end(),
                     [](const auto& a, const auto& b) { return a.first.frame < b.first.frame; });
    // Each view cut apart on its own, on OpenCV's threads; the instance map then takes them frame by frame.
    std::vector<PointCloud> cut(all.size());
    cv::parallel_for_(cv::Range(0, static_cast<int>(all.size())), [&](const cv::Range& range) {
        for (int v = range.start; v < range.end; ++v) cut[v] = fusion.segment(all[v].first);
    });
    std::vector<std::size_t> trackOf;
    for (std::size_t i = 0; i < all.size();) {
        progress.stopIfCancelled();
        std::vector<Observation> frame;
        std::vector<PointCloud> frameThings;
        for (const std::uint32_t at = all[i].first.frame; i < all.size() && all[i].first.frame == at; ++i) {
            frame.push_back(std::move(all[i].first));
            frameThings.push_back(std::move(cut[i]));
            trackOf.push_back(all[i].second);
        }
        fusion.addSegmentedFrame(std::move(frame), std::move(frameThings));
    }

    FusionCounts counts;
    std::vector<FusedThing> things = fusion.things(&counts);
    std::vector<Observation> views = fusion.takeViews();
    std::vector<ObjectTrack> out;
    for (auto& thing : things) {
        // The thing as a track: its views in frame order, the evidence crop of the frame-pass track most of them
        // came from, its fused points and box.
        ObjectTrack track;
        track.category = thing.category;
        track.kind = detectionKind(track.category);
        track.detectedAs = thing.detectedAs;
        track.renamedWhy = thing.renamedWhy;
        std::map<std::size_t, std::size_t> fromTrack;
        for (auto v : thing.views) {
            ++fromTrack[trackOf[v]];
            track.views.push_back(std::move(views[v]));
        }
        auto most = std::max_element(fromTrack.begin(), fromTrack.end(),
                                     [](const auto& a, const auto& b) { return a.second < b.second; });
        track.evidence = tracks[most->first].evidence;
        track.material = tracks[most->first].material;
        for (std::size_t p = 0; p < thing.points.size(); ++p) {
            track.fused.push_back(thing.points.points[p]);
            const auto& c = thing.points.colors[p];
            track.fusedColors.push_back(cv::Vec3b(c[2], c[1], c[0]));
        }
        track.fusedBox = thing.box;
        out.push_back(std::move(track));
    }
    progress.note(fmt::format(
        "objects: {} of {} views showed a thing apart from the floor and walls; fused into {} thing(s) ({} pieces "
        "merged into the things they belong to, {} more merged by their boxes, {} upright ends joined to their beds, "
        "sofas or chairs' seats; {} slivers and {} things seen in too few of the frames that held them dropped; {} "
        "lowered to the top they show; {} reaching down to the floor; {} sink(s) parted from the cabinet their views "
        "took in, {} fitted to the bowl they show)",
        counts.segmented, counts.views, out.size(), counts.mapMerged, counts.pieces, counts.ends, counts.slivers,
        counts.guesses, counts.lowered, counts.grounded, counts.basins, counts.bowls));
    return out;
}

}  // namespace smql::ingest
