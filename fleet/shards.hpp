// A fleet store sharded by scene over several PostgreSQL servers, with PostgreSQL's own machinery
// (docs/fleet.md, "Shards"): each shard is a store of its own (the same schema, indexes and
// predicates); the coordinator holds the same tables hash-partitioned by the scene key, each
// partition a postgres_fdw foreign table on one shard. Every table of a scene version is keyed by
// the same value, so a version's rows all live on one shard: a push of it is one remote transaction,
// a one-scene query touches one server, a fleet query fans out.
#pragma once

#include <string>
#include <vector>

#include "fleet/fleet.hpp"

namespace smql::fleet {

// Makes `url` the coordinator of `shards` (each initialised as a store first). The coordinator's
// foreign servers name each shard's host, port and database, and a user mapping its user: no
// password is stored (libpq on the coordinator's server finds one as it would for any client).
// A coordinator already made is left as it is. Needs a role that may create extensions and
// foreign servers (a superuser).
InitReport initSharded(const std::string& url, const std::vector<std::string>& shards);

}  // namespace smql::fleet
