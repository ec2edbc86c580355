#include "fleet/schema.hpp"

#include <array>
#include <string_view>

#include <fmt/format.h>

#include "model/error.hpp"

namespace smql::fleet {

namespace {

// pg_advisory_xact_lock's key for migrations: any fixed number other programs are unlikely to use.
constexpr const char* kMigrationLock = "SELECT pg_advisory_xact_lock(7236518294411)";

// Version 1: scenes keyed by (device, name, version) under a 63-bit hash of that key (`id`, the
// column a sharded store distributes by); every other table leads with the scene's id. Nodes
// carry the box, its footprint (the world bounds seen from above) and z range for the GiST index
// on (scene, footprint); the B-trees are the ones the PostGIS baseline's queries read.
constexpr const char* kVersion1 = R"sql(
CREATE TABLE smql.scenes(
    id bigint PRIMARY KEY, device text NOT NULL, name text NOT NULL, version bigint NOT NULL,
    source text NOT NULL, capture_time text NOT NULL, alignment float8[] NOT NULL, scale float8 NOT NULL,
    viewpoint_x float8 NOT NULL, viewpoint_y float8 NOT NULL, viewpoint_z float8 NOT NULL,
    viewpoint_yaw float8 NOT NULL, viewpoint_note text NOT NULL,
    node_count integer NOT NULL, relation_count integer NOT NULL, blob_count integer NOT NULL,
    change_count integer NOT NULL, superseded_at text, pushed_at timestamptz NOT NULL DEFAULT now());
CREATE INDEX scenes_by_name ON smql.scenes(name, device, version);
CREATE INDEX scenes_by_device ON smql.scenes(device, name, version);
CREATE TABLE smql.nodes(
    scene bigint NOT NULL, id integer NOT NULL, parent integer NOT NULL, kind smallint NOT NULL,
    category text NOT NULL, geometry smallint NOT NULL,
    cx float8 NOT NULL, cy float8 NOT NULL, cz float8 NOT NULL,
    sx float8 NOT NULL, sy float8 NOT NULL, sz float8 NOT NULL, yaw float8 NOT NULL,
    hidden boolean NOT NULL, confidence float4 NOT NULL, source_id bigint, text text NOT NULL,
    min_z float8, max_z float8, footprint geometry(Polygon),
    PRIMARY KEY (scene, id));
CREATE INDEX nodes_by_scene_footprint ON smql.nodes USING gist (scene, footprint);
CREATE INDEX nodes_by_scene_category ON smql.nodes(scene, category)
    INCLUDE (id, kind, geometry, cx, cy, cz, sx, sy, sz, yaw, hidden, min_z, max_z, footprint);
CREATE INDEX nodes_by_category ON smql.nodes(category, scene) INCLUDE (id, source_id, cx, cy, cz, sx, sy, sz, yaw);
CREATE INDEX nodes_by_parent ON smql.nodes(scene, parent);
CREATE TABLE smql.attributes(
    scene bigint NOT NULL, node integer NOT NULL, position integer NOT NULL, name text NOT NULL,
    value text NOT NULL, PRIMARY KEY (scene, node, position));
CREATE TABLE smql.relations(
    scene bigint NOT NULL, position integer NOT NULL, subject integer NOT NULL, object integer NOT NULL,
    type smallint NOT NULL, frame integer NOT NULL, score float4 NOT NULL, support bigint NOT NULL,
    PRIMARY KEY (scene, position));
CREATE TABLE smql.blobs(
    scene bigint NOT NULL, node integer NOT NULL, name text NOT NULL, media_type text NOT NULL,
    bytes bytea NOT NULL, PRIMARY KEY (scene, node, name));
CREATE TABLE smql.embeddings(
    scene bigint NOT NULL, node integer NOT NULL, vector float4[] NOT NULL, PRIMARY KEY (scene, node));
CREATE TABLE smql.changes(
    scene bigint NOT NULL, position integer NOT NULL, kind smallint NOT NULL, category text NOT NULL,
    before integer NOT NULL, after integer NOT NULL,
    from_cx float8 NOT NULL, from_cy float8 NOT NULL, from_cz float8 NOT NULL, from_sx float8 NOT NULL,
    from_sy float8 NOT NULL, from_sz float8 NOT NULL, from_yaw float8 NOT NULL,
    to_cx float8 NOT NULL, to_cy float8 NOT NULL, to_cz float8 NOT NULL, to_sx float8 NOT NULL,
    to_sy float8 NOT NULL, to_sz float8 NOT NULL, to_yaw float8 NOT NULL,
    PRIMARY KEY (scene, position));
)sql";

// The migrations in order: migration i (from 0) takes the store from version i to i + 1.
constexpr std::array<std::string_view, 1> kMigrations = {kVersion1};

constexpr const char* kVersionTable =
    "CREATE SCHEMA IF NOT EXISTS smql; "
    "CREATE TABLE IF NOT EXISTS smql.schema_version(version integer PRIMARY KEY, "
    "applied_at timestamptz NOT NULL DEFAULT now())";

void rollbackQuietly(pg::Connection& c) {
    try {
        c.exec("ROLLBACK", "rolling back");
    } catch (const Error&) {
        // The connection is gone or the transaction already ended: nothing is committed either way.
    }
}

}  // namespace

// PostGIS and btree_gist (the GiST index on (scene, footprint) leads with a bigint): created when
// missing, which needs a role allowed to; said plainly when the server has no PostGIS at all.
void requireExtensions(pg::Connection& c) {
    pg::Result available = c.exec(
        "SELECT name FROM pg_available_extensions WHERE name IN ('postgis', 'btree_gist') AND installed_version IS "
        "NULL",
        "looking for PostGIS");
    pg::Result installable =
        c.exec("SELECT count(*) FROM pg_available_extensions WHERE name = 'postgis'", "looking for PostGIS");
    if (installable.integer(0, 0) == 0)
        throw Error(ErrorKind::Storage,
                    fmt::format("the fleet store {} has no PostGIS: the server does not offer "
                                "the extension",
                                c.where()),
                    std::nullopt, "install PostGIS 3 on the server (Debian: postgresql-15-postgis-3)");
    for (int i = 0; i < available.rows(); ++i) {
        std::string name(available.text(i, 0));
        try {
            c.exec("BEGIN", "beginning to create an extension");
            takeMigrationLock(c);
            c.exec(fmt::format("CREATE EXTENSION IF NOT EXISTS {}", name), fmt::format("creating extension {}", name));
            c.exec("COMMIT", fmt::format("committing extension {}", name));
        } catch (const Error& e) {
            rollbackQuietly(c);
            throw Error(ErrorKind::Storage, e.message(), std::nullopt,
                        fmt::format("a superuser (or the database's owner, for trusted extensions) runs CREATE "
                                    "EXTENSION {} in the database once; then run smql fleet init again",
                                    name));
        }
    }
}

void createVersionTable(pg::Connection& c) { c.exec(kVersionTable, "creating the schema version table"); }

void takeMigrationLock(pg::Connection& c) { c.exec(kMigrationLock, "waiting for other migrations"); }

std::string_view migrationSql(int version) { return kMigrations.at(static_cast<std::size_t>(version - 1)); }

int latestSchemaVersion() { return static_cast<int>(kMigrations.size()); }

int schemaVersion(pg::Connection& c) {
    pg::Result exists = c.exec("SELECT to_regclass('smql.schema_version') IS NOT NULL", "reading the schema version");
    if (exists.text(0, 0) != "t") return 0;
    pg::Result version =
        c.exec("SELECT coalesce(max(version), 0) FROM smql.schema_version", "reading the schema version");
    return static_cast<int>(version.integer(0, 0));
}

int migrate(pg::Connection& c) {
    const int found = schemaVersion(c);
    if (found > latestSchemaVersion()) requireCurrentSchema(c);
    if (found == latestSchemaVersion()) return found;
    requireExtensions(c);
    for (int target = 1; target <= latestSchemaVersion(); ++target) {
        c.exec("BEGIN", "beginning a migration");
        try {
            takeMigrationLock(c);
            createVersionTable(c);
            if (schemaVersion(c) >= target) {
                c.exec("COMMIT", "ending a migration");
                continue;
            }
            c.exec(kMigrations[static_cast<std::size_t>(target - 1)],
                   fmt::format("migrating the schema to version {}", target));
            c.exec(fmt::format("INSERT INTO smql.schema_version(version) VALUES ({})", target),
                   "recording the schema version");
            c.exec("COMMIT", fmt::format("committing schema version {}", target));
        } catch (...) {
            rollbackQuietly(c);
            throw;
        }
    }
    return found;
}

void requireCurrentSchema(pg::Connection& c) {
    const int version = schemaVersion(c);
    if (version == latestSchemaVersion()) return;
    if (version > latestSchemaVersion())
        throw Error(ErrorKind::Storage,
                    fmt::format("the fleet store {} has schema version {}; this smql knows versions up to {}",
                                c.where(), version, latestSchemaVersion()),
                    std::nullopt, "a newer smql made it: use that smql (or a newer one) with this store");
    throw Error(ErrorKind::Storage,
                version == 0 ? fmt::format("the fleet store {} has no smql schema", c.where())
                             : fmt::format("the fleet store {} has schema version {}; this smql needs version {}",
                                           c.where(), version, latestSchemaVersion()),
                std::nullopt, "run smql fleet init URL first (it creates or upgrades the schema)");
}

}  // namespace smql::fleet
