// What things of a kind usually measure, in metres: the one table of sizes the
// ingest knows. They check, never answer: the scale priors take the heights of
// the kinds whose height varies little; the plausibility checks and the names
// of fused things hold boxes to their kind's extent, and doubt a name in another kind's room.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

namespace smql::ingest {

// A standing thing's usual height above the floor in metres (its top), for the
// kinds whose height varies little: nullopt for the others, and for things that stand on tables.
std::optional<double> typicalHeight(std::string_view category);

// A thing's usual height above the table, desk or counter top it stands on (relations::usualSupport: Surface), for the
// kinds whose height varies little: nullopt for the others. It measures a capture whose floor does not show, its
// lowest surface a table top (scale_priors.hpp: scaleFromHeightsOnTop).
std::optional<double> typicalHeightOnTop(std::string_view category);

// The largest side (height included) things of a kind commonly have, in metres; nullopt for kinds
// the table lacks. A box named so that is several times longer is not that thing, or the
// capture's scale is wrong (plausibility.hpp).
std::optional<double> typicalExtent(std::string_view category);

// The height no thing of a kind stands over, above what it stands on, where the kind's make bounds it (a laptop's
// open lid); nullopt for the others. A desk's monitor seen with its keyboard in front is often detected as a
// "laptop": at 0.41-0.48 m tall, it is not one (TUM fr1/rpy's monitors: 0.41 m from the depth frames, 0.45-0.48 m
// lifted on ten colour frames' dense points).
std::optional<double> tallestHeight(std::string_view category);

// The footprint's shorter side no thing of a kind exceeds, where the kind's make bounds its depth (a fridge's, whose
// largest side, its height, bounds nothing under it); nullopt for the others. Of ScanNet's 243 labelled fridges (its
// training and validation scans) none is deeper than 1.00 m; of the real layouts' 39 (ScanNet's 15 and ARKitScenes'
// 24) none than 0.79 m. ScanNet's apartment from every other depth frame stored its bed, 1.84 x 1.60 x 1.13 m, as
// a "fridge" by its votes.
std::optional<double> deepestFootprint(std::string_view category);

// The footprint's shorter side no thing of a kind `width` wide (its longer side) comes under, where real rooms' labels
// show it; nullopt for the others. Of ARKitScenes' 235 labelled chairs (../shared/data/real-layouts) one in a hundred
// is shallower than 0.33 m (the shallowest 0.27, the median 0.45), and one in a hundred shallower than 0.65 of its
// width (one in twenty than 0.71), 6 of them shallower than one or the other: a chair 0.74 m wide, a wingback
// armchair, is 0.48 m deep or more. ScanNet's labels, often of a chair's visible part, say less.
std::optional<double> shallowestFootprint(std::string_view category, double width = 0);

// The height over the floor no thing of a kind has its top under, where real rooms' labels show it; nullopt for the
// others. Of ScanNet's 488 labelled sinks (its training and validation scans), none has its rim under 0.70 m over its
// room's floor (the 5th percentile of the room's boxes' bottoms), one in a hundred under 0.75 m. ScanNet's lounge from
// every third depth frame stored a round pedestal side table, named "sink" in two views, as a sink 0.66 m tall.
std::optional<double> lowestTop(std::string_view category);

// The side no thing of a kind is thinner than; nullopt for kinds the table lacks. A thinner box of the name is a
// sliver: the edge or the top of something else (a 6 cm thin "table" is a table's edge). Most kinds' is 6 % of
// their typicalExtent; the kinds flat by make have their own, thinner (a closed laptop, a book, a remote: 1 cm; a
// flat tv 2.5 cm): a depth camera measured ScanNet's apartment's remotes 1.4 cm and a book 2.7 cm thin, both
// dropped as slivers before.
std::optional<double> thinnestSide(std::string_view category);
// Whether a kind is flat by make (thinnestSide is its own, not a share of its extent): a thing of it may lie flatter
// than a sliver of a surface (object_fusion.hpp: FusionOptions::minHeight).
bool madeFlat(std::string_view category);

// The least things of a kind measure, in metres, where every labelled thing of the kind in 238 real rooms
// measures more (VSI-Bench's ScanNet and ARKitScenes boxes, tests/unit/ingest/plausibility_test.cpp): the
// largest side (a bed's 1.2 m, where the shortest of 74 beds is 1.73 m) and the height (a sofa's 0.35 m);
// 0 where things of the kind come smaller (ScanNet's boxes fitted to chairs scanned in part, 6 cm tall). A
// box named so that is smaller is no such thing, even seen in part: a 1.14 x 0.80 x 0.16 m "bed" beside
// ScanNet's apartment's sofa.
struct LeastSize {
    double largest = 0;
    double height = 0;
};
std::optional<LeastSize> leastSize(std::string_view category);

// Whether a box with this largest side and height, its bottom this high above the floor, is smaller than any
// thing of the kind (leastSize). The height counts only for a box that stands on the floor (its bottom within
// kStandingReach of it): one that hangs in the air was seen in part.
constexpr double kStandingReach = 0.1;
bool smallerThanKind(std::string_view category, double largest, double height, double bottom);

// A footprint no thing of a kind has, seen whole or in part: this long (its longer horizontal side, metres) or
// longer while shallower than `depth` (its shorter). A chair's footprint is never 0.75 m long and under 0.2 m deep:
// what is that thin is a chair's back seen edge-on, narrower than that (of 235 labelled chairs in ARKitScenes'
// rooms the thinnest footprint is 1.7 times as long as deep; of ScanNet's 370, scanned in part as many are, one
// is 1.17 x 0.17 m and the next longest of those under 0.2 m deep 0.70 m). A 1.28 x 0.18 m "chair" stored in
// ScanNet's lounge, where none stands, is not one, nor a "sofa" (of 134: 0.36 m). A bed lower than 1.0 m is never
// 1.0 m long and under 0.8 m deep: of the 74 beds labelled in ../shared/data/real-layouts, those lower than 1.0 m
// are 0.90 m deep or more, and the shallower ones (0.66-0.86 m) stand 1.19 m tall or more, as does ScanNet's
// 2.03 x 0.29 m headboard scanned alone (1.54 m); of the 388 of ScanNet's training and validation scans, 112 lower
// than 1.0 m, scanned in part as many are, three are under 0.65 m deep and the next 0.88 m. An ottoman of ScanNet's
// lounge, its 100 frames without depth lifted on the dense points, was stored as a 2.30 x 0.58 x 0.83 m "bed" in four
// COLMAP runs of four, and an armless chair of it, from every second of its depth frames, as a 1.47 x 0.60 x 0.66 m
// one (from its first frame on) and as a 1.46 x 0.69 x 0.67 m one (from its second). A fridge lower than 1.1 m is
// never 0.9 m long and under 0.25 m deep (of 39 labelled: 0.36 m the shallowest drawn whole, and ScanNet's scanned in
// part 0.83 x 0.18 and 1.01 x 0.30 m); ScanNet's bathroom had a 0.98 x 0.19 x 0.91 m "fridge" stored on its bathtub's
// side. Nor is a footprint `longLength` long or longer and shallower than `longDepth` a thing of the kind: of the
// labelled chairs under 0.35 m deep, the longest is 0.84 m (ScanNet's; ARKitScenes' 0.41 m), the 1.17 x 0.17 m one
// above aside; of the 5,725 of ScanNet's training and validation scans, one is (0.98 x 0.30 m). ScanNet's lounge from
// its 300 depth frames stored a 1.30 x 0.26 x 0.61 m "chair" by the wall behind an armchair, where none stands (the
// same thing as the 1.28 x 0.18 m one above, from colour resampled anew). Nor is a box `postHeight` tall or taller
// whose footprint's longer side is under `postSide` a thing of the kind: it is a post. Of 6,330 labelled chairs
// (ScanNet's 370 and ARKitScenes' 235 in the real layouts, and the 5,725 of ScanNet's training and validation scans,
// many scanned in part), none 0.4 m tall or taller stands on a footprint under 0.25 m; TUM fr1/rpy's RGB-D memory had a
// 0.23 x 0.08 x 0.86 m "chair" beside its desk, and ScanNet's apartment a 0.20 x 0.18 x 0.55 m one. A box `frontHeight`
// tall or taller is not held to those footprints: it is the front of such a thing, scanned from before it alone (a
// fridge's front, a bed's headboard). Of ScanNet's 243 labelled fridges (its training and validation scans), 9 are
// 0.90-1.09 m long and 0.16-0.25 m deep, each 1.16-2.12 m tall, where the bathroom's "fridge" was 0.91 m tall.
struct Slender {
    double length = 0;
    double depth = 0;
    double longLength = 0;
    double longDepth = 0;
    double postHeight = 0;
    double postSide = 0;
    double frontHeight = 0;
};
bool slenderForKind(std::string_view category, double longer, double shorter, double height);

// A box whose largest side is more than this many times its kind's typicalExtent is not that kind: the name is
// kept only as a guess (detected_as), and fused things are named by the votes that suit their box. A hull
// carved without depth reaches past the thing along the views it was seen from, and is held to the looser
// bound (the dining photos' chairs carve 2.2 m long).
constexpr double kBeyondTypicalExtent = 1.5;
constexpr double kBeyondTypicalHull = 2.5;
// A hull carved without depth whose kind has a standard height (typicalHeight) and no upright end is not that
// kind when it stands more than this many times that height: its top is held to where its surfaces were seen,
// so its height is what such a hull measures best (a kitchen counter's, named "table", 1.06-1.27 m).
constexpr double kTallerThanTypicalHull = 1.4;

// Whether things of a kind stand square to the room's walls, built in or against them: the kinds of a kitchen or a
// bathroom that stand on the floor (roomKind, relations::usualSupport: a fridge, an oven, a toilet). Of the
// people-drawn boxes of ARKitScenes' 150 rooms (../shared/data/real-layouts), 22 of 24 fridges, 25 of 28 stoves and 30
// of 32 toilets turn less than 5 degrees from their room's furniture as a whole; chairs 59 %, sofas 73 %.
bool standsSquare(std::string_view category);

// Whether things are put on the top of things of a kind (a table, a desk, a bed): a horizontal
// surface that is such a thing's top is not the floor.
bool holdsThings(std::string_view category);

// Whether things of kind `thing` are put on the tops of things of kind `carrier` (a monitor on a desk, a mug on a
// table): things usually put on a surface, and a kind that holds things.
bool carries(std::string_view carrier, std::string_view thing);
// The same either way round: two such are never one thing, however close their points lie.
bool oneCarriesTheOther(std::string_view a, std::string_view b);

// Whether things of a kind have a thin upright part at an end or side (a bed's headboard or footboard, a
// sofa's back) that a detector may see as a thing of its own (a "tv", a "suitcase").
bool hasUprightEnds(std::string_view category);

// The one kind of room things of a kind stand in, where there is one: a toilet in a bathroom, a fridge, an oven,
// a microwave or a toaster in a kitchen; Dry for kinds that stand in any room but a bathroom (a bed, a sofa, a desk,
// a chair: of ScanNet's labelled ones in its training and validation scans, 4 of 388 beds, 0 of 503 sofas, 0 of
// 678 desks and 2 of 5,725 chairs stand within 1 m of a toilet, walls aside); Any for the others (a sink, a table).
enum class RoomKind { Any, Kitchen, Bathroom, Dry };
RoomKind roomKind(std::string_view category);
// Whether a kind of room is one room's own (a kitchen, a bathroom), whose kinds tell the room they stand in.
inline bool oneRoom(RoomKind room) { return room == RoomKind::Kitchen || room == RoomKind::Bathroom; }

// Whether `count` things (or kinds) of `room`'s named in one room with `ownCount` of `own`'s tell that room, so that
// own's names there are wrong: more of them, or as many where `room` is a bathroom. A toilet is told by its bowl and
// tank; what detectors call a fridge in a bathroom is any tall white box: ScanNet's bathroom stored a shower's side,
// a shelf on its wall and its bathtub's side as "fridges" beside its toilet, and without depth one "fridge" beside
// its one toilet left its 100 frames' scale to the cameras' height alone. The one toilet named in a kitchen here
// (two white bins, ScanNet's apartment) stood among a fridge, an oven and two microwaves.
inline bool roomOutweighs(RoomKind room, std::size_t count, RoomKind own, std::size_t ownCount) {
    return count > ownCount || (count == ownCount && room == RoomKind::Bathroom && own != RoomKind::Bathroom);
}

// What things of a kind are for, where fusion judges a thing by it (object_fusion.hpp): a seat (a chair, a sofa, a
// bench), luggage (a suitcase or a box, which as large as a low table and standing among seats is used as one:
// lowTablesAmongSeats), a basin (a sink, set into the cabinet under it: objects_from_clusters.hpp), or other.
enum class Role { Other, Seat, Luggage, Basin };
Role role(std::string_view category);

// The name of the kind a category is one of the names of, where models name one kind two ways: a detector's desk
// is the segmenter's (dining) table, its monitor the segmenter's tv; else the category itself. One thing called a
// desk in some views and a table in others is stored once (object_fusion.cpp: pieceOf).
std::string_view kindName(std::string_view category);

}  // namespace smql::ingest
