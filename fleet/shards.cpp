#include "fleet/shards.hpp"

#include <regex>

#include <fmt/format.h>

#include "fleet/predicates_sql.hpp"
#include "fleet/schema.hpp"
#include "fleet/store.hpp"
#include "model/error.hpp"

namespace smql::fleet {

namespace {

struct Table {
    std::string name;
    std::string ddl;  // CREATE TABLE ... PARTITION BY HASH (key)
};

// The coordinator's tables, made from the shards' own migration: the same columns, without the
// keys and indexes (a partitioned table of foreign partitions has none; each shard keeps its own),
// partitioned by the scene key: `id` in scenes, `scene` everywhere else.
std::vector<Table> partitionedTables() {
    static const std::regex createTable(R"(CREATE TABLE smql\.(\w+)\()");
    static const std::regex tableKey(R"(,\s*PRIMARY KEY \([^)]*\))");
    std::vector<Table> out;
    std::string sql(migrationSql(1));
    for (std::size_t start = 0, end = 0; (end = sql.find(';', start)) != std::string::npos; start = end + 1) {
        std::string statement = sql.substr(start, end - start);
        std::smatch m;
        if (!std::regex_search(statement, m, createTable)) continue;  // indexes stay on the shards
        Table t{m[1].str(), std::regex_replace(statement, tableKey, "")};
        for (auto at = t.ddl.find(" PRIMARY KEY"); at != std::string::npos; at = t.ddl.find(" PRIMARY KEY"))
            t.ddl.erase(at, 12);
        t.ddl += fmt::format(" PARTITION BY HASH ({})", t.name == "scenes" ? "id" : "scene");
        out.push_back(std::move(t));
    }
    return out;
}

std::string serverOptions(const pg::UrlParts& shard) {
    // Rows inserted into a shard go in batches of 1,000 (one remote statement each).
    std::string options = "extensions 'postgis', batch_size '1000'";
    if (!shard.host.empty()) options += ", host " + pg::quoted(shard.host);
    if (!shard.port.empty()) options += ", port " + pg::quoted(shard.port);
    if (!shard.database.empty()) options += ", dbname " + pg::quoted(shard.database);
    return options;
}

std::string coordinatorSql(const std::vector<std::string>& shards) {
    std::string sql =
        "CREATE TABLE smql.shards(number integer PRIMARY KEY, server text NOT NULL, store text NOT NULL);\n";
    for (std::size_t i = 0; i < shards.size(); ++i) {
        const pg::UrlParts parts = pg::urlParts(shards[i]);
        sql += fmt::format("CREATE SERVER smql_shard_{0} FOREIGN DATA WRAPPER postgres_fdw OPTIONS ({1});\n", i,
                           serverOptions(parts));
        sql += fmt::format("CREATE USER MAPPING FOR PUBLIC SERVER smql_shard_{0}{1};\n", i,
                           parts.user.empty() ? "" : " OPTIONS (user " + pg::quoted(parts.user) + ")");
        sql += fmt::format("INSERT INTO smql.shards VALUES ({}, 'smql_shard_{}', {});\n", i, i,
                           pg::quoted(pg::describeUrl(shards[i])));
    }
    for (const Table& t : partitionedTables()) {
        sql += t.ddl + ";\n";
        for (std::size_t i = 0; i < shards.size(); ++i)
            sql += fmt::format(
                "CREATE FOREIGN TABLE smql.{0}_{1} PARTITION OF smql.{0} FOR VALUES WITH (MODULUS {2}, REMAINDER {1}) "
                "SERVER smql_shard_{1} OPTIONS (schema_name 'smql', table_name '{0}');\n",
                t.name, i, shards.size());
    }
    return sql + fmt::format("INSERT INTO smql.schema_version(version) VALUES ({});\n", latestSchemaVersion());
}

}  // namespace

InitReport initSharded(const std::string& url, const std::vector<std::string>& shards) {
    if (shards.empty()) throw Error(ErrorKind::Usage, "a sharded fleet store needs at least one shard");
    for (const std::string& shard : shards) init(shard);
    Store store(url);
    pg::Connection& c = store.connection();
    InitReport report;
    report.before = schemaVersion(c);
    if (report.before == 0) {
        requireExtensions(c);  // the footprint's geometry type
        c.exec("BEGIN", "beginning the coordinator's schema");
        try {
            takeMigrationLock(c);
            c.exec("CREATE EXTENSION IF NOT EXISTS postgres_fdw", "creating extension postgres_fdw");
            createVersionTable(c);
            c.exec(coordinatorSql(shards), "creating the coordinator's partitioned tables");
            c.exec("COMMIT", "committing the coordinator's schema");
        } catch (...) {
            try {
                c.exec("ROLLBACK", "rolling back");
            } catch (const Error&) {
                // The connection is gone: nothing was committed.
            }
            throw;
        }
    } else {
        requireCurrentSchema(c);
    }
    report.after = schemaVersion(c);
    report.predicates = installPredicates(c, report.predicatesMissing);
    return report;
}

}  // namespace smql::fleet
