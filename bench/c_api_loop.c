/* smql_bench_c_api: one prepared statement run again and again through the C API, every value of
 * every row read as the Python package reads it (bench/python_bench.py compares the two).
 *
 *     smql_bench_c_api DB RUNS STATEMENT [s:TEXT | i:INTEGER | d:REAL]...
 *
 * Prints "median_us rows": the median time of one run (reset, bind, step to the end). */
#define _POSIX_C_SOURCE 199309L
#include <smql.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now_us(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e6 + t.tv_nsec / 1e3;
}

static int by_value(const void* a, const void* b) {
    double x = *(const double*)a, y = *(const double*)b;
    return (x > y) - (x < y);
}

static int bind_all(smql_stmt* stmt, int count, char** params) {
    for (int i = 0; i < count; ++i) {
        const char* value = params[i] + 2;
        smql_status status;
        if (strncmp(params[i], "i:", 2) == 0)
            status = smql_bind_int(stmt, i + 1, strtoll(value, NULL, 10));
        else if (strncmp(params[i], "d:", 2) == 0)
            status = smql_bind_double(stmt, i + 1, strtod(value, NULL));
        else
            status = smql_bind_text(stmt, i + 1, value);
        if (status != SMQL_OK) return 0;
    }
    return 1;
}

int main(int argc, char** argv) {
    if (argc < 4) {
        fprintf(stderr, "usage: smql_bench_c_api DB RUNS STATEMENT [s:TEXT | i:INTEGER | d:REAL]...\n");
        return 2;
    }
    int runs = atoi(argv[2]);
    smql_db* db = NULL;
    smql_stmt* stmt = NULL;
    if (smql_open(argv[1], SMQL_OPEN_READONLY, &db) != SMQL_OK || smql_prepare(db, argv[3], &stmt) != SMQL_OK) {
        fprintf(stderr, "%s\n", smql_errmsg(db));
        return 1;
    }
    double* times = malloc(sizeof(double) * (size_t)runs);
    size_t rows = 0;
    for (int r = 0; r < runs; ++r) {
        double start = now_us();
        smql_reset(stmt);
        if (!bind_all(stmt, argc - 4, argv + 4)) {
            fprintf(stderr, "%s\n", smql_errmsg(db));
            return 1;
        }
        rows = 0;
        smql_status status;
        while ((status = smql_step(stmt)) == SMQL_ROW) {
            for (size_t c = 0; c < smql_stmt_column_count(stmt); ++c) {
                int64_t i;
                double d;
                const char* t;
                smql_box b;
                switch (smql_stmt_value_type(stmt, c)) {
                    case SMQL_INTEGER:
                        smql_stmt_value_int64(stmt, c, &i);
                        break;
                    case SMQL_REAL:
                        smql_stmt_value_double(stmt, c, &d);
                        break;
                    case SMQL_TEXT:
                        smql_stmt_value_text(stmt, c, &t);
                        break;
                    case SMQL_BOX:
                        smql_stmt_value_box(stmt, c, &b);
                        break;
                    default:
                        break;
                }
            }
            ++rows;
        }
        if (status != SMQL_DONE) {
            fprintf(stderr, "%s\n", smql_errmsg(db));
            return 1;
        }
        times[r] = now_us() - start;
    }
    qsort(times, (size_t)runs, sizeof(double), by_value);
    printf("%.3f %zu\n", times[runs / 2], rows);
    free(times);
    smql_finalize(stmt);
    smql_close(db);
    return 0;
}
