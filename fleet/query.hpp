// SMQL statements that the fleet store's server runs, compiled to SQL: the first of them are a
// COUNT or a FIND of a category in one scene, with at most one predicate on a category
// (`FIND mug WHERE on(table)`, `COUNT chair WHERE near(door, 1 m)`). The predicate is the SQL
// function generated from the predicate table (fleet/predicates_sql.hpp), candidates come from the
// GiST index on (scene, footprint) when the predicate holds only near its reference. Anything else
// is refused with Error(Usage) saying it does not run on the store yet.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "fleet/store.hpp"

namespace smql::fleet {

struct CompiledQuery {
    bool count = false;  // COUNT: one row, the count; FIND: the local ids of the nodes found, ascending
    std::string sql;     // $1: the scene version's key; $2...: `parameters`
    std::vector<std::string> parameters;
};

// Throws smql::Error: the parser's for a statement that does not parse, Usage for one the store
// does not run yet.
CompiledQuery compileQuery(const std::string& statement);

struct QueryAnswer {
    std::optional<std::int64_t> count;  // COUNT
    std::vector<std::int64_t> ids;      // FIND: local ids, ascending
};

// Runs a statement in one stored scene version.
QueryAnswer runQuery(Store& store, const StoredVersion& scene, const std::string& statement);

}  // namespace smql::fleet
