// A device's side of the fleet: the scene versions of a local database as they travel to the fleet
// store and back, the device's id, and a pulled scene stored. Only storage and the model here: the
// C API reads and writes its database with this and leaves the server to the fleet module.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "model/types.hpp"

namespace smql::storage {
class Database;
}

namespace smql::fleet {

// One version of a scene as it travels: the n-th capture of the place (1 for the first import;
// an update makes the next), in local ids (1..n in the order the database holds the nodes, the
// root implied by parent 0), as `smql export json` sees a scene.
struct SceneVersionData {
    std::uint64_t version = 0;
    model::SceneData data;  // info.id, nodeCount and version are 0; a superseded version has no blobs
    // For a version an update replaced: when, and what that update changed (`before` in this
    // version's local ids, `after` in the next version's).
    std::string supersededAt;
    std::vector<model::ObjectChange> changes;
};

// A local scene and how many versions it has (its history and the current one).
struct LocalScene {
    std::string name;
    std::uint64_t versions = 0;
};

// What a push needs of the device: its id, its scenes, and a way to read a scene's versions
// (oldest first) when the server lacks one of them.
struct LocalSource {
    std::string device;
    std::vector<LocalScene> scenes;
    std::function<std::vector<SceneVersionData>(const std::string& scene)> read;
};

// What a push did, and what a pull asks for and gets (the C API passes them to its fleet module).
struct PushReport {
    std::string device;
    std::size_t sent = 0;     // scene versions stored by this push
    std::size_t present = 0;  // versions the store had already (not sent)
    std::size_t nodes = 0;    // nodes of the versions sent
    double seconds = 0;
    // "pushed 3 scene versions (1204 nodes) of device 5f0c...; 2 were there already; 0.40 s"
    std::string summary() const;
};
struct PullRequest {
    std::string scene;
    std::string device;         // the device whose scene it is (a prefix of its id); "" for any
    std::uint64_t version = 0;  // 0: the newest
};
struct Pulled {
    std::string device;
    SceneVersionData version;
};

// The setting that holds the device's id in the local database.
inline constexpr const char* kDeviceSetting = "fleet.device";

// The device's id: made (a random UUID) and stored the first time, so it stays the same for
// every push from this database. Throws smql::Error(Storage) when it is missing and the database
// is read-only.
std::string deviceId(storage::Database& database);
// The source over a database (reads in a read transaction of their own, when the push asks).
LocalSource localSource(storage::Database& database);
// Every version of a scene, oldest first. Throws smql::Error(Binding) when there is no such scene.
std::vector<SceneVersionData> readVersions(storage::Database& database, const std::string& scene);
// Stores a pulled version as a new scene (its parents, ids and attributes as they are: nothing
// is recomputed), in one write transaction. Throws smql::Error(Input) when the name is taken.
void storePulled(storage::Database& database, const SceneVersionData& version);

}  // namespace smql::fleet
