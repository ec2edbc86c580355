// Internal to storage/: what the files behind database.hpp share (database.cpp, scene_validation.cpp,
// scene_writer.cpp, versioning.cpp): the state of a Database and of a transaction, and the lookups
// that read and decode records. It holds LMDB types, so nothing outside storage/ includes it.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include <fmt/format.h>

#include "model/error.hpp"
#include "storage/codec.hpp"
#include "storage/database.hpp"
#include "storage/lmdb_env.hpp"

namespace smql::storage {

struct Database::Impl {
    std::shared_ptr<Environment> env;
    std::string directory;
    bool readOnly;
};

// One LMDB transaction, read-only (a ReadTransaction from beginRead) or not (a WriteTransaction from
// beginWrite): LMDB has one transaction type with a read-only flag, and so do these.
struct ReadTransaction::Impl {
    // A read transaction, with the cursors it kept from its last use (Environment::beginReader).
    Impl(std::shared_ptr<Environment> environment, Environment::Reader reader)
        : env(std::move(environment)), txn(reader.txn), readOnly(true), cursors(reader.cursors) {}
    // A write transaction.
    Impl(std::shared_ptr<Environment> environment, MDB_txn* transaction)
        : env(std::move(environment)), txn(transaction), readOnly(false) {}
    ~Impl() {
        if (readOnly) {
            env->endReader({txn, cursors});  // the cursors go back to the pool with their transaction
            return;
        }
        if (txn) mdb_txn_abort(txn);  // destroyed without commit()
    }
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;

    std::shared_ptr<Environment> env;  // keeps the environment open while the transaction lives
    MDB_txn* txn;                      // a write transaction's is null once committed
    const bool readOnly;
    // A read transaction keeps one cursor per table for its life and hands them on to the next
    // one: opening a cursor allocates, and lookups such as children() run many times per query. A
    // write transaction keeps none (see TableCursor), so these stay null for it.
    mutable std::array<MDB_cursor*, kTableCount> cursors{};
    mutable std::array<bool, kTableCount> cursorBusy{};
    std::string record;  // a write transaction's encode buffer, reused across records
};

inline constexpr std::string_view kImportHint = "fix the importer or the file it read";

// Throws smql::Error(Input) with the hint for a scene an importer got wrong.
[[noreturn]] void importError(std::string message);

// The value stored under `key`, or nothing; other LMDB failures throw.
std::optional<std::string_view> lookup(const Environment& env, MDB_txn* txn, Table table, MDB_val key,
                                       std::string_view operation);

// The scene whose id block holds `id`, named for an error message (read defensively: the damaged
// record may be the one that names it).
std::string sceneNameFor(const Environment& env, MDB_txn* txn, model::NodeId id);

// Runs `decode` and reports a corrupt record as "corrupt record in scene X":
// which scene is damaged is what a user needs to restore or re-import.
template <class Decode>
auto decodeInScene(const Environment& env, MDB_txn* txn, model::NodeId id, Decode&& decode) -> decltype(decode()) {
    try {
        return decode();
    } catch (const codec::CorruptRecord& e) {
        throw Error(ErrorKind::Storage,
                    fmt::format("corrupt record in scene {} of database {}: {}", sceneNameFor(env, txn, id),
                                env.directory(), e.detail()),
                    std::nullopt, e.hint());
    }
}

std::optional<model::SceneInfo> readScene(const Environment& env, MDB_txn* txn, model::NodeId sceneId);
// Calls visit(node) for each stored node of scene `sceneId` in `txn` (read or write), read through
// `cursor`, a cursor on the nodes table. Scene ids are contiguous blocks, the scene node first, so a
// scene's nodes are the run of node records from its id on that carry its id as their scene.
void forEachStoredNode(const Environment& env, MDB_txn* txn, MDB_cursor* cursor, model::NodeId sceneId,
                       const std::function<void(const model::Node&)>& visit);
// The id the name index holds for a scene name.
std::optional<model::NodeId> readSceneId(const Environment& env, MDB_txn* txn, std::string_view name);

// Writes the scene index of a stored scene from its records as they are in `txn` (after an import,
// a rename, an update of its nodes), under the version its scene record now has.
void storeSceneIndex(const Environment& env, MDB_txn* txn, model::NodeId sceneId, std::string& record);

// Ends a cursor scan: running off the end (MDB_NOTFOUND) is how scans stop, anything else is a failure.
inline void endOfScan(const Environment& env, int rc, std::string_view operation) {
    if (rc != MDB_SUCCESS && rc != MDB_NOTFOUND) env.fail(rc, operation);
}

}  // namespace smql::storage
