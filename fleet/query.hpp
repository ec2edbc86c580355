// SMQL on the fleet store: statements compiled to SQL (fleet/query_sql.hpp) and run by the store's
// server, in one stored scene version or in the newest version of every scene.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "fleet/query_sql.hpp"
#include "fleet/store.hpp"
#include "model/result.hpp"
#include "relations/thresholds.hpp"

namespace smql::ast {
struct SetStmt;
struct AsOf;
}  // namespace smql::ast

namespace smql::fleet {

struct QueryAnswer {
    std::optional<std::int64_t> count;  // COUNT
    std::vector<std::int64_t> ids;      // FIND: local ids, in the answer's order
};

// Runs a statement in one stored scene version, with the default thresholds.
QueryAnswer runQuery(Store& store, const StoredVersion& scene, const std::string& statement);

// Statements on the store as the shell runs them (`smql URL -c "USE SCENE 'den'; COUNT chair"`):
// USE SCENE picks the newest version of a scene, or with '*' of every scene (of the devices whose
// id starts with `device`), SET changes the session's thresholds, then COUNT and FIND run there.
// FIND answers with the engine's columns, its ids the scene's local ids (1..n, as `smql export
// json` numbers the nodes).
class StoreSession {
public:
    StoreSession(const std::string& url, std::string device);
    // Hands each statement's result over as it is ready; throws on the first that fails.
    void execute(const std::string& text, const std::function<void(ResultSet&&)>& onResult);

private:
    ResultSet use(const std::string& scene);
    ResultSet set(const ast::SetStmt& set);
    ResultSet scenes();
    QueryScope scopeAsOf(const ast::AsOf& asOf);
    std::string url_;
    Store store_;
    // On a sharded store, the shard that holds the scene chosen: one-scene statements run there,
    // where its rows and indexes are, not through the coordinator's foreign tables row by row.
    std::optional<Store> shard_;
    std::string device_;
    std::optional<QueryScope> scope_;
    relations::Thresholds thresholds_;
};

}  // namespace smql::fleet
