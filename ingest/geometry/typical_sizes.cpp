#include "ingest/geometry/typical_sizes.hpp"

#include <algorithm>

#include "relations/predicates.hpp"

namespace smql::ingest {

using relations::Support;
using relations::usualSupport;

namespace {

// Heights: the common standard sizes (a dining table's top at 28-30 in, a door 80 in), above what the kind stands
// on (the floor; for things that stand on tables, the table's top), only where the kind varies by a tenth or so (0: it
// varies more). A monitor's 0.44 m above its desk is the median of ScanNet's 45 labelled monitors in ../shared's real
// rooms along their boxes' upright axes (a tenth under 0.36 m, a tenth over 0.53): looser than a tenth, yet it is the
// one measure of a desk whose floor does not show besides the cameras' assumed height, which is looser still there
// (scale_priors.hpp: scaleFromHeightsOnTop). Extents: the largest side, height included, things of the kind
// commonly have (a floor lamp's 1.9 m, a bookcase's 2.2 m): what a box named so may reach before its name is doubted.
// What things of the kind usually stand on is the relations library's (relations::usualSupport, shared with the
// predicates); whether things are put on the kind's top (a table's, a bed's) tells a floor from a table top with it
// (floor_evidence.hpp). Upright
// ends: the kind has a thin upright part at an end or side (a bed's headboard, a sofa's back) that a detector may name
// apart (object_fusion.cpp joins it back). Room: the one kind of room the kind stands in (a toilet in a bathroom, a
// fridge or an oven in a kitchen), or any but a bathroom (a bed, a sofa); object_fusion.cpp doubts a name among
// another room's things. Role: what the kind is for where fusion judges a thing by it (typical_sizes.hpp: Role).
// Least: the largest side and the height no thing of the kind comes under (typical_sizes.hpp: LeastSize), where real
// rooms' labels show it; Slender: a footprint too long for its depth for the kind (typical_sizes.hpp). Tallest: the
// height no thing of the kind stands over, above what it stands on, where its make bounds it (a laptop: the lid of the
// largest, a 17.3-inch 16:9 panel 0.215 m tall in a lid of about 0.27 m, opened upright on a base of 2-3 cm stands
// about 0.3 m; 0.35 leaves a depth camera's few centimetres). Deepest: the footprint's shorter side no thing of the
// kind exceeds, where its make bounds it (typical_sizes.hpp: deepestFootprint); shallowest: the one no thing of the
// kind comes under, and shallowShare: the share of its longer side no thing of the kind's is shallower than
// (typical_sizes.hpp: shallowestFootprint); lowest top: the height over the floor no thing of the kind has its top
// under (typical_sizes.hpp: lowestTop). Thinnest: the side no thing of the kind is thinner
// than, where it is flat by make and thinner than a share of its extent (typical_sizes.hpp: thinnestSide). The rows
// cover the memory's names for the detector's COCO classes (detector.cpp) and the kinds of labelled captures.
struct Typical {
    std::string_view category;
    double height;
    double extent;
    bool holdsThings = false;
    bool uprightEnds = false;
    RoomKind room = RoomKind::Any;
    Role role = Role::Other;
    LeastSize least{};
    Slender slender{};
    double tallest = 0;
    double deepest = 0;
    double shallowest = 0;
    double thinnest = 0;
    double shallowShare = 0;
    double lowestTop = 0;
};
// The thinnest side of a kind not flat by make, as a share of its extent (thinnestSide).
constexpr double kThinShare = 0.06;
// The kinds whose shapes are held to more than a footprint's length and depth (typical_sizes.hpp: Slender).
constexpr Slender kChairShape{
    .length = 0.75, .depth = 0.2, .longLength = 0.9, .longDepth = 0.35, .postHeight = 0.4, .postSide = 0.25};
constexpr LeastSize kFridgeLeast{0.5, 0.45};
constexpr Slender kFridgeShape{.length = 0.9, .depth = 0.25, .frontHeight = 1.1};
constexpr Slender kTableShape{.length = 0.75, .depth = 0.25};
constexpr Slender kBedShape{.length = 1.0, .depth = 0.8, .frontHeight = 1.0};
constexpr Typical kTypical[] = {
    {"table", 0.75, 2.4, true, false, RoomKind::Any, Role::Other, {}, kTableShape},
    {"desk", 0.75, 1.9, true, false, RoomKind::Dry, Role::Other, {}, kTableShape},
    {"chair", 0.9, 1.2, false, false, RoomKind::Dry, Role::Seat, {}, kChairShape, 0, 0, 0.33, 0, 0.65},
    {"sofa", 0.85, 2.8, false, true, RoomKind::Dry, Role::Seat, {0, 0.35}, {1.0, 0.3}},
    {"bed", 0.55, 2.3, true, true, RoomKind::Dry, Role::Other, {1.2, 0}, kBedShape},
    {"fridge", 1.75, 2.0, false, false, RoomKind::Kitchen, Role::Other, kFridgeLeast, kFridgeShape, 0, 1.2},
    {"toilet", 0.75, 0.9, false, false, RoomKind::Bathroom, Role::Other, {0.45, 0.35}},
    {"door", 2.03, 2.4},
    {"nightstand", 0.6, 0.8, true},
    {"shelf", 0, 2.4},
    {"cabinet", 0, 2.4},
    {"counter", 0, 4.0, true},
    {"wardrobe", 0, 2.6},
    {"dresser", 0, 1.9},
    {"armchair", 0, 1.2, false, false, RoomKind::Dry, Role::Seat},
    {"stool", 0, 0.9, false, false, RoomKind::Any, Role::Seat},
    {"bench", 0, 2.2, false, true, RoomKind::Any, Role::Seat},
    {"tv", 0, 2.0, false, false, RoomKind::Any, Role::Other, {}, {}, 0, 0, 0, 0.025},
    {"monitor", 0.44, 0.9, false, false, RoomKind::Any, Role::Other, {}, {}, 0, 0, 0, 0.015},
    {"box", 0, 1.0, false, false, RoomKind::Any, Role::Luggage},
    {"camera", 0, 0.3},
    {"lamp", 0, 2.0},
    {"plant", 0, 2.2},
    {"cushion", 0, 0.8},
    {"laptop", 0, 0.5, false, false, RoomKind::Any, Role::Other, {}, {}, 0.35, 0, 0, 0.01},
    {"book", 0, 0.5, false, false, RoomKind::Any, Role::Other, {}, {}, 0, 0, 0, 0.01},
    {"clock", 0, 0.6},
    {"vase", 0, 0.8},
    {"bowl", 0, 0.45},
    {"bottle", 0, 0.45},
    {"mug", 0, 0.2},
    {"microwave", 0, 0.7, false, false, RoomKind::Kitchen},
    {"sink", 0, 1.2, false, false, RoomKind::Any, Role::Basin, {}, {}, 0, 0, 0, 0, 0, 0.7},
    {"oven", 0, 1.0, false, false, RoomKind::Kitchen},
    {"keyboard", 0, 0.55, false, false, RoomKind::Any, Role::Other, {}, {}, 0, 0, 0, 0.01},
    {"backpack", 0, 0.65},
    {"umbrella", 0, 1.2},
    {"handbag", 0, 0.55},
    {"suitcase", 0, 0.9, false, false, RoomKind::Any, Role::Luggage},
    {"sports_ball", 0, 0.35},
    {"tennis_racket", 0, 0.75},
    {"wine_glass", 0, 0.3},
    {"fork", 0, 0.3},
    {"knife", 0, 0.4},
    {"spoon", 0, 0.3},
    {"banana", 0, 0.3},
    {"apple", 0, 0.15},
    {"orange", 0, 0.15},
    {"sandwich", 0, 0.3},
    {"broccoli", 0, 0.35},
    {"carrot", 0, 0.35},
    {"hot_dog", 0, 0.3},
    {"pizza", 0, 0.55},
    {"donut", 0, 0.2},
    {"cake", 0, 0.5},
    {"mouse", 0, 0.2},
    {"remote", 0, 0.3, false, false, RoomKind::Any, Role::Other, {}, {}, 0, 0, 0, 0.01},
    {"phone", 0, 0.25, false, false, RoomKind::Any, Role::Other, {}, {}, 0, 0, 0, 0.006},
    {"toaster", 0, 0.5, false, false, RoomKind::Kitchen},
    {"scissors", 0, 0.35, false, false, RoomKind::Any, Role::Other, {}, {}, 0, 0, 0, 0.006},
    {"toy", 0, 1.0},
    {"hair_dryer", 0, 0.4},
    {"toothbrush", 0, 0.3},
    {"skateboard", 0, 0.9},
};

const Typical* find(std::string_view category) {
    for (const auto& t : kTypical)
        if (t.category == category) return &t;
    return nullptr;
}

// A column the table gives for some kinds only (above zero there), nullopt for the others and for kinds it lacks.
std::optional<double> given(std::string_view category, double Typical::*column) {
    const Typical* t = find(category);
    if (!t || t->*column <= 0) return std::nullopt;
    return t->*column;
}

}  // namespace

std::optional<double> typicalHeight(std::string_view category) {
    const Typical* t = find(category);
    if (!t || t->height <= 0 || usualSupport(t->category) == Support::Surface) return std::nullopt;
    return t->height;
}

std::optional<double> typicalHeightOnTop(std::string_view category) {
    const Typical* t = find(category);
    if (!t || t->height <= 0 || usualSupport(t->category) != Support::Surface) return std::nullopt;
    return t->height;
}

std::optional<double> typicalExtent(std::string_view category) {
    const Typical* t = find(category);
    if (!t) return std::nullopt;
    return t->extent;
}

std::optional<double> tallestHeight(std::string_view category) { return given(category, &Typical::tallest); }

std::optional<double> deepestFootprint(std::string_view category) { return given(category, &Typical::deepest); }

std::optional<double> lowestTop(std::string_view category) { return given(category, &Typical::lowestTop); }

std::optional<double> shallowestFootprint(std::string_view category, double width) {
    const Typical* t = find(category);
    if (!t || t->shallowest <= 0) return std::nullopt;
    return std::max(t->shallowest, t->shallowShare * width);
}

std::optional<double> thinnestSide(std::string_view category) {
    const Typical* t = find(category);
    if (!t) return std::nullopt;
    return t->thinnest > 0 ? t->thinnest : kThinShare * t->extent;
}

bool madeFlat(std::string_view category) { return given(category, &Typical::thinnest).has_value(); }

std::optional<LeastSize> leastSize(std::string_view category) {
    const Typical* t = find(category);
    if (!t || (t->least.largest <= 0 && t->least.height <= 0)) return std::nullopt;
    return t->least;
}

bool smallerThanKind(std::string_view category, double largest, double height, double bottom) {
    const auto least = leastSize(category);
    return least && (largest < least->largest || (bottom <= kStandingReach && height < least->height));
}

bool slenderForKind(std::string_view category, double longer, double shorter, double height) {
    const Typical* t = find(category);
    if (!t) return false;
    const Slender& s = t->slender;
    const bool thin = (s.length > 0 && longer >= s.length && shorter < s.depth) ||
                      (s.longLength > 0 && longer >= s.longLength && shorter < s.longDepth);
    return (thin && (s.frontHeight <= 0 || height < s.frontHeight)) ||
           (s.postHeight > 0 && height >= s.postHeight && longer < s.postSide);
}

bool standsSquare(std::string_view category) {
    const Typical* t = find(category);
    return t && usualSupport(t->category) == Support::Floor && oneRoom(t->room);
}

bool holdsThings(std::string_view category) {
    const Typical* t = find(category);
    return t && t->holdsThings;
}

bool carries(std::string_view carrier, std::string_view thing) {
    return usualSupport(thing) == Support::Surface && holdsThings(carrier);
}

bool oneCarriesTheOther(std::string_view a, std::string_view b) { return carries(a, b) || carries(b, a); }

bool hasUprightEnds(std::string_view category) {
    const Typical* t = find(category);
    return t && t->uprightEnds;
}

std::string_view kindName(std::string_view category) {
    static constexpr std::pair<std::string_view, std::string_view> kNamedAlike[] = {{"desk", "table"},
                                                                                    {"monitor", "tv"}};
    for (const auto& [name, kind] : kNamedAlike)
        if (category == name) return kind;
    return category;
}

Role role(std::string_view category) {
    const Typical* t = find(category);
    return t ? t->role : Role::Other;
}

RoomKind roomKind(std::string_view category) {
    const Typical* t = find(category);
    return t ? t->room : RoomKind::Any;
}

}  // namespace smql::ingest
