#include "fleet/predicates_sql.hpp"

#include "fleet/schema.hpp"

#include <fmt/format.h>

#include "model/error.hpp"
#include "relations/predicates.hpp"

namespace smql::fleet {

namespace {

// The module's name without a folder: the server looks for it in dynamic_library_path, which is
// its own library folder ($libdir) unless set otherwise.
// Every function of the schema is dropped first: a newer smql's signatures (another argument) then
// replace the old ones rather than stand beside them as ambiguous overloads.
constexpr const char* kEntryPoints = R"sql(
DO $$ DECLARE f regprocedure; BEGIN
  FOR f IN SELECT p.oid::regprocedure FROM pg_proc p JOIN pg_namespace s ON s.oid = p.pronamespace
           WHERE s.nspname = 'smql' LOOP
    EXECUTE 'DROP FUNCTION ' || f;
  END LOOP;
END $$;
CREATE FUNCTION smql.predicate_score(code integer, a smql.nodes, b smql.nodes, c smql.nodes,
    viewpoint float8[], distance float8, others smql.nodes[], thresholds float8[])
  RETURNS float8 AS 'smql_pg', 'smql_predicate_score' LANGUAGE C IMMUTABLE PARALLEL SAFE;
CREATE FUNCTION smql.predicate_region(code integer, ref smql.nodes, distance float8, thresholds float8[])
  RETURNS float8[] AS 'smql_pg', 'smql_predicate_region' LANGUAGE C IMMUTABLE PARALLEL SAFE;
CREATE FUNCTION smql.relate(a smql.nodes, b smql.nodes, viewpoint float8[], others smql.nodes[], thresholds float8[])
  RETURNS float8[] AS 'smql_pg', 'smql_relate' LANGUAGE C IMMUTABLE PARALLEL SAFE;
CREATE FUNCTION smql.box_distance(a smql.nodes, b smql.nodes)
  RETURNS float8 AS 'smql_pg', 'smql_box_distance' LANGUAGE C IMMUTABLE STRICT PARALLEL SAFE;
)sql";

// One SQL function per word: its arguments follow the predicate's arity and whether it takes a
// distance; `viewpoint` (x, y, z, facing yaw) gives the view-relative ones their frame, `others`
// the nodes that may stand between, `thresholds` a session's settings (NULL: the defaults).
std::string functionFor(std::string_view word, const relations::PredicateSpec& spec) {
    const int code = static_cast<int>(spec.predicate);
    const bool two = spec.arity == 2;
    return fmt::format(
        "CREATE FUNCTION smql.\"{0}\"(a smql.nodes, b smql.nodes{1}, viewpoint float8[] DEFAULT NULL, "
        "others smql.nodes[] DEFAULT NULL{2}, thresholds float8[] DEFAULT NULL) RETURNS float8 LANGUAGE sql "
        "IMMUTABLE PARALLEL SAFE AS $$ SELECT smql.predicate_score({3}, a, b, {4}, viewpoint, {5}, others, "
        "thresholds) $$;\n",
        word, two ? ", c smql.nodes" : "", spec.takesDistance ? ", distance float8 DEFAULT NULL" : "", code,
        two ? "c" : "NULL", spec.takesDistance ? "distance" : "NULL");
}

}  // namespace

std::string predicateFunctionsSql() {
    std::string sql = kEntryPoints;
    for (const auto& spec : relations::predicates()) {
        sql += functionFor(spec.name(), spec);
        if (!spec.alias.empty()) sql += functionFor(spec.alias, spec);
    }
    return sql;
}

bool installPredicates(pg::Connection& c, std::string& whyNot) {
    c.exec("BEGIN", "beginning to create the predicates");
    try {
        takeMigrationLock(c);  // two inits at once would drop and create the same functions
        c.exec(predicateFunctionsSql(), "creating the predicates");
        c.exec("COMMIT", "committing the predicates");
        return true;
    } catch (const Error& e) {
        // 58P01: the server has no smql_pg.so; 42501: only a superuser may create C functions.
        const bool expected = c.lastState() == "58P01" || c.lastState() == "42501";
        try {
            c.exec("ROLLBACK", "rolling back");
        } catch (const Error&) {
            // The connection is gone: nothing was committed.
        }
        if (!expected) throw;
        whyNot = e.message();
        return false;
    }
}

}  // namespace smql::fleet
