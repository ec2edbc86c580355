// The benchmark's memories: generated rooms (seed = scene index) imported
// into a new smql database and, node for node with the same ids, into a new
// SQLite file and (when a PostgreSQL server runs) a new PostGIS database,
// timing each system's import.
#pragma once

#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace smql::fleet::pg {
class LocalCluster;
}

namespace smql::bench {

struct DataSetSpec {
    std::string label;  // "small", "large"
    int scenes = 1;
    int objectsPerScene = 200;
};

struct ImportTimes {
    double smqlSeconds = 0;     // Engine::importScene over all scenes (tree building, indexes, commit)
    double sqliteSeconds = 0;   // SqliteBaseline::importScene over all scenes (rows, indexes, R*Tree, commit)
    double postgisSeconds = 0;  // PostgisBaseline: COPY of every scene, then the indexes, VACUUM ANALYZE
    // relations::assignParents alone (the part of smql's import that derives the
    // tree), timed on a copy of each of the first few scenes, and smql's whole
    // import of those same scenes.
    double treeSeconds = 0;
    double treeScenesImportSeconds = 0;
};

struct DataSet {
    DataSetSpec spec;
    std::filesystem::path smqlDirectory;
    std::filesystem::path sqliteFile;
    std::string postgisConnection;  // empty when PostGIS does not take part
    std::uint64_t nodes = 0;        // stored nodes, scene nodes left out
    std::uint64_t objects = 0;      // of which objects (the generator may place fewer than asked)
    ImportTimes import;
    std::uint64_t smqlBytes = 0;     // data.mdb
    std::uint64_t sqliteBytes = 0;   // the database file after a WAL checkpoint
    std::uint64_t postgisBytes = 0;  // pg_database_size
};

using PostgresServer = fleet::pg::LocalCluster;  // bench/postgis_baseline.hpp

std::string sceneName(int index);

// Builds the databases under `directory` (which must not hold them yet), and
// a PostGIS database named after the data set on `postgres` unless it is null.
DataSet buildDataSet(const DataSetSpec& spec, const std::filesystem::path& directory, PostgresServer* postgres,
                     std::ostream& progress);

}  // namespace smql::bench
