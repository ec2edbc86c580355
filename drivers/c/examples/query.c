/*
 * query.c - run SMQL against a database through the C API and print the rows,
 * once with the typed accessors and once as JSON.
 *
 *   usage: smql_c_example DB_DIR [STATEMENTS]
 *   e.g.   smql_c_example room.smql "FIND cushion WHERE on(sofa) PATH"
 */
#include <inttypes.h>
#include <stdio.h>

#include "smql.h"

static void print_value(const smql_result* res, size_t row, size_t col) {
    switch (smql_value_type(res, row, col)) {
        case SMQL_INTEGER: {
            int64_t v = 0;
            smql_value_int64(res, row, col, &v);
            printf("%" PRId64, v);
            break;
        }
        case SMQL_REAL: {
            double v = 0;
            smql_value_double(res, row, col, &v);
            printf("%.3f", v);
            break;
        }
        case SMQL_TEXT: {
            const char* v = "";
            smql_value_text(res, row, col, &v);
            fputs(v, stdout);
            break;
        }
        case SMQL_BOX: {
            smql_box b;
            smql_value_box(res, row, col, &b);
            printf("center (%.2f, %.2f, %.2f) size %.2f x %.2f x %.2f yaw %.2f rad", b.center[0], b.center[1],
                   b.center[2], b.size[0], b.size[1], b.size[2], b.yaw);
            break;
        }
        case SMQL_NULL:
            fputs("NULL", stdout);
            break;
        case SMQL_INVALID:
            fputs("?", stdout);
            break;
    }
}

int main(int argc, char** argv) {
    if (argc < 2 || argc > 3) {
        fprintf(stderr, "usage: %s DB_DIR [STATEMENTS]   (smql %s)\n", argv[0], smql_version());
        return 2;
    }
    const char* statements = argc == 3 ? argv[2] : "FIND object LIMIT 5 PATH";

    /* Read-only: querying never needs to write, and a wrong path is reported
     * instead of creating an empty database there. */
    smql_db* db = NULL;
    if (smql_open(argv[1], SMQL_OPEN_READONLY, &db) != SMQL_OK) {
        fprintf(stderr, "%s\n", smql_errmsg(db));
        smql_close(db);
        return 1;
    }

    smql_result* res = NULL;
    smql_status status = smql_execute(db, statements, &res);
    if (status != SMQL_OK) {
        fprintf(stderr, "%s\n", smql_errmsg(db));
        smql_close(db);
        return 1;
    }
    /* The result owns its data: the handle can go now. */
    smql_close(db);

    size_t columns = smql_column_count(res), rows = smql_row_count(res);
    for (size_t c = 0; c < columns; ++c) printf("%s%s", c ? "\t" : "", smql_column_name(res, c));
    if (columns) putchar('\n');
    for (size_t r = 0; r < rows; ++r) {
        for (size_t c = 0; c < columns; ++c) {
            if (c) putchar('\t');
            print_value(res, r, c);
        }
        putchar('\n');
    }
    if (columns) printf("(%zu row%s)\n", rows, rows == 1 ? "" : "s");
    for (size_t r = 0; r < rows; ++r) puts(smql_row_json(res, r));
    /* Statements such as SET, USE or RELATE also answer in a sentence. */
    for (size_t i = 0; i < smql_statement_count(res); ++i)
        if (*smql_statement_message(res, i)) puts(smql_statement_message(res, i));

    smql_result_free(res);
    return 0;
}
