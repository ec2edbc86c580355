// Many devices' memories in one PostgreSQL + PostGIS database (docs/fleet.md): `smql fleet init`,
// `smql push`, `smql pull`, and smql_push / smql_pull in the C API are these calls.
#pragma once

#include <cstdint>
#include <string>

#include "fleet/local/local_scenes.hpp"

namespace smql::storage {
class Database;
}

namespace smql::fleet {

struct InitReport {
    int before = 0;  // the store's schema version before (0: it had none)
    int after = 0;   // and now
    // Whether the predicates' SQL functions are there (fleet/predicates_sql.hpp), and why not.
    bool predicates = false;
    std::string predicatesMissing;
};
// Creates the store's schema in the database the URL names, or brings it up to date, then
// (re)creates the predicates' functions when the server has smql_pg.so.
InitReport init(const std::string& url);

// Sends every scene version of the device that the store lacks, each in one transaction.
PushReport push(const LocalSource& local, const std::string& url);
PushReport push(storage::Database& database, const std::string& url);

// One scene version from the store. Throws smql::Error(Binding) when the store has no such
// scene, or when devices hold scenes of that name and the request does not say whose.
Pulled fetch(const std::string& url, const PullRequest& request);
// fetch, then stored in `database` as a new scene under its name.
Pulled pull(const std::string& url, const PullRequest& request, storage::Database& database);

}  // namespace smql::fleet
