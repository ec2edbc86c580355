// The LMDB environment behind a Database: opening and validating a database
// directory, the named sub-databases ("tables") and small helpers around the
// LMDB C API. Private to storage/ (LMDB types never leave it).
#pragma once

#include <lmdb.h>
#include <sys/types.h>

#include <array>
#include <cstddef>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "storage/database.hpp"

namespace smql::storage {

enum class Table : std::size_t {
    Meta,
    Nodes,
    Scenes,
    SceneNames,
    Children,
    Labels,
    SourceIds,
    Relations,
    Blobs,
    History,
    SceneIndex
};
inline constexpr std::size_t kTableCount = 11;

struct TableSpec {
    const char* name;
    unsigned flags;
};

// The layout of docs/storage.md. Flags are persistent: changing one is a schema change.
inline constexpr std::array<TableSpec, kTableCount> kTables = {{
    {"meta", 0},
    {"nodes", 0},
    {"scenes", 0},
    {"scene_names", 0},
    {"children", MDB_DUPSORT | MDB_DUPFIXED},
    {"labels", MDB_DUPSORT | MDB_DUPFIXED},
    {"source_ids", 0},
    {"relations", MDB_DUPSORT | MDB_DUPFIXED},
    {"blobs", 0},
    {"history", 0},
    {"scene_index", 0},
}};

// Room for the tables still to come (vectors, blobs, spatial index) without
// touching the environment setup.
inline constexpr unsigned kMaxTables = 32;

inline constexpr std::string_view kSchemaVersionKey = "schema_version";
inline constexpr std::string_view kNextIdKey = "next_id";
inline constexpr std::string_view kSettingPrefix = "setting:";
inline constexpr std::string_view kDataFile = "data.mdb";
inline constexpr std::string_view kLockFile = "lock.mdb";

class Environment {
public:
    // Opens (or creates) the environment of `directory`. Within one process a
    // directory maps to one shared Environment: LMDB forbids opening the same
    // environment twice in a process (closing one copy would drop the other's
    // POSIX locks).
    static std::shared_ptr<Environment> open(const std::string& directory, const OpenOptions& options);
    ~Environment();
    Environment(const Environment&) = delete;
    Environment& operator=(const Environment&) = delete;

    MDB_env* env() const { return env_; }
    MDB_dbi dbi(Table table) const { return dbis_[static_cast<std::size_t>(table)]; }
    // False only for the scene index of a version-3 database opened read-only (it predates the
    // table, and a read-only open cannot add it): its scenes are read without one.
    bool has(Table table) const { return !(table == Table::SceneIndex && !hasSceneIndex_); }
    const std::string& directory() const { return directory_; }
    bool readOnly() const { return readOnly_; }
    // LMDB's key size limit (511 bytes in Debian's build); names used as keys are checked against it.
    std::size_t maxKeySize() const { return static_cast<std::size_t>(mdb_env_get_maxkeysize(env_)); }
    // The bytes of a key or value LMDB returned, once they are known to lie in data.mdb: a flipped
    // bit in a page's node header can give a size that reaches past the end of the file, and
    // reading there is a SIGBUS. Throws a Storage error naming the damage instead.
    std::string_view bytes(const MDB_val& v) const;
    // Copies bytes() returned to `into`: from the file by pread when they lie in the map, else
    // from memory. A large record read once and copied (a scene index of 2,000 nodes is 125 KiB)
    // is read this way because the first touch of each page of the map costs a page fault, and
    // each fault a change to the process's page tables: on the 2-core test VM, with the file in
    // the page cache, reading such an index the first time took 82-86 us through the map (its
    // pages mapped in one call, MADV_POPULATE_READ) and takes 22-29 us with pread.
    void copyOut(void* into, std::string_view from) const;

    // A read transaction with the cursors it opened (null where it opened none), one per table.
    struct Reader {
        MDB_txn* txn = nullptr;
        std::array<MDB_cursor*, kTableCount> cursors{};
    };
    // Read transactions come from a pool of reset ones: renewing a transaction reuses its reader
    // slot, where beginning one takes LMDB's reader lock, and renewing its cursors reuses their
    // memory, where opening one allocates (a query opens one to three).
    Reader beginReader();
    void endReader(Reader reader);

    // Throws smql::Error(Storage) when lock.mdb is no longer the file this
    // environment opened (removed, or replaced by a new one). LMDB's writer
    // mutex and reader table live in that file: a process that opens the
    // database after the removal makes a new lock file, and its writes are no
    // longer serialised with ours, so a write from here could undo its commits.
    void checkLockFile(std::string_view operation) const;

    // Throws smql::Error(Storage) naming the database, the operation and LMDB's reason.
    [[noreturn]] void fail(int rc, std::string_view operation) const;
    void check(int rc, std::string_view operation) const {
        if (rc != MDB_SUCCESS) fail(rc, operation);
    }

private:
    Environment(MDB_env* env, std::string directory, bool readOnly);
    // open() once the directory is known to be fit: the environment itself.
    static std::shared_ptr<Environment> openChecked(const std::string& directory, const OpenOptions& options);
    void openTables(bool create);
    void upgradeSchema(std::uint64_t from);
    int widenLabels(MDB_txn* txn);
    void checkFileSize() const;

    // Where LMDB mapped data.mdb in this process (from /proc/self/maps: LMDB does not say), for
    // bytes(); null when it cannot be found, and then bytes() trusts LMDB's sizes.
    void findMap();

    MDB_env* env_;
    std::string directory_;
    bool readOnly_;
    const char* map_ = nullptr;
    std::size_t mapSize_ = 0;
    std::array<MDB_dbi, kTableCount> dbis_{};
    bool hasSceneIndex_ = true;
    // Device and inode of lock.mdb when this environment opened it; unset
    // when LMDB runs without one (a read-only file system).
    std::optional<std::pair<dev_t, ino_t>> lockFile_;
    std::mutex readersMutex_;
    std::vector<Reader> idleReaders_;

public:
    // Label keys that are not canonical category names (model/category.hpp: written before names
    // were folded, or by a program that wrote through storage directly), each with its canonical
    // name: read from `txn` once, kept until a write stores another such key (forgetLegacyLabels).
    // Every write through the engine stores canonical names, so the list does not otherwise grow.
    std::vector<std::pair<std::string, std::string>> legacyLabels(MDB_txn* txn) const;
    void forgetLegacyLabels() const;

private:
    mutable std::mutex legacyMutex_;
    mutable std::optional<std::vector<std::pair<std::string, std::string>>> legacyLabels_;
};

inline MDB_val toVal(std::string_view s) { return {s.size(), const_cast<char*>(s.data())}; }
template <std::size_t N>
MDB_val toVal(const std::array<std::uint8_t, N>& bytes) {
    return {N, const_cast<std::uint8_t*>(bytes.data())};
}
inline std::string_view fromVal(const MDB_val& v) { return {static_cast<const char*>(v.mv_data), v.mv_size}; }

// A cursor closed on scope exit; for write transactions, where cursors are not reused.
class Cursor {
public:
    Cursor(const Environment& env, MDB_txn* txn, Table table);
    ~Cursor() { mdb_cursor_close(cursor_); }
    Cursor(const Cursor&) = delete;
    Cursor& operator=(const Cursor&) = delete;
    MDB_cursor* get() const { return cursor_; }

private:
    MDB_cursor* cursor_ = nullptr;
};

}  // namespace smql::storage
