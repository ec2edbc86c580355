// SMQL statements compiled to SQL for the fleet store's server: COUNT and FIND of a category, a kind
// of node (`object`, `anchor`, `node`), nodes by id or source id, or a sub-query's answer, in one
// scene or in every scene's newest version (`USE SCENE '*'`); WHERE with predicates, comparisons of
// attributes and distances, joined by AND, OR and NOT; NEAREST TO, ORDER BY and LIMIT. Each
// predicate is the SQL function generated from the predicate table (fleet/predicates_sql.hpp), with
// the session's thresholds; its references are probed with the region the table gives when it
// holds only near them. Names resolve as the engine's binder resolves them. Anything else is
// refused with Error(Usage) saying it does not run on the store yet.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "model/error.hpp"
#include "model/result.hpp"
#include "model/types.hpp"
#include "relations/thresholds.hpp"

namespace smql::ast {
struct Statement;
}

namespace smql::fleet {

// What a statement's names resolve against: the scene versions chosen, and what they hold.
struct QueryScope {
    std::string name;        // the scene's name, or "*", for messages
    std::string device;      // the device whose scene it is (one scene)
    bool allScenes = false;  // USE SCENE '*': FIND answers say each node's scene
    std::string keys;        // the versions' keys as a PostgreSQL int8[] literal: the queries' $1
    std::set<std::string> categories;
    std::set<std::string> attributes;  // the names of the attributes stored on their nodes
    // Whether some other stored scene holds a category: naming it is an empty answer, not an error.
    std::function<bool(const std::string&)> knownElsewhere;
    // The category of the node whose `column` (id or source_id) is `value`, if there is one.
    std::function<std::optional<std::string>(const char* column, std::int64_t value)> nodeCategory;
    // A node's id, its box's centre, and whether it is shown (not hidden) with a box.
    struct Located {
        std::int64_t id = 0;
        model::Vec3 centre;
        bool shown = false;
    };
    // Runs a query of located nodes (its columns: id, cx, cy, cz, shown) with its parameters after $1.
    std::function<std::vector<Located>(const std::string& sql, const std::vector<std::string>& parameters)> locate;
    model::Viewpoint viewpoint;  // the scene's (one scene): the default viewer of the sides and lateral predicates
};

struct CompiledQuery {
    // What the query's rows are: COUNT's one count; FIND's nodes (id, category, [scene name],
    // source id, whether placed, box, [distance]); RELATE's pairs (each side's id, category and
    // kind, the relations as (code, score) pairs, the distance); CHECK's one pair (the sides as
    // RELATE's, a third for between, the score, the distance); SHOW TREE's nodes (id, depth, label);
    // DESCRIBE's nodes (id, kind, category, geometry, box, hidden, confidence, source id, text,
    // scene version, path).
    enum class Shape { Count, Find, Return, Relate, Check, Tree, Describe };
    Shape shape = Shape::Find;
    bool distance = false;  // FIND ... NEAREST TO / ORDER BY distance(): a distance column
    bool path = false;      // FIND ... PATH: a last column, the way from the scene down to the node
    // FIND ... RETURN: the columns, each value as its type reads from SQL (a box as a float8[7]).
    std::vector<std::pair<std::string, ValueType>> returned;
    bool third = false;    // CHECK of a predicate of two references
    std::string relation;  // CHECK: the predicate's name
    std::string sql;       // $1: the scene versions' keys (int8[]); $2...: `parameters`
    std::vector<std::string> parameters;
    // RELATE and CHECK: what must be one node, each a query of its nodes' ids; run before `sql`.
    struct Single {
        std::string role;  // "CHECK's subject"
        std::string sql;
        std::vector<std::string> parameters;
    };
    std::vector<Single> singles;
};

// The error for a statement the store does not run yet (Usage), naming `what`.
Error notYet(const std::string& what);

// Throws smql::Error: Binding for an unknown name, Usage for a statement the store does not run yet.
CompiledQuery compileQuery(const ast::Statement& statement, const QueryScope& scope,
                           const relations::Thresholds& thresholds);

// The thresholds as the store's functions take them: a float8[] literal in the order of
// relations::settingsCatalogue.
std::string thresholdsArray(const relations::Thresholds& thresholds);

}  // namespace smql::fleet
