// A private PostgreSQL cluster for tests and benchmarks: initdb into a new temporary folder, the
// server listening only on a unix socket inside it (so no other server shares its name, and a fixed
// port number is free there by construction), stopped and the folder removed when the object dies
// (also when the run fails). As root, initdb and the server run as the user `nobody` (PostgreSQL
// refuses to run as root). The bench's PostGIS baseline and the fleet tests start their servers
// with it.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace smql::fleet::pg {

class LocalCluster {
public:
    struct Options {
        // Server settings besides the socket (`-c name=value ...`), as postgres takes them.
        std::string settings;
        // The temporary folder's name starts with this.
        std::string prefix = "smql-pg";
    };
    // Starts a new cluster; nullptr (with the reason in `whyNot`) when PostgreSQL's server
    // binaries or the PostGIS extension are not installed. Throws when they are but the cluster
    // cannot be made or started.
    static std::unique_ptr<LocalCluster> start(const Options& options, std::string& whyNot);
    ~LocalCluster();
    LocalCluster(const LocalCluster&) = delete;
    LocalCluster& operator=(const LocalCluster&) = delete;

    // A libpq connection string, and the same as a postgresql:// URL, for `database` as `user`.
    std::string connectionString(const std::string& database, const std::string& user = "postgres") const;
    std::string url(const std::string& database, const std::string& user = "postgres") const;
    // Creates an empty database with these extensions.
    void createDatabase(const std::string& database,
                        const std::vector<std::string>& extensions = {"postgis", "btree_gist"});
    // Runs statements as the superuser in `database`.
    void execute(const std::string& database, const std::string& sql);
    // "PostgreSQL 15.5, PostGIS 3.3.2".
    const std::string& version() const { return version_; }
    const std::filesystem::path& directory() const { return directory_; }

private:
    LocalCluster(std::filesystem::path binaries, std::filesystem::path directory);
    std::filesystem::path binaries_;
    std::filesystem::path directory_;  // the cluster (data/), its socket and its log
    bool running_ = false;
    std::string version_;
};

}  // namespace smql::fleet::pg
