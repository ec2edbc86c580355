/*
 * The C API from C: import, query, typed access, JSON, errors, misuse,
 * read-only handles and threads sharing one handle. Needs SMQL_SHARED_DATA
 * (the folder holding replica-room0/). Last line: "N passed, M failed".
 */
#define _XOPEN_SOURCE 700 /* mkdtemp, nftw */

#include <ftw.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "smql.h"

static int passed = 0, failed = 0;

#define CHECK(cond)                                                                  \
    do {                                                                             \
        if (cond) {                                                                  \
            ++passed;                                                                \
        } else {                                                                     \
            ++failed;                                                                \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
        }                                                                            \
    } while (0)

static const char* const kReplica = SMQL_SHARED_DATA "/replica-room0/info_semantic.json";
static const char* const kQuery = "FIND cushion WHERE on(sofa) PATH";

static int contains(const char* text, const char* part) { return text && strstr(text, part) != NULL; }

static int remove_entry(const char* path, const struct stat* st, int flag, struct FTW* ftw) {
    (void)st, (void)flag, (void)ftw;
    return remove(path);
}

static int column_index(const smql_result* res, const char* name) {
    for (size_t c = 0; c < smql_column_count(res); ++c)
        if (strcmp(smql_column_name(res, c), name) == 0) return (int)c;
    return -1;
}

static void test_misuse(void) {
    smql_result* res = (smql_result*)&passed; /* any non-NULL: must come back NULL */
    CHECK(smql_execute(NULL, kQuery, &res) == SMQL_ERROR_MISUSE);
    CHECK(res == NULL);
    CHECK(smql_import_file(NULL, "replica", kReplica, NULL) == SMQL_ERROR_MISUSE);
    CHECK(smql_open("somewhere", 0, NULL) == SMQL_ERROR_MISUSE);
    CHECK(smql_errcode(NULL) == SMQL_ERROR_MISUSE);
    CHECK(contains(smql_errmsg(NULL), "NULL"));

    int64_t i = 0;
    smql_box box;
    CHECK(smql_column_count(NULL) == 0 && smql_row_count(NULL) == 0 && smql_statement_count(NULL) == 0);
    CHECK(smql_column_name(NULL, 0) == NULL);
    CHECK(smql_column_type(NULL, 0) == SMQL_INVALID);
    CHECK(smql_value_type(NULL, 0, 0) == SMQL_INVALID);
    CHECK(smql_value_int64(NULL, 0, 0, &i) == SMQL_ERROR_MISUSE);
    CHECK(smql_value_box(NULL, 0, 0, &box) == SMQL_ERROR_MISUSE);
    CHECK(smql_row_json(NULL, 0) == NULL && smql_result_json(NULL) == NULL && smql_result_message(NULL) == NULL);
    smql_close(NULL);
    smql_result_free(NULL);

    CHECK(strlen(smql_version()) > 0);
    CHECK(smql_complete("COUNT sofa;") == 1 && smql_complete("COUNT sofa") == 0);
    CHECK(smql_complete("FIND mug WHERE on(desk;") == 0 && smql_complete("FIND mug WHERE category = ';") == 0);
    CHECK(smql_complete("  ") == 0 && smql_complete(NULL) == 0);
    CHECK(strcmp(smql_status_string(SMQL_ERROR_SYNTAX), "syntax error") == 0);
}

static void test_open_failure(const char* base) {
    char missing[4096];
    snprintf(missing, sizeof missing, "%s/does-not-exist", base);
    smql_db* db = NULL;
    CHECK(smql_open(missing, SMQL_OPEN_READONLY, &db) == SMQL_ERROR_STORAGE);
    CHECK(db != NULL);
    CHECK(contains(smql_errmsg(db), "no database"));
    CHECK(smql_errcode(db) == SMQL_ERROR_STORAGE);
    CHECK(smql_execute(db, kQuery, NULL) == SMQL_ERROR_MISUSE);
    CHECK(contains(smql_errmsg(db), "failed to open"));
    smql_close(db);

    db = NULL;
    CHECK(smql_open(missing, 0x100, &db) == SMQL_ERROR_MISUSE);
    CHECK(contains(smql_errmsg(db), "flag"));
    smql_close(db);
}

static void test_import(const char* dir) {
    smql_db* db = NULL;
    CHECK(smql_open(dir, 0, &db) == SMQL_OK);
    CHECK(smql_import_file(db, "replica", kReplica, NULL) == SMQL_OK);
    CHECK(strcmp(smql_errmsg(db), "") == 0 && smql_errcode(db) == SMQL_OK);

    CHECK(smql_import_file(db, "replica", SMQL_SHARED_DATA "/no-such-file.json", "other") == SMQL_ERROR_INPUT);
    CHECK(contains(smql_errmsg(db), "no-such-file.json"));
    CHECK(smql_import_file(db, "obj", kReplica, NULL) == SMQL_ERROR_USAGE);
    CHECK(contains(smql_errmsg(db), "hint"));
    CHECK(smql_import_file(db, "replica", NULL, NULL) == SMQL_ERROR_MISUSE);
    smql_close(db);
}

static void write_text(const char* path, const char* text) {
    FILE* f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f) return;
    fputs(text, f);
    fclose(f);
}

/* The first value of a one-statement result, as an integer (-1 when the statement failed). */
static long long count_of(smql_db* db, const char* statement) {
    smql_result* res = NULL;
    int64_t value = -1;
    if (smql_execute(db, statement, &res) != SMQL_OK || smql_value_int64(res, 0, 0, &value) != SMQL_OK) value = -1;
    smql_result_free(res);
    return (long long)value;
}

struct progress_log {
    int started, finished, notes, advanced, stop_at_stage;
    int saw_write, saw_frames;
};

static int on_progress(void* user, const smql_progress* event) {
    struct progress_log* log = (struct progress_log*)user;
    CHECK(event != NULL && event->stage != NULL && event->text != NULL);
    switch (event->kind) {
        case SMQL_PROGRESS_STAGE_STARTED:
            ++log->started;
            if (strcmp(event->stage, "frames") == 0) log->saw_frames = 1;
            break;
        case SMQL_PROGRESS_ADVANCED:
            ++log->advanced;
            CHECK(event->done <= event->total);
            break;
        case SMQL_PROGRESS_STAGE_FINISHED:
            ++log->finished;
            CHECK(event->seconds >= 0);
            if (strcmp(event->stage, "write") == 0) log->saw_write = 1;
            break;
        case SMQL_PROGRESS_NOTE:
            ++log->notes;
            break;
    }
    return log->stop_at_stage > 0 && log->started >= log->stop_at_stage;
}

/* A real RGB-D capture (../shared/data/rgbd-dining) becomes a scene through smql_ingest, with
 * progress; it is stamped as an imported scene is; bad options and a taken name fail before the
 * work; a stop from the callback writes nothing. */
static void test_ingest(const char* base) {
    char dir[4096];
    snprintf(dir, sizeof dir, "%s/ingest-db", base);
    const char* capture = SMQL_SHARED_DATA "/rgbd-dining";
    smql_db* db = NULL;
    CHECK(smql_open(dir, 0, &db) == SMQL_OK);

    CHECK(smql_ingest(db, NULL, NULL, NULL, NULL) == SMQL_ERROR_MISUSE);
    CHECK(smql_ingest(db, capture, "{\"objcts\": \"cluster\"}", NULL, NULL) == SMQL_ERROR_USAGE);
    CHECK(contains(smql_errmsg(db), "unknown ingest option 'objcts'") && contains(smql_errmsg(db), "objects"));
    CHECK(smql_ingest(db, capture, "{\"objects\": \"clustr\"}", NULL, NULL) == SMQL_ERROR_USAGE);
    CHECK(contains(smql_errmsg(db), "did you mean cluster"));
    CHECK(smql_ingest(db, capture, "[1]", NULL, NULL) == SMQL_ERROR_USAGE);
    CHECK(smql_ingest(db, capture, "{\"fps\": -2}", NULL, NULL) == SMQL_ERROR_USAGE);

    /* Stopped by the callback in its second stage: nothing is written. */
    struct progress_log stopped = {0, 0, 0, 0, 2, 0, 0};
    CHECK(smql_ingest(db, capture, "{\"scene\": \"dining\"}", on_progress, &stopped) == SMQL_ERROR_INTERRUPTED);
    CHECK(contains(smql_errmsg(db), "stopped"));
    smql_result* scenes = NULL;
    CHECK(smql_execute(db, "SHOW SCENES", &scenes) == SMQL_OK && smql_row_count(scenes) == 0);
    smql_result_free(scenes);

    struct progress_log log = {0, 0, 0, 0, 0, 0, 0};
    CHECK(smql_ingest(db, capture, "{\"scene\": \"dining\", \"objects\": \"cluster\"}", on_progress, &log) == SMQL_OK);
    CHECK(log.saw_frames && log.saw_write && log.started >= 5 && log.finished >= log.started);
    long long objects = count_of(db, "COUNT object");
    CHECK(objects > 0);
    /* Every object of the ingested scene carries its first- and last-seen stamps ... */
    CHECK(count_of(db, "COUNT object WHERE added SINCE '2000-01-01'") == objects);
    CHECK(count_of(db, "COUNT object WHERE seen SINCE '2000-01-01'") == objects);
    CHECK(count_of(db, "COUNT wall") > 0);

    /* ... as those of an imported one do. */
    CHECK(smql_import_file(db, "replica", kReplica, NULL) == SMQL_OK);
    long long imported = count_of(db, "COUNT object");
    CHECK(imported > 0);
    CHECK(count_of(db, "COUNT object WHERE added SINCE '2000-01-01'") == imported);
    CHECK(count_of(db, "COUNT object WHERE seen SINCE '2000-01-01'") == imported);

    /* The capture's points (docs/formats.md, "PLY"); the imported layout, now the current scene, has none. */
    char points[4096];
    snprintf(points, sizeof points, "%s/points.ply", base);
    CHECK(smql_export_points(db, "dining", points) == SMQL_OK);
    FILE* ply = fopen(points, "rb");
    char head[40] = {0};
    CHECK(ply && fread(head, 1, 36, ply) == 36 && strncmp(head, "ply\nformat binary_little_endian 1.0\n", 36) == 0);
    if (ply) fclose(ply);
    CHECK(smql_export_points(db, NULL, points) == SMQL_ERROR_INPUT && contains(smql_errmsg(db), "holds no points"));
    CHECK(smql_export_points(db, NULL, NULL) == SMQL_ERROR_MISUSE);

    /* A stored name is refused before the work: no progress at all. */
    struct progress_log again = {0, 0, 0, 0, 0, 0, 0};
    CHECK(smql_ingest(db, capture, "{\"scene\": \"dining\"}", on_progress, &again) == SMQL_ERROR_INPUT);
    CHECK(contains(smql_errmsg(db), "already exists") && again.started == 0);
    CHECK(smql_ingest(db, capture, "{\"update\": \"attic\"}", NULL, NULL) == SMQL_ERROR_BINDING);

    /* The same capture again as the scene's next version. */
    CHECK(smql_ingest(db, capture, "{\"update\": \"dining\", \"objects\": \"cluster\"}", NULL, NULL) == SMQL_OK);
    CHECK(count_of(db, "USE SCENE dining; COUNT object") > 0);
    smql_close(db);

    CHECK(smql_open(dir, SMQL_OPEN_READONLY, &db) == SMQL_OK);
    CHECK(smql_ingest(db, capture, "{\"scene\": \"elsewhere\"}", NULL, NULL) == SMQL_ERROR_STORAGE);
    smql_close(db);
}

/* A synthetic capture ingested through the C API, checked against its truth. */
static void test_check_ingest(const char* base, const char* synth) {
    char dir[4096], truth[4096];
    snprintf(dir, sizeof dir, "%s/synth-db", base);
    snprintf(truth, sizeof truth, "%s/truth.json", synth);
    smql_db* db = NULL;
    smql_result* res = NULL;
    CHECK(smql_open(dir, 0, &db) == SMQL_OK);
    CHECK(smql_ingest(db, synth, NULL, NULL, NULL) == SMQL_OK);
    CHECK(smql_check_ingest(db, NULL, NULL, NULL) == SMQL_ERROR_MISUSE);
    /* Without a truth: the plausibility checks. A generated room looks like one. */
    CHECK(smql_check_ingest(db, NULL, NULL, &res) == SMQL_OK);
    int plausible = 0;
    for (size_t r = 0; r < smql_row_count(res); ++r) {
        const char* name = NULL;
        double value = -1;
        CHECK(smql_value_text(res, r, 0, &name) == SMQL_OK && smql_value_double(res, r, 1, &value) == SMQL_OK);
        if (name && strcmp(name, "camera_height_m") == 0) plausible += value > 1.0 && value < 2.0;
        if (name && strcmp(name, "refused") == 0) plausible += value == 0.0;
    }
    CHECK(plausible == 2);
    smql_result_free(res);
    CHECK(smql_check_ingest(db, "/nonexistent/truth.json", NULL, &res) == SMQL_ERROR_INPUT && res == NULL);
    CHECK(smql_check_ingest(db, truth, "synth-capture", &res) == SMQL_OK);
    int found = 0;
    for (size_t r = 0; r < smql_row_count(res); ++r) {
        const char* name = NULL;
        double value = -1;
        CHECK(smql_value_text(res, r, 0, &name) == SMQL_OK && smql_value_double(res, r, 1, &value) == SMQL_OK);
        if (!name) continue;
        if (strcmp(name, "objects_f1") == 0) found += value >= 0.8;
        if (strcmp(name, "anchors_f1") == 0) found += value >= 0.8;
        if (strcmp(name, "scale_error") == 0) found += value < 0.05;
    }
    CHECK(found == 3);
    smql_result_free(res);
    smql_close(db);
}

/* A scene written with smql_export reads back with smql_import_file, and the page as one file. */
static void test_export(const char* dir, const char* base) {
    char json[4096], html[4096], copy[4096];
    snprintf(json, sizeof json, "%s/exported.json", base);
    snprintf(html, sizeof html, "%s/exported.html", base);
    snprintf(copy, sizeof copy, "%s/copy-db", base);
    smql_db* db = NULL;
    CHECK(smql_open(dir, SMQL_OPEN_READONLY, &db) == SMQL_OK);
    CHECK(smql_export(db, "json", "replica-room0", json) == SMQL_OK);
    CHECK(smql_export(db, "html", NULL, html) == SMQL_OK);
    CHECK(smql_export(db, "jsn", NULL, json) == SMQL_ERROR_USAGE && contains(smql_errmsg(db), "did you mean json"));
    CHECK(smql_export(db, "json", "attic", json) == SMQL_ERROR_BINDING);
    CHECK(smql_export(db, NULL, NULL, json) == SMQL_ERROR_MISUSE);
    long long cushions = count_of(db, "COUNT cushion WHERE on(sofa)");
    smql_close(db);
    CHECK(smql_open(copy, 0, &db) == SMQL_OK);
    CHECK(smql_import_file(db, "json", json, NULL) == SMQL_OK);
    CHECK(cushions > 0 && count_of(db, "COUNT cushion WHERE on(sofa)") == cushions);
    smql_close(db);
    FILE* page = fopen(html, "r");
    char head[16] = {0};
    CHECK(page && fread(head, 1, 15, page) == 15 && strcmp(head, "<!doctype html>") == 0);
    if (page) fclose(page);
}

/* The evaluation as a call: the Replica room scored as its own truth finds every object. */
static void test_evaluate(const char* dir) {
    smql_db* db = NULL;
    smql_result* res = NULL;
    CHECK(smql_open(dir, SMQL_OPEN_READONLY, &db) == SMQL_OK);
    CHECK(smql_evaluate(db, NULL, "replica-room0", NULL) == SMQL_ERROR_MISUSE);
    CHECK(smql_evaluate(db, NULL, "attic", &res) == SMQL_ERROR_BINDING && res == NULL);
    CHECK(smql_evaluate(db, "/nonexistent/eval-suite.json", NULL, &res) == SMQL_ERROR_INPUT);
    CHECK(smql_evaluate(db, NULL, "replica-room0", &res) == SMQL_OK);
    CHECK(smql_column_count(res) == 5 && smql_row_count(res) >= 10);
    int metric = column_index(res, "metric"), value = column_index(res, "value"),
        episodes = column_index(res, "episodes");
    int seen = 0;
    for (size_t r = 0; r < smql_row_count(res); ++r) {
        const char* name = NULL;
        double v = -1;
        int64_t n = 0;
        CHECK(smql_value_text(res, r, (size_t)metric, &name) == SMQL_OK);
        CHECK(smql_value_double(res, r, (size_t)value, &v) == SMQL_OK && v >= 0);
        CHECK(smql_value_int64(res, r, (size_t)episodes, &n) == SMQL_OK);
        if (name && (strcmp(name, "SR_obj") == 0 || strcmp(name, "Acc_path") == 0)) {
            CHECK(v == 1.0 && n > 20);
            ++seen;
        }
    }
    CHECK(seen == 2);
    smql_result_free(res);
    smql_close(db);
}

/* A second capture of a place becomes the next version of its scene; SHOW CHANGES reads it back. */
static void test_update(const char* base) {
    char dir[4096], before[4096], after[4096];
    snprintf(dir, sizeof dir, "%s/update-db", base);
    snprintf(before, sizeof before, "%s/before.txt", base);
    snprintf(after, sizeof after, "%s/after.txt", base);
    const char* walls =
        "wall_0=Wall(0,0,0,4,0,0,2.5,0)\nwall_1=Wall(4,0,0,4,4,0,2.5,0)\n"
        "wall_2=Wall(4,4,0,0,4,0,2.5,0)\nwall_3=Wall(0,4,0,0,0,0,2.5,0)\n";
    char text[1024];
    snprintf(text, sizeof text,
             "%sbbox_0=Bbox(chair,1,1,0.45,0,0.5,0.5,0.9)\nbbox_1=Bbox(table,3,1,0.4,0,1.2,0.8,0.8)\n", walls);
    write_text(before, text);
    snprintf(text, sizeof text,
             "%sbbox_0=Bbox(chair,1,3,0.45,0,0.5,0.5,0.9)\nbbox_1=Bbox(lamp,3,3,0.8,0,0.3,0.3,1.6)\n", walls);
    write_text(after, text);

    smql_db* db = NULL;
    CHECK(smql_open(dir, 0, &db) == SMQL_OK);
    CHECK(smql_import_file(db, "spatiallm", before, "den") == SMQL_OK);
    CHECK(smql_update_file(db, "spatiallm", after, "den") == SMQL_OK);
    smql_result* res = NULL;
    CHECK(smql_execute(db, "SHOW CHANGES", &res) == SMQL_OK);
    CHECK(smql_row_count(res) == 3);
    int change = column_index(res, "change"), category = column_index(res, "category");
    const char* kinds[3] = {"missing", "moved", "added"};
    const char* categories[3] = {"table", "chair", "lamp"};
    for (size_t r = 0; r < 3 && r < smql_row_count(res); ++r) {
        const char* text_value = NULL;
        CHECK(smql_value_text(res, r, (size_t)change, &text_value) == SMQL_OK && strcmp(text_value, kinds[r]) == 0);
        CHECK(smql_value_text(res, r, (size_t)category, &text_value) == SMQL_OK &&
              strcmp(text_value, categories[r]) == 0);
    }
    smql_result_free(res);

    CHECK(smql_update_file(db, "spatiallm", after, "attic") == SMQL_ERROR_BINDING);
    CHECK(contains(smql_errmsg(db), "no scene named 'attic'"));
    CHECK(smql_update_file(db, "spatiallm", NULL, "den") == SMQL_ERROR_MISUSE);
    CHECK(smql_execute(db, "RENAME SCENE den TO study; DROP SCENE study; SHOW SCENES", &res) == SMQL_OK);
    CHECK(smql_row_count(res) == 0);
    smql_result_free(res);
    smql_close(db);
}

static void test_query(const char* dir) {
    smql_db* db = NULL;
    CHECK(smql_open(dir, 0, &db) == SMQL_OK);
    smql_result* res = NULL;
    CHECK(smql_execute(db, kQuery, &res) == SMQL_OK);
    CHECK(res != NULL);
    /* The result owns its data: it outlives the handle. */
    smql_close(db);
    if (!res) return;

    size_t rows = smql_row_count(res);
    CHECK(rows > 0);
    int id = column_index(res, "id"), category = column_index(res, "category"), box = column_index(res, "box"),
        path = column_index(res, "path");
    CHECK(id >= 0 && category >= 0 && box >= 0 && path >= 0);
    if (id < 0 || category < 0 || box < 0 || path < 0) {
        smql_result_free(res);
        return;
    }
    CHECK(smql_column_type(res, (size_t)id) == SMQL_INTEGER);
    CHECK(smql_column_type(res, (size_t)category) == SMQL_TEXT);
    CHECK(smql_column_type(res, (size_t)box) == SMQL_BOX);
    CHECK(smql_column_type(res, (size_t)path) == SMQL_TEXT);

    for (size_t r = 0; r < rows; ++r) {
        int64_t node = 0;
        const char* text = NULL;
        smql_box b;
        CHECK(smql_value_int64(res, r, (size_t)id, &node) == SMQL_OK && node > 0);
        CHECK(smql_value_text(res, r, (size_t)category, &text) == SMQL_OK && strcmp(text, "cushion") == 0);
        CHECK(smql_value_text(res, r, (size_t)path, &text) == SMQL_OK && contains(text, " / cushion#"));
        CHECK(smql_value_box(res, r, (size_t)box, &b) == SMQL_OK);
        CHECK(b.size[0] > 0 && b.size[1] > 0 && b.size[2] > 0);
        const char* json = smql_row_json(res, r);
        CHECK(json && json[0] == '{' && contains(json, "\"category\":\"cushion\"") && contains(json, "\"center\""));
        CHECK(smql_row_json(res, r) == json); /* made once, kept until freed */
    }

    /* Wrong type, bad row, bad column: misuse, *out untouched. */
    int64_t untouched = 42;
    double real = 0;
    CHECK(smql_value_int64(res, 0, (size_t)category, &untouched) == SMQL_ERROR_MISUSE && untouched == 42);
    CHECK(smql_value_double(res, 0, (size_t)id, &real) == SMQL_OK && real > 0); /* integers widen */
    CHECK(smql_value_int64(res, rows, (size_t)id, &untouched) == SMQL_ERROR_MISUSE);
    CHECK(smql_value_type(res, rows, 0) == SMQL_INVALID);
    CHECK(smql_value_type(res, 0, smql_column_count(res)) == SMQL_INVALID);
    CHECK(smql_column_name(res, smql_column_count(res)) == NULL);
    CHECK(smql_row_json(res, rows) == NULL);

    const char* all = smql_result_json(res);
    CHECK(all && strncmp(all, "{\"columns\":", 11) == 0 && contains(all, "\"rows\":[{"));
    CHECK(smql_statement_count(res) == 1 && strcmp(smql_result_message(res), "") == 0);
    smql_result_free(res);
}

/* RETURN's columns keep their types: integers, reals in metres, text, null where a node has none. */
static void test_returned_columns(const char* dir) {
    smql_db* db = NULL;
    CHECK(smql_open(dir, 0, &db) == SMQL_OK);
    smql_result* res = NULL;
    CHECK(smql_execute(db, "FIND cushion ORDER BY height DESC LIMIT 3 RETURN id, height, volume, center, parent",
                       &res) == SMQL_OK);
    smql_close(db);
    if (!res) return;
    CHECK(smql_column_count(res) == 5 && smql_row_count(res) == 3);
    CHECK(strcmp(smql_column_name(res, 1), "height") == 0);
    CHECK(smql_column_type(res, 0) == SMQL_INTEGER);
    CHECK(smql_column_type(res, 1) == SMQL_REAL);
    CHECK(smql_column_type(res, 2) == SMQL_REAL);
    CHECK(smql_column_type(res, 3) == SMQL_TEXT);
    CHECK(smql_column_type(res, 4) == SMQL_TEXT);
    double previous = 1e9;
    for (size_t r = 0; r < smql_row_count(res); ++r) {
        double height = 0, volume = 0;
        const char* centre = NULL;
        CHECK(smql_value_double(res, r, 1, &height) == SMQL_OK && height > 0 && height <= previous);
        CHECK(smql_value_double(res, r, 2, &volume) == SMQL_OK && volume > 0);
        CHECK(smql_value_text(res, r, 3, &centre) == SMQL_OK && centre[0] == '(');
        previous = height;
    }
    smql_result_free(res);
}

static void test_statements_and_errors(const char* dir) {
    smql_db* db = NULL;
    CHECK(smql_open(dir, 0, &db) == SMQL_OK);

    /* Several statements: the last one's rows, every one's message. */
    smql_result* res = NULL;
    CHECK(smql_execute(db, "SET near = 0.8 m; FIND cushion WHERE on(sofa)", &res) == SMQL_OK);
    CHECK(smql_statement_count(res) == 2);
    CHECK(contains(smql_statement_message(res, 0), "near"));
    CHECK(smql_statement_message(res, 2) == NULL);
    CHECK(smql_row_count(res) > 0);
    smql_result_free(res);

    res = NULL;
    CHECK(smql_execute(db, "FIND cushion WHERE on(", &res) == SMQL_ERROR_SYNTAX);
    CHECK(res == NULL);
    CHECK(smql_errcode(db) == SMQL_ERROR_SYNTAX);
    CHECK(contains(smql_errmsg(db), "line 1"));
    CHECK(contains(smql_errmsg(db), "^")); /* the caret under the spot */
    CHECK(smql_error_line(db) == 1 && smql_error_column(db) > 0);

    CHECK(smql_execute(db, "FIND cushion;\nFIND sofa WHERE on(", NULL) == SMQL_ERROR_SYNTAX);
    CHECK(contains(smql_errmsg(db), "line 2") && smql_error_line(db) == 2);

    CHECK(smql_execute(db, "FIND unicorn", NULL) == SMQL_ERROR_BINDING);
    CHECK(contains(smql_errmsg(db), "unicorn"));

    /* A call that succeeds clears this thread's error. */
    CHECK(smql_execute(db, kQuery, NULL) == SMQL_OK);
    CHECK(strcmp(smql_errmsg(db), "") == 0 && smql_errcode(db) == SMQL_OK && smql_error_line(db) == 0);
    CHECK(smql_execute(db, NULL, NULL) == SMQL_ERROR_MISUSE);
    smql_close(db);
}

static void test_read_only(const char* dir) {
    smql_db* db = NULL;
    CHECK(smql_open(dir, SMQL_OPEN_READONLY, &db) == SMQL_OK);
    smql_result* res = NULL;
    CHECK(smql_execute(db, kQuery, &res) == SMQL_OK);
    CHECK(smql_row_count(res) > 0);
    smql_result_free(res);

    CHECK(smql_import_file(db, "replica", kReplica, "second") == SMQL_ERROR_STORAGE);
    CHECK(contains(smql_errmsg(db), "read-only"));
    /* The failed import left the handle usable and the database unchanged. */
    CHECK(smql_execute(db, "SHOW SCENES", &res) == SMQL_OK);
    CHECK(smql_row_count(res) == 1);
    smql_result_free(res);
    smql_close(db);
}

/* Threads sharing one handle: each must read its own error, never another's. */
struct worker {
    smql_db* db;
    int bad; /* this worker sends statements that do not parse */
    int failures;
};

static void* work(void* arg) {
    struct worker* w = (struct worker*)arg;
    for (int i = 0; i < 25; ++i) {
        smql_result* res = NULL;
        if (w->bad) {
            if (smql_execute(w->db, "FIND cushion WHERE on(", &res) != SMQL_ERROR_SYNTAX || res) ++w->failures;
            if (!contains(smql_errmsg(w->db), "line 1") || smql_errcode(w->db) != SMQL_ERROR_SYNTAX) ++w->failures;
        } else {
            if (smql_execute(w->db, kQuery, &res) != SMQL_OK || smql_row_count(res) == 0) ++w->failures;
            if (strcmp(smql_errmsg(w->db), "") != 0 || smql_errcode(w->db) != SMQL_OK) ++w->failures;
            smql_result_free(res);
        }
    }
    return NULL;
}

static void test_threads(const char* dir) {
    smql_db* db = NULL;
    CHECK(smql_open(dir, SMQL_OPEN_READONLY, &db) == SMQL_OK);
    struct worker workers[4];
    pthread_t threads[4];
    for (int t = 0; t < 4; ++t) {
        workers[t].db = db;
        workers[t].bad = t % 2;
        workers[t].failures = 0;
        CHECK(pthread_create(&threads[t], NULL, work, &workers[t]) == 0);
    }
    for (int t = 0; t < 4; ++t) {
        pthread_join(threads[t], NULL);
        CHECK(workers[t].failures == 0);
    }
    smql_close(db);
}

/* Steps a prepared statement to its end; the ids of its rows go to ids (up to max), the count is returned. */
static size_t step_ids(smql_stmt* stmt, int64_t* ids, size_t max) {
    size_t n = 0;
    smql_status status;
    while ((status = smql_step(stmt)) == SMQL_ROW) {
        int64_t id = -1;
        CHECK(smql_stmt_value_int64(stmt, 0, &id) == SMQL_OK);
        if (n < max) ids[n] = id;
        ++n;
    }
    CHECK(status == SMQL_DONE);
    CHECK(smql_step(stmt) == SMQL_DONE); /* stays done until reset */
    return n;
}

/* The ids smql_execute finds for the same statement written out, to compare with. */
static size_t execute_ids(smql_db* db, const char* text, int64_t* ids, size_t max) {
    smql_result* res = NULL;
    CHECK(smql_execute(db, text, &res) == SMQL_OK);
    size_t n = smql_row_count(res);
    for (size_t r = 0; r < n && r < max; ++r) CHECK(smql_value_int64(res, r, 0, &ids[r]) == SMQL_OK);
    smql_result_free(res);
    return n;
}

static int same_ids(const int64_t* a, size_t na, const int64_t* b, size_t nb) {
    if (na != nb) return 0;
    for (size_t i = 0; i < na; ++i)
        if (a[i] != b[i]) return 0;
    return 1;
}

/* Prepare once, bind, step, reset, bind again: the answers of the statements written out. */
static void test_prepared(const char* dir) {
    smql_db* db = NULL;
    CHECK(smql_open(dir, 0, &db) == SMQL_OK);
    smql_stmt* stmt = NULL;
    CHECK(smql_prepare(db, "FIND ? WHERE near(?, ?)", &stmt) == SMQL_OK);
    CHECK(stmt != NULL);
    CHECK(smql_bind_parameter_count(stmt) == 3);
    CHECK(smql_stmt_column_count(stmt) == 0 && smql_stmt_row_json(stmt) == NULL); /* not run yet */

    int64_t got[64], want[64];
    CHECK(smql_bind_text(stmt, 1, "cushion") == SMQL_OK);
    CHECK(smql_bind_text(stmt, 2, "sofa") == SMQL_OK);
    CHECK(smql_bind_double(stmt, 3, 0.5) == SMQL_OK);
    size_t n_got = step_ids(stmt, got, 64);
    size_t n_want = execute_ids(db, "FIND cushion WHERE near(sofa, 0.5 m)", want, 64);
    CHECK(n_want > 0);
    CHECK(same_ids(got, n_got, want, n_want));

    /* Bound, not run: binding now is misuse until reset. */
    CHECK(smql_bind_text(stmt, 1, "lamp") == SMQL_ERROR_MISUSE);
    CHECK(contains(smql_errmsg(db), "smql_reset"));
    CHECK(smql_reset(stmt) == SMQL_OK);
    CHECK(smql_bind_text(stmt, 1, "book") == SMQL_OK);
    CHECK(smql_bind_text(stmt, 2, "table") == SMQL_OK);
    CHECK(smql_bind_int(stmt, 3, 1) == SMQL_OK); /* whole metres */
    n_got = step_ids(stmt, got, 64);
    n_want = execute_ids(db, "FIND book WHERE near(table, 1 m)", want, 64);
    CHECK(n_want > 0);
    CHECK(same_ids(got, n_got, want, n_want));

    /* Row accessors on the current row, in the result API's style. */
    CHECK(smql_reset(stmt) == SMQL_OK);
    CHECK(smql_step(stmt) == SMQL_ROW);
    int category = -1;
    for (size_t c = 0; c < smql_stmt_column_count(stmt); ++c)
        if (strcmp(smql_stmt_column_name(stmt, c), "category") == 0) category = (int)c;
    const char* text = NULL;
    CHECK(category >= 0 && smql_stmt_value_text(stmt, (size_t)category, &text) == SMQL_OK && strcmp(text, "book") == 0);
    CHECK(smql_stmt_value_type(stmt, 0) == SMQL_INTEGER && smql_stmt_column_type(stmt, 0) == SMQL_INTEGER);
    CHECK(smql_stmt_value_int64(stmt, (size_t)category, &got[0]) == SMQL_ERROR_MISUSE); /* text, not integer */
    CHECK(smql_stmt_value_type(stmt, 999) == SMQL_INVALID);
    CHECK(contains(smql_stmt_row_json(stmt), "\"category\":\"book\""));

    /* Wrong index, wrong type. */
    CHECK(smql_reset(stmt) == SMQL_OK);
    CHECK(smql_bind_text(stmt, 0, "mug") == SMQL_ERROR_MISUSE);
    CHECK(smql_bind_text(stmt, 4, "mug") == SMQL_ERROR_MISUSE);
    CHECK(contains(smql_errmsg(db), "no placeholder 4"));
    CHECK(smql_bind_int(stmt, 1, 7) == SMQL_ERROR_MISUSE);
    CHECK(contains(smql_errmsg(db), "stands for a name"));
    CHECK(smql_bind_text(stmt, 3, "far") == SMQL_ERROR_MISUSE);
    CHECK(contains(smql_errmsg(db), "stands for a distance"));
    CHECK(smql_bind_text(stmt, 1, NULL) == SMQL_ERROR_MISUSE);
    CHECK(smql_bind_text(NULL, 1, "mug") == SMQL_ERROR_MISUSE);
    /* What SMQL text cannot hold cannot be bound: NaN, an infinite distance, a text of 400 KB
       (refused at once, its message not a copy of it). */
    CHECK(smql_bind_double(stmt, 3, NAN) == SMQL_ERROR_MISUSE);
    CHECK(contains(smql_errmsg(db), "not a number SMQL compares"));
    CHECK(smql_bind_double(stmt, 3, INFINITY) == SMQL_ERROR_MISUSE);
    {
        size_t size = 400 * 1000;
        char* huge = malloc(size + 1);
        memset(huge, 'a', size);
        huge[size] = '\0';
        CHECK(smql_bind_text(stmt, 1, huge) == SMQL_ERROR_MISUSE);
        CHECK(contains(smql_errmsg(db), "400000 bytes of text: at most 4096"));
        CHECK(strlen(smql_errmsg(db)) < 2000);
        free(huge);
    }
    CHECK(smql_bind_parameter_count(NULL) == 0 && smql_step(NULL) == SMQL_ERROR_MISUSE);

    /* Unbound and NULL placeholders are named when the statement runs. */
    CHECK(smql_clear_bindings(stmt) == SMQL_OK);
    CHECK(smql_step(stmt) == SMQL_ERROR_USAGE);
    CHECK(contains(smql_errmsg(db), "placeholder ? number 1 has no value"));
    CHECK(smql_step(stmt) == SMQL_ERROR_USAGE); /* the same until reset */
    CHECK(smql_reset(stmt) == SMQL_OK);
    CHECK(smql_bind_text(stmt, 1, "cushion") == SMQL_OK);
    CHECK(smql_bind_null(stmt, 2) == SMQL_OK);
    CHECK(smql_bind_double(stmt, 3, 0.5) == SMQL_OK);
    CHECK(smql_step(stmt) == SMQL_ERROR_USAGE);
    CHECK(contains(smql_errmsg(db), "? number 2 is bound to NULL"));
    smql_finalize(stmt);
    smql_finalize(NULL);

    /* $n placeholders, one used twice; LIMIT and a comparison bound. */
    CHECK(smql_prepare(db, "FIND $1 WHERE near($2, 1 m) OR on($2) LIMIT $3", &stmt) == SMQL_OK);
    CHECK(smql_bind_parameter_count(stmt) == 3);
    CHECK(smql_bind_text(stmt, 3, "five") == SMQL_ERROR_MISUSE);
    CHECK(smql_bind_text(stmt, 1, "cushion") == SMQL_OK && smql_bind_text(stmt, 2, "sofa") == SMQL_OK);
    CHECK(smql_bind_int(stmt, 3, 1) == SMQL_OK);
    CHECK(step_ids(stmt, got, 64) == 1);
    smql_finalize(stmt);
    CHECK(smql_prepare(db, "COUNT object WHERE category = ?", &stmt) == SMQL_OK);
    CHECK(smql_bind_text(stmt, 1, "lamp") == SMQL_OK);
    CHECK(smql_step(stmt) == SMQL_ROW);
    CHECK(smql_stmt_value_int64(stmt, 0, &got[0]) == SMQL_OK && got[0] == 6);
    smql_finalize(stmt);

    /* Errors of prepare: mixed placeholders, syntax, more than one statement. */
    CHECK(smql_prepare(db, "FIND ? WHERE near($1)", &stmt) == SMQL_ERROR_SYNTAX);
    CHECK(stmt == NULL && contains(smql_errmsg(db), "cannot mix"));
    CHECK(smql_prepare(db, "FIND ? WHERE", &stmt) == SMQL_ERROR_SYNTAX);
    CHECK(smql_prepare(db, "FIND ?; FIND ?", &stmt) == SMQL_ERROR_USAGE);
    CHECK(smql_prepare(db, NULL, &stmt) == SMQL_ERROR_MISUSE);
    /* Without values, a statement with placeholders fails naming the first. */
    CHECK(smql_execute(db, "FIND ? WHERE near(sofa)", NULL) == SMQL_ERROR_USAGE);
    CHECK(contains(smql_errmsg(db), "? number 1 has no value"));
    smql_close(db);
}

/* SIMILAR TO ? with a vector ranks the nodes by the embeddings stored on them (blobs `embedding`,
 * little-endian float32, here from a scene JSON file): mug (1, 0, 0), cup (0.8, 0.6, 0), book
 * (0, 1, 0), plant (0, 0, 1); the lamp has none and is left out. */
static void test_bind_vector(const char* base) {
    char dir[4096], scene[4096];
    snprintf(dir, sizeof dir, "%s/vector-db", base);
    snprintf(scene, sizeof scene, "%s/vectors.json", base);
    write_text(scene,
               "{\"smql_scene\": 1, \"scene\": {\"name\": \"shelf\"}, \"nodes\": [\n"
               "  {\"id\": 1, \"kind\": \"object\", \"category\": \"mug\", \"box\": {\"center\": [0, 0, 0.1], "
               "\"size\": [0.1, 0.1, 0.1]}},\n"
               "  {\"id\": 2, \"kind\": \"object\", \"category\": \"cup\", \"box\": {\"center\": [1, 0, 0.1], "
               "\"size\": [0.1, 0.1, 0.1]}},\n"
               "  {\"id\": 3, \"kind\": \"object\", \"category\": \"book\", \"box\": {\"center\": [2, 0, 0.1], "
               "\"size\": [0.2, 0.1, 0.3]}},\n"
               "  {\"id\": 4, \"kind\": \"object\", \"category\": \"plant\", \"box\": {\"center\": [3, 0, 0.2], "
               "\"size\": [0.3, 0.3, 0.4]}},\n"
               "  {\"id\": 5, \"kind\": \"object\", \"category\": \"lamp\", \"box\": {\"center\": [4, 0, 0.3], "
               "\"size\": [0.2, 0.2, 0.6]}}],\n"
               "\"blobs\": [\n"
               "  {\"node\": 1, \"name\": \"embedding\", \"media_type\": \"application/x-float32\", "
               "\"base64\": \"AACAPwAAAAAAAAAA\"},\n"
               "  {\"node\": 2, \"name\": \"embedding\", \"media_type\": \"application/x-float32\", "
               "\"base64\": \"zcxMP5qZGT8AAAAA\"},\n"
               "  {\"node\": 3, \"name\": \"embedding\", \"media_type\": \"application/x-float32\", "
               "\"base64\": \"AAAAAAAAgD8AAAAA\"},\n"
               "  {\"node\": 4, \"name\": \"embedding\", \"media_type\": \"application/x-float32\", "
               "\"base64\": \"AAAAAAAAAAAAAIA/\"}]}\n");
    smql_db* db = NULL;
    CHECK(smql_open(dir, 0, &db) == SMQL_OK);
    CHECK(smql_import_file(db, "json", scene, NULL) == SMQL_OK);

    smql_stmt* stmt = NULL;
    CHECK(smql_prepare(db, "FIND object SIMILAR TO ? RETURN category, similarity", &stmt) == SMQL_OK);
    const float query[3] = {1.0f, 0.1f, 0.0f};
    CHECK(smql_bind_vector(stmt, 1, query, 3) == SMQL_OK);
    const char* order[4] = {"mug", "cup", "book", "plant"};
    const double similarity[4] = {0.995, 0.856, 0.1, 0.0};
    for (int r = 0; r < 4; ++r) {
        CHECK(smql_step(stmt) == SMQL_ROW);
        const char* category = NULL;
        double value = -2;
        CHECK(smql_stmt_value_text(stmt, 0, &category) == SMQL_OK && category && strcmp(category, order[r]) == 0);
        CHECK(smql_stmt_value_double(stmt, 1, &value) == SMQL_OK && value == similarity[r]);
    }
    CHECK(smql_step(stmt) == SMQL_DONE); /* the lamp has no embedding */

    /* A vector of another length than the scene's embeddings, when the statement runs. */
    const float wide[4] = {1.0f, 0.0f, 0.0f, 0.0f};
    CHECK(smql_reset(stmt) == SMQL_OK);
    CHECK(smql_bind_vector(stmt, 1, wide, 4) == SMQL_OK);
    CHECK(smql_step(stmt) == SMQL_ERROR_USAGE);
    CHECK(contains(smql_errmsg(db), "the scene's embeddings have 3 dimensions; the bound vector has 4"));
    /* Misuse: no values, no length, a vector where a name goes. */
    CHECK(smql_reset(stmt) == SMQL_OK);
    CHECK(smql_bind_vector(stmt, 1, NULL, 3) == SMQL_ERROR_MISUSE);
    CHECK(smql_bind_vector(stmt, 1, query, 0) == SMQL_ERROR_MISUSE);
    CHECK(smql_bind_vector(NULL, 1, query, 3) == SMQL_ERROR_MISUSE);
    smql_finalize(stmt);
    CHECK(smql_prepare(db, "FIND ? SIMILAR TO ?", &stmt) == SMQL_OK);
    CHECK(smql_bind_vector(stmt, 1, query, 3) == SMQL_ERROR_MISUSE);
    CHECK(contains(smql_errmsg(db), "stands for a name, not a vector"));
    /* Text still searches the built-in embedder's space. */
    CHECK(smql_bind_text(stmt, 1, "object") == SMQL_OK && smql_bind_text(stmt, 2, "light") == SMQL_OK);
    CHECK(smql_step(stmt) == SMQL_ROW);
    const char* first = NULL;
    CHECK(smql_stmt_value_text(stmt, 1, &first) == SMQL_OK && first && strcmp(first, "lamp") == 0);
    smql_finalize(stmt);
    smql_close(db);
}

/* A bound value is data: quotes in it are part of the name and never SMQL. */
static void test_prepared_quotes(const char* base) {
    char dir[4096], layout[4096];
    snprintf(dir, sizeof dir, "%s/quotes-db", base);
    snprintf(layout, sizeof layout, "%s/quotes.txt", base);
    write_text(layout,
               "wall_0=Wall(0,0,0,4,0,0,2.5,0)\nwall_1=Wall(4,0,0,4,4,0,2.5,0)\n"
               "wall_2=Wall(4,4,0,0,4,0,2.5,0)\nwall_3=Wall(0,4,0,0,0,0,2.5,0)\n"
               "bbox_0=Bbox(desk,2,2,0.375,0,1.2,0.6,0.75)\n"
               "bbox_1=Bbox(o'brien's mug,2,2,0.8,0,0.08,0.08,0.1)\n"
               "bbox_2=Bbox(it's,1.8,2,0.8,0,0.1,0.1,0.1)\n");
    smql_db* db = NULL;
    CHECK(smql_open(dir, 0, &db) == SMQL_OK);
    CHECK(smql_import_file(db, "spatiallm", layout, "office") == SMQL_OK);
    smql_stmt* stmt = NULL;
    CHECK(smql_prepare(db, "FIND ? WHERE on(?)", &stmt) == SMQL_OK);
    const char* names[2] = {"O'Brien's mug", "it's"};
    const char* stored[2] = {"o'brien's-mug", "it's"}; /* by their canonical names: o'brien's-mug */
    for (int i = 0; i < 2; ++i) {
        CHECK(smql_reset(stmt) == SMQL_OK);
        CHECK(smql_bind_text(stmt, 1, names[i]) == SMQL_OK);
        CHECK(smql_bind_text(stmt, 2, "desk") == SMQL_OK);
        CHECK(smql_step(stmt) == SMQL_ROW);
        const char* category = NULL;
        CHECK(smql_stmt_value_text(stmt, 1, &category) == SMQL_OK && category && strcmp(category, stored[i]) == 0);
        CHECK(smql_step(stmt) == SMQL_DONE);
    }
    /* SMQL in a value is a name that does not exist, not a statement. */
    CHECK(smql_reset(stmt) == SMQL_OK);
    CHECK(smql_bind_text(stmt, 1, "mug') OR on(desk") == SMQL_OK);
    CHECK(smql_step(stmt) == SMQL_ERROR_BINDING);
    CHECK(contains(smql_errmsg(db), "unknown category"));
    CHECK(smql_reset(stmt) == SMQL_OK);
    CHECK(smql_bind_text(stmt, 1, "x; DROP SCENE office") == SMQL_OK);
    CHECK(smql_step(stmt) == SMQL_ERROR_BINDING);
    smql_finalize(stmt);
    smql_result* res = NULL;
    CHECK(smql_execute(db, "SHOW SCENES", &res) == SMQL_OK);
    CHECK(smql_row_count(res) == 1);
    smql_result_free(res);
    smql_close(db);
}

/* smql_interrupt from another thread stops a prepared statement that is stepping its first row. */
struct long_step {
    smql_stmt* stmt;
    smql_db* db;
    smql_status status;
    int said_interrupted;
    volatile int done;
};

static void* step_long_statement(void* arg) {
    struct long_step* job = arg;
    job->status = smql_step(job->stmt);
    job->said_interrupted = contains(smql_errmsg(job->db), "interrupted");
    job->done = 1;
    return NULL;
}

static void test_prepared_interrupt(const char* base) {
    /* A synthetic hall of 2,025 objects on a 1 m grid: between(object, object) for every object
     * weighs 4 million pairs per candidate, far more work than the test waits for. */
    char dir[4096], layout[4096];
    snprintf(dir, sizeof dir, "%s/hall-db", base);
    snprintf(layout, sizeof layout, "%s/hall.txt", base);
    FILE* f = fopen(layout, "w");
    CHECK(f != NULL);
    if (!f) return;
    fputs(
        "wall_0=Wall(0,0,0,46,0,0,3,0)\nwall_1=Wall(46,0,0,46,46,0,3,0)\n"
        "wall_2=Wall(46,46,0,0,46,0,3,0)\nwall_3=Wall(0,46,0,0,0,0,3,0)\n",
        f);
    for (int i = 0; i < 45 * 45; ++i)
        fprintf(f, "bbox_%d=Bbox(crate,%d.5,%d.5,0.25,0,0.5,0.5,0.5)\n", i, 1 + i % 45, 1 + i / 45);
    fclose(f);

    smql_db* db = NULL;
    CHECK(smql_open(dir, 0, &db) == SMQL_OK);
    CHECK(smql_import_file(db, "spatiallm", layout, "hall") == SMQL_OK);
    CHECK(smql_execute(db, "SET max_pairs = 100000000; SET max_rows = 100000000", NULL) == SMQL_OK);
    smql_stmt* stmt = NULL;
    CHECK(smql_prepare(db, "COUNT ? WHERE between(?, ?)", &stmt) == SMQL_OK);
    CHECK(smql_bind_text(stmt, 1, "object") == SMQL_OK && smql_bind_text(stmt, 2, "object") == SMQL_OK &&
          smql_bind_text(stmt, 3, "object") == SMQL_OK);
    struct long_step job = {stmt, db, SMQL_OK, 0, 0};
    pthread_t thread;
    CHECK(pthread_create(&thread, NULL, step_long_statement, &job) == 0);
    /* An interrupt that comes before the statement starts is dropped: keep sending until it ends. */
    struct timespec pause = {0, 1000000};
    while (!job.done) {
        smql_interrupt(db);
        nanosleep(&pause, NULL);
    }
    pthread_join(thread, NULL);
    CHECK(job.status == SMQL_ERROR_INTERRUPTED);
    CHECK(job.said_interrupted);
    /* The statement is usable again after a reset. */
    CHECK(smql_reset(stmt) == SMQL_OK);
    CHECK(smql_bind_text(stmt, 1, "wall") == SMQL_OK && smql_bind_text(stmt, 2, "wall") == SMQL_OK &&
          smql_bind_text(stmt, 3, "wall") == SMQL_OK);
    smql_status again = smql_step(stmt);
    CHECK(again == SMQL_ROW || again == SMQL_DONE);
    smql_finalize(stmt);
    smql_close(db);
}

/* smql_interrupt from another thread stops a long statement with SMQL_ERROR_INTERRUPTED. */
struct long_statement {
    smql_db* db;
    smql_status status;
    int said_interrupted; /* errors are per thread: read in the thread that failed */
    volatile int done;
};

static void* run_long_statement(void* arg) {
    struct long_statement* job = arg;
    /* Every pair of the room's nodes for each node, many times over: seconds of work without an interrupt. */
    char text[4096] = "SET max_pairs = 1000000";
    for (int i = 0; i < 100; ++i) strcat(text, "; COUNT node WHERE between(node, node)");
    job->status = smql_execute(job->db, text, NULL);
    job->said_interrupted = contains(smql_errmsg(job->db), "interrupted");
    job->done = 1;
    return NULL;
}

static void test_interrupt(const char* dir) {
    smql_db* db = NULL;
    CHECK(smql_open(dir, 0, &db) == SMQL_OK);
    smql_interrupt(NULL); /* ignored */
    smql_interrupt(db);   /* nothing running: no effect on the next statement */
    CHECK(smql_execute(db, kQuery, NULL) == SMQL_OK);
    struct long_statement job = {db, SMQL_OK, 0, 0};
    pthread_t thread;
    CHECK(pthread_create(&thread, NULL, run_long_statement, &job) == 0);
    /* An interrupt that comes before the statement starts is dropped: keep sending until it ends. */
    struct timespec pause = {0, 1000000};
    while (!job.done) {
        smql_interrupt(db);
        nanosleep(&pause, NULL);
    }
    pthread_join(thread, NULL);
    CHECK(job.status == SMQL_ERROR_INTERRUPTED);
    CHECK(job.said_interrupted);
    CHECK(smql_execute(db, kQuery, NULL) == SMQL_OK);
    smql_close(db);
}

/* The child of test_close_at_exit: an atexit() handler registered before the
 * first smql_open closes the handles. Handlers run in the reverse order of
 * registration, so it runs after the library's own static objects, which were
 * made later (at the first open), are destroyed. Two handles, one on a new
 * database whose query fails, so closing has real work to do. */
static smql_db* exit_dbs[2] = {NULL, NULL};
static const char* exit_marker = NULL;

static void close_at_exit(void) {
    smql_close(exit_dbs[0]);
    smql_close(exit_dbs[1]);
    FILE* marker = fopen(exit_marker, "w");
    if (marker) fclose(marker);
}

static int close_at_exit_child(const char* dir, const char* fresh, const char* marker) {
    exit_marker = marker;
    if (atexit(close_at_exit) != 0) return 2;
    if (smql_open(dir, 0, &exit_dbs[0]) != SMQL_OK || smql_open(fresh, 0, &exit_dbs[1]) != SMQL_OK) return 3;
    if (smql_execute(exit_dbs[0], kQuery, NULL) != SMQL_OK) return 4;
    if (smql_execute(exit_dbs[1], kQuery, NULL) != SMQL_ERROR_BINDING) return 5; /* no scene yet */
    return 0;
}

/* ASK's translator set and read through the API, as SET translator does: a URL that is not http
 * is refused and changes nothing; an endpoint that is not there leaves the question to the
 * built-in reader, with a note; NULL restores the built-in reader. */
static void test_translator(const char* dir) {
    smql_db* db = NULL;
    CHECK(smql_open(dir, 0, &db) == SMQL_OK);
    CHECK(smql_translator(db) != NULL && strcmp(smql_translator(db), "built-in") == 0);
    CHECK(smql_set_translator(db, "ftp://127.0.0.1/v1") == SMQL_ERROR_BINDING);
    CHECK(contains(smql_errmsg(db), "translator"));
    CHECK(strcmp(smql_translator(db), "built-in") == 0);

    /* Port 9 (discard) on the loopback: nothing listens there, so the model cannot answer. */
    CHECK(smql_set_translator(db, "http://127.0.0.1:9/v1") == SMQL_OK);
    CHECK(strcmp(smql_translator(db), "http://127.0.0.1:9/v1") == 0);
    smql_result* res = NULL;
    CHECK(smql_execute(db, "ASK 'how many cushions are on the couch?'", &res) == SMQL_OK);
    const char* message = res ? smql_result_message(res) : NULL;
    CHECK(contains(message, "COUNT cushion WHERE on(sofa)"));
    CHECK(contains(message, "built-in reader"));
    CHECK(contains(message, "7 cushions"));
    smql_result_free(res);

    /* SET translator and the call are one setting. */
    CHECK(smql_execute(db, "SET translator = 'built-in'", NULL) == SMQL_OK);
    CHECK(strcmp(smql_translator(db), "built-in") == 0);
    CHECK(smql_set_translator(db, "http://127.0.0.1:9/v1") == SMQL_OK);
    CHECK(smql_set_translator(db, NULL) == SMQL_OK);
    CHECK(strcmp(smql_translator(db), "built-in") == 0);

    CHECK(smql_set_translator(NULL, "built-in") == SMQL_ERROR_MISUSE);
    CHECK(smql_translator(NULL) == NULL);
    smql_close(db);
}

static void test_close_at_exit(const char* dir, const char* base) {
    char marker[4096], fresh[4096];
    snprintf(marker, sizeof marker, "%s/closed-at-exit", base);
    snprintf(fresh, sizeof fresh, "%s/exit-db", base);
    pid_t child = fork();
    CHECK(child >= 0);
    if (child == 0) {
        /* A fresh process image: nothing of smql is initialised before atexit(). */
        execl("/proc/self/exe", "smql_c_api_tests", "close-at-exit", dir, fresh, marker, (char*)NULL);
        _exit(127);
    }
    int status = 0;
    CHECK(waitpid(child, &status, 0) == child);
    if (WIFSIGNALED(status)) fprintf(stderr, "close-at-exit: the child died of signal %d\n", WTERMSIG(status));
    if (WIFEXITED(status) && WEXITSTATUS(status) != 0)
        fprintf(stderr, "close-at-exit: the child exited with %d\n", WEXITSTATUS(status));
    CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    CHECK(access(marker, F_OK) == 0);
}

int main(int argc, char** argv) {
    if (argc == 5 && strcmp(argv[1], "close-at-exit") == 0) return close_at_exit_child(argv[2], argv[3], argv[4]);

    char base[] = "/tmp/smql-c-api-XXXXXX";
    if (!mkdtemp(base)) {
        perror("mkdtemp");
        return 1;
    }
    char dir[4096];
    snprintf(dir, sizeof dir, "%s/db", base);

    test_misuse();
    test_open_failure(base);
    test_import(dir);
    test_update(base);
    test_ingest(base);
    if (argc >= 2) test_check_ingest(base, argv[1]);
    test_query(dir);
    test_evaluate(dir);
    test_export(dir, base);
    test_returned_columns(dir);
    test_statements_and_errors(dir);
    test_read_only(dir);
    test_threads(dir);
    test_interrupt(dir);
    test_prepared(dir);
    test_prepared_quotes(base);
    test_bind_vector(base);
    test_prepared_interrupt(base);
    test_translator(dir);
    test_close_at_exit(dir, base);

    nftw(base, remove_entry, 8, FTW_DEPTH | FTW_PHYS);
    printf("%d passed, %d failed\n", passed, failed);
    return failed == 0 ? 0 : 1;
}
