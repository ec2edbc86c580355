// Metric scale for captures whose poses are up to scale (COLMAP's): several
// priors, each giving metres per capture unit, combined by their median and
// reported with how well they agree (docs/ingest.md, "Geometry and metric
// alignment"). The priors are the camera's height above the floor, the
// floor-to-ceiling height, and the typical heights of things of known kinds
// (a table's top, a chair's back, a door).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ingest/geometry/typical_sizes.hpp"
#include "model/types.hpp"

namespace smql::ingest {

// A thing a capture shows, named, with its points (capture frame).
struct NamedThing {
    std::string category;
    std::vector<model::Vec3> points;
    // False for a name the objects stage did not keep (stored as "object" with detected_as, the name here): the
    // thing measures nothing and weighs no surface, yet a detector saw a thing of that kind there, which puts
    // the names of another room's things beside it in doubt (scaleFromHeights).
    bool measures = true;
};

// One prior's answer: metres per capture unit.
struct ScaleEstimate {
    std::string prior;  // "median camera height taken as 1.50 m"
    double scale = 1;
    // Measured well enough to be the scale, which the other estimates only check: the heights of things of
    // which two agree within kThingsAgree (scaleFromHeights), or the cameras' height given (AlignOptions).
    bool leads = false;
    // False for the heights of things fused on depth of which no two agree within kThingsAgree: each
    // measures something else (a shelf named "desk", a chair seen in part), and they are noted, not counted.
    bool heldTogether = true;
    std::string things{};  // the heights prior's things: "1 chair (0.90 m), 1 desk (0.75 m)"
};

// The heights prior: each named thing of a typical height, its top (the
// highest of its points along `up`, outliers aside: detail::robustRange) above
// `floorHeight`, gives one estimate; their median is the prior's answer. A thing
// whose points reach well below the floor (floor_evidence.hpp: reachesBelow,
// `unit` cloud units per metre) is left out: its points hold more than the
// thing, and its highest ones too. With `seenWhole` (things fused on depth, whose
// tops are where their surfaces were seen), a thing whose top is short of
// kShortOfItsKind of the tallest of its kind (kindName) is left out as well: seen in
// part, and no two of the rest within kThingsAgree make the estimate not heldTogether.
// Two that agree within kThingsAgree, fused on depth or carved without it, make the
// estimate lead. Kinds of one room (a fridge, a toilet) standing in one room with another's
// count only where more of their room's kinds are named there (scale_priors.cpp says how).
// nullopt with fewer than `minThings` things.
std::optional<ScaleEstimate> scaleFromHeights(const std::vector<NamedThing>& things, const model::Vec3& up,
                                              double floorHeight, double unit, bool seenWhole = false,
                                              std::size_t minThings = 2);

// The heights prior of a capture whose floor does not show, its lowest surface a table top (alignment.hpp:
// tableTopHeight): each thing standing on the top with a typical height above it (typicalHeightOnTop: a monitor),
// its top above `topHeight`, gives one estimate, as scaleFromHeights takes those above the floor (hulls as
// carved: seenWhole off), from one thing on. It checks the cameras' assumed height, which reaches the top only
// through a table's assumed height under it: those two placed the floor under TUM fr1/rpy's desk (its 100 colour
// frames without depth) at 1.04-1.09x the true scale in every COLMAP run forced to store, yet a camera held 0.45 m over
// a table (from a chair) rather than a standing person's 0.75 m makes them 1.7x off, and nothing but such a thing
// tells.
std::optional<ScaleEstimate> scaleFromHeightsOnTop(const std::vector<NamedThing>& things, const model::Vec3& up,
                                                   double topHeight, double unit);

// The things of a typical height scaleFromHeights leaves out before measuring, and those it takes, each listed as
// "3 fridges, 2 toilets" (empty where none is): for a refusal to say why they did not check the scale.
struct HeightsLeftOut {
    std::string doubted;     // named beside another room's things (their names in doubt as measures of the room)
    std::string belowFloor;  // their points reaching well below the floor (reachesBelow)
    std::string partial;     // seen in part (with `seenWhole`: kShortOfItsKind)
    std::string counted;     // taken: fewer than two where no prior was made
};
HeightsLeftOut heightsLeftOut(const std::vector<NamedThing>& things, const model::Vec3& up, double floorHeight,
                              double unit, bool seenWhole = false);

// A thing fused on depth is measured only by what its views showed, so it is never taller than it is: one
// whose top is under this share of the tallest of its kind was seen in part (a chair's seat with its back
// hidden, a 0.25 x 0.25 m piece of one). ScanNet's apartment's 300 frames without depth, lifted on the dense
// points: of five "chairs", the tallest stood 0.93 m, the other four 0.57-0.68 m (each saying the room was
// 1.33-1.58 times too large) and its scale by their heights came out 1.19x.
inline constexpr double kShortOfItsKind = 0.8;

// Things lead the scale where two of them say the same within this share: then they measure the room, where
// the cameras' assumed height is a fifth off either way (ScanNet's cameras stand 1.2-1.35 m up, TUM's
// 1.5-1.7). ScanNet's bathroom, 100 frames without depth: two toilets carved from the sparse points said
// 1.01x the true scale and the cameras' height 1.18x; their median stored it 1.10x, the toilets leading
// 1.01x. Things fused on depth of which no two agree are set aside: TUM's office photos, one COLMAP run of
// several, lifted a 1.39 m "desk" (a shelf beside the desk) and a chair, 1.74 times apart; their median
// stored the room 0.77x its size, the cameras' assumed height 22 % away checking it. Hulls carved without
// depth that do not agree stay one prior among the others, whose median outvotes what they get wrong.
inline constexpr double kThingsAgree = 0.15;

struct ScaleChoice {
    double scale = 1;
    // (largest - smallest) / chosen, over the estimates: 0 with one estimate.
    double spread = 0;
    // The factor between two estimates that leave no majority (more than kDisagreement apart): one of
    // them measured something wrong. 0 when they agree.
    double split = 0;
    std::string note;  // the choice, each prior's answer and their agreement, for the ingest's notes
};

// Two estimates further apart than this factor disagree: the first is kept.
inline constexpr double kDisagreement = 1.5;

// The median of the estimates (at least one), given the most trusted first;
// of two that disagree, the first; the first alone when it leads (ScaleEstimate::leads), the others
// then measuring only how far they agree with it.
ScaleChoice combineScales(const std::vector<ScaleEstimate>& estimates);

}  // namespace smql::ingest
