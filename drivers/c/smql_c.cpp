// The C API over smql::Engine. Every entry point catches everything: a C
// caller sees a status and an error text, never an exception.
#include "smql.h"

#include <dlfcn.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <new>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <unordered_map>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "engine/ask/model_translator.hpp"
#include "engine/engine.hpp"
#include "engine/eval/evaluation.hpp"
#include "engine/format.hpp"
#include "fleet/local/local_scenes.hpp"
#include "fleet_module.hpp"
#include "ingest/import/registry.hpp"
#include "ingest_module.hpp"
#include "model/error.hpp"
#include "model/result.hpp"
#include "storage/database.hpp"
#include "storage/output_guard.hpp"
#include "view/view.hpp"

struct smql_db {
    // A type of the handle's own, not of the file's anonymous namespace: smql_db is declared in smql.h, and
    // a field of such a type would give it internal linkage in part (GCC's -Wsubobject-linkage).
    struct LastError {
        smql_status status = SMQL_OK;
        std::string text;
        int line = 0;
        int column = 0;
    };

    std::unique_ptr<smql::Engine> engine;  // null when smql_open failed: the handle only reports why
    // A handle smql_open made of a postgresql:// URL: statements run in the fleet store's server
    // (docs/fleet.md), through the fleet module, which owns the session.
    smql::fleet::StoreSession* store = nullptr;
    std::string directory;   // smql_push and smql_pull read and write it through storage
    std::string translator;  // smql_translator's text, until its next call
    bool readOnly = false;
    // Errors are kept per calling thread so that threads sharing a handle
    // read their own error; an entry exists only while its last call failed.
    mutable std::mutex errorsMutex;
    std::unordered_map<std::thread::id, LastError> errors;
    // smql_interrupt's word to a running smql_ingest, which asks between frames.
    std::atomic<bool> ingestInterrupted{false};
};

using LastError = smql_db::LastError;

struct smql_result {
    smql::ResultSet set;                // the last statement's columns and rows
    std::vector<std::string> messages;  // one per statement that ran
    // JSON text is made on first request and kept until the result is freed;
    // readers on several threads may ask at once, hence the mutex.
    mutable std::mutex cacheMutex;
    mutable std::unordered_map<std::size_t, std::string> rowJson;
    mutable std::optional<std::string> resultJson;
};

// A prepared statement: the engine's PreparedStatement, the text error carets point into, and the
// rows of its current run, read one at a time by smql_step.
struct smql_stmt {
    smql_db* db;
    std::string text;
    smql::PreparedStatement prepared;
    std::unique_ptr<smql_result> rows;  // null until the run; kept after it until smql_reset
    smql_status finished = SMQL_OK;     // SMQL_DONE or the run's error, once smql_step has no more rows
    std::size_t nextRow = 0;            // the row the next step makes current; current = nextRow - 1
};

namespace {

constexpr const char* kNullHandleMessage = "misuse: the smql_db handle is NULL";

smql_status statusOf(smql::ErrorKind kind) {
    switch (kind) {
        case smql::ErrorKind::Syntax:
            return SMQL_ERROR_SYNTAX;
        case smql::ErrorKind::Binding:
            return SMQL_ERROR_BINDING;
        case smql::ErrorKind::Input:
            return SMQL_ERROR_INPUT;
        case smql::ErrorKind::Storage:
            return SMQL_ERROR_STORAGE;
        case smql::ErrorKind::Usage:
            return SMQL_ERROR_USAGE;
        case smql::ErrorKind::Limit:
            return SMQL_ERROR_LIMIT;
        case smql::ErrorKind::Interrupted:
            return SMQL_ERROR_INTERRUPTED;
    }
    return SMQL_ERROR_INTERNAL;
}

smql_type typeOf(smql::ValueType type) {
    switch (type) {
        case smql::ValueType::Null:
            return SMQL_NULL;
        case smql::ValueType::Integer:
            return SMQL_INTEGER;
        case smql::ValueType::Real:
            return SMQL_REAL;
        case smql::ValueType::Text:
            return SMQL_TEXT;
        case smql::ValueType::Box:
            return SMQL_BOX;
    }
    return SMQL_INVALID;
}

const LastError* lastError(const smql_db* db) {
    std::lock_guard lock(db->errorsMutex);
    auto it = db->errors.find(std::this_thread::get_id());
    // Only this thread writes its own entry, and unordered_map keeps element
    // addresses stable across other threads' inserts, so the pointer may
    // outlive the lock.
    return it == db->errors.end() ? nullptr : &it->second;
}

void forgetError(smql_db* db) noexcept {
    std::lock_guard lock(db->errorsMutex);
    db->errors.erase(std::this_thread::get_id());
}

smql_status recordError(smql_db* db, smql_status status, std::string text, int line = 0, int column = 0) {
    std::lock_guard lock(db->errorsMutex);
    db->errors[std::this_thread::get_id()] = LastError{status, std::move(text), line, column};
    return status;
}

// Runs `body` on an open handle, turning every exception into a status and
// the handle's error text; `source` is the statement text carets point into.
template <class Body>
smql_status guarded(smql_db* db, std::string_view source, Body&& body) noexcept {
    try {
        try {
            body();
        } catch (const smql::Error& e) {
            int line = e.where() ? e.where()->line : 0;
            int column = e.where() ? e.where()->column : 0;
            return recordError(db, statusOf(e.kind()), e.render(source), line, column);
        } catch (const std::bad_alloc&) {
            return recordError(db, SMQL_ERROR_INTERNAL, "internal error: out of memory");
        } catch (const std::exception& e) {
            return recordError(db, SMQL_ERROR_INTERNAL, std::string("internal error: ") + e.what());
        } catch (...) {
            return recordError(db, SMQL_ERROR_INTERNAL, "internal error: unknown exception");
        }
        forgetError(db);
        return SMQL_OK;
    } catch (...) {
        // Recording the error needed memory that is not there: report the
        // status without a text rather than a stale one.
        forgetError(db);
        return SMQL_ERROR_INTERNAL;
    }
}

smql_status misuse(smql_db* db, const char* what) noexcept {
    try {
        return recordError(db, SMQL_ERROR_MISUSE, std::string("misuse: ") + what);
    } catch (...) {
        forgetError(db);
        return SMQL_ERROR_MISUSE;
    }
}

// The checks every call on a handle starts with; SMQL_OK when it may go on.
smql_status checkOpen(smql_db* db) noexcept {
    if (!db) return SMQL_ERROR_MISUSE;
    if (db->engine) return SMQL_OK;
    if (db->store) return misuse(db, "a handle on a fleet store runs statements only (smql_execute)");
    return misuse(db, "this handle failed to open: read smql_errmsg right after smql_open, then smql_close it");
}

const smql::Value* cell(const smql_result* res, std::size_t row, std::size_t col) {
    if (!res || row >= res->set.rows.size() || col >= res->set.rows[row].size()) return nullptr;
    return &res->set.rows[row][col];
}

std::string dumpJson(const nlohmann::ordered_json& json) {
    // Text read from user files may hold invalid UTF-8: replace it, never throw.
    return json.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// A module libsmql.so loads (dlopen) once per process from the folder it was itself loaded from
// (its installed place, or the build tree's): the library, or why it could not be loaded.
struct ModuleLibrary {
    void* handle = nullptr;
    std::string path;
    std::string failure;
};

ModuleLibrary openModule(const char* file, const char* what) {
    ModuleLibrary out;
    Dl_info self{};
    std::filesystem::path path = file;
    if (dladdr(reinterpret_cast<void*>(&smql_version), &self) && self.dli_fname)
        path = std::filesystem::path(self.dli_fname).parent_path() / file;
    out.path = path.string();
    out.handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!out.handle) {
        const char* why = dlerror();
        out.failure = fmt::format("cannot load the {} module {}: {}", what, out.path, why ? why : "unknown reason");
    }
    return out;
}

template <class Step>
Step entry(const ModuleLibrary& library, const char* name) {
    return library.handle ? reinterpret_cast<Step>(dlsym(library.handle, name)) : nullptr;
}

// Runs a module's step; its error thrown as ours.
template <class Step, class Call>
void runStep(Step step, Call& call) {
    step(call);
    if (call.error) throw *call.error;
}

// The fleet module's calls.
struct FleetModule {
    smql::capi::PushStep push = nullptr;
    smql::capi::FetchStep fetch = nullptr;
    smql::capi::SessionStep session = nullptr;
    std::string failure;  // why it could not be loaded
};

const FleetModule& loadedFleetModule() {
    static const FleetModule module = [] {
        const ModuleLibrary library = openModule(smql::capi::kFleetModuleFile, "fleet");
        FleetModule out{entry<smql::capi::PushStep>(library, smql::capi::kPushEntry),
                        entry<smql::capi::FetchStep>(library, smql::capi::kFetchEntry),
                        entry<smql::capi::SessionStep>(library, smql::capi::kSessionEntry), library.failure};
        if (out.failure.empty() && (!out.push || !out.fetch || !out.session))
            out.failure = library.path + " is not smql's fleet module";
        return out;
    }();
    if (!module.failure.empty())
        throw smql::Error(smql::ErrorKind::Usage, module.failure, std::nullopt,
                          "make install puts libsmql_fleet.so beside libsmql.so");
    return module;
}

bool isStoreUrl(std::string_view dir) { return dir.starts_with("postgresql://") || dir.starts_with("postgres://"); }

}  // namespace

const char* smql_version(void) { return SMQL_VERSION_STRING; }

int smql_complete(const char* statements) { return statements && smql::statementComplete(statements) ? 1 : 0; }

const char* smql_status_string(smql_status status) {
    switch (status) {
        case SMQL_OK:
            return "ok";
        case SMQL_ERROR_SYNTAX:
            return "syntax error";
        case SMQL_ERROR_BINDING:
            return "name does not resolve";
        case SMQL_ERROR_INPUT:
            return "bad input file";
        case SMQL_ERROR_STORAGE:
            return "storage error";
        case SMQL_ERROR_USAGE:
            return "usage error";
        case SMQL_ERROR_MISUSE:
            return "API misuse";
        case SMQL_ERROR_INTERNAL:
            return "internal error";
        case SMQL_ERROR_LIMIT:
            return "limit exceeded";
        case SMQL_ERROR_INTERRUPTED:
            return "interrupted";
        case SMQL_ROW:
            return "row";
        case SMQL_DONE:
            return "done";
    }
    return "unknown status";
}

smql_status smql_open(const char* dir, int flags, smql_db** out) {
    if (!out) return SMQL_ERROR_MISUSE;
    *out = new (std::nothrow) smql_db();
    if (!*out) return SMQL_ERROR_INTERNAL;
    smql_db* db = *out;
    if (!dir) return misuse(db, "smql_open: dir is NULL");
    if (flags & ~SMQL_OPEN_READONLY) return misuse(db, "smql_open: unknown flag bits (only SMQL_OPEN_READONLY exists)");
    db->directory = dir;
    db->readOnly = (flags & SMQL_OPEN_READONLY) != 0;
    if (isStoreUrl(dir))
        return guarded(db, {}, [&] {
            smql::capi::SessionCall call;
            call.url = dir;
            runStep(loadedFleetModule().session, call);
            db->store = call.session;
        });
    return guarded(db, {}, [&] { db->engine = smql::Engine::open(dir, db->readOnly); });
}

void smql_close(smql_db* db) {
    if (db && db->store) {
        smql::capi::SessionCall call;
        call.session = db->store;
        call.close = true;
        loadedFleetModule().session(call);  // the module was loaded when the handle opened
    }
    delete db;
}

const char* smql_errmsg(const smql_db* db) {
    if (!db) return kNullHandleMessage;
    const LastError* error = lastError(db);
    return error ? error->text.c_str() : "";
}

smql_status smql_errcode(const smql_db* db) {
    if (!db) return SMQL_ERROR_MISUSE;
    const LastError* error = lastError(db);
    return error ? error->status : SMQL_OK;
}

int smql_error_line(const smql_db* db) {
    const LastError* error = db ? lastError(db) : nullptr;
    return error ? error->line : 0;
}

int smql_error_column(const smql_db* db) {
    const LastError* error = db ? lastError(db) : nullptr;
    return error ? error->column : 0;
}

smql_status smql_execute(smql_db* db, const char* statements, smql_result** out) {
    if (out) *out = nullptr;
    if (db && db->store && statements) {
        return guarded(db, statements, [&] {
            smql::capi::SessionCall call;
            call.session = db->store;
            call.statements = statements;
            runStep(loadedFleetModule().session, call);
            if (!out) return;
            auto result = std::make_unique<smql_result>();
            for (const auto& set : call.results) result->messages.push_back(set.message);
            if (!call.results.empty()) result->set = std::move(call.results.back());
            *out = result.release();
        });
    }
    if (smql_status status = checkOpen(db); status != SMQL_OK) return status;
    if (!statements) return misuse(db, "smql_execute: statements is NULL");
    return guarded(db, statements, [&] {
        auto sets = db->engine->execute(statements);
        if (!out) return;
        auto result = std::make_unique<smql_result>();
        for (const auto& set : sets) result->messages.push_back(set.message);
        if (!sets.empty()) result->set = std::move(sets.back());
        *out = result.release();
    });
}

smql_status smql_set_translator(smql_db* db, const char* url) {
    if (smql_status status = checkOpen(db); status != SMQL_OK) return status;
    return guarded(db, {}, [&] {
        const std::string to = url ? url : "";
        // The engine's own reading of SET translator: the same URL check and fallback.
        db->engine->setAskTranslator(
            to.empty() || to == "built-in" || to == "builtin" ? nullptr : smql::ask::modelTranslator(to));
    });
}

const char* smql_translator(smql_db* db) {
    if (!db || !db->engine) return nullptr;
    try {
        db->translator = db->engine->askTranslatorName();
    } catch (...) {
        return nullptr;
    }
    return db->translator.c_str();
}

void smql_interrupt(smql_db* db) {
    if (!db || !db->engine) return;
    db->engine->interrupt();
    db->ingestInterrupted = true;
}

smql_status smql_import_file(smql_db* db, const char* format, const char* path, const char* scene_name) {
    if (smql_status status = checkOpen(db); status != SMQL_OK) return status;
    if (!format || !path) return misuse(db, "smql_import_file: format and path must not be NULL");
    return guarded(db, {}, [&] {
        // The whole file is read and checked before the database is touched.
        db->engine->importScene(smql::import::read(format, path, scene_name ? scene_name : ""));
    });
}

smql_status smql_update_file(smql_db* db, const char* format, const char* path, const char* scene_name) {
    if (smql_status status = checkOpen(db); status != SMQL_OK) return status;
    if (!format || !path) return misuse(db, "smql_update_file: format and path must not be NULL");
    return guarded(
        db, {}, [&] { db->engine->updateScene(scene_name ? scene_name : "", smql::import::read(format, path, "")); });
}

namespace {

// The ingest module's steps.
struct IngestModule {
    smql::capi::IngestStep read = nullptr;
    smql::capi::IngestStep run = nullptr;
    smql::capi::CheckStep check = nullptr;
    std::string failure;  // why it could not be loaded
};

const IngestModule& ingestModule() {
    static const IngestModule module = [] {
        const ModuleLibrary library = openModule(smql::capi::kIngestModuleFile, "ingest");
        IngestModule out{entry<smql::capi::IngestStep>(library, smql::capi::kReadEntry),
                         entry<smql::capi::IngestStep>(library, smql::capi::kRunEntry),
                         entry<smql::capi::CheckStep>(library, smql::capi::kCheckEntry), library.failure};
        if (out.failure.empty() && (!out.read || !out.run || !out.check))
            out.failure = library.path + " is not smql's ingest module";
        return out;
    }();
    return module;
}

const IngestModule& loadedIngestModule() {
    const IngestModule& module = ingestModule();
    if (!module.failure.empty())
        throw smql::Error(smql::ErrorKind::Usage, module.failure, std::nullopt,
                          "make install puts libsmql_ingest.so beside libsmql.so; smql ingest needs no module");
    return module;
}

}  // namespace

smql_status smql_ingest(smql_db* db, const char* capture, const char* options, smql_progress_callback progress,
                        void* user) {
    if (smql_status status = checkOpen(db); status != SMQL_OK) return status;
    if (!capture) return misuse(db, "smql_ingest: capture must not be NULL");
    return guarded(db, {}, [&] {
        const IngestModule& module = loadedIngestModule();
        smql::capi::IngestCall call;
        call.capture = capture;
        call.options = options ? options : "";
        if (progress) call.progress = [&](const smql_progress& event) { return progress(user, &event) != 0; };
        db->ingestInterrupted = false;
        call.interrupted = &db->ingestInterrupted;
        runStep(module.read, call);
        // The name is checked before the work, not after it.
        db->engine->checkIngestTarget(call.sceneName, call.update);
        runStep(module.run, call);

        auto start = std::chrono::steady_clock::now();
        std::string summary, stored = call.sceneName;
        if (call.update.empty()) {
            db->engine->importScene(std::move(call.scene));
            summary = "one transaction";
        } else {
            const auto updated = db->engine->updateScene(call.update, call.scene);
            summary = updated.summary();
            if (const auto warning = updated.warning()) summary += "; warning: " + *warning;
            stored = updated.scene;
        }
        if (call.progress) {
            double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            call.progress({SMQL_PROGRESS_STAGE_FINISHED, "write", 1, 1, seconds, summary.c_str()});
            // The things the checks flagged, by the ids they are stored under (the ingest's own are not those).
            smql::capi::CheckCall check;
            check.stored = db->engine->readScene(stored);
            runStep(module.check, check);
            for (const auto& warning : check.warnings)
                call.progress({SMQL_PROGRESS_NOTE, "", 0, 0, 0.0, warning.c_str()});
        }
    });
}

smql_status smql_check_ingest(smql_db* db, const char* truth, const char* scene, smql_result** out) {
    if (out) *out = nullptr;
    if (smql_status status = checkOpen(db); status != SMQL_OK) return status;
    if (!out) return misuse(db, "smql_check_ingest: out must not be NULL");
    return guarded(db, {}, [&] {
        smql::capi::CheckCall call;
        call.stored = db->engine->exportScene(scene ? scene : "");
        call.truth = truth ? truth : "";
        runStep(loadedIngestModule().check, call);
        auto res = std::make_unique<smql_result>();
        res->set.columns = {{"name", smql::ValueType::Text}, {"value", smql::ValueType::Real}};
        for (const auto& [name, value] : call.figures) res->set.rows.push_back({name, value});
        *out = res.release();
    });
}

namespace {

// The handle's database as storage sees it: within a process it shares the engine's environment.
std::unique_ptr<smql::storage::Database> storageOf(const smql_db* db) {
    return smql::storage::Database::open(db->directory, {.readOnly = db->readOnly, .create = false});
}

}  // namespace

smql_status smql_push(smql_db* db, const char* url, smql_result** out) {
    if (out) *out = nullptr;
    if (smql_status status = checkOpen(db); status != SMQL_OK) return status;
    if (!url) return misuse(db, "smql_push: url must not be NULL");
    return guarded(db, {}, [&] {
        const FleetModule& module = loadedFleetModule();
        auto database = storageOf(db);
        smql::fleet::LocalSource local = smql::fleet::localSource(*database);
        // No smql::Error crosses into the module: a failed read is kept here and reported as it was.
        std::optional<smql::Error> readFailure;
        local.read = [&](const std::string& scene) {
            try {
                return smql::fleet::readVersions(*database, scene);
            } catch (const smql::Error& e) {
                readFailure = e;
                throw std::runtime_error(e.message());
            }
        };
        smql::capi::PushCall call;
        call.url = url;
        call.local = &local;
        module.push(call);
        if (readFailure) throw *readFailure;
        if (call.error) throw *call.error;
        if (!out) return;
        auto res = std::make_unique<smql_result>();
        using smql::ValueType;
        res->set.columns = {{"device", ValueType::Text},
                            {"sent", ValueType::Integer},
                            {"present", ValueType::Integer},
                            {"nodes", ValueType::Integer},
                            {"seconds", ValueType::Real}};
        const auto& r = call.report;
        res->set.rows.push_back({r.device, static_cast<std::int64_t>(r.sent), static_cast<std::int64_t>(r.present),
                                 static_cast<std::int64_t>(r.nodes), r.seconds});
        res->set.message = r.summary();
        res->messages.push_back(res->set.message);
        *out = res.release();
    });
}

smql_status smql_pull(smql_db* db, const char* url, const char* scene, const char* device, uint64_t version) {
    if (smql_status status = checkOpen(db); status != SMQL_OK) return status;
    if (!url || !scene) return misuse(db, "smql_pull: url and scene must not be NULL");
    return guarded(db, {}, [&] {
        if (db->readOnly)
            throw smql::Error(smql::ErrorKind::Storage, "the database is open read-only: a pull cannot store its scene",
                              std::nullopt, "open it read-write");
        smql::capi::FetchCall call;
        call.url = url;
        call.request.scene = scene;
        call.request.device = device ? device : "";
        call.request.version = version;
        loadedFleetModule().fetch(call);
        if (call.error) throw *call.error;
        smql::fleet::storePulled(*storageOf(db), call.pulled.version);
    });
}

smql_status smql_evaluate(smql_db* db, const char* suite, const char* scene, smql_result** out) {
    if (out) *out = nullptr;
    if (smql_status status = checkOpen(db); status != SMQL_OK) return status;
    if (!out) return misuse(db, "smql_evaluate: out must not be NULL");
    return guarded(db, {}, [&] {
        auto report = smql::eval::evaluate(*db->engine, {.suite = suite ? suite : "", .scene = scene ? scene : ""});
        auto res = std::make_unique<smql_result>();
        using smql::ValueType;
        res->set.columns = {{"task", ValueType::Text},
                            {"metric", ValueType::Text},
                            {"value", ValueType::Real},
                            {"episodes", ValueType::Integer},
                            {"median_us", ValueType::Real}};
        for (const auto& m : report.metrics)
            res->set.rows.push_back(
                {m.task, m.metric, m.value, static_cast<std::int64_t>(m.episodes), m.medianMicroseconds});
        res->set.message = "scored scene '" + report.scene + "'";
        res->messages.push_back(res->set.message);
        *out = res.release();
    });
}

namespace {

// An export's bytes into `path`, never over the open database's own files.
void writeExport(smql_db* db, const std::string& bytes, const char* path) {
    smql::storage::refuseDatabaseFile(path, db->directory);
    std::ofstream out(path, std::ios::binary);
    out << bytes;
    out.close();
    if (!out)
        throw smql::Error(smql::ErrorKind::Storage, std::string("cannot write ") + path, std::nullopt,
                          "check that the folder exists and is writable");
}

}  // namespace

smql_status smql_export(smql_db* db, const char* format, const char* scene_name, const char* path) {
    if (smql_status status = checkOpen(db); status != SMQL_OK) return status;
    if (!format || !path) return misuse(db, "smql_export: format and path must not be NULL");
    return guarded(db, {}, [&] {
        const std::string scene = scene_name ? scene_name : "";
        writeExport(
            db,
            std::string_view(format) == "html"
                ? smql::view::standalonePage(*db->engine, scene)
                : smql::import::write(format, smql::import::writesFileIds(format) ? db->engine->exportScene(scene)
                                                                                  : db->engine->readScene(scene)),
            path);
    });
}

smql_status smql_export_points(smql_db* db, const char* scene_name, const char* path) {
    if (smql_status status = checkOpen(db); status != SMQL_OK) return status;
    if (!path) return misuse(db, "smql_export_points: path must not be NULL");
    return guarded(db, {}, [&] { writeExport(db, db->engine->scenePoints(scene_name ? scene_name : ""), path); });
}

void smql_result_free(smql_result* res) { delete res; }

size_t smql_column_count(const smql_result* res) { return res ? res->set.columns.size() : 0; }

size_t smql_row_count(const smql_result* res) { return res ? res->set.rows.size() : 0; }

const char* smql_column_name(const smql_result* res, size_t col) {
    if (!res || col >= res->set.columns.size()) return nullptr;
    return res->set.columns[col].name.c_str();
}

smql_type smql_column_type(const smql_result* res, size_t col) {
    if (!res || col >= res->set.columns.size()) return SMQL_INVALID;
    return typeOf(res->set.columns[col].type);
}

smql_type smql_value_type(const smql_result* res, size_t row, size_t col) {
    const smql::Value* value = cell(res, row, col);
    return value ? typeOf(smql::typeOf(*value)) : SMQL_INVALID;
}

smql_status smql_value_int64(const smql_result* res, size_t row, size_t col, int64_t* out) {
    const smql::Value* value = cell(res, row, col);
    const auto* integer = value ? std::get_if<std::int64_t>(value) : nullptr;
    if (!integer || !out) return SMQL_ERROR_MISUSE;
    *out = *integer;
    return SMQL_OK;
}

smql_status smql_value_double(const smql_result* res, size_t row, size_t col, double* out) {
    const smql::Value* value = cell(res, row, col);
    if (!value || !out) return SMQL_ERROR_MISUSE;
    if (const auto* real = std::get_if<double>(value)) {
        *out = *real;
        return SMQL_OK;
    }
    if (const auto* integer = std::get_if<std::int64_t>(value)) {
        *out = static_cast<double>(*integer);
        return SMQL_OK;
    }
    return SMQL_ERROR_MISUSE;
}

smql_status smql_value_text(const smql_result* res, size_t row, size_t col, const char** out) {
    const smql::Value* value = cell(res, row, col);
    const auto* text = value ? std::get_if<std::string>(value) : nullptr;
    if (!text || !out) return SMQL_ERROR_MISUSE;
    *out = text->c_str();
    return SMQL_OK;
}

smql_status smql_value_box(const smql_result* res, size_t row, size_t col, smql_box* out) {
    const smql::Value* value = cell(res, row, col);
    const auto* box = value ? std::get_if<smql::model::Box>(value) : nullptr;
    if (!box || !out) return SMQL_ERROR_MISUSE;
    *out = smql_box{{box->center.x, box->center.y, box->center.z}, {box->size.x, box->size.y, box->size.z}, box->yaw};
    return SMQL_OK;
}

const char* smql_row_json(const smql_result* res, size_t row) {
    if (!res || row >= res->set.rows.size()) return nullptr;
    try {
        std::lock_guard lock(res->cacheMutex);
        auto it = res->rowJson.find(row);
        if (it == res->rowJson.end()) it = res->rowJson.emplace(row, dumpJson(smql::rowJson(res->set, row))).first;
        return it->second.c_str();
    } catch (...) {
        return nullptr;  // out of memory
    }
}

const char* smql_result_json(const smql_result* res) {
    if (!res) return nullptr;
    try {
        std::lock_guard lock(res->cacheMutex);
        if (!res->resultJson) res->resultJson = dumpJson(smql::resultJson(res->set));
        return res->resultJson->c_str();
    } catch (...) {
        return nullptr;  // out of memory
    }
}

const char* smql_result_message(const smql_result* res) { return res ? res->set.message.c_str() : nullptr; }

size_t smql_statement_count(const smql_result* res) { return res ? res->messages.size() : 0; }

const char* smql_statement_message(const smql_result* res, size_t index) {
    if (!res || index >= res->messages.size()) return nullptr;
    return res->messages[index].c_str();
}

// ---- Prepared statements ------------------------------------------------

namespace {

// The current row, or nothing between steps.
std::optional<std::size_t> currentRow(const smql_stmt* stmt) {
    if (!stmt || !stmt->rows || stmt->nextRow == 0 || stmt->finished != SMQL_OK) return std::nullopt;
    return stmt->nextRow - 1;
}

// Binds through the engine, which checks the index and the kind of value; its refusals are
// the caller's misuse, as a bad index is in the result accessors.
smql_status bindValue(smql_stmt* stmt, int index, smql::ParameterValue value, const char* call) noexcept {
    if (!stmt) return SMQL_ERROR_MISUSE;
    if (stmt->rows)
        return misuse(stmt->db, (std::string(call) + ": the statement has run; smql_reset it before binding").c_str());
    if (index < 1) return misuse(stmt->db, (std::string(call) + ": placeholders are numbered from 1").c_str());
    try {
        stmt->prepared.bind(static_cast<std::size_t>(index), std::move(value));
    } catch (const smql::Error& e) {
        return misuse(stmt->db, (std::string(call) + ": " + e.message()).c_str());
    } catch (...) {
        return SMQL_ERROR_INTERNAL;  // out of memory
    }
    forgetError(stmt->db);
    return SMQL_OK;
}

}  // namespace

smql_status smql_prepare(smql_db* db, const char* statement, smql_stmt** out) {
    if (out) *out = nullptr;
    if (smql_status status = checkOpen(db); status != SMQL_OK) return status;
    if (!statement || !out) return misuse(db, "smql_prepare: statement and out must not be NULL");
    return guarded(db, statement,
                   [&] { *out = new smql_stmt{db, statement, db->engine->prepare(statement), nullptr, SMQL_OK, 0}; });
}

int smql_bind_parameter_count(const smql_stmt* stmt) {
    return stmt ? static_cast<int>(stmt->prepared.parameterCount()) : 0;
}

smql_status smql_bind_text(smql_stmt* stmt, int index, const char* text) {
    if (stmt && !text) return misuse(stmt->db, "smql_bind_text: text is NULL (smql_bind_null binds NULL)");
    try {
        return bindValue(stmt, index, std::string(text ? text : ""), "smql_bind_text");
    } catch (...) {
        return SMQL_ERROR_INTERNAL;  // out of memory copying the text
    }
}

smql_status smql_bind_int(smql_stmt* stmt, int index, int64_t value) {
    return bindValue(stmt, index, std::int64_t{value}, "smql_bind_int");
}

smql_status smql_bind_double(smql_stmt* stmt, int index, double value) {
    return bindValue(stmt, index, value, "smql_bind_double");
}

smql_status smql_bind_vector(smql_stmt* stmt, int index, const float* values, int count) {
    if (stmt && (!values || count < 1))
        return misuse(stmt->db, "smql_bind_vector: values must not be NULL and count must be 1 or more");
    try {
        return bindValue(stmt, index, std::vector<float>(values, values + (stmt ? count : 0)), "smql_bind_vector");
    } catch (...) {
        return SMQL_ERROR_INTERNAL;  // out of memory copying the vector
    }
}

smql_status smql_bind_null(smql_stmt* stmt, int index) {
    return bindValue(stmt, index, std::monostate{}, "smql_bind_null");
}

smql_status smql_step(smql_stmt* stmt) {
    if (!stmt) return SMQL_ERROR_MISUSE;
    if (stmt->finished != SMQL_OK) return stmt->finished;
    if (!stmt->rows) {
        smql_status status = guarded(stmt->db, stmt->text, [&] {
            auto rows = std::make_unique<smql_result>();
            rows->set = stmt->prepared.execute();
            rows->messages.push_back(rows->set.message);
            stmt->rows = std::move(rows);
        });
        if (status != SMQL_OK) return stmt->finished = status;
    }
    if (stmt->nextRow < stmt->rows->set.rows.size()) {
        ++stmt->nextRow;
        return SMQL_ROW;
    }
    return stmt->finished = SMQL_DONE;
}

smql_status smql_reset(smql_stmt* stmt) {
    if (!stmt) return SMQL_ERROR_MISUSE;
    stmt->rows.reset();
    stmt->finished = SMQL_OK;
    stmt->nextRow = 0;
    return SMQL_OK;
}

smql_status smql_clear_bindings(smql_stmt* stmt) {
    if (!stmt) return SMQL_ERROR_MISUSE;
    stmt->prepared.clearBindings();
    return SMQL_OK;
}

void smql_finalize(smql_stmt* stmt) { delete stmt; }

size_t smql_stmt_column_count(const smql_stmt* stmt) { return stmt ? smql_column_count(stmt->rows.get()) : 0; }

const char* smql_stmt_column_name(const smql_stmt* stmt, size_t col) {
    return stmt ? smql_column_name(stmt->rows.get(), col) : nullptr;
}

smql_type smql_stmt_column_type(const smql_stmt* stmt, size_t col) {
    return stmt ? smql_column_type(stmt->rows.get(), col) : SMQL_INVALID;
}

smql_type smql_stmt_value_type(const smql_stmt* stmt, size_t col) {
    auto row = currentRow(stmt);
    return row ? smql_value_type(stmt->rows.get(), *row, col) : SMQL_INVALID;
}

smql_status smql_stmt_value_int64(const smql_stmt* stmt, size_t col, int64_t* out) {
    auto row = currentRow(stmt);
    return row ? smql_value_int64(stmt->rows.get(), *row, col, out) : SMQL_ERROR_MISUSE;
}

smql_status smql_stmt_value_double(const smql_stmt* stmt, size_t col, double* out) {
    auto row = currentRow(stmt);
    return row ? smql_value_double(stmt->rows.get(), *row, col, out) : SMQL_ERROR_MISUSE;
}

smql_status smql_stmt_value_text(const smql_stmt* stmt, size_t col, const char** out) {
    auto row = currentRow(stmt);
    return row ? smql_value_text(stmt->rows.get(), *row, col, out) : SMQL_ERROR_MISUSE;
}

smql_status smql_stmt_value_box(const smql_stmt* stmt, size_t col, smql_box* out) {
    auto row = currentRow(stmt);
    return row ? smql_value_box(stmt->rows.get(), *row, col, out) : SMQL_ERROR_MISUSE;
}

const char* smql_stmt_row_json(const smql_stmt* stmt) {
    auto row = currentRow(stmt);
    return row ? smql_row_json(stmt->rows.get(), *row) : nullptr;
}

const char* smql_stmt_message(const smql_stmt* stmt) {
    return stmt && stmt->rows ? stmt->rows->set.message.c_str() : nullptr;
}
