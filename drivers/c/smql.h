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
typedef struct smql_stmt smql_stmt;

typedef enum smql_status {
    SMQL_OK = 0,
    SMQL_ERROR_SYNTAX = 1,      /* a statement does not parse */
    SMQL_ERROR_BINDING = 2,     /* a name does not resolve: category, scene, setting, node */
    SMQL_ERROR_INPUT = 3,       /* a malformed or missing import file */
    SMQL_ERROR_STORAGE = 4,     /* the database cannot be opened or written (read-only, schema, I/O) */
    SMQL_ERROR_USAGE = 5,       /* a statement or option used wrongly */
    SMQL_ERROR_MISUSE = 6,      /* the API used wrongly: NULL handle or argument, bad index, wrong type */
    SMQL_ERROR_INTERNAL = 7,    /* a bug or out of memory; the message says which */
    SMQL_ERROR_LIMIT = 8,       /* a statement would exceed a limit (max_rows, max_pairs); SET raises it */
    SMQL_ERROR_INTERRUPTED = 9, /* smql_interrupt stopped the statement */
    SMQL_ROW = 100,             /* smql_step: a row is ready (not an error) */
    SMQL_DONE = 101             /* smql_step: the statement has run and every row was stepped over */
} smql_status;

typedef enum smql_type {
    SMQL_INVALID = -1, /* returned for a NULL result or an index out of range */
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

/* 1 when `statements` ends with a complete statement (a closing ';' outside strings and
 * parentheses), 0 when more text is needed or there is none (NULL, blanks); as sqlite3_complete:
 * a front end reading lines calls it to know when to run what it has. */
SMQL_API int smql_complete(const char* statements);

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

/* ASK's translator for this handle, as SET translator = '...' sets it (docs/ask.md): `url` is a
 * language model's OpenAI-compatible endpoint ("http://127.0.0.1:8080/v1"), asked with the
 * question, the scene's vocabulary and SMQL in brief, whose statement is parsed and bound before it
 * runs; the built-in reader answers when it is absent or fails. NULL, "" or "built-in" restores the
 * built-in reader. A URL that is not http:// is SMQL_ERROR_BINDING, as for SET, and changes nothing. */
SMQL_API smql_status smql_set_translator(smql_db* db, const char* url);

/* The translator ASK uses on this handle: the endpoint's URL, or "built-in". The text belongs to
 * the handle and stays valid until the next smql_translator or smql_close on it; NULL for a NULL
 * handle or one that failed to open. */
SMQL_API const char* smql_translator(smql_db* db);

/* Stops the statement smql_execute or smql_step is running on `db` in another thread: that call returns
 * SMQL_ERROR_INTERRUPTED and changes nothing. Safe from any thread and from a signal handler; with
 * no statement running it does nothing. NULL is ignored. */
SMQL_API void smql_interrupt(smql_db* db);

/* Imports a scene layout file in one write transaction and makes it the
 * current scene. format: "replica" (info_semantic.json), "spatiallm" (layout
 * text) or "json" (the smql scene format). scene_name may be NULL: replica
 * files are named after their folder, spatiallm files after the file, json
 * files keep the name they hold. */
SMQL_API smql_status smql_import_file(smql_db* db, const char* format, const char* path, const char* scene_name);

/* Reads a scene layout file (formats as for smql_import_file) as a new capture of the place
 * stored as `scene_name` (NULL: the current scene) and makes it that scene's next version, in one
 * write transaction: objects seen again, moved, new and missing are matched and recorded, and the
 * version before stays in the scene's history (docs/history.md). SHOW CHANGES then lists what
 * changed; smql_errmsg says why an update was refused. */
SMQL_API smql_status smql_update_file(smql_db* db, const char* format, const char* path, const char* scene_name);

/* Writes the stored scene `scene_name` (NULL: the current scene) to the file `path` in `format`:
 * "json" (the smql scene format, which smql_import_file reads back), the other formats of
 * `smql export` (docs/formats.md: glTF, PLY, GeoJSON, Spark-DSG ...), or "html" (the view's page
 * as one file, docs/view.md). An unknown format is SMQL_ERROR_USAGE naming the known ones. */
SMQL_API smql_status smql_export(smql_db* db, const char* format, const char* scene_name, const char* path);

/* Writes the capture's points of the stored scene `scene_name` (NULL: the current scene) to `path`:
 * the coloured point cloud ingest fused from every frame, as a binary PLY (what `smql export ply
 * --points` writes, docs/formats.md). A scene without points (imported from a layout) is
 * SMQL_ERROR_INPUT. */
SMQL_API smql_status smql_export_points(smql_db* db, const char* scene_name, const char* path);

/* ---- Ingest ---------------------------------------------------------- */

/* What an ingest reports as it goes (smql_ingest's progress callback). */
typedef enum smql_progress_kind {
    SMQL_PROGRESS_STAGE_STARTED = 0,  /* a stage begins; total: its steps (0 or 1: not counted) */
    SMQL_PROGRESS_ADVANCED = 1,       /* done of total steps of the stage are done */
    SMQL_PROGRESS_STAGE_FINISHED = 2, /* the stage ended after `seconds`; text: what it made */
    SMQL_PROGRESS_NOTE = 3            /* text: a note on the capture (a default it used, what it skipped) */
} smql_progress_kind;

typedef struct smql_progress {
    smql_progress_kind kind;
    const char* stage; /* "frames", "geometry", "align", "objects", ..., "write"; "" for notes */
    size_t done;
    size_t total;
    double seconds;
    const char* text; /* never NULL; valid during the call only */
} smql_progress;

/* Called for each progress event, on the thread that called smql_ingest. Return 0 to go on;
 * non-zero stops the ingest, as sqlite3_progress_handler's callback does. */
typedef int (*smql_progress_callback)(void* user, const smql_progress* progress);

/* Turns a capture (a folder of RGB-D frames, TUM, nerfstudio, COLMAP, photos, a video: the
 * layouts of docs/ingest.md) into a new scene of the database, in one write transaction at the
 * end, and makes it the current scene; `smql ingest CAPTURE --db DIR` is the same work.
 *
 * options: NULL, or a JSON object of the options `smql ingest --help` lists, named without the
 * dashes and with '_' for '-': {"scene": "kitchen", "objects": "cluster", "max_size": 0,
 * "update": "kitchen"}; values are text or numbers. An unknown name or a bad value is
 * SMQL_ERROR_USAGE, and a scene name already stored (without "update") is SMQL_ERROR_INPUT,
 * both before any work. progress may be NULL.
 *
 * The work runs outside the handle's lock (other threads may query meanwhile) and takes seconds
 * to minutes. The progress callback returning non-zero, or smql_interrupt(db) from another
 * thread, stops it at the next frame with SMQL_ERROR_INTERRUPTED; a failed or stopped ingest
 * writes nothing. The first call loads libsmql_ingest.so, installed beside libsmql.so (the
 * libraries for images and point clouds are loaded only by programs that ingest); without it
 * the call fails with SMQL_ERROR_USAGE saying where it looked. Needs a read-write handle. */
SMQL_API smql_status smql_ingest(smql_db* db, const char* capture, const char* options, smql_progress_callback progress,
                                 void* user);

/* Checks a stored scene (`smql check-ingest`; docs/ingest.md), scene NULL for the most recent. With
 * truth, the capture's truth.json (smql synth writes it, with pose.txt and visibility.json beside
 * it): how close the scene is to it. Without (NULL): whether it looks like a room at all
 * ("Plausibility"). On SMQL_OK *out holds one row per figure: name and value; with a truth
 * anchors_f1, objects_precision, color_accuracy, parent_accuracy, mean_center_error_m, scale_error
 * (when the cameras could be registered) ...; without, camera_height_m, ceiling_height_m and
 * size_ratio (those measured), named_things, warnings and refused (1 when an ingest would have
 * refused it). Loads the ingest module as smql_ingest does. */
SMQL_API smql_status smql_check_ingest(smql_db* db, const char* truth, const char* scene, smql_result** out);

/* Scores a memory with the research system's metrics (docs/eval.md; `smql eval` is the same):
 * relative position, guidance and object retrieval against a truth scene. suite: an evaluation
 * suite file (smql synth writes one beside its capture), or NULL to generate one from the scene,
 * which is then its own truth (an imported real layout). scene: the memory's scene, or NULL for
 * the suite's (else the only or current one); it becomes the current scene. On SMQL_OK *out holds
 * one row per metric: task, metric, value, episodes, median_us (of the statements it ran). */
SMQL_API smql_status smql_evaluate(smql_db* db, const char* suite, const char* scene, smql_result** out);

/* ---- Fleet ----------------------------------------------------------- */

/* Sends every scene version of this database that the fleet store at `url` lacks (a PostgreSQL +
 * PostGIS database that `smql fleet init URL` prepared; docs/fleet.md), each in one transaction of
 * its own, idempotent: a push cut short at any moment and run again leaves no partial scene and no
 * duplicate. `smql push DB URL` is the same work. url: postgresql://USER@HOST:PORT/DATABASE, given
 * to libpq as it is (a password from ~/.pgpass or PGPASSWORD, TLS from sslmode=... or PGSSLMODE;
 * smql stores nothing of it). The first push gives the database its device id (a random UUID kept
 * in the database), so it needs a read-write handle once. On SMQL_OK, *out (when out is not NULL)
 * holds one row: device, sent, present (versions the store had already), nodes, seconds. A store
 * that cannot be reached, lacks the schema or has a newer one, or a role that may not write, is
 * SMQL_ERROR_STORAGE with what to do. The first call loads libsmql_fleet.so, installed beside
 * libsmql.so (libpq and its TLS libraries are loaded only by programs that talk to a store); without
 * it the call fails with SMQL_ERROR_USAGE saying where it looked. */
SMQL_API smql_status smql_push(smql_db* db, const char* url, smql_result** out);

/* Brings version `version` (0: the newest) of the scene named `scene` from the fleet store at `url`
 * into this database as a new scene of that name, stored exactly as it was pushed (its JSON export
 * is the original's, byte for byte). device: the id of the device whose scene it is, or its first
 * characters; NULL when only one device holds a scene of that name (else SMQL_ERROR_BINDING naming
 * them). A name already stored here is SMQL_ERROR_INPUT. Needs a read-write handle; loads the fleet
 * module as smql_push does. */
SMQL_API smql_status smql_pull(smql_db* db, const char* url, const char* scene, const char* device, uint64_t version);

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

/* ---- Prepared statements --------------------------------------------
 *
 * One statement parsed once and run many times with values for its placeholders,
 * `?` (numbered 1, 2, ... in order) or `$1`, `$2`, ... (docs/language.md, "Parameters"):
 *
 *     smql_stmt* stmt = NULL;
 *     smql_prepare(db, "FIND ? WHERE near(?, ?)", &stmt);
 *     smql_bind_text(stmt, 1, "cushion");
 *     smql_bind_text(stmt, 2, "sofa");
 *     smql_bind_double(stmt, 3, 0.5);                 (metres)
 *     while (smql_step(stmt) == SMQL_ROW) puts(smql_stmt_row_json(stmt));
 *     smql_reset(stmt);                               (then bind other values, step again)
 *     smql_finalize(stmt);
 *
 * A bound value is data, never SMQL text: "O'Brien's mug" is a name, whatever its quotes.
 * A statement belongs to its handle: finalize it before smql_close, and do not use one
 * statement from two threads at once. Errors are read with smql_errmsg(db), as for every
 * call on the handle. */

/* Parses one statement; on SMQL_OK *out is a statement to bind and step (free it with
 * smql_finalize). On failure *out is NULL and smql_errmsg(db) tells why; a text with more
 * than one statement is SMQL_ERROR_USAGE. */
SMQL_API smql_status smql_prepare(smql_db* db, const char* statement, smql_stmt** out);

/* How many placeholders the statement has (the highest index); 0 for NULL. */
SMQL_API int smql_bind_parameter_count(const smql_stmt* stmt);

/* Bind a value to placeholder `index` (1-based); it stays bound until smql_clear_bindings or
 * another bind, across smql_reset. Text is copied. A double is metres where a distance goes
 * (near(?, ?)). SMQL_ERROR_MISUSE for a NULL argument, an index out of range, a value its
 * place cannot take (a number for a name, text for LIMIT), or a statement stepped and not
 * reset. NULL is accepted here and is an error when the statement runs. */
SMQL_API smql_status smql_bind_text(smql_stmt* stmt, int index, const char* text);
SMQL_API smql_status smql_bind_int(smql_stmt* stmt, int index, int64_t value);
SMQL_API smql_status smql_bind_double(smql_stmt* stmt, int index, double value);
SMQL_API smql_status smql_bind_null(smql_stmt* stmt, int index);
/* A vector of `count` floats (copied) for SIMILAR TO ?: the nodes are ranked by the cosine of it
 * and the vector an external model gave each at ingest (docs/similarity.md), most similar first;
 * nodes without one are left out. Only SIMILAR TO takes a vector (SMQL_ERROR_MISUSE elsewhere, and
 * for NULL values or count < 1). When the statement runs, a vector that is not as long as the
 * scene's embeddings, a scene without embeddings, and a zero or non-finite vector are
 * SMQL_ERROR_USAGE. */
SMQL_API smql_status smql_bind_vector(smql_stmt* stmt, int index, const float* values, int count);

/* The first step runs the statement with the values bound (a placeholder without one is
 * SMQL_ERROR_USAGE naming it; smql_interrupt stops it with SMQL_ERROR_INTERRUPTED); each step
 * then makes the next row current: SMQL_ROW while there is one, SMQL_DONE after the last (at
 * once for statements without rows, whose sentence smql_stmt_message gives). After SMQL_DONE or
 * an error, smql_step returns the same until smql_reset. */
SMQL_API smql_status smql_step(smql_stmt* stmt);

/* Forgets the run and its rows, keeping the bindings: the next smql_step runs it again. */
SMQL_API smql_status smql_reset(smql_stmt* stmt);
/* Unbinds every placeholder. */
SMQL_API smql_status smql_clear_bindings(smql_stmt* stmt);
/* Frees the statement; NULL is a no-op. */
SMQL_API void smql_finalize(smql_stmt* stmt);

/* The current row, after smql_step returned SMQL_ROW, read as the result accessors above read
 * a row: same types, same sentinels (0, NULL, SMQL_INVALID, SMQL_ERROR_MISUSE) for NULL, a
 * column out of range or no current row. Columns are known once the statement has run (after
 * the first step). Text stays valid until the next step, reset or finalize. */
SMQL_API size_t smql_stmt_column_count(const smql_stmt* stmt);
SMQL_API const char* smql_stmt_column_name(const smql_stmt* stmt, size_t col);
SMQL_API smql_type smql_stmt_column_type(const smql_stmt* stmt, size_t col);
SMQL_API smql_type smql_stmt_value_type(const smql_stmt* stmt, size_t col);
SMQL_API smql_status smql_stmt_value_int64(const smql_stmt* stmt, size_t col, int64_t* out);
SMQL_API smql_status smql_stmt_value_double(const smql_stmt* stmt, size_t col, double* out);
SMQL_API smql_status smql_stmt_value_text(const smql_stmt* stmt, size_t col, const char** out);
SMQL_API smql_status smql_stmt_value_box(const smql_stmt* stmt, size_t col, smql_box* out);
/* The current row as JSON (as smql_row_json); NULL without a current row. */
SMQL_API const char* smql_stmt_row_json(const smql_stmt* stmt);
/* The sentence the statement answered with ("" if none); NULL before it has run. */
SMQL_API const char* smql_stmt_message(const smql_stmt* stmt);

#ifdef __cplusplus
}
#endif

#endif /* SMQL_H */
