/* Built against an installed smql (pkg-config or find_package): links, loads, runs. */
#include <stdio.h>

#include <smql.h>

int main(void) {
    smql_db* db = NULL;
    /* A missing database opened read-only: a clean error, nothing created. */
    smql_status status = smql_open("/nonexistent/smql-db", SMQL_OPEN_READONLY, &db);
    printf("smql %s: %s\n", smql_version(), smql_status_string(status));
    int ok = status == SMQL_ERROR_STORAGE && smql_errmsg(db)[0] != '\0';
    /* The prepared-statement calls are exported too; on a handle that failed to open they are misuse. */
    smql_stmt* stmt = NULL;
    ok = ok && smql_prepare(db, "FIND ?", &stmt) == SMQL_ERROR_MISUSE && stmt == NULL;
    ok = ok && smql_step(stmt) == SMQL_ERROR_MISUSE && smql_bind_parameter_count(stmt) == 0;
    smql_finalize(stmt);
    smql_close(db);
    return ok ? 0 : 1;
}
