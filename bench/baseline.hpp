// What the benchmark asks of a baseline database (SQLite, PostGIS): the query
// classes as an application on that database would answer them. SQL finds the
// candidates; the exact geometry runs in C++ with the engine's own predicate
// code (relations::evaluate), so every system answers with the same
// definitions and only the data access differs.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "model/geometry.hpp"
#include "model/types.hpp"
#include "relations/predicates.hpp"

namespace smql::bench {

// An answer in a form all systems can be compared in: node ids in answer
// order, a one-element count, or relation codes (relations::Predicate) in
// the order RELATE lists them.
using Answer = std::vector<std::int64_t>;

// One metric predicate of a FIND: `near(window, 1.5 m)`.
struct PredicateTerm {
    relations::Predicate predicate = relations::Predicate::Near;
    std::string category;
    std::optional<double> nearDistance;
};

class Baseline {
public:
    virtual ~Baseline() = default;
    // The name the report gives this system ("SQLite", "PostGIS").
    virtual std::string name() const = 0;

    // The scene the single-scene queries run against (an application keeps it, as USE SCENE does).
    virtual void useScene(const std::string& scene) = 0;
    // FIND object WHERE first AND second, in the current scene: ids in id order.
    virtual Answer findObjects(const PredicateTerm& first, const PredicateTerm& second) = 0;
    // RELATE #a TO #b from the scene's default viewpoint: the relations that hold, best first.
    virtual Answer relate(model::NodeId a, model::NodeId b) = 0;
    // FIND object NEAREST TO <category> LIMIT k: ids, nearest first (ties by id).
    virtual Answer nearestObjects(const std::string& category, int limit) = 0;
    // FIND <category> LIMIT n across every scene: ids in id order.
    virtual Answer findCategoryAll(const std::string& category, int limit) = 0;
    // COUNT <category> across every scene.
    virtual Answer countCategoryAll(const std::string& category) = 0;
};

// Margins around a reference's world bounds where a node's bounds must lie
// for `predicate(node, reference)` to hold: a necessary condition, so an
// index probe of the region returns a superset of the answers.
struct ProbeMargins {
    double horizontal = 0;  // x and y, both ways
    double below = 0;       // under the reference's bottom
    double above = 0;       // over the reference's top
};
ProbeMargins probeMargins(const PredicateTerm& term, const relations::Thresholds& thresholds);
model::Aabb probeRegion(const PredicateTerm& term, const model::Node& reference,
                        const relations::Thresholds& thresholds);
bool intersects(const model::Aabb& a, const model::Aabb& b);

// Whether the term holds for node `a` and reference `b`, by the engine's formulas.
bool holds(const PredicateTerm& term, const model::Node& a, const model::Node& b,
           const relations::Thresholds& thresholds, const relations::Frame& frame);

// FIND object WHERE first AND second as both baselines answer it: the candidates come from a probe
// around the smaller reference set (as smql's planner chooses), and each one that meets that term is
// checked against the other term through the regions of its references.
class TwoTermFind {
public:
    TwoTermFind(const PredicateTerm& first, std::vector<model::Node> firstRefs, const PredicateTerm& second,
                std::vector<model::Node> secondRefs, const relations::Thresholds& thresholds,
                const relations::Frame& frame);
    const PredicateTerm& probeTerm() const { return *probeTerm_; }
    const std::vector<model::Node>& probeReferences() const { return *probeRefs_; }
    // Whether `candidate` meets the probe term with `reference`, by the engine's formulas.
    bool meetsProbe(const model::Node& candidate, const model::Node& reference) const;
    // Whether `candidate` meets the other term with any of its references.
    bool meetsCheck(const model::Node& candidate) const;

private:
    std::vector<model::Node> firstRefs_, secondRefs_;
    const PredicateTerm* probeTerm_;
    const PredicateTerm* checkTerm_;
    const std::vector<model::Node>* probeRefs_;
    std::vector<std::pair<const model::Node*, model::Aabb>> checkRegions_;
    const relations::Thresholds& thresholds_;
    const relations::Frame& frame_;
};

// RELATE #a TO #b from the rows a baseline read for the two nodes, in any order, and the objects it
// read around them (aroundPair's region: near gives way to nearer things in a crowd): the relations
// that hold, best first, by the engine's formulas. Throws naming `system` when either is missing.
Answer relateRows(const std::string& system, model::NodeId a, model::NodeId b, const std::vector<model::Node>& rows,
                  const std::vector<model::Node>& around, const relations::Thresholds& thresholds,
                  const relations::Frame& frame);
// Where the objects that may crowd a pair out of near stand: both boxes grown by near.distance.
model::Aabb aroundPair(const std::vector<model::Node>& rows, const relations::Thresholds& thresholds);

// The k nearest of `distances` (exact box distance, id), nearest first and ties by id, as smql orders them.
Answer nearestFirst(std::vector<std::pair<double, model::NodeId>> distances, int limit);

}  // namespace smql::bench
