// FIND and COUNT: gather candidates by the planned access path, filter by WHERE, order, limit,
// project. Across scenes: the label index.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <queue>

#include <fmt/format.h>

#include "engine/catalog/attributes.hpp"
#include "engine/exec/executor.hpp"
#include "engine/exec/like.hpp"
#include "engine/similar/text_embedder.hpp"
#include "model/geometry.hpp"
#include "storage/database.hpp"

namespace smql::exec {

using binder::BoundExpr;
using binder::NodeSet;
using model::Node;
using planner::Access;

namespace {

std::string lower(std::string_view text) {
    std::string out(text);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

bool sameChar(char text, char pattern) {
    return pattern == '_' ||
           std::tolower(static_cast<unsigned char>(text)) == std::tolower(static_cast<unsigned char>(pattern));
}

// Whether `piece` (no %) matches `text` at `at`.
bool pieceAt(std::string_view text, std::size_t at, std::string_view piece) {
    if (at + piece.size() > text.size()) return false;
    for (std::size_t k = 0; k < piece.size(); ++k)
        if (!sameChar(text[at + k], piece[k])) return false;
    return true;
}

}  // namespace

// Without backtracking: the pattern is cut at its %s into pieces; the first must match at the start,
// the last at the end, and each one between at its leftmost place after the one before (leftmost is
// never worse for what follows), so '%%%...x' is as quick as 'x'.
bool like(std::string_view text, std::string_view pattern) {
    std::vector<std::string_view> pieces;
    for (std::size_t from = 0;;) {
        const std::size_t percent = pattern.find('%', from);
        pieces.push_back(
            pattern.substr(from, percent == std::string_view::npos ? std::string_view::npos : percent - from));
        if (percent == std::string_view::npos) break;
        from = percent + 1;
    }
    if (pieces.size() == 1) return text.size() == pattern.size() && pieceAt(text, 0, pattern);
    const std::string_view first = pieces.front(), last = pieces.back();
    if (first.size() + last.size() > text.size() || !pieceAt(text, 0, first) ||
        !pieceAt(text, text.size() - last.size(), last))
        return false;
    std::size_t at = first.size();
    const std::size_t end = text.size() - last.size();  // the middle pieces lie in [at, end)
    for (std::size_t p = 1; p + 1 < pieces.size(); ++p) {
        const std::string_view piece = pieces[p];
        while (at + piece.size() <= end && !pieceAt(text, at, piece)) ++at;
        if (at + piece.size() > end) return false;
        at += piece.size();
    }
    return true;
}

namespace {

// An attribute's value as a comparison or ORDER BY sees it: a number or text; nothing for null.
std::optional<std::variant<double, std::string>> comparable(const Value& value) {
    if (const auto* whole = std::get_if<std::int64_t>(&value)) return static_cast<double>(*whole);
    if (const auto* real = std::get_if<double>(&value)) return *real;
    if (const auto* text = std::get_if<std::string>(&value)) return *text;
    return std::nullopt;
}

// A stored attribute's text as a number ("2" captures), when it is one.
std::optional<double> number(const std::variant<double, std::string>& value) {
    if (const auto* d = std::get_if<double>(&value)) return *d;
    const auto& s = std::get<std::string>(value);
    char* end = nullptr;
    double parsed = std::strtod(s.c_str(), &end);
    if (s.empty() || *end != '\0') return std::nullopt;
    return parsed;
}

catalog::AttributeInfo attributeNamed(const std::string& name) {
    if (const catalog::AttributeInfo* builtIn = catalog::builtInAttribute(name)) return *builtIn;
    return catalog::storedAttribute(name);
}

template <typename T>
bool ordered(ast::CompareOp op, const T& a, const T& b) {
    switch (op) {
        case ast::CompareOp::Eq:
            return a == b;
        case ast::CompareOp::Ne:
            return a != b;
        case ast::CompareOp::Lt:
            return a < b;
        case ast::CompareOp::Le:
            return a <= b;
        case ast::CompareOp::Gt:
            return a > b;
        case ast::CompareOp::Ge:
            return a >= b;
        case ast::CompareOp::Like:
        case ast::CompareOp::IsNull:
        case ast::CompareOp::IsNotNull:
            return false;
    }
    return false;
}

Value boxValue(const Node& n) {
    if (n.geometry == model::GeometryKind::None) return std::monostate{};
    return n.box;
}

// Three decimals: the embedder's floats carry no more, and rows then print the same everywhere.
double roundedSimilarity(double similarity) { return std::round(similarity * 1000) / 1000; }

Value sourceValue(const Node& n) {
    if (!n.sourceId) return std::monostate{};
    return *n.sourceId;
}

}  // namespace

double Executor::distanceToOthers(catalog::Slot slot, const std::vector<catalog::Slot>& refs) const {
    const Node& node = scene().node(slot);
    double nearest = std::numeric_limits<double>::infinity();
    for (catalog::Slot r : refs)
        if (r != slot) nearest = std::min(nearest, model::distance(node.box, scene().node(r).box));
    return nearest;
}

double Executor::distanceTo(catalog::Slot slot, const NodeSet& to, const relations::Frame& frame) {
    if (to.source == NodeSet::Source::Here) return model::footprintGap(scene().node(slot).box, frame.position);
    return distanceToOthers(slot, slots(to, frame));
}

model::Aabb Executor::standingLine(const relations::Frame& frame) {
    constexpr double kEverywhere = std::numeric_limits<double>::max();
    return {{frame.position.x, frame.position.y, -kEverywhere}, {frame.position.x, frame.position.y, kEverywhere}};
}

bool Executor::compare(const BoundExpr& expr, catalog::Slot slot, const relations::Frame& frame) {
    if (expr.op == ast::CompareOp::IsNull || expr.op == ast::CompareOp::IsNotNull) {
        const Value have = catalog::attributeValue(
            scene(), slot, expr.builtIn ? *expr.builtIn : catalog::storedAttribute(expr.attribute));
        return std::holds_alternative<std::monostate>(have) == (expr.op == ast::CompareOp::IsNull);
    }
    std::optional<std::variant<double, std::string>> value;
    if (expr.distanceTo) {
        if (scene().node(slot).geometry == model::GeometryKind::None) return false;
        const double nearest = distanceTo(slot, *expr.distanceTo, frame);
        if (std::isinf(nearest)) return false;  // nothing to measure to but itself
        value = nearest;
    } else {
        value = comparable(catalog::attributeValue(
            scene(), slot, expr.builtIn ? *expr.builtIn : catalog::storedAttribute(expr.attribute)));
    }
    if (!value) return false;  // a node without the field never matches, as NULL in SQL
    if (std::holds_alternative<std::string>(expr.literal)) {
        std::string have = std::holds_alternative<std::string>(*value) ? std::get<std::string>(*value)
                                                                       : fmt::format("{}", std::get<double>(*value));
        if (expr.op == ast::CompareOp::Like) return like(have, expr.literalFolded);
        return ordered(expr.op, lower(have), expr.literalFolded);
    }
    double want = std::holds_alternative<double>(expr.literal)
                      ? std::get<double>(expr.literal)
                      : static_cast<double>(std::get<std::int64_t>(expr.literal));
    std::optional<double> have = number(*value);
    if (!have || expr.op == ast::CompareOp::Like) return false;
    return ordered(expr.op, *have, want);
}

bool Executor::matches(const BoundExpr& expr, catalog::Slot slot, const relations::Frame& frame) {
    switch (expr.kind) {
        case BoundExpr::Kind::And:
            return std::all_of(expr.children.begin(), expr.children.end(),
                               [&](const BoundExpr& c) { return matches(c, slot, frame); });
        case BoundExpr::Kind::Or:
            return std::any_of(expr.children.begin(), expr.children.end(),
                               [&](const BoundExpr& c) { return matches(c, slot, frame); });
        case BoundExpr::Kind::Not:
            return !matches(expr.children.front(), slot, frame);
        case BoundExpr::Kind::Compare:
            return compare(expr, slot, frame);
        case BoundExpr::Kind::Predicate:
            return holdsForSome(expr, slot, frame);
    }
    return false;
}

double Executor::score(relations::Predicate p, const Node& a, const Node& b, const relations::Frame& frame,
                       const Node* c, std::optional<double> writtenDistance) const {
    return relations::evaluate(p, a, b, thresholds_, frame, catalog::SceneObstacles(scene()), c, writtenDistance);
}

std::vector<relations::RelationHit> Executor::relate(const Node& a, const Node& b,
                                                     const relations::Frame& frame) const {
    return relations::relate(a, b, thresholds_, frame, catalog::SceneObstacles(scene()));
}

bool Executor::holdsForHere(const BoundExpr& expr, catalog::Slot slot, const relations::Frame& frame) {
    const auto& snap = scene();
    const Node viewer = relations::viewerAt(frame);
    // Each argument's nodes: HERE's one person, or the set's nodes other than the candidate.
    auto nodesOf = [&](const NodeSet& set) {
        std::vector<const Node*> out;
        if (set.source == NodeSet::Source::Here) return std::vector<const Node*>{&viewer};
        for (catalog::Slot s : slots(set, frame))
            if (s != slot) out.push_back(&snap.node(s));
        return out;
    };
    const Node& a = snap.node(slot);
    const auto first = nodesOf(expr.args[0]);
    const auto second = expr.args.size() == 2 ? nodesOf(expr.args[1]) : std::vector<const Node*>{nullptr};
    for (const Node* b : first)
        for (const Node* c : second) {
            poll();
            if (b != c && relations::holds(expr.predicate, a, *b, thresholds_, frame, catalog::SceneObstacles(snap), c,
                                           expr.nearDistance))
                return true;
        }
    return false;
}

bool Executor::holdsForSome(const BoundExpr& expr, catalog::Slot slot, const relations::Frame& frame) {
    const auto& snap = scene();
    const auto& spec = relations::spec(expr.predicate);
    if (std::any_of(expr.args.begin(), expr.args.end(),
                    [](const NodeSet& set) { return set.source == NodeSet::Source::Here; }))
        return holdsForHere(expr, slot, frame);
    if (expr.args.size() == 2) {
        const Node& a = snap.node(slot);
        const auto& second = slots(expr.args[1], frame);
        for (catalog::Slot b : slots(expr.args[0], frame))
            for (catalog::Slot c : second) {
                poll();
                if (b != slot && c != slot && c != b &&
                    score(expr.predicate, a, snap.node(b), frame, &snap.node(c)) > 0)
                    return true;
            }
        return false;
    }
    double nearDistance = expr.nearDistance.value_or(thresholds_.nearDistance);
    // Where a reference must be for the predicate to hold: a cheap bounds test before the exact one.
    std::optional<model::Aabb> region;
    if (spec.referenceRegion) region = spec.referenceRegion(snap.bounds(slot), nearDistance, thresholds_);
    // The candidate is decoded only once a reference passes the bounds test.
    auto holds = [&](catalog::Slot b) {
        poll();
        if (b == slot || (region && !relations::intersects(snap.bounds(b), *region))) return false;
        return relations::holds(expr.predicate, snap.node(slot), snap.node(b), thresholds_, frame,
                                catalog::SceneObstacles(snap), nullptr, expr.nearDistance);
    };
    const auto& refs = slots(expr.args[0], frame);
    if (!region) return std::any_of(refs.begin(), refs.end(), holds);
    // Up to a few thousand references, a sweep of their bounds sorted along x (48 bytes each, in
    // order) finds those that meet the region faster than the R-tree, which visits the boxes of
    // every category there and returns them in a new list; beyond, the R-tree names the few close.
    constexpr std::size_t kScannedReferences = 4096;
    if (refs.size() > kScannedReferences) {
        const auto& member = membership(expr.args[0], frame);
        std::vector<catalog::Slot> close;
        snap.intersecting(*region, close);
        return std::any_of(close.begin(), close.end(), [&](catalog::Slot b) { return member[b] && holds(b); });
    }
    const ReferenceSweep& sweep = sweepOf(expr.args[0], frame);
    // With slack for the rounding of the subtraction: a reference is never skipped for it. A NaN
    // bound starts the sweep at the first reference, which is slower, never wrong.
    const double from = region->min.x - sweep.widest - 1e-9 * (1 + std::abs(region->min.x) + sweep.widest);
    auto first = std::lower_bound(sweep.bounds.begin(), sweep.bounds.end(), from,
                                  [](const model::Aabb& b, double x) { return b.min.x < x; });
    for (auto it = first; it != sweep.bounds.end() && it->min.x <= region->max.x; ++it)
        if (relations::intersects(*it, *region) &&
            holds(sweep.slots[static_cast<std::size_t>(it - sweep.bounds.begin())]))
            return true;
    return false;
}

bool Executor::inTarget(const binder::Target& target, catalog::Slot slot, const relations::Frame& frame) {
    // From the scene's index: a candidate the target rules out is never decoded.
    const auto& snap = scene();
    switch (target.kind) {
        case binder::Target::Kind::Category:
            return snap.category(slot) == target.category;
        case binder::Target::Kind::NodeKind:
            return snap.kind(slot) == target.nodeKind && !snap.hidden(slot);
        case binder::Target::Kind::AnyNode:
            return snap.kind(slot) != model::NodeKind::Scene && !snap.hidden(slot);
        case binder::Target::Kind::Thing:
            return ast::isThing(snap.kind(slot)) && !snap.hidden(slot);
        case binder::Target::Kind::Nodes: {
            const auto& nodes = slots(target.nodes, frame);
            return std::binary_search(nodes.begin(), nodes.end(), slot);
        }
    }
    return false;
}

std::vector<Hit> Executor::nearestFirst(const planner::FindPlan& plan, const relations::Frame& frame) {
    const auto& f = *plan.find;
    const auto& snap = scene();
    const bool here = f.distanceTo->source == NodeSet::Source::Here;
    // The one reference's slot; from HERE there is none, and every slot is a candidate.
    const catalog::Slot ref = here ? catalog::Slot{} : slots(*f.distanceTo, frame).front();
    const auto want = static_cast<std::size_t>(*f.limit);
    const model::Aabb around = here ? standingLine(frame) : snap.bounds(ref);
    auto boundsGap = [&](const model::Aabb& b) {
        double dx = std::max({0.0, b.min.x - around.max.x, around.min.x - b.max.x});
        double dy = std::max({0.0, b.min.y - around.max.y, around.min.y - b.max.y});
        double dz = std::max({0.0, b.min.z - around.max.z, around.min.z - b.max.z});
        return std::sqrt(dx * dx + dy * dy + dz * dz);
    };
    if (want == 0) return {};
    std::vector<Hit> hits;
    std::priority_queue<double> best;  // the `want` smallest exact distances so far, the largest on top
    auto walk = snap.walkNearest(around);
    while (const std::optional<catalog::Slot> s = walk.next()) {
        // The candidates come nearest bounds first, and a box is never nearer than its bounds: once
        // `want` answers are strictly nearer than this one's bounds, no later one can beat them.
        if (best.size() == want && best.top() < boundsGap(snap.bounds(*s))) break;
        poll();
        // The one reference itself has nothing else to measure to (as in find()).
        if ((!here && *s == ref) || !inTarget(f.target, *s, frame) || (f.where && !matches(*f.where, *s, frame)))
            continue;
        const double distance = here ? model::footprintGap(snap.node(*s).box, frame.position)
                                     : model::distance(snap.node(*s).box, snap.node(ref).box);
        hits.push_back({*s, distance});
        best.push(distance);
        if (best.size() > want) best.pop();
    }
    std::sort(hits.begin(), hits.end(), [&](const Hit& a, const Hit& b) {
        return a.distance != b.distance ? a.distance < b.distance : snap.node(a.slot).id < snap.node(b.slot).id;
    });
    if (hits.size() > want) hits.resize(want);
    return hits;
}

// The space SIMILAR TO searches: the built-in text embedder's, with the text embedded once per
// statement, or the vectors an external model gave the nodes, with the bound vector.
Executor::SimilaritySpace Executor::similaritySpace(const binder::BoundSimilarTo& similarTo) const {
    if (similarTo.stored()) return {*scene().storedEmbeddings(txn_), {}, similarTo.vector};
    return {scene().embeddings(), similar::embedQuery(similarTo.text), {}};
}

// SIMILAR TO over a large target without WHERE: the index's top k, widened until k of them are
// in the target (hidden nodes and other kinds are in the index too).
std::vector<Hit> Executor::similarFirst(const planner::FindPlan& plan, const relations::Frame& frame) {
    const auto& f = *plan.find;
    const SimilaritySpace space = similaritySpace(*f.similarTo);
    const auto want = static_cast<std::size_t>(*f.limit);
    for (std::size_t k = std::max<std::size_t>(2 * want, 32);; k *= 4) {
        poll();
        std::vector<Hit> hits;
        const auto matches = space.index.mostSimilar(space.query(), k);
        for (const auto& match : matches)
            if (inTarget(f.target, match.position, frame)) hits.push_back({match.position, 0, match.similarity});
        if (hits.size() >= want || matches.size() < k || k >= space.index.size()) {
            if (hits.size() > want) hits.resize(want);
            return hits;
        }
    }
}

// SIMILAR TO over filtered candidates: each one's similarity, exactly; those without a vector or
// below the space's least similarity are left out, the rest go most similar first (ties in id order).
void Executor::rankBySimilarity(const planner::FindPlan& plan, std::vector<Hit>& hits) const {
    const auto& f = *plan.find;
    const auto& snap = scene();
    const SimilaritySpace space = similaritySpace(*f.similarTo);
    std::erase_if(hits, [&](Hit& h) {
        if (!space.index.hasVector(h.slot)) return true;
        h.similarity = space.index.similarity(h.slot, space.query());
        return !(h.similarity >= space.index.least());
    });
    auto before = [&](const Hit& a, const Hit& b) {
        return a.similarity != b.similarity ? a.similarity > b.similarity : snap.node(a.slot).id < snap.node(b.slot).id;
    };
    const auto k = plan.topK ? std::min(hits.size(), static_cast<std::size_t>(*f.limit)) : hits.size();
    std::partial_sort(hits.begin(), hits.begin() + static_cast<std::ptrdiff_t>(k), hits.end(), before);
    hits.resize(k);
}

model::Aabb Executor::probeRegion(const BoundExpr& term, const model::Aabb& around) const {
    if (term.kind == BoundExpr::Kind::Compare) {
        const double reach = std::holds_alternative<double>(term.literal)
                                 ? std::get<double>(term.literal)
                                 : static_cast<double>(std::get<std::int64_t>(term.literal));
        const model::Vec3 pad{reach, reach, reach};
        return {{around.min.x - pad.x, around.min.y - pad.y, around.min.z - pad.z},
                {around.max.x + pad.x, around.max.y + pad.y, around.max.z + pad.z}};
    }
    double nearDistance = term.nearDistance.value_or(thresholds_.nearDistance);
    return relations::spec(term.predicate).candidateRegion(around, nearDistance, thresholds_);
}

std::vector<Hit> Executor::filtered(const planner::FindPlan& plan, const relations::Frame& frame) {
    const auto& f = *plan.find;
    const auto& snap = scene();
    std::vector<catalog::Slot> candidates;
    if (plan.access == Access::RTreeProbe) {
        const BoundExpr& term = plan.probeTerm();
        // HERE: around the line where the viewer stands for distance(HERE), around the person there for a predicate.
        if (const NodeSet& around = *planner::probeReferences(term); around.source == NodeSet::Source::Here)
            snap.intersecting(probeRegion(term, term.kind == BoundExpr::Kind::Compare
                                                    ? standingLine(frame)
                                                    : model::worldAabb(relations::viewerAt(frame).box)),
                              candidates);
        else
            for (catalog::Slot ref : slots(around, frame))
                snap.intersecting(probeRegion(term, snap.bounds(ref)), candidates);
        std::sort(candidates.begin(), candidates.end());
        candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
        std::erase_if(candidates, [&](catalog::Slot s) { return !inTarget(f.target, s, frame); });
    } else {
        candidates = slots(f.target.nodes, frame);
    }
    std::vector<Hit> hits;
    hits.reserve(candidates.size());
    for (catalog::Slot s : candidates) {
        poll();
        if (!f.where || matches(*f.where, s, frame)) hits.push_back({s, 0});
    }
    return hits;
}

std::vector<Hit> Executor::find(const planner::FindPlan& plan) {
    const auto& f = *plan.find;
    if (f.limit && *f.limit <= 0) return {};
    const auto& snap = scene();
    relations::Frame viewer = frame(f.view);
    if (plan.access == Access::NearestFirst) return nearestFirst(plan, viewer);
    if (plan.access == Access::SimilarFirst) return similarFirst(plan, viewer);

    std::vector<Hit> hits = filtered(plan, viewer);
    if (f.distanceTo) {
        static const std::vector<catalog::Slot> none;
        const auto& refs = f.distanceTo->source == NodeSet::Source::Here ? none : slots(*f.distanceTo, viewer);
        // A node's distance to x is to the nodes of x other than itself, as `distance(x) < d` measures
        // it ("FIND chair ORDER BY distance(chair)": each chair to the nearest other chair). Nodes
        // without a place, or with nothing else to measure to, have no distance and are left out;
        // NEAREST TO x leaves x itself out.
        std::erase_if(hits, [&](const Hit& h) {
            return snap.node(h.slot).geometry == model::GeometryKind::None ||
                   (f.nearest && std::find(refs.begin(), refs.end(), h.slot) != refs.end());
        });
        for (auto& h : hits) h.distance = distanceTo(h.slot, *f.distanceTo, viewer);
        std::erase_if(hits, [](const Hit& h) { return std::isinf(h.distance); });
        std::stable_sort(hits.begin(), hits.end(), [&](const Hit& a, const Hit& b) {
            if (a.distance != b.distance) return f.descending ? a.distance > b.distance : a.distance < b.distance;
            return snap.node(a.slot).id < snap.node(b.slot).id;
        });
    }
    if (!f.orderAttribute.empty()) orderByAttribute(plan, hits);
    if (f.similarTo) rankBySimilarity(plan, hits);
    if (f.limit && hits.size() > static_cast<std::size_t>(*f.limit)) hits.resize(static_cast<std::size_t>(*f.limit));
    return hits;
}

// ORDER BY an attribute: numbers by value, text case-insensitively; nodes without it go last in
// either direction, and ties keep id order. With a LIMIT only the first k are sorted (the plan's top-k).
void Executor::orderByAttribute(const planner::FindPlan& plan, std::vector<Hit>& hits) const {
    const auto& f = *plan.find;
    const catalog::AttributeInfo attribute = attributeNamed(f.orderAttribute);
    struct Keyed {
        Hit hit;
        std::optional<double> number;
        std::optional<std::string> text;
        model::NodeId id;
    };
    std::vector<Keyed> keyed;
    keyed.reserve(hits.size());
    for (const Hit& h : hits) {
        Keyed k{h, std::nullopt, std::nullopt, scene().node(h.slot).id};
        if (auto value = comparable(catalog::attributeValue(scene(), h.slot, attribute))) {
            k.number = number(*value);
            if (!k.number) k.text = lower(std::get<std::string>(*value));
        }
        keyed.push_back(std::move(k));
    }
    auto before = [&](const Keyed& a, const Keyed& b) {
        // numbers, then text, then nodes without the attribute
        int rankA = a.number ? 0 : a.text ? 1 : 2, rankB = b.number ? 0 : b.text ? 1 : 2;
        if (rankA != rankB) return rankA < rankB;
        if (rankA == 0 && *a.number != *b.number) return f.descending ? *a.number > *b.number : *a.number < *b.number;
        if (rankA == 1 && *a.text != *b.text) return f.descending ? *a.text > *b.text : *a.text < *b.text;
        return a.id < b.id;
    };
    const auto k = plan.topK ? std::min(keyed.size(), static_cast<std::size_t>(*f.limit)) : keyed.size();
    std::partial_sort(keyed.begin(), keyed.begin() + static_cast<std::ptrdiff_t>(k), keyed.end(), before);
    keyed.resize(k);
    hits.clear();
    for (const Keyed& key : keyed) hits.push_back(key.hit);
}

ResultSet Executor::run(const binder::BoundFind& f) {
    auto hits = find(*plan_.find);
    if (f.countOnly) return countAnswer(hits.size());
    checkRows(hits.size());
    if (!f.columns.empty()) return returned(f, hits);
    ResultSet rs;
    rs.columns = {{"id", ValueType::Integer},
                  {"category", ValueType::Text},
                  {"source_id", ValueType::Integer},
                  {"box", ValueType::Box}};
    if (f.distanceTo) rs.columns.push_back({"distance", ValueType::Real});
    if (f.similarTo) rs.columns.push_back({"similarity", ValueType::Real});
    if (f.path) rs.columns.push_back({"path", ValueType::Text});
    rs.rows.reserve(hits.size());
    for (const auto& h : hits) {
        const Node& n = scene().node(h.slot);
        // Made where it stays: a row's values are held in it, so a row moved is a row copied.
        Row& row = rs.rows.emplace_back();
        row.reserve(4 + (f.distanceTo ? 1 : 0) + (f.similarTo ? 1 : 0) + (f.path ? 1 : 0));
        row.emplace_back(static_cast<std::int64_t>(n.id));
        row.emplace_back(n.category);
        row.emplace_back(sourceValue(n));
        row.emplace_back(boxValue(n));
        if (f.distanceTo) row.emplace_back(h.distance);
        if (f.similarTo) row.emplace_back(roundedSimilarity(h.similarity));
        if (f.path) row.emplace_back(scene().path(h.slot));
    }
    return rs;
}

// RETURN a, b: the named columns in order, each typed as its attribute (SHOW ATTRIBUTES), then PATH.
ResultSet Executor::returned(const binder::BoundFind& f, const std::vector<Hit>& hits) const {
    ResultSet rs;
    // none: the distance or similarity column
    std::vector<std::optional<catalog::AttributeInfo>> attributes;
    for (const auto& column : f.columns) {
        const bool measured = (column == "distance" && f.distanceTo) || (column == "similarity" && f.similarTo);
        if (measured && !catalog::builtInAttribute(column)) {
            attributes.emplace_back(std::nullopt);
            rs.columns.push_back({column, ValueType::Real});
        } else {
            attributes.emplace_back(attributeNamed(column));
            rs.columns.push_back({column, attributes.back()->type});
        }
    }
    if (f.path) rs.columns.push_back({"path", ValueType::Text});
    rs.rows.reserve(hits.size());
    for (const auto& h : hits) {
        Row& row = rs.rows.emplace_back();
        row.reserve(attributes.size() + (f.path ? 1 : 0));
        for (std::size_t i = 0; i < attributes.size(); ++i) {
            if (attributes[i])
                row.push_back(catalog::attributeValue(scene(), h.slot, *attributes[i]));
            else
                row.emplace_back(f.columns[i] == "similarity" ? roundedSimilarity(h.similarity) : h.distance);
        }
        if (f.path) row.emplace_back(scene().path(h.slot));
    }
    return rs;
}

ResultSet Executor::run(const binder::BoundCatalogFind& f) {
    if (!f.countOnly) return catalogFind(txn_, session_, f.category, f.keys, f.limit, f.count);
    return countAnswer(f.count);
}

// Category search over every scene through the label index: no snapshot is loaded.
ResultSet catalogFind(const storage::ReadTransaction& txn, const catalog::Session& session, std::string_view category,
                      const std::vector<std::string>& keys, std::optional<std::int64_t> limit, std::uint64_t count) {
    static const std::vector<Column> kColumns = {{"id", ValueType::Integer},
                                                 {"category", ValueType::Text},
                                                 {"scene", ValueType::Integer},
                                                 {"source_id", ValueType::Integer},
                                                 {"box", ValueType::Box}};
    ResultSet rs;
    std::size_t rows = limit ? static_cast<std::size_t>(std::max<std::int64_t>(*limit, 0)) : SIZE_MAX;
    // One row past the session's limit is enough to know it is exceeded.
    rows = std::min(rows, static_cast<std::size_t>(session.limits.maxRows) + 1);
    rs.columns = kColumns;
    rs.rows.reserve(std::min<std::uint64_t>(rows, count));
    // The label index's entries carry every column: no node record is read, and each entry
    // becomes its row as it is read.
    txn.forEachCategoryRow(keys, rows, [&](const storage::CategoryRow& node) {
        auto& row = rs.rows.emplace_back();
        row.reserve(5);
        row.emplace_back(static_cast<std::int64_t>(node.id));
        row.emplace_back(std::in_place_type<std::string>, category);
        row.emplace_back(static_cast<std::int64_t>(node.scene));
        if (node.sourceId)
            row.emplace_back(*node.sourceId);
        else
            row.emplace_back(std::monostate{});
        if (node.geometry == model::GeometryKind::None)
            row.emplace_back(std::monostate{});
        else
            row.emplace_back(node.box);
    });
    checkRowLimit(session, rs.rows.size());
    return rs;
}

}  // namespace smql::exec
