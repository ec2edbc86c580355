// The PostGIS baseline: the same memory in a PostgreSQL database with PostGIS,
// written the way a competent PostGIS application would: data loaded with
// COPY, a GiST index on (scene, footprint) through btree_gist, covering
// B-tree indexes, a per-category count table kept by statement triggers, and
// every query a prepared statement run with generic plans
// (plan_cache_mode = force_generic_plan). Like the SQLite baseline, SQL finds
// the candidates and the exact geometry runs in C++ with the engine's code.
//
// PostgresServer runs a private cluster for the benchmark: initdb into a new
// temporary directory, the server listening only on a unix socket inside it,
// stopped and the directory removed when the object dies (also when the run
// fails). As root, initdb and the server run as the user `nobody` (PostgreSQL
// refuses to run as root).
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bench/baseline.hpp"
#include "model/types.hpp"

namespace smql::bench {

class PostgresServer {
public:
    // Starts a new cluster; nullopt (with the reason in `whyNot`) when
    // PostgreSQL's server binaries or the PostGIS extension are not installed.
    static std::unique_ptr<PostgresServer> start(std::string& whyNot);
    ~PostgresServer();
    PostgresServer(const PostgresServer&) = delete;
    PostgresServer& operator=(const PostgresServer&) = delete;

    // A libpq connection string for `database` on this server.
    std::string connectionString(const std::string& database) const;
    // Creates an empty database with the postgis and btree_gist extensions.
    void createDatabase(const std::string& database);
    // "PostgreSQL 15.5, PostGIS 3.3.2".
    const std::string& version() const { return version_; }

private:
    PostgresServer(std::filesystem::path binaries, std::filesystem::path directory);
    std::filesystem::path binaries_;
    std::filesystem::path directory_;  // the cluster (data/), its socket and its log
    bool running_ = false;
    std::string version_;
};

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
