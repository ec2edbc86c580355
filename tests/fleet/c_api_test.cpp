// smql_push and smql_pull through libsmql.so, as a C program calls them: the fleet module loaded on
// the first call, the scene back byte for byte, errors as statuses with their text; and a handle
// smql_open makes of the store's URL, whose statements the store's server runs.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

#include "fleet/fleet.hpp"
#include "fleet/schema.hpp"
#include "fleet_support.hpp"
#include "smql.h"

using namespace smql::testing;

namespace {

std::string contents(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

struct Handle {
    smql_db* db = nullptr;
    explicit Handle(const std::string& dir, int flags = 0) { REQUIRE(smql_open(dir.c_str(), flags, &db) == SMQL_OK); }
    ~Handle() { smql_close(db); }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
};

}  // namespace

TEST_CASE("smql_push and smql_pull carry a scene to the fleet store and back") {
    const std::string url = freshStore("fleet_c_api");
    smql::fleet::pg::Connection c(url, "the store");
    smql::fleet::migrate(c);
    TempDir dir;
    const std::string replica = std::string(SMQL_SHARED_DATA) + "/replica-room0/info_semantic.json";
    Handle device(dir.sub("device"));
    REQUIRE(smql_import_file(device.db, "replica", replica.c_str(), "replica-room0") == SMQL_OK);

    smql_result* report = nullptr;
    REQUIRE(smql_push(device.db, url.c_str(), &report) == SMQL_OK);
    REQUIRE(smql_row_count(report) == 1);
    int64_t sent = 0;
    REQUIRE(smql_value_int64(report, 0, 1, &sent) == SMQL_OK);
    CHECK(sent == 1);
    smql_result_free(report);
    REQUIRE(smql_push(device.db, url.c_str(), nullptr) == SMQL_OK);  // nothing to send; no report asked for

    Handle copy(dir.sub("copy"));
    REQUIRE(smql_pull(copy.db, url.c_str(), "replica-room0", nullptr, 0) == SMQL_OK);
    REQUIRE(smql_export(device.db, "json", "replica-room0", dir.sub("original.json").c_str()) == SMQL_OK);
    REQUIRE(smql_export(copy.db, "json", "replica-room0", dir.sub("pulled.json").c_str()) == SMQL_OK);
    CHECK(contents(dir.sub("pulled.json")).size() > 1000);
    CHECK(contents(dir.sub("pulled.json")) == contents(dir.sub("original.json")));

    CHECK(smql_pull(copy.db, url.c_str(), "attic", nullptr, 0) == SMQL_ERROR_BINDING);
    CHECK_THAT(smql_errmsg(copy.db), Catch::Contains("has no scene named 'attic'"));
    CHECK(smql_push(device.db, "mysql://elsewhere", nullptr) == SMQL_ERROR_USAGE);
    CHECK_THAT(smql_errmsg(device.db), Catch::Contains("is not a fleet store URL"));
    CHECK(smql_pull(copy.db, nullptr, "replica-room0", nullptr, 0) == SMQL_ERROR_MISUSE);

    Handle readOnly(dir.sub("copy"), SMQL_OPEN_READONLY);
    CHECK(smql_pull(readOnly.db, url.c_str(), "replica-room0", nullptr, 0) == SMQL_ERROR_STORAGE);
    CHECK_THAT(smql_errmsg(readOnly.db), Catch::Contains("read-only"));
}

TEST_CASE("smql_open of a postgresql:// URL runs statements in the fleet store") {
#ifndef SMQL_PG_MODULE_DIR
    WARN("skipped: smql_pg.so was not built (no PostgreSQL server headers: postgresql-server-dev-15)");
    return;
#endif
    const std::string url = freshStore("fleet_c_api_open");
    smql::fleet::init(url);
    TempDir dir;
    const std::string replica = std::string(SMQL_SHARED_DATA) + "/replica-room0/info_semantic.json";
    Handle device(dir.sub("device"));
    REQUIRE(smql_import_file(device.db, "replica", replica.c_str(), "replica-room0") == SMQL_OK);
    REQUIRE(smql_push(device.db, url.c_str(), nullptr) == SMQL_OK);

    const char* statements = "USE SCENE 'replica-room0'; COUNT cushion WHERE on(sofa)";
    smql_result* local = nullptr;
    REQUIRE(smql_execute(device.db, statements, &local) == SMQL_OK);
    Handle store(url);
    smql_result* remote = nullptr;
    REQUIRE(smql_execute(store.db, statements, &remote) == SMQL_OK);
    int64_t here = 0, there = -1;
    REQUIRE(smql_value_int64(local, 0, 0, &here) == SMQL_OK);
    REQUIRE(smql_value_int64(remote, 0, 0, &there) == SMQL_OK);
    CHECK(here > 0);
    CHECK(there == here);
    CHECK_THAT(smql_statement_message(remote, 0), Catch::Contains("using scene 'replica-room0'"));
    smql_result_free(local);
    smql_result_free(remote);

    CHECK(smql_execute(store.db, "FIND chiar", nullptr) == SMQL_ERROR_BINDING);
    CHECK_THAT(smql_errmsg(store.db), Catch::Contains("unknown category 'chiar'"));
    CHECK(smql_import_file(store.db, "replica", replica.c_str(), "again") == SMQL_ERROR_MISUSE);
    CHECK_THAT(smql_errmsg(store.db), Catch::Contains("runs statements only"));

    smql_db* down = nullptr;
    CHECK(smql_open("postgresql://nobody@/nowhere?host=/nonexistent", 0, &down) == SMQL_ERROR_STORAGE);
    CHECK_FALSE(std::string(smql_errmsg(down)).empty());
    smql_close(down);
}
