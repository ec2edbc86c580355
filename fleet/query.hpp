// SMQL statements that the fleet store's server runs, compiled to SQL: the first of them are a
// COUNT or a FIND of a category in one scene, with at most one predicate on a category
// (`FIND mug WHERE on(table)`, `COUNT chair WHERE near(door, 1 m)`). The predicate is the SQL
// function generated from the predicate table (fleet/predicates_sql.hpp), candidates come from the
// GiST index on (scene, footprint) when the predicate holds only near its reference. Anything else
// is refused with Error(Usage) saying it does not run on the store yet.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "fleet/store.hpp"
#include "model/result.hpp"

namespace smql::ast {
struct Statement;
}

namespace smql::fleet {

struct CompiledQuery {
    bool count = false;  // COUNT: one row, the count; FIND: the local ids of the nodes found, ascending
    std::string sql;     // $1: the scene version's key; $2...: `parameters`
    std::vector<std::string> parameters;
};

// Throws smql::Error: the parser's for a statement that does not parse, Usage for one the store
// does not run yet.
CompiledQuery compileQuery(const std::string& statement);
CompiledQuery compileQuery(const ast::Statement& statement);

struct QueryAnswer {
    std::optional<std::int64_t> count;  // COUNT
    std::vector<std::int64_t> ids;      // FIND: local ids, ascending
};

// Runs a statement in one stored scene version.
QueryAnswer runQuery(Store& store, const StoredVersion& scene, const std::string& statement);

// Statements on the store as the shell runs them (`smql URL -c "USE SCENE 'den'; COUNT chair"`):
// USE SCENE picks the newest version of a scene (of the device whose id starts with `device`),
// then COUNT and FIND run in it. FIND answers with the engine's columns, its ids the scene's local
// ids (1..n, as `smql export json` numbers the nodes).
class StoreSession {
public:
    StoreSession(const std::string& url, std::string device);
    // Hands each statement's result over as it is ready; throws on the first that fails.
    void execute(const std::string& text, const std::function<void(ResultSet&&)>& onResult);

private:
    ResultSet use(const std::string& scene);
    Store store_;
    std::string device_;
    std::optional<StoredVersion> scene_;
};

}  // namespace smql::fleet
