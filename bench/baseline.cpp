#include "bench/baseline.hpp"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

namespace smql::bench {

using relations::Predicate;

ProbeMargins probeMargins(const PredicateTerm& term, const relations::Thresholds& thresholds) {
    switch (term.predicate) {
        case Predicate::On:
        case Predicate::In:
            return {0, 0, thresholds.onMaxGap};
        case Predicate::Near: {
            double d = term.nearDistance.value_or(thresholds.nearDistance);
            return {d, d, d};
        }
        default:
            throw std::logic_error(
                fmt::format("the baselines have no probe for {}()", relations::toString(term.predicate)));
    }
}

model::Aabb probeRegion(const PredicateTerm& term, const model::Node& reference,
                        const relations::Thresholds& thresholds) {
    ProbeMargins m = probeMargins(term, thresholds);
    model::Aabb b = model::worldAabb(reference.box);
    b.min = {b.min.x - m.horizontal, b.min.y - m.horizontal, b.min.z - m.below};
    b.max = {b.max.x + m.horizontal, b.max.y + m.horizontal, b.max.z + m.above};
    return b;
}

bool intersects(const model::Aabb& a, const model::Aabb& b) {
    return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y && a.min.z <= b.max.z &&
           b.min.z <= a.max.z;
}

// The peers read the rows a query needs, not the nodes around them: the benchmark's rooms have no
// wall between the pairs it asks and no lamp box whose floor other things take (relations' `on`), and
// every answer is checked equal to smql's, which reads them.
const relations::NodeObstacles kNoWallsRead{std::span<const model::Node>{}};

bool holds(const PredicateTerm& term, const model::Node& a, const model::Node& b,
           const relations::Thresholds& thresholds, const relations::Frame& frame) {
    return relations::evaluate(term.predicate, a, b, thresholds, frame, kNoWallsRead, nullptr, term.nearDistance) > 0;
}

TwoTermFind::TwoTermFind(const PredicateTerm& first, std::vector<model::Node> firstRefs, const PredicateTerm& second,
                         std::vector<model::Node> secondRefs, const relations::Thresholds& thresholds,
                         const relations::Frame& frame)
    : firstRefs_(std::move(firstRefs)), secondRefs_(std::move(secondRefs)), thresholds_(thresholds), frame_(frame) {
    const bool swap = secondRefs_.size() < firstRefs_.size();
    probeTerm_ = swap ? &second : &first;
    checkTerm_ = swap ? &first : &second;
    probeRefs_ = swap ? &secondRefs_ : &firstRefs_;
    for (const model::Node& ref : swap ? firstRefs_ : secondRefs_)
        if (ref.geometry != model::GeometryKind::None)
            checkRegions_.emplace_back(&ref, probeRegion(*checkTerm_, ref, thresholds_));
}

bool TwoTermFind::meetsProbe(const model::Node& candidate, const model::Node& reference) const {
    return holds(*probeTerm_, candidate, reference, thresholds_, frame_);
}

bool TwoTermFind::meetsCheck(const model::Node& candidate) const {
    const model::Aabb bounds = model::worldAabb(candidate.box);
    return std::any_of(checkRegions_.begin(), checkRegions_.end(), [&](const auto& region) {
        return intersects(bounds, region.second) && holds(*checkTerm_, candidate, *region.first, thresholds_, frame_);
    });
}

model::Aabb aroundPair(const std::vector<model::Node>& rows, const relations::Thresholds& thresholds) {
    model::Aabb out{{1e300, 1e300, 1e300}, {-1e300, -1e300, -1e300}};
    for (const model::Node& n : rows) {
        const model::Aabb b = model::worldAabb(n.box);
        out.min = {std::min(out.min.x, b.min.x), std::min(out.min.y, b.min.y), std::min(out.min.z, b.min.z)};
        out.max = {std::max(out.max.x, b.max.x), std::max(out.max.y, b.max.y), std::max(out.max.z, b.max.z)};
    }
    const double d = thresholds.nearDistance;
    out.min = {out.min.x - d, out.min.y - d, out.min.z - d};
    out.max = {out.max.x + d, out.max.y + d, out.max.z + d};
    return out;
}

Answer relateRows(const std::string& system, model::NodeId a, model::NodeId b, const std::vector<model::Node>& rows,
                  const std::vector<model::Node>& around, const relations::Thresholds& thresholds,
                  const relations::Frame& frame) {
    auto find = [&](model::NodeId id) {
        return std::find_if(rows.begin(), rows.end(), [&](auto& n) { return n.id == id; });
    };
    auto subject = find(a), object = find(b);
    if (subject == rows.end() || object == rows.end())
        throw std::runtime_error(fmt::format("{}: #{} or #{} is not in the current scene", system, a, b));
    Answer out;
    const relations::NodeObstacles crowd{std::span<const model::Node>(around)};
    for (const auto& hit : relations::relate(*subject, *object, thresholds, frame, crowd))
        out.push_back(static_cast<std::int64_t>(hit.predicate));
    return out;
}

Answer nearestFirst(std::vector<std::pair<double, model::NodeId>> distances, int limit) {
    auto k = std::min(distances.size(), static_cast<std::size_t>(std::max(limit, 0)));
    std::partial_sort(distances.begin(), distances.begin() + static_cast<std::ptrdiff_t>(k), distances.end());
    Answer out;
    for (std::size_t i = 0; i < k; ++i) out.push_back(static_cast<std::int64_t>(distances[i].second));
    return out;
}

}  // namespace smql::bench
