#include "relations/predicates.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "model/geometry.hpp"
#include "relations/visibility.hpp"

namespace smql::relations {

using model::Box;
using model::Node;

namespace {

// Categories are open vocabulary; `plant stand`, `plant_stand` and `plant-stand` are one word here.
bool sameCategory(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    auto fold = [](char c) { return c == ' ' || c == '_' ? '-' : c; };
    for (std::size_t i = 0; i < a.size(); ++i)
        if (fold(a[i]) != fold(b[i])) return false;
    return true;
}

bool hasGeometry(const Node& n) { return n.geometry != model::GeometryKind::None; }

double overlapShare(const Box& a, const Box& b) {
    double smaller = std::min(model::footprintArea(a), model::footprintArea(b));
    return smaller > 0 ? model::footprintOverlap(a, b) / smaller : 0.0;
}

bool contained(const Node& a, const Node& b, const Thresholds& t) {
    return model::fractionInside(a.box, b.box) >= t.inMinInside;
}

double dot(model::Vec2 a, model::Vec2 b) { return a.x * b.x + a.y * b.y; }

model::Vec2 centreOffset(const Node& from, const Node& to) {
    return {to.box.center.x - from.box.center.x, to.box.center.y - from.box.center.y};
}

// Maps a positive offset (>= the threshold) to a score in [0.5, 1).
double offsetScore(double offset, double threshold) {
    if (offset < threshold || offset <= 0) return 0.0;
    return offset / (offset + std::max(threshold, 1e-3));
}

}  // namespace

namespace {

// Shorter names first, then by their bytes: most steps of a search then compare two lengths,
// not two strings (on looks its carrier's category up for every candidate and reference it tests).
constexpr bool shortFirst(std::string_view a, std::string_view b) {
    return a.size() != b.size() ? a.size() < b.size() : a < b;
}

template <std::size_t N>
constexpr std::array<std::string_view, N> inShortFirstOrder(std::array<std::string_view, N> names) {
    std::sort(names.begin(), names.end(), shortFirst);
    return names;
}

// Whether `category`, folded as sameCategory folds it, is one of `names` (written folded, in
// shortFirst order).
template <std::size_t N>
bool listed(const std::array<std::string_view, N>& names, std::string_view category) {
    constexpr std::size_t kLongest = 32;  // longer than any listed name
    if (category.size() > kLongest) return false;
    std::array<char, kLongest> folded{};
    for (std::size_t i = 0; i < category.size(); ++i)
        folded[i] = category[i] == ' ' || category[i] == '_' ? '-' : category[i];
    return std::binary_search(names.begin(), names.end(), std::string_view(folded.data(), category.size()), shortFirst);
}

constexpr auto kHolders = inShortFirstOrder(std::array<std::string_view, 26>{
    "plant-stand", "basket",    "bowl",  "box",   "bin", "trash-can", "wastebasket", "vase",    "pot",
    "planter",     "cup",       "mug",   "glass", "jar", "bag",       "bucket",      "sink",    "bathtub",
    "crate",       "container", "basin", "pan",   "tub", "flowerpot", "case",        "backpack"});
constexpr auto kEnclosures = inShortFirstOrder(
    std::array<std::string_view, 20>{"cabinet",  "base-cabinet", "wall-cabinet",     "cupboard",        "wardrobe",
                                     "closet",   "drawer",       "chest-of-drawers", "dresser",         "shelf-unit",
                                     "bookcase", "bookshelf",    "fridge",           "refrigerator",    "microwave",
                                     "oven",     "dishwasher",   "washing-machine",  "kitchen-cabinet", "nightstand"});
// The enclosures made to keep food, dishes or clothes (inScore): what stands on floors is in none of them, nor is
// another of them.
constexpr auto kAppliances = inShortFirstOrder(std::array<std::string_view, 7>{
    "fridge", "refrigerator", "oven", "microwave", "dishwasher", "washing-machine", "toaster"});
// Things whose boxes hold others that do not rest on them: an arc lamp's box spread over a sofa and its
// cushions (Replica room 0), a plant's leaves over a table, a curtain's folds; and the ceiling, whose slab a light
// sunk into it reaches into (what is at a ceiling hangs from it: attached).
constexpr auto kCarryNothing = inShortFirstOrder(std::array<std::string_view, 16>{
    "lamp", "floor-lamp", "table-lamp", "desk-lamp", "light", "ceiling-light", "chandelier", "plant", "curtain",
    "blinds", "door", "window", "picture", "mirror", "clock", "ceiling"});
// Things that stand on a top or on the floor, whose boxes may spread over what stands beside them (a lamp's
// arm or cord, a plant's leaves): restsWithinItsBound.
constexpr auto kSpreading = inShortFirstOrder(
    std::array<std::string_view, 6>{"lamp", "floor-lamp", "table-lamp", "desk-lamp", "plant", "indoor-plant"});
constexpr auto kFronted = inShortFirstOrder(std::array<std::string_view, 25>{
    "sofa",       "couch",    "armchair",  "chair",        "office-chair", "bed",      "tv",         "television",
    "tv-screen",  "monitor",  "desk",      "cabinet",      "cupboard",     "wardrobe", "dresser",    "chest-of-drawers",
    "nightstand", "bookcase", "bookshelf", "refrigerator", "fridge",       "oven",     "dishwasher", "fireplace",
    "toilet"});

// The kinds of usualSupport, as the detectors' classes and the labelled captures name them; any other kind stands on
// either or is unknown.
constexpr auto kStandsOnFloor = inShortFirstOrder(std::array<std::string_view, 20>{
    "table",   "desk",    "chair",    "sofa",    "bed",      "fridge", "toilet", "door", "nightstand", "shelf",
    "cabinet", "counter", "wardrobe", "dresser", "armchair", "stool",  "bench",  "oven", "suitcase",   "skateboard"});
constexpr auto kStandsOnTops = inShortFirstOrder(std::array<std::string_view, 31>{
    "monitor",   "camera",   "laptop",     "book",    "vase",     "bowl",       "bottle",    "mug",
    "microwave", "keyboard", "wine-glass", "fork",    "knife",    "spoon",      "banana",    "apple",
    "orange",    "sandwich", "broccoli",   "carrot",  "hot-dog",  "pizza",      "donut",     "cake",
    "mouse",     "remote",   "phone",      "toaster", "scissors", "hair-dryer", "toothbrush"});

}  // namespace

Support usualSupport(std::string_view category) {
    if (listed(kStandsOnFloor, category)) return Support::Floor;
    return listed(kStandsOnTops, category) ? Support::Surface : Support::Either;
}

Affordance affordanceOf(std::string_view category) {
    // A statement asks again and again of the same few categories (on(table) of every candidate):
    // the last answer of this thread is kept with its name, which is compared instead of searched.
    struct Last {
        std::array<char, 32> name;
        std::size_t size = SIZE_MAX;  // nothing kept
        Affordance kind = Affordance::Surface;
    };
    thread_local Last last;
    if (category.size() == last.size && std::equal(category.begin(), category.end(), last.name.begin()))
        return last.kind;
    Affordance kind = Affordance::Surface;
    if (listed(kHolders, category))
        kind = Affordance::Holder;
    else if (listed(kEnclosures, category))
        kind = Affordance::Enclosure;
    else if (listed(kCarryNothing, category))
        kind = Affordance::Nothing;
    if (category.size() <= last.name.size()) {
        std::copy(category.begin(), category.end(), last.name.begin());
        last.size = category.size();
        last.kind = kind;
    }
    return kind;
}

bool hasFront(std::string_view category) { return listed(kFronted, category); }

model::Vec2 frontDirection(const Box& box) { return {std::cos(box.yaw), std::sin(box.yaw)}; }

bool isVerticalPlane(const Node& node) {
    if (node.kind != model::NodeKind::Anchor) return false;
    const auto& s = node.box.size;
    // A plane segment stands upright when its thin axis is horizontal.
    return node.geometry == model::GeometryKind::Plane && s.z > std::min(s.x, s.y);
}

bool isCeiling(const Node& node) {
    return node.kind == model::NodeKind::Anchor && sameCategory(node.category, "ceiling");
}

Frame viewFrame(const model::Viewpoint& viewpoint) {
    Frame f;
    f.forward = {std::cos(viewpoint.facingYaw), std::sin(viewpoint.facingYaw)};
    f.right = {f.forward.y, -f.forward.x};
    f.position = {viewpoint.position.x, viewpoint.position.y};
    return f;
}

model::Node viewerAt(const Frame& frame) {
    model::Node viewer;
    viewer.id = model::kNoNode;
    viewer.kind = model::NodeKind::Object;
    viewer.category = "here";
    viewer.geometry = model::GeometryKind::Box;
    viewer.box.center = {frame.position.x, frame.position.y, kEyeHeight / 2};
    viewer.box.size = {kBodyWidth, kBodyWidth, kEyeHeight};
    viewer.box.yaw = std::atan2(frame.forward.y, frame.forward.x);
    return viewer;
}

// A slab at most kHungThickness thick and three times as tall as thick, that a wall holds hangs on it: at least
// kHungFace across (a picture, a board), or flush with the wall, at most kFlushThickness thick (a switch, a wall
// plug: Replica room 0's are 0-2 cm). A book standing on a shelf the memory does not hold (ScanNet's apartment: 0.19
// x 0.06 x 0.20 m) is a slab too, smaller than what people hang and thicker than a fitting.
constexpr double kHungThickness = 0.1;
constexpr double kHungFace = 0.25;
constexpr double kFlushThickness = 0.03;
bool hungShape(const model::Box& box) {
    const double thickness = std::min(box.size.x, box.size.y);
    const double face = std::max({box.size.x, box.size.y, box.size.z});
    return thickness <= kHungThickness && box.size.z >= 3 * thickness &&
           (face >= kHungFace || thickness <= kFlushThickness);
}

namespace {

// A supporter's footprint is at least half that of what it carries: a sofa does not rest on the
// blanket lying on it.
constexpr double kMinSupporterArea = 0.5;

// supportScore with the overlap of a's footprint and b's measured by the caller: on measures it
// first, and the clipping is the dearest part of the test.
double supportGivenOverlap(const Node& a, const Node& b, const Thresholds& t, double overlap) {
    if (&a == &b || (a.id == b.id && a.id != model::kNoNode)) return 0.0;
    if (!hasGeometry(a) || !hasGeometry(b) || isVerticalPlane(b)) return 0.0;
    const double smaller = std::min(model::footprintArea(a.box), model::footprintArea(b.box));
    double share = smaller > 0 ? overlap / smaller : 0.0;  // overlapShare
    if (share < t.onMinOverlap) return 0.0;
    double height = b.box.size.z;
    auto rise = [&](double z) {
        return height > 1e-3 ? (z - model::bottom(b.box)) / height : (z > b.box.center.z ? 1.0 : 0.0);
    };
    // a's centre in b's upper part; or, for a cover spread over b (at least half b's footprint,
    // mostly within b's box, hanging clear of what b stands on: a comforter over a bed whose box
    // holds its headboard, a cloth hanging from a table), its top.
    if (rise(a.box.center.z) < t.onMinRise &&
        (rise(model::top(a.box)) < t.onMinRise || model::bottom(a.box) - model::bottom(b.box) < t.aboveTolerance ||
         model::footprintArea(a.box) < kMinSupporterArea * model::footprintArea(b.box) ||
         model::fractionInside(a.box, b.box) < t.inMinInside))
        return 0.0;
    if (model::bottom(a.box) - model::top(b.box) > t.onMaxGap) return 0.0;
    return std::min(1.0, share);
}

}  // namespace

double supportScore(const Node& a, const Node& b, const Thresholds& t) {
    if (&a == &b || (a.id == b.id && a.id != model::kNoNode)) return 0.0;
    if (!hasGeometry(a) || !hasGeometry(b) || isVerticalPlane(b)) return 0.0;
    return supportGivenOverlap(a, b, t, model::footprintOverlap(a.box, b.box));
}

namespace {

constexpr double kUnbounded = 1e9;

model::Aabb grown(model::Aabb b, double d) {
    b.min = {b.min.x - d, b.min.y - d, b.min.z - d};
    b.max = {b.max.x + d, b.max.y + d, b.max.z + d};
    return b;
}

// The formulas, one per predicate; docs/relations.md states each.

// b carries a: the support geometry, b lower (its bottom below a's: a thing resting on b's top
// reaches no lower than b does, and no two things carry each other), and a not hanging on a wall.
// The tree's parents are chosen among the things that carry.
// `overlap`: a's footprint over b's, when the caller has measured it.
double carried(const PredicateInputs& in, std::optional<double> overlap = std::nullopt) {
    if (model::bottom(in.b.box) >= model::bottom(in.a.box)) return 0.0;
    const double score = overlap ? supportGivenOverlap(in.a, in.b, in.t, *overlap) : supportScore(in.a, in.b, in.t);
    return score > 0 && !wallHolding(in.a, in.obstacles, in.t) ? score : 0.0;
}

// The area two bounds share on the floor plane.
double flatOverlap(const model::Aabb& a, const model::Aabb& b) {
    const double dx = std::min(a.max.x, b.max.x) - std::max(a.min.x, b.min.x);
    const double dy = std::min(a.max.y, b.max.y) - std::max(a.min.y, b.min.y);
    return std::max(0.0, dx) * std::max(0.0, dy);
}

// A box of a spreading kind (kSpreading) whose floor other things take is a bound of more than the thing: it
// does not stand on that floor, and rests on the uppermost top that stands on the floor within it. Replica room 0's
// lamp 6 is a 0.90 x 2.55 m box from the floor to 1.35 m, over sofa 9 and the two nested side tables at its end,
// which take the floor under it; a piece the size of a lamp's base rests on the upper table inside it, where
// the people who labelled the room saw the lamp stand (docs/relations.md, "A box whose floor other things take").
// b carries a so when b stands on the floor a stands on (its bottom within kSameFloor of a's), lies mostly within
// a's footprint (kWithinBound of b's), its top under a's and no other such top over it, and things standing on
// that floor (their tops kFloorTaker or more above it: not a rug) take kTakenFloor of a's footprint. Returns the
// share of b within a, or 0. A floor lamp beside a side table stands on floor of its own, and its box is taken
// as it is.
constexpr double kSameFloor = 0.15;    // m
constexpr double kFloorTaker = 0.1;    // m
constexpr double kTakenFloor = 0.9;    // of a's footprint
constexpr double kWithinBound = 0.75;  // of b's footprint
constexpr int kFloorSamples = 12;      // a's footprint sampled kFloorSamples x kFloorSamples times

double restsWithinItsBound(const PredicateInputs& in) {
    const Node& a = in.a;
    const Node& b = in.b;
    if (model::bottom(b.box) < model::bottom(a.box) || model::bottom(b.box) > model::bottom(a.box) + kSameFloor ||
        model::top(b.box) >= model::top(a.box))
        return 0.0;
    const double area = model::footprintArea(b.box);
    if (area <= 0 || model::footprintArea(a.box) <= area) return 0.0;
    const model::Aabb span = in.obstacles.bounds(a), other = in.obstacles.bounds(b);
    if (flatOverlap(span, other) < kWithinBound * area || !listed(kSpreading, a.category)) return 0.0;
    const double within = model::footprintOverlap(a.box, b.box) / area;
    if (within < kWithinBound) return 0.0;
    std::vector<const Node*> around;
    in.obstacles.within(span, around);
    std::vector<const Node*> standing;
    for (const Node* n : around) {
        if (n->id == a.id || !hasGeometry(*n) || isVerticalPlane(*n) || n->kind != model::NodeKind::Object ||
            model::bottom(n->box) > model::bottom(a.box) + kSameFloor ||
            model::top(n->box) < model::bottom(a.box) + kFloorTaker)
            continue;
        // Another top of the same floor within a, over b's and under a's: a rests on that one.
        const Affordance kind = affordanceOf(n->category);
        if (n->id != b.id && (kind == Affordance::Surface || kind == Affordance::Enclosure) &&
            model::top(n->box) > model::top(b.box) && model::top(n->box) < model::top(a.box) &&
            model::footprintArea(n->box) > 0 &&
            model::footprintOverlap(a.box, n->box) >= kWithinBound * model::footprintArea(n->box))
            return 0.0;
        standing.push_back(n);
    }
    std::vector<model::BoxFrame> takers;
    for (const Node* n : standing) takers.emplace_back(n->box);
    const model::BoxFrame own(a.box);
    int taken = 0;
    for (int i = 0; i < kFloorSamples; ++i)
        for (int j = 0; j < kFloorSamples; ++j) {
            const model::Vec2 p = own.world(
                {a.box.size.x * ((i + 0.5) / kFloorSamples - 0.5), a.box.size.y * ((j + 0.5) / kFloorSamples - 0.5)});
            taken += std::any_of(takers.begin(), takers.end(), [&](const model::BoxFrame& f) { return f.contains(p); });
        }
    return taken >= kTakenFloor * kFloorSamples * kFloorSamples ? std::min(1.0, within) : 0.0;
}

// Real support, as Sr3D's "supported-by": most of a's own footprint lies over b (a box that only
// grazes b's edge, or a large thing over a small one, is not on it), on top of the support rule; or a box
// whose floor other things take, over b (restsWithinItsBound).
// `overlapOf` gives the overlap of a's footprint and b's (holds() may know it without clipping).
template <typename Overlap>
double onScoreWith(const PredicateInputs& in, Overlap overlapOf) {
    Affordance kind = affordanceOf(in.b.category);
    if (kind == Affordance::Holder || kind == Affordance::Nothing) return 0.0;
    if (kind == Affordance::Enclosure && contained(in.a, in.b, in.t)) return 0.0;
    double own = model::footprintArea(in.a.box);
    if (own <= 0) return 0.0;
    if (model::bottom(in.b.box) >= model::bottom(in.a.box)) return restsWithinItsBound(in);
    const double overlap = overlapOf();
    if (overlap / own < in.t.onMinOverlap) return 0.0;
    if (model::footprintArea(in.b.box) < kMinSupporterArea * own) return 0.0;
    return carried(in, overlap);
}
double onScore(const PredicateInputs& in) {
    return onScoreWith(in, [&] { return model::footprintOverlap(in.a.box, in.b.box); });
}

// Inside a holder or an enclosure: mostly within its box (the holder the larger of the two, so that
// two boxes of one thing are not each in the other), or carried by a holder (a plant in its pot). A fridge, an oven
// or a dishwasher keeps food, dishes or clothes: a thing that stands on floors or another appliance whose box its
// box takes in stands beside it in a kitchen's run. ScanNet's apartment's fridge, its box 1.34 m deep, took in the
// base cabinet beside it (named an oven) and the toaster oven on that: "what is in the fridge?" named both, and
// the tree hung them under the fridge.
double inScore(const PredicateInputs& in) {
    Affordance kind = affordanceOf(in.b.category);
    if (kind == Affordance::Surface || kind == Affordance::Nothing) return 0.0;
    if (listed(kAppliances, in.b.category) &&
        (usualSupport(in.a.category) == Support::Floor || listed(kAppliances, in.a.category)))
        return 0.0;
    double inside = model::fractionInside(in.a.box, in.b.box);
    if (inside >= in.t.inMinInside && model::volume(in.b.box) > model::volume(in.a.box)) return inside;
    return kind == Affordance::Holder ? carried(in) : 0.0;
}

double aboveScore(const Node& a, const Node& b, const Thresholds& t) {
    if (model::bottom(a.box) < model::top(b.box) - t.aboveTolerance) return 0.0;
    double share = overlapShare(a.box, b.box);
    return share >= t.aboveMinOverlap && share > 0 ? std::min(1.0, share) : 0.0;
}
// What rests on a thing and rises over its top is above it, however far its box sinks into the top (TUM fr1/rpy's
// monitor 9 cm into its desk's): "what is under the monitor?" is the desk it stands on. A cushion on a sofa's seat,
// its middle under the sofa's top (the back's), is on the sofa, not above it (Replica room 0's labels); a wall's
// picture is not above the wall.
double aboveScore(const PredicateInputs& in) {
    const double over = aboveScore(in.a, in.b, in.t);
    if (over > 0 || in.a.box.center.z <= model::top(in.b.box) || isVerticalPlane(in.a) || isVerticalPlane(in.b))
        return over;
    return onScore(in);
}
double belowScore(const PredicateInputs& in) {
    return aboveScore(PredicateInputs{in.b, in.a, in.c, in.t, in.frame, in.writtenDistance, in.obstacles});
}

model::Vec3 centre(const Node& n) { return n.box.center; }

// An opening (a window, a door) in a wall or against it: the wall does not stand between it and
// the room, whichever side of the wall's middle its box ends up.
bool openingIn(const Node& opening, const Node& wall, const Thresholds& t) {
    return isVerticalPlane(opening) && !sameCategory(opening.category, kWall) &&
           model::distance(opening.box, wall.box) <= t.attachedMaxGap;
}

// How far a way round the walls keeps off their corners: a few centimetres, so that a way along a
// wall's face does not graze its box.
constexpr double kStandOff = 0.05;

// The shortest way from p to q that passes through none of `walls`, over the corners of their boxes stood
// off by kStandOff, as long as it is at most `longest`; infinity when there is none as short. A few walls
// stand around a pair, so the corners are few and Dijkstra's search over them, every pair of corners in
// sight of each other, is small.
double wayRound(const model::Vec3& p, const model::Vec3& q, std::span<const Node* const> walls, double longest) {
    const double z = (p.z + q.z) / 2;
    auto length = [](const model::Vec3& u, const model::Vec3& v) { return std::hypot(u.x - v.x, u.y - v.y); };
    auto clear = [&](const model::Vec3& u, const model::Vec3& v) {
        return std::none_of(walls.begin(), walls.end(), [&](const Node* w) { return segmentCrosses(u, v, w->box); });
    };
    std::vector<model::Vec3> points{p, q};
    for (const Node* w : walls) {
        const model::BoxFrame frame(w->box);
        const double hx = w->box.size.x / 2 + kStandOff, hy = w->box.size.y / 2 + kStandOff;
        for (const double u : {-hx, hx})
            for (const double v : {-hy, hy}) {
                const model::Vec2 at = frame.world({u, v});
                const model::Vec3 corner{at.x, at.y, z};
                const bool inWall =
                    std::any_of(walls.begin(), walls.end(), [&](const Node* o) { return pointInBox(corner, o->box); });
                if (!inWall && length(p, corner) + length(corner, q) <= longest) points.push_back(corner);
            }
    }
    std::vector<double> way(points.size(), std::numeric_limits<double>::infinity());
    std::vector<bool> done(points.size(), false);
    way[0] = 0;
    for (;;) {
        std::size_t next = points.size();
        for (std::size_t i = 0; i < points.size(); ++i)
            if (!done[i] && way[i] <= longest && (next == points.size() || way[i] < way[next])) next = i;
        if (next == points.size()) return std::numeric_limits<double>::infinity();
        if (next == 1) return way[1];
        done[next] = true;
        for (std::size_t i = 0; i < points.size(); ++i) {
            const double through = way[next] + length(points[next], points[i]);
            if (!done[i] && through < way[i] && clear(points[next], points[i])) way[i] = through;
        }
    }
}

// A wall stands between a and b when the line joining their centres passes through it (neither centre
// in it, neither a nor b an opening in it) and the way round the walls is longer than that line by more
// than `reach`: a wall between two rooms parts what stands on either side of it, but the pillar between
// two benches along one wall, or the corner of an L-shaped room, does not.
bool wallBetween(const Node& a, const Node& b, double reach, const Thresholds& t, const Obstacles& obstacles) {
    model::Aabb span = obstacles.bounds(a);
    const model::Aabb other = obstacles.bounds(b);
    span.min = {std::min(span.min.x, other.min.x), std::min(span.min.y, other.min.y),
                std::min(span.min.z, other.min.z)};
    span.max = {std::max(span.max.x, other.max.x), std::max(span.max.y, other.max.y),
                std::max(span.max.z, other.max.z)};
    auto inTheWay = [&](const Node* w) {
        return w->id != a.id && w->id != b.id && isVerticalPlane(*w) && !pointInBox(centre(a), w->box) &&
               !pointInBox(centre(b), w->box) && !openingIn(a, *w, t) && !openingIn(b, *w, t);
    };
    std::vector<const Node*> walls;
    obstacles.wallsWithin(span, walls);
    if (std::none_of(walls.begin(), walls.end(),
                     [&](const Node* w) { return segmentCrosses(centre(a), centre(b), w->box) && inTheWay(w); }))
        return false;
    // The walls a way round may pass: those within reach of the two.
    walls.clear();
    obstacles.wallsWithin(grown(span, reach), walls);
    std::erase_if(walls, [&](const Node* w) { return !inTheWay(w); });
    const double straight = std::hypot(centre(a).x - centre(b).x, centre(a).y - centre(b).y);
    return wayRound(centre(a), centre(b), walls, straight + reach) > straight + reach;
}

// What stands around x for near's crowding: another object of x's kind, visible, that x does not rest on or
// in and that does not rest on or in x (the sofa under a cushion, the cushion on a chair are x's own). A
// crowd is of like things (cushions in a row, chairs side by side): the table two chairs stand at, or a
// picture on the wall behind one, does not keep them from being near each other.
bool neighbourOf(const Node& x, const Node& c, const Thresholds& t) {
    if (c.id == x.id || c.hidden || c.kind != model::NodeKind::Object || !hasGeometry(c)) return false;
    if (!sameCategory(c.category, x.category)) return false;
    if (supportScore(x, c, t) > 0 || supportScore(c, x, t) > 0) return false;
    return model::fractionInside(x.box, c.box) < t.inMinInside && model::fractionInside(c.box, x.box) < t.inMinInside;
}

// In a crowded spot a person calls near what is nearest: b is crowded out of a's nearness when other
// things of a's kind stand closer to a than b does by more than near.min_distance, and things of b's kind
// closer to b than a does (neighbourOf).
bool crowdedOut(const Node& a, const Node& b, double gap, const Thresholds& t, const Obstacles& obstacles) {
    const double closer = gap - t.nearMinDistance;
    if (closer <= 0) return false;
    auto surrounded = [&](const Node& x, const Node& other) {
        std::vector<const Node*> around;
        obstacles.within(grown(obstacles.bounds(x), closer), around);
        return std::any_of(around.begin(), around.end(), [&](const Node* c) {
            return c->id != other.id && neighbourOf(x, *c, t) && model::distance(x.box, c->box) < closer;
        });
    };
    return surrounded(a, b) && surrounded(b, a);
}

// near with a written distance (near(window, 1.5 m)) is that distance and the walls; near without one is
// at the two things' scale and gives way to nearer things in a crowd.
double nearScore(const PredicateInputs& in) {
    double limit = nearLimit(in.a, in.b, in.t, in.writtenDistance);
    double d = model::distance(in.a.box, in.b.box);
    if (d > limit || wallBetween(in.a, in.b, limit, in.t, in.obstacles)) return 0.0;
    if (!in.writtenDistance && crowdedOut(in.a, in.b, d, in.t, in.obstacles)) return 0.0;
    return limit > 0 ? std::max(0.01, 1.0 - d / limit) : 1.0;
}

// Whether `a` is on something (on's own rule, the floor included): the nodes whose boxes reach the band just under
// a's bottom are the ones on can hold for.
bool restsOnSomething(const PredicateInputs& in) {
    model::Aabb under = in.obstacles.bounds(in.a);
    under.max.z = under.min.z + in.t.aboveTolerance;
    under.min.z -= in.t.onMaxGap;
    std::vector<const Node*> below;
    in.obstacles.within(under, below);
    return std::any_of(below.begin(), below.end(), [&](const Node* n) {
        return n->id != in.a.id && !isVerticalPlane(*n) &&
               evaluate(Predicate::On, in.a, *n, in.t, in.frame, in.obstacles) > 0;
    });
}

double attachedScore(const PredicateInputs& in) {
    const bool fromCeiling = isCeiling(in.b) && !isVerticalPlane(in.a) && in.a.kind == model::NodeKind::Object;
    if (!isVerticalPlane(in.a) && !isVerticalPlane(in.b) && !sameCategory(in.b.category, "pillar") && !fromCeiling)
        return 0.0;
    // What hangs from a ceiling (a light, a vent, a fan) has its bottom in the room's upper half (the floor at z = 0):
    // a wardrobe whose top meets the ceiling stands on the floor.
    if (fromCeiling && model::bottom(in.a.box) < model::bottom(in.b.box) / 2) return 0.0;
    // What a wall holds hangs there: a sofa pushed against the wall stands on the floor beside it (its bottom at
    // the wall's foot), a microwave on a counter against it is on the counter. A flat thing upright against the
    // wall (a picture just over a sofa's back) hangs whatever is under it (on asks the wall first: wallHolding).
    // What stands on tops and is no hung slab (a mug, a book) rests on a top the scene may not hold.
    if (!isVerticalPlane(in.a) && sameCategory(in.b.category, kWall) &&
        (model::bottom(in.a.box) < model::bottom(in.b.box) + in.t.attachedMinRise ||
         (!hungShape(in.a.box) && (usualSupport(in.a.category) == Support::Surface || restsOnSomething(in)))))
        return 0.0;
    double d = model::distance(in.a.box, in.b.box);
    double limit = in.t.attachedMaxGap;
    return d <= limit ? std::max(0.01, 1.0 - d / std::max(limit, 1e-3)) : 0.0;
}

double leftOfScore(const PredicateInputs& in) {
    return offsetScore(dot(centreOffset(in.a, in.b), in.frame.right), in.t.lateralMinOffset);
}
double rightOfScore(const PredicateInputs& in) {
    return offsetScore(dot(centreOffset(in.b, in.a), in.frame.right), in.t.lateralMinOffset);
}
double inFrontOfScore(const PredicateInputs& in) {
    return offsetScore(dot(centreOffset(in.a, in.b), in.frame.forward), in.t.lateralMinOffset);
}
double behindScore(const PredicateInputs& in) {
    return offsetScore(dot(centreOffset(in.b, in.a), in.frame.forward), in.t.lateralMinOffset);
}

double betweenScore(const PredicateInputs& in) {
    if (!in.c || !hasGeometry(*in.c)) return 0.0;
    // What stands on, in or under one of the two (the lamp on a nightstand: its centre over the
    // nightstand's footprint) is at it, not between them.
    const model::Vec2 centre{in.a.box.center.x, in.a.box.center.y};
    if (model::footprintContains(in.b.box, centre) || model::footprintContains(in.c->box, centre)) return 0.0;
    model::Vec2 seg = centreOffset(in.b, *in.c);
    double len2 = dot(seg, seg);
    if (len2 <= 1e-9) return 0.0;
    model::Vec2 rel = centreOffset(in.b, in.a);
    double along = dot(rel, seg) / len2;
    if (along <= 0 || along >= 1) return 0.0;
    double px = rel.x - along * seg.x, py = rel.y - along * seg.y;
    double off = std::sqrt(px * px + py * py);
    double limit = in.t.betweenMaxOffset;
    if (off <= limit) return std::max(0.01, 1.0 - off / std::max(limit, 1e-3));
    // A large thing whose centre is off the line still lies between when the line between the two
    // crosses its footprint (the bed between the nightstands at its head).
    constexpr int kSamples = 32;
    for (int k = 1; k < kSamples; ++k) {
        double f = static_cast<double>(k) / kSamples;
        model::Vec2 point{in.b.box.center.x + f * seg.x, in.b.box.center.y + f * seg.y};
        if (model::footprintContains(in.a.box, point)) return 0.01;
    }
    return 0.0;
}

// visible_from(a, x): from an eye at x, enough of a's sample points are in sight. With a heading
// (VIEW FROM .. FACING ..) only what lies within kHalfFieldOfView of it counts.
constexpr double kHalfFieldOfView = M_PI / 3;  // a person's 120 degrees of binocular field

double visibleFromScore(const PredicateInputs& in) {
    model::Vec3 eye = eyeAt(in.b.box);
    std::vector<const Node*> obstacles;
    model::Aabb span = in.obstacles.bounds(in.a);
    span.min = {std::min(span.min.x, eye.x), std::min(span.min.y, eye.y), std::min(span.min.z, eye.z)};
    span.max = {std::max(span.max.x, eye.x), std::max(span.max.y, eye.y), std::max(span.max.z, eye.z)};
    in.obstacles.within(span, obstacles);
    std::optional<ViewCone> cone;
    if (in.frame.headingGiven)
        cone = ViewCone{{in.frame.forward.x, in.frame.forward.y, 0},
                        {in.frame.right.x, in.frame.right.y, 0},
                        {0, 0, 1},
                        std::tan(kHalfFieldOfView),
                        std::numeric_limits<double>::infinity()};
    double share = visibleShare(eye, in.a, obstacles, cone ? &*cone : nullptr, &in.b);
    return share > 0 && share >= in.t.visibleMinShare ? share : 0.0;
}

// Sr3D's sections of a thing with a front widen by 10 degrees on each side beyond its sides.
const double kSectionFlare = std::tan(10.0 * model::kDegree);

// Where `point` lies in box's own frame: `ahead` beyond its front face (negative: behind its back
// face), `aside` beyond the section's flared side (<= 0: within the section).
struct SectionPlace {
    double ahead;
    double aside;
};
SectionPlace placeInFront(const Box& box, model::Vec2 point, double direction) {
    model::Vec2 front = frontDirection(box);
    model::Vec2 left{-front.y, front.x};
    model::Vec2 d{point.x - box.center.x, point.y - box.center.y};
    double along = direction * dot(d, front) - box.size.x / 2;
    double lateral = std::abs(dot(d, left));
    return {along, lateral - box.size.y / 2 - kSectionFlare * std::max(0.0, along)};
}

// facing(a, b): a has a front, b's centre lies ahead of a's front face, and b's footprint reaches
// into a's front section: a corner inside it, or corners on both sides of a's front axis (a chair
// at the end of a long table faces the table).
double facingScore(const PredicateInputs& in) {
    if (!hasFront(in.a.category)) return 0.0;
    SectionPlace middle = placeInFront(in.a.box, {in.b.box.center.x, in.b.box.center.y}, 1.0);
    if (middle.ahead <= 0) return 0.0;
    model::Vec2 front = frontDirection(in.a.box);
    bool inside = false, leftSide = false, rightSide = false;
    for (model::Vec2 corner : model::footprint(in.b.box)) {
        SectionPlace p = placeInFront(in.a.box, corner, 1.0);
        inside |= p.ahead > 0 && p.aside <= 0;
        double side = front.x * (corner.y - in.a.box.center.y) - front.y * (corner.x - in.a.box.center.x);
        leftSide |= side > 0;
        rightSide |= side < 0;
    }
    if (!inside && !(leftSide && rightSide)) return 0.0;
    // Straight ahead scores 1; the score falls as b's centre moves out of the section.
    return 1.0 / (1.0 + std::max(0.0, middle.aside));
}

// at_front_of(a, b) / at_back_of(a, b): b has a front, a's centre lies in b's front (back) section
// and a is near b.
double sectionScore(const PredicateInputs& in, double direction) {
    if (!hasFront(in.b.category)) return 0.0;
    SectionPlace p = placeInFront(in.b.box, {in.a.box.center.x, in.a.box.center.y}, direction);
    if (p.ahead <= 0 || p.aside > 0) return 0.0;
    return nearScore(in);
}
double atFrontOfScore(const PredicateInputs& in) { return sectionScore(in, 1.0); }
double atBackOfScore(const PredicateInputs& in) { return sectionScore(in, -1.0); }

// Where a must be when on(a, ref) / in(a, ref) holds: a's footprint overlaps ref's and a's bottom is at
// most on.max_gap above ref's top.
model::Aabb restingOnRegion(const model::Aabb& ref, double, const Thresholds& t) {
    model::Aabb b = ref;
    b.max.z += t.onMaxGap;
    return b;
}
// Where the support must be for on(a, b) / in(a, b): its footprint overlaps a's and its top reaches
// to within on.max_gap of a's bottom.
model::Aabb supportRegion(const model::Aabb& a, double, const Thresholds& t) {
    model::Aabb b = a;
    b.min.z -= t.onMaxGap;
    b.max.z = kUnbounded;
    return b;
}
// The column over a box and the column under it. What rests on a box may sink into its top, so the column over it
// starts at its bottom (restingOnRegion's), and the one under a box reaches up as far as supportRegion's: the whole
// column.
model::Aabb columnAbove(const model::Aabb& around, double, const Thresholds&) {
    model::Aabb b = around;
    b.max.z = kUnbounded;
    return b;
}
model::Aabb columnBelow(const model::Aabb& around, double, const Thresholds&) {
    model::Aabb b = around;
    b.min.z = -kUnbounded;
    b.max.z = kUnbounded;
    return b;
}
model::Aabb withinNear(const model::Aabb& around, double nearDistance, const Thresholds&) {
    return grown(around, nearDistance);
}
model::Aabb withinAttached(const model::Aabb& around, double, const Thresholds& t) {
    return grown(around, t.attachedMaxGap);
}

using P = Predicate;
// One row per predicate, in code order (model::RelationType). Columns: predicate, alias, arity,
// view-relative, takes a distance, formula, candidate region, reference region, RELATE rank, usage,
// and the English phrases that ask for it (ASK's only list of them, '|' between phrases).
constexpr PredicateSpec kPredicates[] = {
    {P::On, "", 1, false, false, onScore, restingOnRegion, supportRegion, 2, "on(desk)",
     "on|on top of|onto|upon|atop|sitting on|lying on|resting on|standing on|placed on|kept on|piled on|supported "
     "by",
     Occluders::WallsOrAllWhenSpreading},
    {P::In, "inside", 1, false, false, inScore, restingOnRegion, supportRegion, 1, "in(cabinet)",
     "in|inside|inside of|within|stored in|kept in|contained in|into|built into|built in to", Occluders::Walls},
    {P::Above, "", 1, false, false, aboveScore, columnAbove, columnBelow, 4, "above(bed)", "above|over|higher than",
     Occluders::WallsOrAllWhenSpreading},
    {P::Below, "under", 1, false, false, belowScore, columnBelow, columnAbove, 5, "below(lamp)",
     "below|under|underneath|beneath|lower than", Occluders::WallsOrAllWhenSpreading},
    {P::Near, "", 1, false, true, nearScore, withinNear, withinNear, 14, "near(sofa) or near(sofa, 1.5 m)",
     "near|near to|nearby|close to|next to|beside|by|around|adjacent to|alongside|along|"
     "close by|against|at|surrounding|surround|surrounds|touching|touches|"
     "on either side of|on both sides of|on each side of|either side of|flanking",
     Occluders::All},
    {P::Attached, "", 1, false, false, attachedScore, withinAttached, withinAttached, 3, "attached(wall)",
     "attached to|fixed to|mounted on|hanging on|hanging from|hanging off|hung on|hangs on|hang on"},
    {P::LeftOf, "", 1, true, false, leftOfScore, nullptr, nullptr, 6, "left_of(window)",
     "left of|to the left of|on the left of|on the left side of|at the left of"},
    {P::RightOf, "", 1, true, false, rightOfScore, nullptr, nullptr, 7, "right_of(window)",
     "right of|to the right of|on the right of|on the right side of|at the right of"},
    {P::InFrontOf, "", 1, true, false, inFrontOfScore, nullptr, nullptr, 8, "in_front_of(sofa)", "in front of"},
    {P::Behind, "", 1, true, false, behindScore, nullptr, nullptr, 9, "behind(sofa)", "behind|in back of|beyond"},
    {P::Between, "", 2, false, false, betweenScore, nullptr, nullptr, 0,
     "between(lamp, sofa): the target lies between the two", "between|in between"},
    {P::VisibleFrom, "", 1, false, false, visibleFromScore, nullptr, nullptr, 0,
     "visible_from(door): in sight of an eye standing at the door",
     "visible from|seen from|in sight of|in view of|in sight from|seeable from", Occluders::All},
    {P::Facing, "", 1, false, false, facingScore, nullptr, nullptr, 11, "facing(table): its front faces the table",
     "facing|face|faces|facing toward|facing towards|turned toward|turned towards|pointing at|pointed at|looking at|"
     "across from|across the room from|opposite|opposite to|opposite of"},
    {P::AtFrontOf, "", 1, false, false, atFrontOfScore, withinNear, withinNear, 12,
     "at_front_of(sofa): by the sofa's own front", "at the front of|at the foot of|at the end of", Occluders::All},
    {P::AtBackOf, "", 1, false, false, atBackOfScore, withinNear, withinNear, 13,
     "at_back_of(sofa): by the sofa's own back", "at the back of|at the head of|behind the back of", Occluders::All},
};

constexpr bool rowsInCodeOrder() {
    for (std::size_t i = 0; i < std::size(kPredicates); ++i)
        if (static_cast<std::size_t>(kPredicates[i].predicate) != i) return false;
    return true;
}
static_assert(std::size(kPredicates) == model::kRelationTypeCount,
              "every relation type in model/types.hpp needs its row in kPredicates");
static_assert(rowsInCodeOrder(), "kPredicates rows must follow model::RelationType's order");

// RELATE's order, derived once from the ranks.
std::vector<const PredicateSpec*> relateOrder() {
    std::vector<const PredicateSpec*> out;
    for (const auto& row : kPredicates)
        if (row.relateRank > 0) out.push_back(&row);
    std::sort(out.begin(), out.end(), [](const auto* a, const auto* b) { return a->relateRank < b->relateRank; });
    return out;
}

}  // namespace

std::span<const PredicateSpec> predicates() { return kPredicates; }

std::span<const std::string_view> spreadingKinds() { return kSpreading; }

const PredicateSpec& spec(Predicate p) { return kPredicates[static_cast<std::size_t>(p)]; }

const PredicateSpec* predicateNamed(std::string_view word) {
    for (const auto& row : kPredicates)
        if (row.name() == word || (!row.alias.empty() && row.alias == word)) return &row;
    return nullptr;
}

std::vector<std::string> predicateWords() {
    std::vector<std::string> out;
    for (const auto& row : kPredicates) {
        out.emplace_back(row.name());
        if (!row.alias.empty()) out.emplace_back(row.alias);
    }
    return out;
}

std::vector<std::string_view> englishPhrases(const PredicateSpec& spec) {
    std::vector<std::string_view> out;
    for (std::string_view rest = spec.phrases; !rest.empty();) {
        std::size_t bar = rest.find('|');
        out.push_back(rest.substr(0, bar));
        rest = bar == std::string_view::npos ? std::string_view{} : rest.substr(bar + 1);
    }
    return out;
}

double nearLimit(const Node& a, const Node& b, const Thresholds& t, std::optional<double> writtenDistance) {
    if (writtenDistance) return *writtenDistance;
    auto size = [](const Node& n) { return std::max(n.box.size.x, n.box.size.y); };
    return std::min(t.nearDistance, std::max(t.nearMinDistance, size(a) + size(b)));
}

double evaluate(Predicate p, const Node& a, const Node& b, const Thresholds& t, const Frame& frame,
                const Obstacles& obstacles, const Node* c, std::optional<double> writtenDistance) {
    if (!hasGeometry(a) || !hasGeometry(b) || a.id == b.id) return 0.0;
    return spec(p).evaluate({a, b, c, t, frame, writtenDistance, obstacles});
}

namespace {

// The radius of the largest ball about a box's centre that lies in it (its smallest half side),
// or NaN for a box whose sides are not all finite and positive, so that no test passes on it.
double inscribedRadius(const Box& box) {
    const model::Vec3& s = box.size;
    if (!(std::isfinite(s.x) && std::isfinite(s.y) && std::isfinite(s.z)) || s.x <= 0 || s.y <= 0 || s.z <= 0)
        return std::numeric_limits<double>::quiet_NaN();
    return std::min(s.x, std::min(s.y, s.z)) / 2;
}

// Whether the two boxes are surely within `limit` of each other: the points on the line between
// the centres where it leaves each inscribed ball lie in the boxes, so their gap is at least the
// boxes' distance. A nanometre of slack covers the rounding of both this and model::distance, so
// what this accepts model::distance puts within the limit too.
bool surelyWithin(const Box& a, const Box& b, double limit) {
    const double apart = model::centerDistance(a, b) - inscribedRadius(a) - inscribedRadius(b);
    return apart <= limit - 1e-9;  // false for a NaN centre or size: the exact test decides
}

// Whether bounds a lie within b on the floor plane.
bool flatWithin(const model::Aabb& a, const model::Aabb& b) {
    return a.min.x >= b.min.x && a.max.x <= b.max.x && a.min.y >= b.min.y && a.max.y <= b.max.y;
}

// Whether a's footprint lies within b's: then their overlap is a's own area, and the clipping of
// the one by the other (model::footprintOverlap) gives that area up to its rounding.
bool footprintWithin(const Box& a, const Box& b) {
    const model::BoxFrame frame(b);
    const auto corners = model::footprint(a);
    return std::all_of(corners.begin(), corners.end(), [&](model::Vec2 p) { return frame.contains(p); });
}

}  // namespace

bool holds(Predicate p, const Node& a, const Node& b, const Thresholds& t, const Frame& frame,
           const Obstacles& obstacles, const Node* c, std::optional<double> writtenDistance) {
    if (p == Predicate::On && hasGeometry(a) && hasGeometry(b) && a.id != b.id) {
        const model::Aabb boundsA = obstacles.bounds(a), boundsB = obstacles.bounds(b);
        // The footprints lie within their bounds, so a's overlaps b's no more than the bounds do:
        // short of on's share by more than any rounding, on fails without clipping the two.
        // (A spreading kind's box as low as its carrier is judged by restsWithinItsBound, not by that share.)
        const double own = model::footprintArea(a.box);
        if (own > 0 && flatOverlap(boundsA, boundsB) / own < t.onMinOverlap - 1e-6 &&
            (model::bottom(b.box) < model::bottom(a.box) || !listed(kSpreading, a.category)))
            return false;
        // A footprint within x's: the overlap is a's area, so on's overlap shares are 1 or more, and
        // a threshold at least a millionth under 1 decides the same with it as with the clipped
        // area, whose rounding is far smaller; the rest of on's formula runs as written. Such a
        // footprint has bounds within x's, so the corners are compared only when those are.
        if (t.onMinOverlap <= 1 - 1e-6 && flatWithin(boundsA, boundsB) && footprintWithin(a.box, b.box)) {
            const PredicateInputs in{a, b, c, t, frame, writtenDistance, obstacles};
            return onScoreWith(in, [&] { return model::footprintArea(a.box); }) > 0;
        }
    }
    // near(x, d): within d and no wall between (nearScore, which is then positive). Without a
    // written distance near also gives way in a crowd, which the exact score decides.
    if (p == Predicate::Near && writtenDistance && *writtenDistance >= 0 && hasGeometry(a) && hasGeometry(b) &&
        a.id != b.id && surelyWithin(a.box, b.box, *writtenDistance))
        return !wallBetween(a, b, *writtenDistance, t, obstacles);
    return evaluate(p, a, b, t, frame, obstacles, c, writtenDistance) > 0;
}

const Node* wallHolding(const Node& a, const Obstacles& obstacles, const Thresholds& t) {
    if (!hungShape(a.box)) return nullptr;
    std::vector<const Node*> walls;
    obstacles.wallsWithin(spec(Predicate::Attached).referenceRegion(obstacles.bounds(a), 0, t), walls);
    static const Frame frame{};
    const Node* best = nullptr;
    double bestScore = 0;
    for (const Node* wall : walls) {
        if (!isVerticalPlane(*wall)) continue;
        const double score = evaluate(Predicate::Attached, a, *wall, t, frame, obstacles);
        if (score > bestScore) bestScore = score, best = wall;
    }
    return best;
}

std::vector<RelationHit> relate(const Node& a, const Node& b, const Thresholds& t, const Frame& frame,
                                const Obstacles& obstacles) {
    static const auto order = relateOrder();
    std::vector<RelationHit> hits;
    for (const auto* row : order) {
        double score = evaluate(row->predicate, a, b, t, frame, obstacles);
        if (score > 0) hits.push_back({row->predicate, score});
    }
    return hits;
}

void Obstacles::wallsWithin(const model::Aabb& region, std::vector<const Node*>& out) const {
    const std::size_t first = out.size();
    within(region, out);
    out.erase(std::remove_if(out.begin() + static_cast<std::ptrdiff_t>(first), out.end(),
                             [](const Node* n) { return !sameCategory(n->category, kWall); }),
              out.end());
}

void NodeObstacles::within(const model::Aabb& region, std::vector<const Node*>& out) const {
    for (const Node& n : nodes_)
        if (hasGeometry(n) && intersects(model::worldAabb(n.box), region)) out.push_back(&n);
}

}  // namespace smql::relations
