// The fleet store: scene versions of many devices in PostgreSQL + PostGIS (docs/fleet.md). One
// connection; each scene version is written in one transaction and read back whole.
#pragma once

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "fleet/local/local_scenes.hpp"
#include "fleet/pg/connection.hpp"

namespace smql::fleet {

// The 63-bit key a scene version has in the store, from (device, scene, version): the same on
// every device and server, so a push needs no sequence and a sharded store can route by it.
std::int64_t sceneKey(const std::string& device, const std::string& scene, std::uint64_t version);

// A version the store holds, as a pull names it.
struct StoredVersion {
    std::int64_t key = 0;
    std::string device;
    std::string scene;
    std::uint64_t version = 0;
};

class Store {
public:
    // Connects (the URL goes to libpq as it is: ~/.pgpass, PGSSLMODE and the rest apply).
    explicit Store(const std::string& url);

    pg::Connection& connection() { return connection_; }

    // The (scene, version) pairs the store holds of a device.
    std::set<std::pair<std::string, std::uint64_t>> versionsOf(const std::string& device);
    // Throws smql::Error(Storage) naming the role when it may not write scenes (a read-only role).
    void requireWriteAccess();
    // Stores one version in one transaction; false when the store already had it (then nothing
    // was written). A push killed at any moment leaves the version whole or absent.
    bool put(const std::string& device, const SceneVersionData& version);
    // The versions of a scene named `scene` (of devices whose id starts with `devicePrefix`), by
    // device, then version.
    std::vector<StoredVersion> versionsNamed(const std::string& scene, const std::string& devicePrefix);
    // The newest version of every scene of the devices whose id starts with `devicePrefix`.
    std::vector<StoredVersion> newestVersions(const std::string& devicePrefix);
    // One stored version, whole, in local ids.
    SceneVersionData get(const StoredVersion& stored);

private:
    enum class Staging { Direct, Staged };
    void prepareStaging();
    void copyRows(const char* table, const char* columns, const std::string& rows, const std::string& what);
    pg::Connection connection_;
    std::optional<Staging> staging_;  // known at the first put
};

}  // namespace smql::fleet
