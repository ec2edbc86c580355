// The PostGIS baseline: the same memory in a PostgreSQL database with PostGIS,
// written the way a competent PostGIS application would: data loaded with
// COPY, a GiST index on (scene, footprint) through btree_gist, covering
// B-tree indexes, a per-category count table kept by statement triggers, and
// every query a prepared statement run with generic plans
// (plan_cache_mode = force_generic_plan). Like the SQLite baseline, SQL finds
// the candidates and the exact geometry runs in C++ with the engine's code.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bench/baseline.hpp"
#include "fleet/pg/local_cluster.hpp"
#include "model/types.hpp"

namespace smql::bench {

// The benchmark's private PostgreSQL cluster: fleet/pg/local_cluster.hpp, shared with the fleet tests.
using PostgresServer = fleet::pg::LocalCluster;
// Starts one with the benchmark's server settings; nullptr (with the reason in `whyNot`) when
// PostgreSQL's server binaries or the PostGIS extension are not installed.
std::unique_ptr<PostgresServer> startPostgres(std::string& whyNot);

class PostgisBaseline final : public Baseline {
public:
    // Connects, and with `create` makes the schema, then prepares every statement.
    PostgisBaseline(const std::string& connection, bool create);
    ~PostgisBaseline() override;
    PostgisBaseline(const PostgisBaseline&) = delete;
    PostgisBaseline& operator=(const PostgisBaseline&) = delete;

    // Loading: beginLoad() opens a COPY per table, addScene() streams a scene's
    // rows (the nodes as smql stored them, ids included), endLoad() ends the
    // COPYs, builds the indexes and analyses the tables.
    void beginLoad();
    void addScene(const model::SceneInfo& info, const std::vector<model::Node>& nodes);
    void endLoad();
    // The database's size on disk (tables and indexes).
    std::uint64_t databaseBytes();

    std::string name() const override { return "PostGIS"; }
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
