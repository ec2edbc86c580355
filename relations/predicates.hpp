// The metric spatial predicates, evaluated on boxes in the aligned (z-up)
// frame. Each returns a score in (0, 1] when it holds and 0 when it does not;
// docs/relations.md states each formula with its thresholds.
//
// The predicates are one table (predicates.cpp, `kPredicates`): a row gives a
// predicate's words, arity, whether it needs a viewpoint, its formula and the
// regions an index probe may use, and the English phrases that ask for it. The binder, planner, executor, RELATE and
// the shell's completion all read that table; nothing else lists predicates.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "model/geometry.hpp"
#include "model/types.hpp"
#include "relations/thresholds.hpp"

namespace smql::relations {

// A predicate is a stored relation type: what a query asks and what ingest records share one code.
using Predicate = model::RelationType;

struct Frame {
    model::Vec2 forward{0, 1};  // unit vector the viewer faces
    model::Vec2 right{1, 0};    // forward turned 90 degrees clockwise
    model::Vec2 position{0, 0};
    bool headingGiven = false;  // VIEW FROM x FACING y: visible_from keeps to the field of view
};
Frame viewFrame(const model::Viewpoint& viewpoint);

// HERE in a predicate (`visible_from(HERE)`, `left_of(HERE)`): a person standing where the viewer stands, a
// kBodyWidth square of floor as tall as the eye (visibility.hpp: kEyeHeight); no node of the scene.
inline constexpr double kBodyWidth = 0.5;
model::Node viewerAt(const Frame& frame);

// The category of the anchors that stand between rooms' parts: near's wall check, the tree's walls.
inline constexpr std::string_view kWall = "wall";

// The boxes that may stand between two nodes, for visible_from and near: every caller says what they
// are, so that one pair gets one answer wherever it is asked. The executor answers from the scene's
// R-tree; a caller that holds a scene's nodes without an index uses NodeObstacles.
class Obstacles {
public:
    virtual ~Obstacles() = default;
    // Appends every node with geometry whose world bounds intersect `region`.
    virtual void within(const model::Aabb& region, std::vector<const model::Node*>& out) const = 0;
    // The same, walls only (what near asks): by default `within`, filtered; a scene that lists its
    // walls answers from the list, a few nodes, rather than every node the region holds.
    virtual void wallsWithin(const model::Aabb& region, std::vector<const model::Node*>& out) const;
    // model::worldAabb of a node's box: by default computed (a sine and a cosine); a scene that
    // keeps its decoded nodes' bounds answers from them, for the pair tests that ask it per pair.
    virtual model::Aabb bounds(const model::Node& node) const { return model::worldAabb(node.box); }
};

// The nodes of a list, scanned (a scene being built, a truth file, a benchmark peer's rows).
class NodeObstacles final : public Obstacles {
public:
    explicit NodeObstacles(std::span<const model::Node> nodes) : nodes_(nodes) {}
    void within(const model::Aabb& region, std::vector<const model::Node*>& out) const override;

private:
    std::span<const model::Node> nodes_;
};

// What a formula sees: `p(a, b)` or `between(a, b, c)`.
struct PredicateInputs {
    const model::Node& a;
    const model::Node& b;
    const model::Node* c;  // the second reference of a two-reference predicate
    const Thresholds& t;
    const Frame& frame;                     // lateral predicates measure in it
    std::optional<double> writtenDistance;  // the distance written in near(x, 1 m), if any
    const Obstacles& obstacles;             // what may stand between
};

// What a predicate's formula asks of the nodes around (Obstacles): nothing; the walls (in: a wall holds a
// picture); the walls, and everything where the subject is of a spreading kind (on: a lamp's box whose
// floor other things take, spreadingKinds); or everything (visible_from's line of sight, near's crowd).
enum class Occluders { None, Walls, WallsOrAllWhenSpreading, All };

struct PredicateSpec {
    Predicate predicate;
    std::string_view alias;  // a second accepted word (`inside`, `under`), or empty
    int arity;               // reference arguments: 1, or 2 for between
    bool viewRelative;       // measured in the viewer's frame (VIEW FROM)
    bool takesDistance;      // accepts near(x, 1 m)
    double (*evaluate)(const PredicateInputs&);
    // Necessary regions, for index probes and quick rejection: when p(a, ref) holds, a's world bounds
    // intersect candidateRegion(ref); when p(a, b) holds, b's bounds intersect referenceRegion(a).
    // Null for predicates that can hold far away, which no index probe can serve.
    model::Aabb (*candidateRegion)(const model::Aabb& ref, double nearDistance, const Thresholds& t);
    model::Aabb (*referenceRegion)(const model::Aabb& a, double nearDistance, const Thresholds& t);
    int relateRank;          // position in RELATE's answer, most specific first; 0: RELATE leaves it out
    std::string_view usage;  // how to write it, for error hints
    // English phrases that ask for it, '|' between them ("on|on top of|onto"): the one list ASK
    // reads (engine/ask), so every predicate is reachable from English.
    std::string_view phrases;
    Occluders occluders = Occluders::None;

    std::string_view name() const { return model::toString(predicate); }
    // Holds only close to its reference, so an R-tree probe around the reference finds every candidate.
    bool local() const { return candidateRegion != nullptr; }
};

// Every predicate, in code order.
std::span<const PredicateSpec> predicates();
// The kinds whose boxes may spread over what stands beside them (a lamp, a plant), in canonical names: the
// subjects for which Occluders::WallsOrAllWhenSpreading asks for every node around.
std::span<const std::string_view> spreadingKinds();
const PredicateSpec& spec(Predicate p);
// By name or alias; null when no predicate has that word.
const PredicateSpec* predicateNamed(std::string_view word);
// Every word that names a predicate (names and aliases), for hints and completion.
std::vector<std::string> predicateWords();
// A predicate's English phrases, split ("on", "on top of", ...).
std::vector<std::string_view> englishPhrases(const PredicateSpec& spec);

inline std::string_view toString(Predicate p) { return model::toString(p); }

// What a supporting category affords: things resting on a Holder are *in* it
// (a plant in a plant stand, fruit in a basket); things inside an Enclosure's
// box are in it, things on top are on it (a cabinet, a shelf unit); Surfaces
// only carry things *on* them (a table, a sofa, a chair); Nothing rests on a
// lamp, a plant or what hangs on a wall, whatever its box holds.
enum class Affordance { Surface, Holder, Enclosure, Nothing };
Affordance affordanceOf(std::string_view category);

// What things of a kind usually stand on: the floor (chairs, beds, doors), a table, desk or counter top (mugs,
// laptops, keyboards), or either or unknown. The ingest tells a floor from a table top by it; attached does not hang
// on a wall what stands on tops (a mug by a wall, off the floor, rests on a shelf the scene does not hold).
enum class Support { Floor, Surface, Either };
Support usualSupport(std::string_view category);

// Whether things of this category have a front (a sofa, a chair, a tv; docs/relations.md lists
// them): only those can face something or have things at their front or back.
bool hasFront(std::string_view category);
// The direction a box's front faces: its own +x axis (the yaw direction), in the floor plane.
model::Vec2 frontDirection(const model::Box& box);

// The shape of what hangs on a wall: a slab standing upright (a picture, a screen, a clock). Anything else a wall
// is the nearest anchor of, off the floor, rests on something the scene does not hold (a mug on a shelf).
bool hungShape(const model::Box& box);
// A vertical plane anchor: a wall, door, window or the like.
bool isVerticalPlane(const model::Node& node);
// A ceiling anchor: what a ceiling light or a vent hangs from (attached).
bool isCeiling(const model::Node& node);

// The score of `p(a, b)`, or of `between(a, b, c)`: the one evaluation of a predicate, which every
// path that decides one calls. `obstacles` is what may stand between (walls for near, anything for
// visible_from); `writtenDistance` the distance of near(x, 1 m).
double evaluate(Predicate p, const model::Node& a, const model::Node& b, const Thresholds& t, const Frame& frame,
                const Obstacles& obstacles, const model::Node* c = nullptr,
                std::optional<double> writtenDistance = std::nullopt);

// Whether `p(a, b)` holds (evaluate(...) > 0), for a filter that needs no score: the same answer,
// with near(x, d) settled without the exact box distance when the centres alone show it is within
// d (FIND's WHERE tests a pair per candidate and reference).
bool holds(Predicate p, const model::Node& a, const model::Node& b, const Thresholds& t, const Frame& frame,
           const Obstacles& obstacles, const model::Node* c = nullptr,
           std::optional<double> writtenDistance = std::nullopt);

// near's limit for the two boxes: the written distance, else the sum of their sizes (the longer
// side of each footprint) kept between near.min_distance and near.distance.
double nearLimit(const model::Node& a, const model::Node& b, const Thresholds& t,
                 std::optional<double> writtenDistance = std::nullopt);

struct RelationHit {
    Predicate predicate;
    double score;
};

// Every binary relation that holds from a to b, in the table's RELATE order: containment and
// support (in, on, attached) before vertical order (above, below), then the view-relative ones,
// then near (the score says how clearly each holds).
std::vector<RelationHit> relate(const model::Node& a, const model::Node& b, const Thresholds& t, const Frame& frame,
                                const Obstacles& obstacles);

inline bool intersects(const model::Aabb& a, const model::Aabb& b) {
    return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y && a.min.z <= b.max.z &&
           b.min.z <= a.max.z;
}

// The support geometry under on and in: most of the smaller footprint shared, a's centre in b's
// upper half or above, a's bottom no more than on.max_gap over b's top (docs/relations.md).
double supportScore(const model::Node& a, const model::Node& b, const Thresholds& t);

// A thin upright slab (a picture, a mirror, a board) held by a wall hangs on it, whatever its lower
// edge touches: the wall that holds `a`, of those `obstacles` has near it, or null. on and in are
// false for such a thing, and the tree hangs it under that wall: one rule.
const model::Node* wallHolding(const model::Node& a, const Obstacles& obstacles, const Thresholds& t);

}  // namespace smql::relations
