// The metric spatial predicates, evaluated on boxes in the aligned (z-up)
// frame. Each returns a score in (0, 1] when it holds and 0 when it does not;
// docs/relations.md states each formula with its thresholds.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "engine/model/geometry.hpp"
#include "engine/model/types.hpp"
#include "engine/relations/thresholds.hpp"

namespace smql::relations {

enum class Predicate { On, In, Above, Below, Near, Attached, LeftOf, RightOf, InFrontOf, Behind, Between };

// `inside` and `under` are accepted as aliases of `in` and `below`.
std::optional<Predicate> predicateFromName(std::string_view name);
std::string_view toString(Predicate p);
model::RelationType relationType(Predicate p);
// Lateral predicates need a viewpoint; vertical ones do not.
bool isLateral(Predicate p);
// How many reference arguments the predicate takes (between: 2, others: 1).
int arity(Predicate p);

// What a supporting category affords: things resting on a Holder are *in* it
// (a plant in a plant stand, fruit in a basket); things inside an Enclosure's
// box are in it, things on top are on it (a cabinet, a shelf unit); Surfaces
// only carry things *on* them (a table, a sofa, a chair).
enum class Affordance { Surface, Holder, Enclosure };
Affordance affordanceOf(std::string_view category);

// A vertical plane anchor: a wall, door, window or the like.
bool isVerticalPlane(const model::Node& node);

struct Frame {
    model::Vec2 forward{0, 1};  // unit vector the viewer faces
    model::Vec2 right{1, 0};    // forward turned 90 degrees clockwise
    model::Vec2 position{0, 0};
};
Frame viewFrame(const model::Viewpoint& viewpoint);

// The score of `p(a, b)`, or of `between(a, b, c)`. `frame` is used by the
// lateral predicates; `nearDistance` overrides the threshold for near(x, 1 m).
double evaluate(Predicate p, const model::Node& a, const model::Node& b, const Thresholds& t, const Frame& frame,
                const model::Node* c = nullptr, std::optional<double> nearDistance = std::nullopt);

struct RelationHit {
    Predicate predicate;
    double score;
};

// Every binary relation that holds from a to b, best first: containment and
// support (in, on, attached) before vertical order (above, below), then the
// view-relative ones, then near (the score says how clearly each holds).
std::vector<RelationHit> relate(const model::Node& a, const model::Node& b, const Thresholds& t, const Frame& frame);

// Necessary regions, for index probes and quick rejection: when p(a, ref)
// holds, a's world bounds intersect candidateRegion(p, ref); when p(a, b)
// holds, b's bounds intersect referenceRegion(p, a). Empty for predicates that
// hold far away (the view-relative ones and between).
std::optional<model::Aabb> candidateRegion(Predicate p, const model::Aabb& ref, double nearDistance, const Thresholds& t);
std::optional<model::Aabb> referenceRegion(Predicate p, const model::Aabb& a, double nearDistance, const Thresholds& t);
inline bool intersects(const model::Aabb& a, const model::Aabb& b) {
    return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y && a.min.z <= b.max.z &&
           b.min.z <= a.max.z;
}

// The support relation that makes `b` the parent of `a` in the tree, if any.
double supportScore(const model::Node& a, const model::Node& b, const Thresholds& t);

}  // namespace smql::relations
