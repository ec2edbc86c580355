// What the fleet tests share: the private PostgreSQL cluster main.cpp starts, a fresh database on
// it per test, local databases of real rooms, and the store's own consistency checks.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>

#include "engine/engine.hpp"
#include "fleet/pg/local_cluster.hpp"
#include "storage/database.hpp"

namespace smql::testing {

// The cluster of this run (started by main.cpp before any test).
fleet::pg::LocalCluster& cluster();
// A new, empty database on the cluster with PostGIS and btree_gist; its URL as `user`.
std::string freshStore(const std::string& name);

// A fresh folder, removed when the test ends.
struct TempDir {
    std::filesystem::path path;
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    std::string sub(const std::string& name) const { return (path / name).string(); }
};

// A local database of real rooms: the Replica room, three VSI-Bench layouts, and a generated room
// `den` with stored embeddings and an evidence blob that has two versions (an update moved and
// removed objects). Six scene versions in all.
void buildRooms(Engine& engine);
inline constexpr std::size_t kRoomVersions = 6;
// Every VSI-Bench room of real-layouts/ (238 ScanNet and ARKitScenes rooms), for the kill test's
// longer pushes.
void buildRealLayouts(Engine& engine);

// SMQL_FLEET_KILLS, else `otherwise`: how many pushes a kill test kills.
inline int killCount(int otherwise) {
    const char* set = std::getenv("SMQL_FLEET_KILLS");
    return set ? std::atoi(set) : otherwise;
}
struct KilledPushes {
    int cutShort = 0;  // kills that fell after the first scene version's commit and before the last's
    double wholeMilliseconds = 0;
};
// Pushes `database` to `url` with `smql-fleet push` (as a new device each time), SIGKILLed at a
// moment drawn uniformly over a whole push's time, `kills` times; after each the store must hold no
// partial and no duplicated version, and a last push must complete (kill_test.cpp).
KilledPushes killPushes(storage::Database& database, const std::string& url, int kills);

// The scene as `smql export json` writes it.
std::string exportedJson(Engine& engine, const std::string& scene);

// Scene versions whose rows in the store do not add up to what their scene row says (a partial
// scene), plus rows of a key stored twice, plus rows no scene owns. 0 for a consistent store.
long long inconsistencies(const std::string& url);
// Scene versions the store holds (of one device, when given).
long long storedVersions(const std::string& url, const std::string& device = "");

}  // namespace smql::testing
