#include "fleet/pg/local_cluster.hpp"

#include <unistd.h>

#include <cctype>
#include <cstdlib>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "fleet/pg/connection.hpp"

namespace smql::fleet::pg {

namespace fs = std::filesystem;

namespace {

// The socket lives in the cluster's own folder, so a fixed port number is free there.
constexpr int kPort = 5432;
constexpr const char* kUnprivilegedUser = "nobody";

int run(const std::string& command) {
    int status = std::system(command.c_str());
    return status == -1 ? -1 : WEXITSTATUS(status);
}

// The newest PostgreSQL server installed the Debian way (/usr/lib/postgresql/<version>/bin).
std::optional<fs::path> serverBinaries() {
    std::optional<fs::path> best;
    int bestVersion = 0;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator("/usr/lib/postgresql", ec)) {
        int version = std::atoi(entry.path().filename().c_str());
        if (version > bestVersion && fs::exists(entry.path() / "bin" / "initdb") &&
            fs::exists(entry.path() / "bin" / "pg_ctl")) {
            bestVersion = version;
            best = entry.path() / "bin";
        }
    }
    return best;
}

std::string asServerUser(const std::string& command) {
    return geteuid() == 0 ? fmt::format("runuser -u {} -- {}", kUnprivilegedUser, command) : command;
}

// A URL's query value: everything but unreserved characters and '/' percent-encoded.
std::string urlEncoded(const std::string& text) {
    std::string out;
    for (unsigned char c : text) {
        if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~' || c == '/')
            out += static_cast<char>(c);
        else
            out += fmt::format("%{:02X}", c);
    }
    return out;
}

}  // namespace

std::unique_ptr<LocalCluster> LocalCluster::start(const Options& options, std::string& whyNot) {
    auto binaries = serverBinaries();
    if (!binaries) {
        whyNot = "no PostgreSQL server under /usr/lib/postgresql/*/bin (Debian: postgresql-15-postgis-3)";
        return nullptr;
    }
    std::string pattern = (fs::temp_directory_path() / (options.prefix + "-XXXXXX")).string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a folder for the PostgreSQL cluster");
    std::unique_ptr<LocalCluster> cluster(new LocalCluster(*binaries, pattern));
    if (geteuid() == 0 && run(fmt::format("chown {} {}", kUnprivilegedUser, pattern)) != 0)
        throw std::runtime_error(fmt::format("cannot give {} to the user {}", pattern, kUnprivilegedUser));
    const fs::path& dir = cluster->directory_;
    if (run(asServerUser(fmt::format("{} -D {} -U postgres -A trust -E UTF8 --locale=C --no-sync > {} 2>&1",
                                     (*binaries / "initdb").string(), (dir / "data").string(),
                                     (dir / "initdb.log").string()))) != 0)
        throw std::runtime_error(fmt::format("initdb failed; see {}", (dir / "initdb.log").string()));
    if (run(asServerUser(fmt::format("{} -D {} -l {} -w -o \"-k {} -p {} -c listen_addresses='' {}\" start > /dev/null",
                                     (*binaries / "pg_ctl").string(), (dir / "data").string(),
                                     (dir / "server.log").string(), dir.string(), kPort, options.settings))) != 0)
        throw std::runtime_error(
            fmt::format("the PostgreSQL server did not start; see {}", (dir / "server.log").string()));
    cluster->running_ = true;

    Connection c(cluster->connectionString("postgres"), "the local cluster");
    Result available =
        c.exec("SELECT default_version FROM pg_available_extensions WHERE name = 'postgis'", "looking for PostGIS");
    if (available.rows() == 0) {
        whyNot = "PostgreSQL has no PostGIS extension installed (Debian: postgresql-15-postgis-3)";
        return nullptr;
    }
    Result server = c.exec("SHOW server_version", "asking for the version");
    cluster->version_ = fmt::format("PostgreSQL {}, PostGIS {}", server.text(0, 0), available.text(0, 0));
    return cluster;
}

LocalCluster::LocalCluster(fs::path binaries, fs::path directory)
    : binaries_(std::move(binaries)), directory_(std::move(directory)) {}

LocalCluster::~LocalCluster() {
    if (running_)
        run(asServerUser(fmt::format("{} -D {} -m fast -w stop > /dev/null 2>&1", (binaries_ / "pg_ctl").string(),
                                     (directory_ / "data").string())));
    std::error_code ignored;
    fs::remove_all(directory_, ignored);
}

std::string LocalCluster::connectionString(const std::string& database, const std::string& user) const {
    return fmt::format("host={} port={} user={} dbname={}", directory_.string(), kPort, user, database);
}

std::string LocalCluster::url(const std::string& database, const std::string& user) const {
    return fmt::format("postgresql://{}@/{}?host={}&port={}", user, database, urlEncoded(directory_.string()), kPort);
}

void LocalCluster::createDatabase(const std::string& database, const std::vector<std::string>& extensions) {
    execute("postgres", fmt::format("CREATE DATABASE {}", database));
    for (const std::string& extension : extensions)
        execute(database, fmt::format("CREATE EXTENSION IF NOT EXISTS {}", extension));
}

void LocalCluster::execute(const std::string& database, const std::string& sql) {
    Connection c(connectionString(database), fmt::format("the local cluster's database {}", database));
    c.exec(sql, sql);
}

}  // namespace smql::fleet::pg
