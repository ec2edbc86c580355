#include "engine/relations/predicates.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace smql::relations {

using model::Box;
using model::Node;

namespace {

struct NamedPredicate {
    std::string_view name;
    Predicate predicate;
};
constexpr std::array<NamedPredicate, 13> kNames = {{{"on", Predicate::On},
                                                     {"in", Predicate::In},
                                                     {"inside", Predicate::In},
                                                     {"above", Predicate::Above},
                                                     {"below", Predicate::Below},
                                                     {"under", Predicate::Below},
                                                     {"near", Predicate::Near},
                                                     {"attached", Predicate::Attached},
                                                     {"left_of", Predicate::LeftOf},
                                                     {"right_of", Predicate::RightOf},
                                                     {"in_front_of", Predicate::InFrontOf},
                                                     {"behind", Predicate::Behind},
                                                     {"between", Predicate::Between}}};

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

std::optional<Predicate> predicateFromName(std::string_view name) {
    for (const auto& n : kNames)
        if (n.name == name) return n.predicate;
    return std::nullopt;
}

std::string_view toString(Predicate p) {
    for (const auto& n : kNames)
        if (n.predicate == p) return n.name;
    return "?";
}

model::RelationType relationType(Predicate p) { return static_cast<model::RelationType>(static_cast<int>(p)); }

bool isLateral(Predicate p) {
    return p == Predicate::LeftOf || p == Predicate::RightOf || p == Predicate::InFrontOf || p == Predicate::Behind;
}

int arity(Predicate p) { return p == Predicate::Between ? 2 : 1; }

Affordance affordanceOf(std::string_view category) {
    static const std::array<std::string_view, 26> holders = {
        "plant-stand", "basket", "bowl", "box", "bin", "trash-can", "wastebasket", "vase", "pot",
        "planter", "cup", "mug", "glass", "jar", "bag", "bucket", "sink", "bathtub", "crate",
        "container", "basin", "pan", "tub", "flowerpot", "case", "backpack"};
    static const std::array<std::string_view, 20> enclosures = {
        "cabinet", "base-cabinet", "wall-cabinet", "cupboard", "wardrobe", "closet", "drawer",
        "chest-of-drawers", "dresser", "shelf-unit", "bookcase", "bookshelf", "fridge", "refrigerator",
        "microwave", "oven", "dishwasher", "washing-machine", "kitchen-cabinet", "nightstand"};
    auto listed = [&](const auto& names) {
        return std::any_of(names.begin(), names.end(), [&](std::string_view n) { return sameCategory(n, category); });
    };
    if (listed(holders)) return Affordance::Holder;
    if (listed(enclosures)) return Affordance::Enclosure;
    return Affordance::Surface;
}

bool isVerticalPlane(const Node& node) {
    if (node.kind != model::NodeKind::Anchor) return false;
    const auto& s = node.box.size;
    // A plane segment stands upright when its thin axis is horizontal.
    return node.geometry == model::GeometryKind::Plane && s.z > std::min(s.x, s.y);
}

Frame viewFrame(const model::Viewpoint& viewpoint) {
    Frame f;
    f.forward = {std::cos(viewpoint.facingYaw), std::sin(viewpoint.facingYaw)};
    f.right = {f.forward.y, -f.forward.x};
    f.position = {viewpoint.position.x, viewpoint.position.y};
    return f;
}

double supportScore(const Node& a, const Node& b, const Thresholds& t) {
    if (&a == &b || a.id == b.id && a.id != model::kNoNode) return 0.0;
    if (!hasGeometry(a) || !hasGeometry(b) || isVerticalPlane(b)) return 0.0;
    double share = overlapShare(a.box, b.box);
    if (share < t.onMinOverlap) return 0.0;
    double height = b.box.size.z;
    double rise = height > 1e-3 ? (a.box.center.z - model::bottom(b.box)) / height
                                : (a.box.center.z > b.box.center.z ? 1.0 : 0.0);
    if (rise < t.onMinRise) return 0.0;
    if (model::bottom(a.box) - model::top(b.box) > t.onMaxGap) return 0.0;
    return std::min(1.0, share);
}

double evaluate(Predicate p, const Node& a, const Node& b, const Thresholds& t, const Frame& frame, const Node* c,
                std::optional<double> nearDistance) {
    if (!hasGeometry(a) || !hasGeometry(b) || a.id == b.id) return 0.0;
    switch (p) {
        case Predicate::On: {
            Affordance kind = affordanceOf(b.category);
            if (kind == Affordance::Holder) return 0.0;
            if (kind == Affordance::Enclosure && contained(a, b, t)) return 0.0;
            return supportScore(a, b, t);
        }
        case Predicate::In: {
            Affordance kind = affordanceOf(b.category);
            if (kind == Affordance::Surface) return 0.0;
            double inside = model::fractionInside(a.box, b.box);
            if (inside >= t.inMinInside) return inside;
            return kind == Affordance::Holder ? supportScore(a, b, t) : 0.0;
        }
        case Predicate::Above: {
            if (model::bottom(a.box) < model::top(b.box) - t.aboveTolerance) return 0.0;
            double share = overlapShare(a.box, b.box);
            return share >= t.aboveMinOverlap && share > 0 ? std::min(1.0, share) : 0.0;
        }
        case Predicate::Below:
            return evaluate(Predicate::Above, b, a, t, frame);
        case Predicate::Near: {
            double limit = nearDistance.value_or(t.nearDistance);
            double d = model::distance(a.box, b.box);
            if (d > limit) return 0.0;
            return limit > 0 ? std::max(0.01, 1.0 - d / limit) : 1.0;
        }
        case Predicate::Attached: {
            if (!isVerticalPlane(a) && !isVerticalPlane(b) && !sameCategory(b.category, "pillar")) return 0.0;
            double d = model::distance(a.box, b.box);
            return d <= t.attachedMaxGap ? std::max(0.01, 1.0 - d / std::max(t.attachedMaxGap, 1e-3)) : 0.0;
        }
        case Predicate::LeftOf:
            return offsetScore(dot(centreOffset(a, b), frame.right), t.lateralMinOffset);
        case Predicate::RightOf:
            return offsetScore(dot(centreOffset(b, a), frame.right), t.lateralMinOffset);
        case Predicate::InFrontOf:
            return offsetScore(dot(centreOffset(a, b), frame.forward), t.lateralMinOffset);
        case Predicate::Behind:
            return offsetScore(dot(centreOffset(b, a), frame.forward), t.lateralMinOffset);
        case Predicate::Between: {
            if (!c || !hasGeometry(*c)) return 0.0;
            model::Vec2 seg = centreOffset(b, *c);
            double len2 = dot(seg, seg);
            if (len2 <= 1e-9) return 0.0;
            model::Vec2 rel = centreOffset(b, a);
            double along = dot(rel, seg) / len2;
            if (along <= 0 || along >= 1) return 0.0;
            double px = rel.x - along * seg.x, py = rel.y - along * seg.y;
            double off = std::sqrt(px * px + py * py);
            return off <= t.betweenMaxOffset ? std::max(0.01, 1.0 - off / std::max(t.betweenMaxOffset, 1e-3)) : 0.0;
        }
    }
    return 0.0;
}

std::vector<RelationHit> relate(const Node& a, const Node& b, const Thresholds& t, const Frame& frame) {
    // Most specific first: what holds a thing, then what it touches, then order in space, then proximity.
    static constexpr std::array<Predicate, 10> order = {
        Predicate::In,     Predicate::On,      Predicate::Attached,  Predicate::Above,  Predicate::Below,
        Predicate::LeftOf, Predicate::RightOf, Predicate::InFrontOf, Predicate::Behind, Predicate::Near};
    std::vector<RelationHit> hits;
    for (Predicate p : order) {
        double score = evaluate(p, a, b, t, frame);
        if (score > 0) hits.push_back({p, score});
    }
    return hits;
}

namespace {
constexpr double kUnbounded = 1e9;

model::Aabb grown(model::Aabb b, double d) {
    b.min = {b.min.x - d, b.min.y - d, b.min.z - d};
    b.max = {b.max.x + d, b.max.y + d, b.max.z + d};
    return b;
}
}  // namespace

std::optional<model::Aabb> candidateRegion(Predicate p, const model::Aabb& ref, double nearDistance, const Thresholds& t) {
    model::Aabb b = ref;
    switch (p) {
        case Predicate::On:
        case Predicate::In:
            // a's footprint overlaps b's and a's bottom is at most on.max_gap above b's top.
            b.max.z += t.onMaxGap;
            return b;
        case Predicate::Above:
            b.min.z = b.max.z - t.aboveTolerance;
            b.max.z = kUnbounded;
            return b;
        case Predicate::Below:
            b.max.z = b.min.z + t.aboveTolerance;
            b.min.z = -kUnbounded;
            return b;
        case Predicate::Near: return grown(b, nearDistance);
        case Predicate::Attached: return grown(b, t.attachedMaxGap);
        default: return std::nullopt;
    }
}

std::optional<model::Aabb> referenceRegion(Predicate p, const model::Aabb& a, double nearDistance, const Thresholds& t) {
    model::Aabb b = a;
    switch (p) {
        case Predicate::On:
        case Predicate::In:
            // b's footprint overlaps a's and b's top reaches to within on.max_gap of a's bottom.
            b.min.z -= t.onMaxGap;
            b.max.z = kUnbounded;
            return b;
        case Predicate::Above:
            b.max.z = b.min.z + t.aboveTolerance;
            b.min.z = -kUnbounded;
            return b;
        case Predicate::Below:
            b.min.z = b.max.z - t.aboveTolerance;
            b.max.z = kUnbounded;
            return b;
        case Predicate::Near: return grown(b, nearDistance);
        case Predicate::Attached: return grown(b, t.attachedMaxGap);
        default: return std::nullopt;
    }
}

}  // namespace smql::relations
