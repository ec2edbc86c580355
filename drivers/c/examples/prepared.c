/*
 * prepared.c - prepare one SMQL statement with placeholders, bind the values given on the
 * command line and step its rows; then run it again with the same values, as a program that
 * answers many questions of one shape would.
 *
 *   usage: smql_c_prepared_example DB_DIR STATEMENT [VALUE...]
 *   e.g.   smql_c_prepared_example room.smql "FIND ? WHERE near(?, ?)" cushion sofa 0.5
 *
 * A value that reads as a whole number is bound with smql_bind_int, one that reads as a
 * number with smql_bind_double (metres, for a distance), anything else with smql_bind_text.
 */
#include <stdio.h>
#include <stdlib.h>

#include "smql.h"

static smql_status bind_argument(smql_stmt* stmt, int index, const char* value) {
    char* end = NULL;
    long long whole = strtoll(value, &end, 10);
    if (*value && *end == '\0') return smql_bind_int(stmt, index, (int64_t)whole);
    double real = strtod(value, &end);
    if (*value && *end == '\0') return smql_bind_double(stmt, index, real);
    return smql_bind_text(stmt, index, value);
}

static int fail(smql_db* db, smql_stmt* stmt) {
    fprintf(stderr, "%s\n", smql_errmsg(db));
    smql_finalize(stmt);
    smql_close(db);
    return 1;
}

int main(int argc, char** argv) {
    if (argc < 3) {
        fprintf(stderr, "usage: %s DB_DIR STATEMENT [VALUE...]   (smql %s)\n", argv[0], smql_version());
        return 2;
    }
    smql_db* db = NULL;
    if (smql_open(argv[1], SMQL_OPEN_READONLY, &db) != SMQL_OK) return fail(db, NULL);

    /* Parsed once, here; the runs below only bind, plan and execute. */
    smql_stmt* stmt = NULL;
    if (smql_prepare(db, argv[2], &stmt) != SMQL_OK) return fail(db, NULL);
    int count = smql_bind_parameter_count(stmt);
    if (argc - 3 != count) {
        fprintf(stderr, "the statement has %d placeholder(s); %d value(s) given\n", count, argc - 3);
        smql_finalize(stmt);
        smql_close(db);
        return 2;
    }
    for (int i = 1; i <= count; ++i)
        if (bind_argument(stmt, i, argv[2 + i]) != SMQL_OK) return fail(db, stmt);

    for (int run = 1; run <= 2; ++run) {
        size_t rows = 0;
        smql_status status;
        while ((status = smql_step(stmt)) == SMQL_ROW) {
            printf("%s\n", smql_stmt_row_json(stmt));
            ++rows;
        }
        if (status != SMQL_DONE) return fail(db, stmt);
        printf("run %d: %zu row(s)%s%s\n", run, rows, *smql_stmt_message(stmt) ? "; " : "", smql_stmt_message(stmt));
        smql_reset(stmt); /* keeps the bindings */
    }
    smql_finalize(stmt);
    smql_close(db);
    return 0;
}
