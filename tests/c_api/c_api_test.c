/*
 * The C API from C: import, query, typed access, JSON, errors, misuse,
 * read-only handles and threads sharing one handle. Needs SMQL_SHARED_DATA
 * (the folder holding replica-room0/). Last line: "N passed, M failed".
 */
#define _XOPEN_SOURCE 700 /* mkdtemp, nftw */

#include <ftw.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/wait.h>
#include <unistd.h>

#include "smql.h"

static int passed = 0, failed = 0;

#define CHECK(cond)                                                                 \
    do {                                                                            \
        if (cond) {                                                                 \
            ++passed;                                                               \
        } else {                                                                    \
            ++failed;                                                               \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
        }                                                                           \
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

/* smql_interrupt from another thread stops a long statement with SMQL_ERROR_INTERRUPTED. */
struct long_statement {
    smql_db* db;
    smql_status status;
    int said_interrupted; /* errors are per thread: read in the thread that failed */
    volatile int done;
};

static void* run_long_statement(void* arg) {
    struct long_statement* job = arg;
    /* Every pair of the room's nodes, many times over: seconds of work without an interrupt. */
    char text[4096] = "SET max_pairs = 1000000";
    for (int i = 0; i < 100; ++i) strcat(text, "; RELATE node TO node");
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
    if (WIFEXITED(status) && WEXITSTATUS(status) != 0) fprintf(stderr, "close-at-exit: the child exited with %d\n", WEXITSTATUS(status));
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
    test_query(dir);
    test_statements_and_errors(dir);
    test_read_only(dir);
    test_threads(dir);
    test_interrupt(dir);
    test_close_at_exit(dir, base);

    nftw(base, remove_entry, 8, FTW_DEPTH | FTW_PHYS);
    printf("%d passed, %d failed\n", passed, failed);
    return failed == 0 ? 0 : 1;
}
