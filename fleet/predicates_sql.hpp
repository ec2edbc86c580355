// The predicates as SQL functions of the fleet store, generated from the predicate table
// (relations/predicates.cpp): `smql.on(a, b, viewpoint, others)`, `smql.near(a, b, viewpoint,
// others, distance)` ... each a call of smql_pg.so's smql_predicate_score with the predicate's
// code, so the server decides a pair with the engine's own code (fleet/server/smql_pg.cpp).
#pragma once

#include <string>

#include "fleet/pg/connection.hpp"

namespace smql::fleet {

// The SQL that (re)creates the functions: the two C entry points of smql_pg.so and one SQL
// function per predicate name and alias.
std::string predicateFunctionsSql();

// Creates them in one transaction. False (with the reason in `whyNot`) when the server cannot
// load smql_pg.so (not installed in its library folder) or the role may not create C functions
// (a superuser's right): push and pull work without them, statements on the store do not.
bool installPredicates(pg::Connection& connection, std::string& whyNot);

}  // namespace smql::fleet
