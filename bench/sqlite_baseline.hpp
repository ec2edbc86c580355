// The SQLite baseline: the same memory in SQLite tables with an R*Tree over
// the boxes, and the benchmark's query classes written the way a competent
// SQLite application would write them: prepared statements bound with
// parameters, covering indexes, an R*Tree over the bounds joined to the nodes
// by primary key (faster here than auxiliary columns, see kSchema), and a
// per-category count table that triggers keep up to date.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bench/baseline.hpp"
#include "model/types.hpp"

namespace smql::bench {

class SqliteBaseline final : public Baseline {
public:
    // Opens the database file and prepares every statement; `create` makes
    // the tables and indexes first.
    SqliteBaseline(const std::string& path, bool create);
    ~SqliteBaseline() override;
    SqliteBaseline(const SqliteBaseline&) = delete;
    SqliteBaseline& operator=(const SqliteBaseline&) = delete;

    // Stores a scene (the nodes as smql stored them, ids included) in one transaction.
    void importScene(const model::SceneInfo& info, const std::vector<model::Node>& nodes);
    // Folds the write-ahead log into the database file, so its size is the data's.
    void checkpoint();

    std::string name() const override { return "SQLite"; }
    void useScene(const std::string& scene) override;
    Answer findObjects(const PredicateTerm& first, const PredicateTerm& second) override;
    Answer relate(model::NodeId a, model::NodeId b) override;
    Answer nearestObjects(const std::string& category, int limit) override;
    Answer findCategoryAll(const std::string& category, int limit) override;
    Answer countCategoryAll(const std::string& category) override;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace smql::bench
