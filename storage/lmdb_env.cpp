#include "storage/lmdb_env.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <tuple>

#include <fmt/format.h>

#include "model/category.hpp"
#include "model/error.hpp"
#include "storage/codec.hpp"

namespace smql::storage {

namespace {

namespace fs = std::filesystem;

// Each ReadTransaction holds a reader slot (MDB_NOTLS ties slots to
// transactions, not threads), so leave room for many concurrent readers.
constexpr unsigned kMaxReaders = 512;

[[noreturn]] void openError(const std::string& message, std::string hint) {
    throw Error(ErrorKind::Storage, message, std::nullopt, std::move(hint));
}

constexpr std::string_view kDamagedHint =
    "restore the directory from a backup, or import its scenes again into a new database";

[[noreturn]] void damaged(const std::string& directory, std::string_view why) {
    openError(fmt::format("database {} is damaged: {}", directory, why), std::string(kDamagedHint));
}

[[noreturn]] void notSmqlDatabase(const std::string& directory, std::string_view why) {
    openError(fmt::format("{} is not an smql database: {}", directory, why),
              "give the directory of an smql database, or a new or empty directory to create one");
}

// Environments open in this process, by (pid, device, inode) of the directory.
// The pid keeps a child forked while an environment was open from reusing the
// parent's handle, which LMDB forbids.
using RegistryKey = std::tuple<pid_t, dev_t, ino_t>;

// The registry and its mutex are never destroyed: a database may be closed
// from an atexit() handler (the C API's users do), and a handler registered
// before the first open runs after every static object made since, so a
// static registry would already be gone. They are reachable to the end, so
// leak checkers do not report them.
std::recursive_mutex& registryMutex() {
    // Recursive: an Environment that fails half-way through open() is destroyed
    // while open() still holds the lock, and its destructor takes it too.
    static auto* mutex = new std::recursive_mutex;
    return *mutex;
}

std::map<RegistryKey, std::weak_ptr<Environment>>& registry() {
    static auto* environments = new std::map<RegistryKey, std::weak_ptr<Environment>>;
    return *environments;
}

// Schema 2 lacks the history and scene index tables, schema 3 the scene index, and schemas 2 to 4
// have label entries of the two ids alone: a writable open adds the tables (empty) and rewrites the
// label entries in place. A read-only open reads a version-3 database without scene indexes, as
// every scene of it lacks one anyway, and the label entries of versions 3 and 4 as they are (the
// rows of a category search then come from the node records); a version-2 one it cannot, for want
// of the history table. Schemas 4 and 5 hold scene indexes of format 1, which are read as they are
// (a writable open only sets the version: a scene's next write stores format 2).
constexpr std::uint64_t kOldestUpgradableSchemaVersion = 2;
constexpr std::uint64_t kReadableWithoutSceneIndex = 3;
constexpr std::uint64_t kReadableWithIdsOnlyLabels = 4;
constexpr std::uint64_t kReadableWithDoubleBounds = 5;

// Returns the stored version: kSchemaVersion, or an older one this open can read or upgrade.
std::uint64_t checkSchemaVersion(const std::string& directory, MDB_txn* txn, MDB_dbi meta, bool upgradable) {
    MDB_val key = toVal(kSchemaVersionKey), value;
    int rc = mdb_get(txn, meta, &key, &value);
    if (rc == MDB_NOTFOUND) notSmqlDatabase(directory, "its meta table has no schema version");
    if (rc != MDB_SUCCESS)
        openError(fmt::format("cannot read the schema version of {}: {}", directory, mdb_strerror(rc)), {});
    std::uint64_t version = codec::decodeU64(fromVal(value), "schema version");
    if (version == kSchemaVersion) return version;
    if (version >= kOldestUpgradableSchemaVersion && version < kSchemaVersion) {
        if (upgradable || version == kReadableWithoutSceneIndex || version == kReadableWithIdsOnlyLabels ||
            version == kReadableWithDoubleBounds)
            return version;
        openError(fmt::format("database {} has schema version {}; this smql reads version {}", directory, version,
                              kSchemaVersion),
                  "open it once for writing (without --read-only): that upgrades it in place, adding the empty "
                  "tables of the versions since (the history, the scene indexes) and widening the label entries");
    }
    openError(fmt::format("database {} has schema version {}; this smql reads version {}", directory, version,
                          kSchemaVersion),
              version > kSchemaVersion
                  ? "it was written by a newer smql: open it with that smql, or upgrade this one"
                  : "it was written by an older smql: export its scenes with that smql (smql export json) and "
                    "import them into a new database with this one");
}

// A data.mdb of 0 bytes is what LMDB would silently initialise as a new,
// empty database, losing every scene the directory held. It is legitimately
// empty only for the instant another process is creating it, and then that
// process holds LMDB's exclusive lock on lock.mdb (taken before data.mdb is
// created, released after its first meta pages are written): mdb_env_open
// waits for that lock, so then the open goes ahead. F_GETLK only asks; it
// takes no lock, so closing the descriptor cannot drop one of ours either.
void checkEmptyDataFile(const std::string& directory) {
    struct stat data {};
    if (::stat((fs::path(directory) / kDataFile).c_str(), &data) != 0 || data.st_size != 0) return;
    int fd = ::open((fs::path(directory) / kLockFile).c_str(), O_RDONLY | O_CLOEXEC);
    bool beingCreated = false;
    if (fd >= 0) {
        struct flock probe {};
        probe.l_type = F_WRLCK;
        probe.l_whence = SEEK_SET;
        probe.l_start = 0;
        probe.l_len = 1;
        beingCreated = ::fcntl(fd, F_GETLK, &probe) == 0 && probe.l_type != F_UNLCK;
        ::close(fd);
    }
    if (!beingCreated)
        damaged(directory,
                fmt::format("its {} is empty (0 bytes); smql does not re-create a database in place", kDataFile));
}

// What an open that makes a new database created, so that a failure can
// take it away again: a failed creation leaves nothing behind.
struct Creation {
    bool newDatabase = false;
    std::vector<fs::path> createdDirectories;  // deepest first
    bool lockFileExisted = false;

    void undo(const std::string& directory) const {
        if (!newDatabase) return;
        std::error_code ec;
        fs::remove(fs::path(directory) / kDataFile, ec);
        if (!lockFileExisted) fs::remove(fs::path(directory) / kLockFile, ec);
        for (const auto& created : createdDirectories) fs::remove(created, ec);  // only while empty
    }
};

// The bytes free for this user on the file system holding `path`; nullopt when unknown.
std::optional<std::uint64_t> freeBytes(const std::string& path) {
    struct statvfs fsInfo {};
    if (::statvfs(path.c_str(), &fsInfo) != 0) return std::nullopt;
    return std::uint64_t(fsInfo.f_bavail) * fsInfo.f_frsize;
}

// A new database writes lock.mdb (~33 KB for 512 readers, through a shared
// map: a page the file system cannot back is SIGBUS, not an error), the first
// two meta pages and its tables. Below this much free space, creating is
// refused up front instead.
constexpr std::uint64_t kCreateMinimumFree = 1 << 20;

// Its own type so that only a creation that ran out of space is undone: any
// other failure may come from a second process creating the same database
// at the same moment, whose files must stay.
class NoSpace : public Error {
public:
    using Error::Error;
};

[[noreturn]] void noSpace(const std::string& directory, std::string_view operation, std::optional<std::uint64_t> free) {
    throw NoSpace(ErrorKind::Storage,
                  fmt::format("{} failed on database {}: no space left on device{}", operation, directory,
                              free ? fmt::format(" ({} bytes free on its file system)", *free) : std::string()),
                  std::nullopt,
                  "free some space on that file system (or move the database to another), then try again; the "
                  "database is as it was before");
}

// Every path below that the directory cannot be an smql database ends in an
// Error before LMDB is asked to create anything in it.
// A new database's name that is a URL or a libpq connection string (a fleet store's, mistyped: it
// would become a folder, a password in its name): refused, the text not repeated (it may hold one).
void refuseConnectionString(const std::string& directory) {
    const bool url = directory.find("://") != std::string::npos;
    bool conninfo = false;
    for (const char* key : {"host=", "hostaddr=", "dbname=", "user=", "password=", "port=", "sslmode="})
        conninfo =
            conninfo || directory.rfind(key, 0) == 0 || directory.find(std::string(" ") + key) != std::string::npos;
    if (url || conninfo)
        throw Error(ErrorKind::Usage,
                    url ? "the database given is a URL, not a folder: no database was created"
                        : "the database given is a connection string (key=value pairs), not a folder: no database "
                          "was created",
                    std::nullopt,
                    "a fleet store's URL begins postgresql:// (docs/fleet.md); a database here is a folder's path");
}

Creation checkDirectory(const std::string& directory, const OpenOptions& options) {
    Creation creation;
    std::error_code ec;
    fs::file_status status = fs::status(directory, ec);
    if (ec && status.type() != fs::file_type::not_found)
        openError(fmt::format("cannot open database {}: {}", directory, ec.message()),
                  "check that the path and its parent directories are readable");
    if (status.type() == fs::file_type::not_found) {
        if (!options.create || options.readOnly)
            openError(fmt::format("no database at {}", directory),
                      "check the path; smql creates a database only when it opens it for writing");
        refuseConnectionString(directory);
        for (fs::path missing = fs::absolute(directory, ec).lexically_normal();
             !missing.empty() && !fs::exists(missing, ec) && missing != missing.parent_path();
             missing = missing.parent_path())
            creation.createdDirectories.push_back(missing);
        fs::create_directories(directory, ec);
        if (ec)
            openError(fmt::format("cannot create database directory {}: {}", directory, ec.message()),
                      "check that the parent directory exists and is writable");
        creation.newDatabase = true;
        return creation;
    }
    if (!fs::is_directory(status))
        openError(fmt::format("database path {} is not a directory", directory),
                  "a database is a directory: give the path of one, or of a new directory to create");

    if (fs::exists(fs::path(directory) / kDataFile, ec)) {
        checkEmptyDataFile(directory);
        return creation;
    }
    fs::directory_iterator entries(directory, ec);
    if (ec)
        openError(fmt::format("cannot read database directory {}: {}", directory, ec.message()),
                  "check the permissions of the directory");
    for (const auto& entry : entries)
        if (entry.path().filename() != "lock.mdb")
            notSmqlDatabase(directory, fmt::format("it holds other files (such as {}) but no {}",
                                                   entry.path().filename().string(), kDataFile));
    if (!options.create || options.readOnly)
        openError(fmt::format("no database at {} (the directory is empty)", directory),
                  "open it once for writing to create the database");
    creation.newDatabase = true;
    creation.lockFileExisted = fs::exists(fs::path(directory) / kLockFile, ec);
    return creation;
}

}  // namespace

std::shared_ptr<Environment> Environment::open(const std::string& directory, const OpenOptions& options) {
    const Creation creation = checkDirectory(directory, options);
    if (creation.newDatabase)
        if (auto free = freeBytes(directory); free && *free < kCreateMinimumFree) {
            creation.undo(directory);
            noSpace(directory, "creating the database", free);
        }
    try {
        return openChecked(directory, options);
    } catch (const NoSpace&) {
        creation.undo(directory);
        throw;
    }
}

std::shared_ptr<Environment> Environment::openChecked(const std::string& directory, const OpenOptions& options) {
    struct stat st {};
    if (::stat(directory.c_str(), &st) != 0)
        openError(fmt::format("cannot open database {}: {}", directory, std::strerror(errno)), {});
    RegistryKey registryKey{::getpid(), st.st_dev, st.st_ino};

    std::lock_guard lock(registryMutex());
    if (auto it = registry().find(registryKey); it != registry().end())
        if (auto shared = it->second.lock()) {
            if (shared->readOnly() && !options.readOnly)
                openError(fmt::format("database {} is already open read-only in this process", directory),
                          "close it first, or open this handle read-only too");
            return shared;
        }

    MDB_env* env = nullptr;
    int rc = mdb_env_create(&env);
    if (rc != MDB_SUCCESS) openError(fmt::format("cannot open database {}: {}", directory, mdb_strerror(rc)), {});
    // Owned from here on, so every failure below closes the environment.
    std::shared_ptr<Environment> environment(new Environment(env, directory, options.readOnly));
    environment->check(mdb_env_set_maxdbs(env, kMaxTables), "setting the table count");
    environment->check(mdb_env_set_maxreaders(env, kMaxReaders), "setting the reader count");
    environment->check(mdb_env_set_mapsize(env, options.mapSize), "setting the map size");

    // MDB_NOTLS: a ReadTransaction may move between threads (thread pools, the C API).
    unsigned flags = MDB_NOTLS | (options.readOnly ? MDB_RDONLY : 0);
    rc = mdb_env_open(env, directory.c_str(), flags, 0644);
    if (rc == MDB_INVALID || rc == MDB_VERSION_MISMATCH)
        notSmqlDatabase(directory, fmt::format("its {} is not an LMDB file this smql can read", kDataFile));
    if (rc == EACCES || rc == EPERM || rc == EROFS)
        openError(fmt::format("cannot open database {}: {}", directory, mdb_strerror(rc)),
                  options.readOnly ? "check the permissions of the directory, data.mdb and lock.mdb"
                                   : "check the permissions, or open the database read-only");
    environment->check(rc, "opening");
    environment->checkFileSize();
    environment->findMap();
    struct stat lockFile {};
    if (::stat((fs::path(directory) / kLockFile).c_str(), &lockFile) == 0)
        environment->lockFile_ = std::pair(lockFile.st_dev, lockFile.st_ino);

    // Free the reader slots of processes that died holding a read transaction,
    // so they do not pin old pages forever. Costs one pass over the reader table.
    int deadReaders = 0;
    environment->check(mdb_reader_check(env, &deadReaders), "clearing stale readers");

    environment->openTables(options.create);
    registry()[registryKey] = environment;
    return environment;
}

Environment::Environment(MDB_env* env, std::string directory, bool readOnly)
    : env_(env), directory_(std::move(directory)), readOnly_(readOnly) {}

namespace {
// Enough for the threads that query one database at once; more are aborted when they end.
constexpr std::size_t kMaxIdleReaders = 16;

void closeReader(const Environment::Reader& reader) {
    for (MDB_cursor* cursor : reader.cursors)
        if (cursor) mdb_cursor_close(cursor);
    mdb_txn_abort(reader.txn);
}
}  // namespace

Environment::Reader Environment::beginReader() {
    Reader reader;
    {
        std::lock_guard lock(readersMutex_);
        if (!idleReaders_.empty()) {
            reader = idleReaders_.back();
            idleReaders_.pop_back();
        }
    }
    if (reader.txn) {
        if (mdb_txn_renew(reader.txn) == MDB_SUCCESS) {
            for (MDB_cursor*& cursor : reader.cursors)
                if (cursor && mdb_cursor_renew(reader.txn, cursor) != MDB_SUCCESS) {
                    mdb_cursor_close(cursor);
                    cursor = nullptr;  // opened again when a lookup needs it
                }
            return reader;
        }
        closeReader(reader);
        reader = {};
    }
    check(mdb_txn_begin(env_, nullptr, MDB_RDONLY, &reader.txn), "beginning a read transaction");
    return reader;
}

void Environment::endReader(Reader reader) {
    mdb_txn_reset(reader.txn);
    {
        std::lock_guard lock(readersMutex_);
        if (idleReaders_.size() < kMaxIdleReaders) {
            idleReaders_.push_back(reader);
            return;
        }
    }
    closeReader(reader);
}

Environment::~Environment() {
    for (const Reader& reader : idleReaders_) closeReader(reader);
    // Closing under the registry lock: a concurrent open() of the same
    // directory must not create a second environment while this one still
    // holds the directory's locks.
    std::lock_guard lock(registryMutex());
    mdb_env_close(env_);
    std::erase_if(registry(), [](const auto& entry) { return entry.second.expired(); });
}

// LMDB maps data.mdb and reads pages straight from the map: a page past the
// end of a file that was cut short (a copy interrupted, a full disk, a
// truncate) is SIGBUS on first touch, not an error. The meta pages were read
// with pread by mdb_env_open and say where the last committed page is, so the
// file must reach at least that far before any transaction looks at the map.
void Environment::checkFileSize() const {
    MDB_envinfo info{};
    MDB_stat stat{};
    check(mdb_env_info(env_, &info), "reading the environment");
    check(mdb_env_stat(env_, &stat), "reading the environment");
    int fd = -1;
    check(mdb_env_get_fd(env_, &fd), "reading the environment");
    struct stat file {};
    if (::fstat(fd, &file) != 0) fail(errno, "reading the size of data.mdb");
    const std::uint64_t needed = (std::uint64_t(info.me_last_pgno) + 1) * stat.ms_psize;
    if (std::uint64_t(file.st_size) < needed)
        damaged(directory_, fmt::format("its {} is {} bytes, but its last committed page ends at byte {} (the file "
                                        "was cut short)",
                                        kDataFile, file.st_size, needed));
}

// Reads the meta table in a read transaction first, so opening never waits for
// a writer in another process; only a brand-new database takes a write
// transaction. No step depends on the amount of data stored.
void Environment::openTables(bool create) {
    MDB_txn* txn = nullptr;
    check(mdb_txn_begin(env_, nullptr, MDB_RDONLY, &txn), "beginning a read transaction");
    MDB_dbi meta = 0;
    int rc = mdb_dbi_open(txn, kTables[0].name, kTables[0].flags, &meta);
    if (rc == MDB_NOTFOUND) {
        MDB_stat mainStat{};
        MDB_dbi main = 0;
        rc = mdb_dbi_open(txn, nullptr, 0, &main);
        if (rc == MDB_SUCCESS) rc = mdb_stat(txn, main, &mainStat);
        mdb_txn_abort(txn);
        check(rc, "reading the main table");
        if (mainStat.ms_entries != 0) notSmqlDatabase(directory_, "it is an LMDB database without smql's meta table");
        if (readOnly_ || !create)
            openError(fmt::format("database {} is empty (it was never initialised)", directory_),
                      "open it once for writing to initialise it");

        check(mdb_txn_begin(env_, nullptr, 0, &txn), "beginning a write transaction");
        for (std::size_t i = 0; i < kTableCount; ++i) {
            rc = mdb_dbi_open(txn, kTables[i].name, kTables[i].flags | MDB_CREATE, &dbis_[i]);
            if (rc != MDB_SUCCESS) {
                mdb_txn_abort(txn);
                fail(rc, fmt::format("creating table {}", kTables[i].name));
            }
        }
        // Another process may have initialised it between the two transactions.
        MDB_val key = toVal(kSchemaVersionKey), value;
        rc = mdb_get(txn, dbis_[0], &key, &value);
        if (rc == MDB_NOTFOUND) {
            std::string version = codec::encodeU64(kSchemaVersion), nextId = codec::encodeU64(1);
            MDB_val versionVal = toVal(version), nextKey = toVal(kNextIdKey), nextVal = toVal(nextId);
            rc = mdb_put(txn, dbis_[0], &key, &versionVal, 0);
            if (rc == MDB_SUCCESS) rc = mdb_put(txn, dbis_[0], &nextKey, &nextVal, 0);
        }
        if (rc != MDB_SUCCESS) {
            mdb_txn_abort(txn);
            fail(rc, "initialising the meta table");
        }
        check(mdb_txn_commit(txn), "committing the new database");
        return;
    }
    if (rc == MDB_INCOMPATIBLE) {
        mdb_txn_abort(txn);
        notSmqlDatabase(directory_, "its 'meta' entry is not an smql meta table");
    }
    if (rc != MDB_SUCCESS) {
        mdb_txn_abort(txn);
        fail(rc, "opening the meta table");
    }
    std::uint64_t version = 0;
    try {
        version = checkSchemaVersion(directory_, txn, meta, !readOnly_);
    } catch (...) {
        mdb_txn_abort(txn);
        throw;
    }
    if (version != kSchemaVersion && readOnly_) {
        hasSceneIndex_ = version >= 4;
    } else if (version != kSchemaVersion) {
        mdb_txn_abort(txn);
        upgradeSchema(version);
        check(mdb_txn_begin(env_, nullptr, MDB_RDONLY, &txn), "beginning a read transaction");
        check(mdb_dbi_open(txn, kTables[0].name, kTables[0].flags, &meta), "opening the meta table");
    }
    dbis_[0] = meta;
    for (std::size_t i = 1; i < kTableCount; ++i) {
        if (!has(static_cast<Table>(i))) continue;
        rc = mdb_dbi_open(txn, kTables[i].name, kTables[i].flags, &dbis_[i]);
        if (rc != MDB_SUCCESS) {
            mdb_txn_abort(txn);
            if (rc == MDB_NOTFOUND || rc == MDB_INCOMPATIBLE)
                openError(fmt::format("database {} is damaged: table {} is {}", directory_, kTables[i].name,
                                      rc == MDB_NOTFOUND ? "missing" : "of the wrong kind"),
                          "restore it from a backup, or import its scenes again into a new database");
            fail(rc, fmt::format("opening table {}", kTables[i].name));
        }
    }
    // Committing a read transaction is what makes its table handles usable by later transactions.
    check(mdb_txn_commit(txn), "opening the tables");
}

// An older schema -> kSchemaVersion in one write transaction: the tables it lacks, then the version.
// Another process may have upgraded it between our read and this write; then there is nothing left to do.
void Environment::upgradeSchema(std::uint64_t from) {
    const std::string operation =
        fmt::format("upgrading the database from schema version {} to {}", from, kSchemaVersion);
    MDB_txn* txn = nullptr;
    check(mdb_txn_begin(env_, nullptr, 0, &txn), "beginning a write transaction");
    MDB_dbi meta = 0, table = 0;
    int rc = mdb_dbi_open(txn, kTables[0].name, kTables[0].flags, &meta);
    for (Table added : {Table::History, Table::SceneIndex}) {
        const auto& spec = kTables[static_cast<std::size_t>(added)];
        if (rc == MDB_SUCCESS) rc = mdb_dbi_open(txn, spec.name, spec.flags | MDB_CREATE, &table);
    }
    std::string version = codec::encodeU64(kSchemaVersion);
    MDB_val key = toVal(kSchemaVersionKey), value = toVal(version);
    if (rc == MDB_SUCCESS) rc = mdb_put(txn, meta, &key, &value, 0);
    if (rc == MDB_SUCCESS) {
        try {
            rc = widenLabels(txn);
        } catch (...) {  // a damaged node record
            mdb_txn_abort(txn);
            throw;
        }
    }
    if (rc != MDB_SUCCESS) {
        mdb_txn_abort(txn);
        fail(rc, operation);
    }
    check(mdb_txn_commit(txn), operation);
}

// Schema 5: every label entry of the two ids alone becomes the covering entry made from its node's
// record (codec::labelEntry), in the upgrade's transaction. The entries of one key have one size
// (DUPFIXED), so a key's entries are replaced together; keys already widened are left as they are.
int Environment::widenLabels(MDB_txn* txn) {
    MDB_dbi labels = 0, nodes = 0;
    const auto& labelSpec = kTables[static_cast<std::size_t>(Table::Labels)];
    const auto& nodeSpec = kTables[static_cast<std::size_t>(Table::Nodes)];
    int rc = mdb_dbi_open(txn, labelSpec.name, labelSpec.flags | MDB_CREATE, &labels);
    if (rc == MDB_SUCCESS) rc = mdb_dbi_open(txn, nodeSpec.name, nodeSpec.flags | MDB_CREATE, &nodes);
    if (rc != MDB_SUCCESS) return rc;
    // The narrow entries by key, copied out of the map before any write moves the pages they lie in.
    std::vector<std::pair<std::string, std::vector<codec::LabelPrefix>>> narrow;
    MDB_cursor* cursor = nullptr;
    if ((rc = mdb_cursor_open(txn, labels, &cursor)) != MDB_SUCCESS) return rc;
    MDB_val key, value;
    for (rc = mdb_cursor_get(cursor, &key, &value, MDB_FIRST); rc == MDB_SUCCESS;
         rc = mdb_cursor_get(cursor, &key, &value, MDB_NEXT)) {
        if (value.mv_size != codec::kIdsOnlyLabelEntrySize) continue;
        if (narrow.empty() || narrow.back().first != fromVal(key)) narrow.emplace_back(std::string(fromVal(key)), 0);
        std::memcpy(narrow.back().second.emplace_back().data(), value.mv_data, codec::kIdsOnlyLabelEntrySize);
    }
    mdb_cursor_close(cursor);
    if (rc != MDB_NOTFOUND) return rc;
    model::Node node;
    for (const auto& [category, entries] : narrow) {
        MDB_val labelKey = toVal(category);
        if ((rc = mdb_del(txn, labels, &labelKey, nullptr)) != MDB_SUCCESS) return rc;
        for (const auto& ids : entries) {
            const model::NodeId sceneId = codec::readBigEndian64(ids.data());
            const model::NodeId id = codec::readBigEndian64(ids.data() + 8);
            auto idKey = codec::idKey(id);
            MDB_val k = toVal(idKey), record;
            if ((rc = mdb_get(txn, nodes, &k, &record)) != MDB_SUCCESS) return rc == MDB_NOTFOUND ? MDB_CORRUPTED : rc;
            codec::decodeNode(id, fromVal(record), node);
            auto entry = codec::labelEntry(category, sceneId, id, node);
            MDB_val wide = toVal(entry);
            if ((rc = mdb_put(txn, labels, &labelKey, &wide, MDB_APPENDDUP)) != MDB_SUCCESS) return rc;
        }
    }
    return MDB_SUCCESS;
}

void Environment::checkLockFile(std::string_view operation) const {
    if (!lockFile_) return;
    struct stat now {};
    const bool present = ::stat((fs::path(directory_) / kLockFile).c_str(), &now) == 0;
    if (present && now.st_dev == lockFile_->first && now.st_ino == lockFile_->second) return;
    throw Error(ErrorKind::Storage,
                fmt::format("{} refused on database {}: its lock file {}/{} was {} while this process had the "
                            "database open, so writers are no longer serialised and this write could undo another "
                            "process's commits",
                            operation, directory_, directory_, kLockFile, present ? "removed or replaced" : "removed"),
                std::nullopt,
                fmt::format("{} is part of the database: close every process that uses {}, then open it again "
                            "(`smql check {}` lists the processes still holding the old lock file)",
                            kLockFile, directory_, directory_));
}

// Free space below which an I/O error from a write is taken to be a full
// disk: after a short write the file system has less than the rest of it left.
constexpr std::uint64_t kFullBelow = 256 << 10;

void Environment::fail(int rc, std::string_view operation) const {
    std::string hint;
    switch (rc) {
        case MDB_MAP_FULL: {
            MDB_envinfo info{};
            mdb_env_info(env_, &info);
            hint = fmt::format("the database reached its map size ({} bytes); open it with a larger map size",
                               info.me_mapsize);
            break;
        }
        case MDB_READERS_FULL:
            hint = fmt::format("more than {} read transactions are open at once; close idle ones", kMaxReaders);
            break;
        case MDB_CORRUPTED:
        case MDB_PAGE_NOTFOUND:
            hint = "the database file is damaged; restore it from a backup";
            break;
        case EACCES:
        case EROFS:
            hint = "check the permissions of the database directory and its files";
            break;
        case ENOSPC:
        case EDQUOT:
            noSpace(directory_, operation, freeBytes(directory_));
        case EIO:
            // LMDB reports a short write as EIO; on a local file system that is
            // the disk filling up half-way through the transaction's pages.
            if (auto free = freeBytes(directory_); free && *free < kFullBelow) noSpace(directory_, operation, free);
            break;
        default:
            break;
    }
    throw Error(ErrorKind::Storage,
                fmt::format("{} failed on database {}: {}", operation, directory_, mdb_strerror(rc)), std::nullopt,
                std::move(hint));
}

Cursor::Cursor(const Environment& env, MDB_txn* txn, Table table) {
    env.check(mdb_cursor_open(txn, env.dbi(table), &cursor_), "opening a cursor");
}

void Environment::findMap() {
    struct stat data {};
    if (::stat((fs::path(directory_) / kDataFile).c_str(), &data) != 0) return;
    std::ifstream maps("/proc/self/maps");
    for (std::string line; std::getline(maps, line);) {
        std::istringstream fields(line);
        std::string range, perms, offset, device;
        unsigned long inode = 0;
        if (!(fields >> range >> perms >> offset >> device >> inode) || inode != data.st_ino) continue;
        unsigned major = 0, minor = 0;
        unsigned long long begin = 0, end = 0;
        if (std::sscanf(device.c_str(), "%x:%x", &major, &minor) != 2 || makedev(major, minor) != data.st_dev ||
            std::sscanf(range.c_str(), "%llx-%llx", &begin, &end) != 2 ||
            offset.find_first_not_of('0') != std::string::npos)
            continue;
        map_ = reinterpret_cast<const char*>(begin);
        mapSize_ = static_cast<std::size_t>(end - begin);
        return;
    }
}

std::string_view Environment::bytes(const MDB_val& v) const {
    const char* at = static_cast<const char*>(v.mv_data);
    // Pages a write transaction has changed are in memory of its own, outside the map: only what
    // lies in the map is read from the file, which ends after its last committed page.
    if (map_ && at >= map_ && at < map_ + mapSize_) {
        MDB_envinfo info{};
        MDB_stat stat{};
        mdb_env_info(env_, &info);
        mdb_env_stat(env_, &stat);
        const char* end = map_ + (info.me_last_pgno + 1) * static_cast<std::size_t>(stat.ms_psize);
        if (at > end || v.mv_size > static_cast<std::size_t>(end - at))
            throw Error(ErrorKind::Storage,
                        fmt::format("database {} is damaged: a record of {} bytes reaches past the end of {}",
                                    directory_, v.mv_size, kDataFile),
                        std::nullopt,
                        "smql check names what is damaged; smql check --salvage OUT keeps the sound scenes");
    }
    return {at, v.mv_size};
}

void Environment::copyOut(void* into, std::string_view from) const {
    const char* at = from.data();
    mdb_filehandle_t fd = -1;
    if (map_ && at >= map_ && at < map_ + mapSize_ && mdb_env_get_fd(env_, &fd) == MDB_SUCCESS) {
        // data.mdb is mapped from its first byte, and a committed page in the map is that page of
        // the file: both are the page cache's.
        auto* out = static_cast<char*>(into);
        auto offset = static_cast<off_t>(at - map_);
        std::size_t left = from.size();
        while (left > 0) {
            const ssize_t n = ::pread(fd, out, left, offset);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) break;  // the map, below, reads what the file would not
            out += n;
            offset += n;
            left -= static_cast<std::size_t>(n);
        }
        std::memcpy(out, from.data() + (from.size() - left), left);
        return;
    }
    std::memcpy(into, at, from.size());
}

std::vector<std::pair<std::string, std::string>> Environment::legacyLabels(MDB_txn* txn) const {
    std::lock_guard lock(legacyMutex_);
    if (!legacyLabels_) {
        std::vector<std::pair<std::string, std::string>> found;
        Cursor cursor(*this, txn, Table::Labels);
        MDB_val key, value;
        int rc = mdb_cursor_get(cursor.get(), &key, &value, MDB_FIRST);
        for (; rc == MDB_SUCCESS; rc = mdb_cursor_get(cursor.get(), &key, &value, MDB_NEXT_NODUP)) {
            std::string_view name = bytes(key);
            if (!model::isCategoryName(name)) found.emplace_back(std::string(name), model::categoryName(name));
        }
        if (rc != MDB_NOTFOUND) check(rc, "listing categories");
        legacyLabels_ = std::move(found);
    }
    return *legacyLabels_;
}

void Environment::forgetLegacyLabels() const {
    std::lock_guard lock(legacyMutex_);
    legacyLabels_.reset();
}

}  // namespace smql::storage
