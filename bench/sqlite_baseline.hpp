// The SQLite baseline: the same memory in SQLite tables with an R*Tree over
// the boxes, and the benchmark's query classes written the way a competent
// SQLite application would write them (prepared statements, the
// (scene, category) and category indexes, the R*Tree for spatial candidates).
// SQL finds the candidates; the exact geometry checks run in C++ with the
// engine's own predicate code (relations::evaluate), so both systems answer
// with the same definitions and only the data access differs.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "model/types.hpp"
#include "engine/relations/predicates.hpp"

namespace smql::bench {

// An answer in a form both systems can be compared in: node ids in answer
// order, a one-element count, or relation codes (relations::Predicate) in
// the order RELATE lists them.
using Answer = std::vector<std::int64_t>;

// One metric predicate of a FIND: `near(window, 1.5 m)`.
struct PredicateTerm {
    relations::Predicate predicate = relations::Predicate::Near;
    std::string category;
    std::optional<double> nearDistance;
};

class SqliteBaseline {
public:
    // Opens the database file and prepares every statement; `create` makes
    // the tables and indexes first.
    SqliteBaseline(const std::string& path, bool create);
    ~SqliteBaseline();
    SqliteBaseline(const SqliteBaseline&) = delete;
    SqliteBaseline& operator=(const SqliteBaseline&) = delete;

    // Stores a scene (the nodes as smql stored them, ids included) in one transaction.
    void importScene(const model::SceneInfo& info, const std::vector<model::Node>& nodes);
    // Folds the write-ahead log into the database file, so its size is the data's.
    void checkpoint();

    // The scene the single-scene queries run against (an application keeps it, as USE SCENE does).
    void useScene(const std::string& name);

    // FIND object WHERE first AND second, in the current scene: ids in id order.
    Answer findObjects(const PredicateTerm& first, const PredicateTerm& second);
    // RELATE #a TO #b from the scene's default viewpoint: the relations that hold, best first.
    Answer relate(model::NodeId a, model::NodeId b);
    // FIND object NEAREST TO <category> LIMIT k: ids, nearest first.
    Answer nearestObjects(const std::string& category, int limit);
    // FIND <category> LIMIT n across every scene: ids in id order.
    Answer findCategoryAll(const std::string& category, int limit);
    // COUNT <category> across every scene.
    Answer countCategoryAll(const std::string& category);

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace smql::bench
