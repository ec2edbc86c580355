// The fleet store's schema in PostgreSQL: an ordered list of migrations, each applied in one
// transaction and recorded in smql.schema_version, so `smql fleet init` brings any older store up
// to date and a second run does nothing (docs/fleet.md, "Schema").
#pragma once

#include <string_view>

#include "fleet/pg/connection.hpp"

namespace smql::fleet {

// The version this smql writes and reads: the number of migrations it knows.
int latestSchemaVersion();

// Migration `version`'s SQL (1 ... latestSchemaVersion()): a sharded store's coordinator makes its
// partitioned tables from the same statements (fleet/shards.cpp).
std::string_view migrationSql(int version);

// The store's version (0 when it has no smql schema yet).
int schemaVersion(pg::Connection& connection);

// Applies every migration the store lacks, each in a transaction of its own under an advisory
// lock (two inits at once take turns). Returns the version it found. Throws smql::Error(Storage)
// for a store of a newer version, a server without PostGIS, or a role that cannot create it.
int migrate(pg::Connection& connection);

// PostGIS and btree_gist, created when missing (each under the migration lock). Throws
// smql::Error(Storage) when the server has no PostGIS or the role may not create them.
void requireExtensions(pg::Connection& connection);
// The schema `smql` and its version table, when missing.
void createVersionTable(pg::Connection& connection);

// Inside a transaction: waits for other migrations (and predicate installs) of the store, until the
// transaction ends, so that two inits at once take turns.
void takeMigrationLock(pg::Connection& connection);

// Throws smql::Error(Storage), with what to do, unless the store is at latestSchemaVersion().
void requireCurrentSchema(pg::Connection& connection);

}  // namespace smql::fleet
