/*
 * smql.h - the C API of smql, an embedded spatial memory engine.
 *
 * Pure C99. Opaque handles (smql_db, smql_result), a status code from every
 * call that can fail, and the error text kept in the database handle. No C++
 * exception ever crosses this interface. docs/c-api.md is the full reference.
 *
 *     smql_db* db = NULL;
 *     if (smql_open("my.smql", 0, &db) != SMQL_OK) {
 *         fprintf(stderr, "%s\n", smql_errmsg(db));
 *         smql_close(db);
 *         return 1;
 *     }
 *     smql_result* res = NULL;
 *     if (smql_execute(db, "FIND mug WHERE on(desk) PATH", &res) == SMQL_OK) {
 *         for (size_t r = 0; r < smql_row_count(res); ++r) puts(smql_row_json(res, r));
 *         smql_result_free(res);
 *     }
 *     smql_close(db);
 *
 * THREAD-SAFETY CONTRACT
 *
 *  - A smql_db may be shared by threads. Calls on one handle are serialised
 *    (the engine takes a lock per call), so sharing is safe but not parallel:
 *    for parallel queries, open one handle per thread.
 *  - Error state is kept per handle AND per calling thread: smql_errmsg,
 *    smql_errcode, smql_error_line and smql_error_column report the last call
 *    that THIS thread made on the handle, even while other threads use it.
 *    The string smql_errmsg returns stays valid until this thread's next call
 *    on the handle (or smql_close).
 *  - smql_close must not race with any other call on the same handle; it
 *    needs every other thread to be done with the handle.
 *  - A smql_result is an independent object owned by the caller: it keeps its
 *    data after smql_close of the handle that made it. Any number of threads
 *    may read one result at once; smql_result_free must not race with readers.
 *  - Several handles (in one process or in several processes) may open the
 *    same database directory: readers never block (LMDB MVCC) and writes
 *    (imports) take turns, one writer at a time. Within one process, opening
 *    a directory for writing while a read-only handle on it is open fails:
 *    open the read-write handle first, or both read-only.
 *  - Do not use a handle in a child process after fork(); open a new one.
 *
 * CONVENTIONS
 *
 *  - Fallible calls return smql_status; SMQL_OK is 0.
 *  - Calls that only look something up (counts, names, types, JSON, messages)
 *    return it directly, with a documented sentinel on misuse (0, NULL or
 *    SMQL_INVALID); they never touch the handle's error state.
 *  - Strings returned by the API are UTF-8, NUL-terminated and owned by the
 *    object they came from: never free them.
 */
#ifndef SMQL_H
#define SMQL_H

#include <stddef.h>
#include <stdint.h>

#if defined(__GNUC__)
#define SMQL_API __attribute__((visibility("default")))
#else
#define SMQL_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

typedef struct smql_db smql_db;
typedef struct smql_result smql_result;

typedef enum smql_status {
    SMQL_OK = 0,
    SMQL_ERROR_SYNTAX = 1,   /* a statement does not parse */
    SMQL_ERROR_BINDING = 2,  /* a name does not resolve: category, scene, setting, node */
    SMQL_ERROR_INPUT = 3,    /* a malformed or missing import file */
    SMQL_ERROR_STORAGE = 4,  /* the database cannot be opened or written (read-only, schema, I/O) */
    SMQL_ERROR_USAGE = 5,    /* a statement or option used wrongly */
    SMQL_ERROR_MISUSE = 6,   /* the API used wrongly: NULL handle or argument, bad index, wrong type */
    SMQL_ERROR_INTERNAL = 7, /* a bug or out of memory; the message says which */
    SMQL_ERROR_LIMIT = 8,    /* a statement would exceed a limit (max_rows, max_pairs); SET raises it */
    SMQL_ERROR_INTERRUPTED = 9 /* smql_interrupt stopped the statement */
} smql_status;

typedef enum smql_type {
    SMQL_INVALID = -1,  /* returned for a NULL result or an index out of range */
    SMQL_NULL = 0,
    SMQL_INTEGER = 1,
    SMQL_REAL = 2,
    SMQL_TEXT = 3,
    SMQL_BOX = 4
} smql_type;

/* An upright oriented box in metres, z up: full extents along the box's own
 * axes; yaw in radians, counter-clockwise about +z. */
typedef struct smql_box {
    double center[3];
    double size[3];
    double yaw;
} smql_box;

/* smql_open flags (0: read-write, the database is created if missing). */
#define SMQL_OPEN_READONLY 0x1

/* The library version, "major.minor.patch". */
SMQL_API const char* smql_version(void);

/* A short English description of a status ("syntax error", ...); never NULL. */
SMQL_API const char* smql_status_string(smql_status status);

/* ---- Database handles ------------------------------------------------ */

/* Opens the database in directory `dir`. On SMQL_OK *out is a usable handle.
 * On any other status *out is still a handle (unless out is NULL or memory
 * ran out) that only reports the error: read smql_errmsg(*out), then
 * smql_close(*out). Every other call on such a handle gives SMQL_ERROR_MISUSE. */
SMQL_API smql_status smql_open(const char* dir, int flags, smql_db** out);

/* Closes the handle; NULL is a no-op. Results it produced stay valid. Safe at
 * process exit too: from an atexit() handler (registered before or after the
 * first smql_open) or a static destructor. */
SMQL_API void smql_close(smql_db* db);

/* The calling thread's last error on `db`: multi-line text with the position,
 * the offending line with a caret under the spot, and a hint. "" when that
 * call succeeded; a fixed message when db is NULL. Never NULL. */
SMQL_API const char* smql_errmsg(const smql_db* db);
/* The status of the calling thread's last call on `db` (SMQL_ERROR_MISUSE for NULL). */
SMQL_API smql_status smql_errcode(const smql_db* db);
/* 1-based line and column in the statement text of the last error; 0 when it has no position. */
SMQL_API int smql_error_line(const smql_db* db);
SMQL_API int smql_error_column(const smql_db* db);

/* Runs every ';'-separated statement of `statements`, in order, each atomic
 * on its own. On SMQL_OK *out receives the rows of the LAST statement and the
 * messages of all of them (free it with smql_result_free); out may be NULL to
 * discard them. On failure *out is NULL, the statements before the failing
 * one have run, and smql_errmsg tells what failed and where. */
SMQL_API smql_status smql_execute(smql_db* db, const char* statements, smql_result** out);

/* Stops the statement smql_execute is running on `db` in another thread: that call returns
 * SMQL_ERROR_INTERRUPTED and changes nothing. Safe from any thread and from a signal handler; with
 * no statement running it does nothing. NULL is ignored. */
SMQL_API void smql_interrupt(smql_db* db);

/* Imports a scene layout file in one write transaction and makes it the
 * current scene. format: "replica" (info_semantic.json), "spatiallm" (layout
 * text) or "json" (the smql scene format). scene_name may be NULL: replica
 * files are named after their folder, spatiallm files after the file, json
 * files keep the name they hold. */
SMQL_API smql_status smql_import_file(smql_db* db, const char* format, const char* path, const char* scene_name);

/* ---- Results --------------------------------------------------------- */

/* Frees a result and every string taken from it; NULL is a no-op. */
SMQL_API void smql_result_free(smql_result* res);

/* Columns and rows of the last statement's result; 0 for NULL. */
SMQL_API size_t smql_column_count(const smql_result* res);
SMQL_API size_t smql_row_count(const smql_result* res);
/* NULL when res is NULL or col is out of range. */
SMQL_API const char* smql_column_name(const smql_result* res, size_t col);
/* The declared type of a column; single values may still be SMQL_NULL. */
SMQL_API smql_type smql_column_type(const smql_result* res, size_t col);
/* The type of one value: check it before calling the matching accessor. */
SMQL_API smql_type smql_value_type(const smql_result* res, size_t row, size_t col);

/* Typed accessors. Each returns SMQL_ERROR_MISUSE, leaving *out untouched,
 * for a NULL argument, an index out of range or a value of another type.
 * smql_value_double also accepts SMQL_INTEGER values. Text stays valid until
 * the result is freed. */
SMQL_API smql_status smql_value_int64(const smql_result* res, size_t row, size_t col, int64_t* out);
SMQL_API smql_status smql_value_double(const smql_result* res, size_t row, size_t col, double* out);
SMQL_API smql_status smql_value_text(const smql_result* res, size_t row, size_t col, const char** out);
SMQL_API smql_status smql_value_box(const smql_result* res, size_t row, size_t col, smql_box* out);

/* One row as a JSON object, {"id": 12, "box": {"center": [..], "size": [..], "yaw": 0.0}, ...};
 * NULL for a NULL result or a row out of range. Valid until the result is freed. */
SMQL_API const char* smql_row_json(const smql_result* res, size_t row);
/* The whole result, {"columns": [...], "rows": [{...}], "message": "..."}; NULL for NULL. */
SMQL_API const char* smql_result_json(const smql_result* res);

/* The sentence the last statement answered with (RELATE, SET, USE ...), "" if none; NULL for NULL. */
SMQL_API const char* smql_result_message(const smql_result* res);
/* How many statements ran, and the message of each (0-based, in order; NULL out of range). */
SMQL_API size_t smql_statement_count(const smql_result* res);
SMQL_API const char* smql_statement_message(const smql_result* res, size_t index);

#ifdef __cplusplus
}
#endif

#endif /* SMQL_H */
