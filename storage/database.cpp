// Database and the transactions: opening, beginning and committing, every read (either kind of
// transaction offers them), settings. The other jobs behind database.hpp have their own files:
// scene_validation.cpp checks an incoming scene, scene_writer.cpp writes a scene and its indexes,
// versioning.cpp replaces, drops and renames scenes and reads their history.
#include "storage/database.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <filesystem>
#include <utility>

#include <fmt/format.h>

#include "model/category.hpp"
#include "model/error.hpp"
#include "storage/codec.hpp"
#include "storage/crc32c.hpp"
#include "storage/database_internal.hpp"
#include "storage/lmdb_env.hpp"

namespace smql::storage {

using model::Node;
using model::NodeId;
using model::SceneInfo;

// ---------------------------------------- shared with the other files of storage/ (database_internal.hpp)

[[noreturn]] void importError(std::string message) {
    throw Error(ErrorKind::Input, std::move(message), std::nullopt, std::string(kImportHint));
}

std::optional<std::string_view> lookup(const Environment& env, MDB_txn* txn, Table table, MDB_val key,
                                       std::string_view operation) {
    MDB_val value;
    int rc = mdb_get(txn, env.dbi(table), &key, &value);
    if (rc == MDB_NOTFOUND) return std::nullopt;
    env.check(rc, operation);
    return env.bytes(value);
}

// The scene whose id block holds `id`, named for an error message: the scene
// with the greatest id not above it. Read defensively, since the damaged
// record may be the one that names it: the scene record, else the scene
// node, else the name index, else the id.
std::string sceneNameFor(const Environment& env, MDB_txn* txn, NodeId id) {
    try {
        Cursor cursor(env, txn, Table::Scenes);
        auto from = codec::idKey(id);
        MDB_val key = toVal(from), value;
        int rc = mdb_cursor_get(cursor.get(), &key, &value, MDB_SET_RANGE);
        if (rc == MDB_SUCCESS && codec::idFromKey(env.bytes(key), "scene") != id)
            rc = mdb_cursor_get(cursor.get(), &key, &value, MDB_PREV);
        else if (rc == MDB_NOTFOUND)
            rc = mdb_cursor_get(cursor.get(), &key, &value, MDB_LAST);
        if (rc != MDB_SUCCESS) return fmt::format("unknown (no scene holds id {})", id);
        const NodeId sceneId = codec::idFromKey(env.bytes(key), "scene");
        try {
            return fmt::format("'{}'", codec::decodeScene(sceneId, env.bytes(value)).name);
        } catch (const codec::CorruptRecord&) {
        }
        try {
            auto nodeKey = codec::idKey(sceneId);
            if (auto bytes = lookup(env, txn, Table::Nodes, toVal(nodeKey), "reading a node"))
                return fmt::format("'{}'", codec::decodeNode(sceneId, *bytes).category);
        } catch (const codec::CorruptRecord&) {
        }
        Cursor names(env, txn, Table::SceneNames);
        for (rc = mdb_cursor_get(names.get(), &key, &value, MDB_FIRST); rc == MDB_SUCCESS;
             rc = mdb_cursor_get(names.get(), &key, &value, MDB_NEXT))
            if (value.mv_size == 8 && codec::idFromKey(env.bytes(value), "scene name index") == sceneId)
                return fmt::format("'{}'", env.bytes(key));
        return fmt::format("#{}", sceneId);
    } catch (const Error&) {
        return fmt::format("unknown (the scene holding id {} cannot be read)", id);
    }
}

std::optional<SceneInfo> readScene(const Environment& env, MDB_txn* txn, NodeId sceneId) {
    auto key = codec::idKey(sceneId);
    auto bytes = lookup(env, txn, Table::Scenes, toVal(key), "reading a scene");
    if (!bytes) return std::nullopt;
    return decodeInScene(env, txn, sceneId, [&] { return codec::decodeScene(sceneId, *bytes); });
}

std::optional<NodeId> readSceneId(const Environment& env, MDB_txn* txn, std::string_view name) {
    if (name.empty() || name.size() > env.maxKeySize()) return std::nullopt;
    auto bytes = lookup(env, txn, Table::SceneNames, toVal(name), "looking up a scene name");
    if (!bytes) return std::nullopt;
    return codec::idFromKey(*bytes, "scene name index");
}

namespace {

std::string settingKey(std::string_view key) {
    std::string full;
    full.reserve(kSettingPrefix.size() + key.size());
    full.append(kSettingPrefix).append(key);
    return full;
}

bool validSettingKey(const Environment& env, std::string_view key) {
    return !key.empty() && kSettingPrefix.size() + key.size() <= env.maxKeySize();
}

// The size of a label entry: the ids alone (schema version 4) or the covering entry (5); any other is damage.
std::size_t labelEntrySize(std::string_view category, const MDB_val& value) {
    if (value.mv_size == codec::kLabelEntrySize || value.mv_size == codec::kIdsOnlyLabelEntrySize) return value.mv_size;
    throw Error(ErrorKind::Storage,
                fmt::format("corrupt label index entry for '{}': {} bytes instead of {}", category, value.mv_size,
                            codec::kLabelEntrySize),
                std::nullopt, "the database file is damaged; restore it from a backup");
}

std::size_t duplicateCount(const Environment& env, MDB_cursor* cursor) {
    std::size_t count = 0;
    env.check(mdb_cursor_count(cursor, &count), "counting index entries");
    return count;
}

// Calls visit(entries, n) for the duplicates of the key `cursor` was just positioned on, a page's
// block at a time straight from the map: n fixed-size entries one after another; visit returns
// false to stop. `first` is the value the positioning call returned and `count` the key's
// duplicate count.
template <class Visit>
void forEachDuplicateBlock(const Environment& env, MDB_cursor* cursor, const MDB_val& first, std::size_t count,
                           std::size_t entrySize, Visit&& visit) {
    if (first.mv_size != entrySize)
        throw Error(ErrorKind::Storage,
                    fmt::format("corrupt index entry: {} bytes instead of {}", first.mv_size, entrySize), std::nullopt,
                    "the database file is damaged; restore it from a backup");
    // A key with a single value has no duplicate page for MDB_GET_MULTIPLE to return.
    if (count == 1) {
        visit(static_cast<const char*>(first.mv_data), std::size_t{1});
        return;
    }
    MDB_val key, block;
    int rc = mdb_cursor_get(cursor, &key, &block, MDB_GET_MULTIPLE);
    while (rc == MDB_SUCCESS) {
        if (!visit(static_cast<const char*>(block.mv_data), block.mv_size / entrySize)) return;
        rc = mdb_cursor_get(cursor, &key, &block, MDB_NEXT_MULTIPLE);
    }
    if (rc != MDB_NOTFOUND) env.fail(rc, "reading index entries");
}

// forEachDuplicateBlock one entry at a time: visit(entry) returns false to stop.
template <class Visit>
void forEachDuplicate(const Environment& env, MDB_cursor* cursor, const MDB_val& first, std::size_t count,
                      std::size_t entrySize, Visit&& visit) {
    forEachDuplicateBlock(env, cursor, first, count, entrySize, [&](const char* entries, std::size_t n) {
        for (std::size_t i = 0; i < n; ++i)
            if (!visit(std::string_view(entries + i * entrySize, entrySize))) return false;
        return true;
    });
}

// Borrows a read transaction's cached cursor for a table, or opens a private one
// when the cached one is in use further up the stack (a visitor calling back
// into the same transaction) or the transaction writes: LMDB frees a write
// transaction's cursors when it commits, and adjusts each open one on every write.
class TableCursor {
public:
    TableCursor(const ReadTransaction::Impl& txn, Table table) : txn_(txn), slot_(static_cast<std::size_t>(table)) {
        if (!txn.readOnly || (txn.cursors[slot_] && txn.cursorBusy[slot_])) {
            txn.env->check(mdb_cursor_open(txn.txn, txn.env->dbi(table), &cursor_), "opening a cursor");
            owned_ = true;
            return;
        }
        if (!txn.cursors[slot_])
            txn.env->check(mdb_cursor_open(txn.txn, txn.env->dbi(table), &txn.cursors[slot_]), "opening a cursor");
        cursor_ = txn.cursors[slot_];
        txn.cursorBusy[slot_] = true;
    }
    ~TableCursor() {
        if (owned_)
            mdb_cursor_close(cursor_);
        else
            txn_.cursorBusy[slot_] = false;
    }
    TableCursor(const TableCursor&) = delete;
    TableCursor& operator=(const TableCursor&) = delete;

    int get(MDB_val& key, MDB_val& value, MDB_cursor_op op) const { return mdb_cursor_get(cursor_, &key, &value, op); }
    MDB_cursor* cursor() const { return cursor_; }

private:
    const ReadTransaction::Impl& txn_;
    std::size_t slot_;
    MDB_cursor* cursor_ = nullptr;
    bool owned_ = false;
};

// One range scan over the relation index keys of the scene's id block; each
// relation is reported once, from its subject's entries (which sort first).
void scanSceneRelations(const Environment& env, MDB_txn* txn, MDB_cursor* cursor, NodeId sceneId,
                        const std::function<void(const model::Relation&)>& visit) {
    auto info = readScene(env, txn, sceneId);
    if (!info) return;
    const NodeId last = sceneId + info->nodeCount;
    auto from = codec::idKey(sceneId);
    MDB_val key = toVal(from), value;
    // Every relation is stored under both of its ends, both in the scene: as many entries under
    // subjects as under objects, or an entry was lost or moved, and the scene's relations are not
    // all here. Such a read fails rather than answer with some of them.
    std::size_t subjects = 0, objects = 0;
    int rc = mdb_cursor_get(cursor, &key, &value, MDB_SET_RANGE);
    for (; rc == MDB_SUCCESS; rc = mdb_cursor_get(cursor, &key, &value, MDB_NEXT_NODUP)) {
        NodeId id = codec::idFromKey(env.bytes(key), "relation index");
        if (id > last) break;
        std::size_t count = duplicateCount(env, cursor);
        forEachDuplicate(env, cursor, value, count, codec::kRelationEntrySize, [&](std::string_view entry) {
            if (codec::relationEntrySide(entry) != codec::RelationSide::Subject) {
                ++objects;
                return true;
            }
            ++subjects;
            visit(decodeInScene(env, txn, id, [&] { return codec::decodeRelationEntry(id, entry); }));
            return true;
        });
    }
    if (rc != MDB_SUCCESS) endOfScan(env, rc, "reading the relations of a scene");
    if (subjects != objects)
        throw Error(
            ErrorKind::Storage,
            fmt::format("the relations of scene '{}' in database {} are damaged: {} stored under their subject, "
                        "{} under their object",
                        info->name, env.directory(), subjects, objects),
            std::nullopt, "smql check names what is damaged; smql check --salvage OUT keeps the sound scenes");
}

// Every duplicate under `id`'s key in a DUPFIXED table, decoded entry by entry.
template <class T, class Decode>
std::vector<T> readDuplicates(const ReadTransaction::Impl& impl, Table table, NodeId id, std::size_t entrySize,
                              std::string_view operation, Decode decode) {
    const Environment& env = *impl.env;
    TableCursor cursor(impl, table);
    std::vector<T> out;
    auto key = codec::idKey(id);
    MDB_val k = toVal(key), value;
    int rc = cursor.get(k, value, MDB_SET_KEY);
    if (rc == MDB_NOTFOUND) return out;
    env.check(rc, operation);
    std::size_t count = duplicateCount(env, cursor.cursor());
    out.reserve(count);
    forEachDuplicate(env, cursor.cursor(), value, count, entrySize, [&](std::string_view entry) {
        out.push_back(decode(entry));
        return true;
    });
    return out;
}

}  // namespace

// ---------------------------------------------------------------- Database

Database::Database(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Database::~Database() = default;

std::unique_ptr<Database> Database::open(const std::string& directory, const OpenOptions& options) {
    auto env = Environment::open(directory, options);
    return std::unique_ptr<Database>(new Database(std::make_unique<Impl>(Impl{env, directory, options.readOnly})));
}

ReadTransaction Database::beginRead() const {
    return ReadTransaction(std::make_unique<ReadTransaction::Impl>(impl_->env, impl_->env->beginReader()));
}

WriteTransaction Database::beginWrite() {
    if (impl_->readOnly)
        throw Error(ErrorKind::Storage, fmt::format("database {} is open read-only", impl_->directory), std::nullopt,
                    "open it without read-only to change it");
    MDB_txn* txn = nullptr;
    impl_->env->check(mdb_txn_begin(impl_->env->env(), nullptr, 0, &txn), "beginning a write transaction");
    // Owned from here on, so a refusal below aborts the transaction.
    WriteTransaction write(std::make_unique<ReadTransaction::Impl>(impl_->env, txn));
    // Checked once the writer lock is held: the lock file may have gone while this waited for it.
    impl_->env->checkLockFile("beginning a write transaction");
    return write;
}

const std::string& Database::directory() const { return impl_->directory; }
bool Database::readOnly() const { return impl_->readOnly; }

std::uint64_t Database::fileSizeBytes() const {
    std::error_code ec;
    auto size = std::filesystem::file_size(std::filesystem::path(impl_->directory) / kDataFile, ec);
    if (ec)
        throw Error(ErrorKind::Storage,
                    fmt::format("cannot read the size of {}/{}: {}", impl_->directory, kDataFile, ec.message()));
    return size;
}

std::uint64_t Database::lastCommittedTransaction() const {
    MDB_envinfo info{};
    impl_->env->check(mdb_env_info(impl_->env->env(), &info), "reading the last committed transaction");
    return info.me_last_txnid;
}

// --------------------------------------------------------- ReadTransaction

ReadTransaction::ReadTransaction(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
ReadTransaction::ReadTransaction(ReadTransaction&&) noexcept = default;
ReadTransaction& ReadTransaction::operator=(ReadTransaction&&) noexcept = default;
ReadTransaction::~ReadTransaction() = default;

ReadTransaction::Impl& ReadTransaction::live() const {
    assert(impl_->txn && "transaction used after commit()");
    return *impl_;
}

std::uint64_t ReadTransaction::transactionId() const { return mdb_txn_id(live().txn); }

std::vector<SceneInfo> ReadTransaction::scenes() const {
    const Impl& state = live();
    const Environment& env = *state.env;
    TableCursor cursor(state, Table::Scenes);
    std::vector<SceneInfo> out;
    MDB_val key, value;
    int rc = cursor.get(key, value, MDB_FIRST);
    for (; rc == MDB_SUCCESS; rc = cursor.get(key, value, MDB_NEXT)) {
        NodeId id = codec::idFromKey(env.bytes(key), "scene");
        out.push_back(decodeInScene(env, state.txn, id, [&] { return codec::decodeScene(id, env.bytes(value)); }));
    }
    endOfScan(env, rc, "listing scenes");
    return out;
}

std::optional<SceneInfo> ReadTransaction::scene(NodeId sceneId) const {
    const Impl& state = live();
    return readScene(*state.env, state.txn, sceneId);
}

std::optional<SceneInfo> ReadTransaction::sceneByName(std::string_view name) const {
    const Impl& state = live();
    auto id = readSceneId(*state.env, state.txn, name);
    if (!id) return std::nullopt;
    return readScene(*state.env, state.txn, *id);
}

bool ReadTransaction::readNode(NodeId id, Node& into) const {
    const Impl& state = live();
    auto key = codec::idKey(id);
    auto bytes = lookup(*state.env, state.txn, Table::Nodes, toVal(key), "reading a node");
    if (!bytes) return false;
    decodeInScene(*state.env, state.txn, id, [&] { codec::decodeNode(id, *bytes, into); });
    return true;
}

std::optional<Node> ReadTransaction::node(NodeId id) const {
    const Impl& state = live();
    std::optional<Node> out;
    auto key = codec::idKey(id);
    auto bytes = lookup(*state.env, state.txn, Table::Nodes, toVal(key), "reading a node");
    if (bytes) decodeInScene(*state.env, state.txn, id, [&] { codec::decodeNode(id, *bytes, out.emplace()); });
    return out;
}

std::uint64_t ReadTransaction::nodeCount() const {
    const Impl& state = live();
    MDB_stat stat{};
    state.env->check(mdb_stat(state.txn, state.env->dbi(Table::Nodes), &stat), "counting nodes");
    return stat.ms_entries;
}

std::vector<NodeId> ReadTransaction::children(NodeId parent) const {
    const Impl& state = live();
    return readDuplicates<NodeId>(
        state, Table::Children, parent, sizeof(NodeId), "reading children", [](std::string_view entry) {
            return codec::readBigEndian64(reinterpret_cast<const std::uint8_t*>(entry.data()));
        });
}

void forEachStoredNode(const Environment& env, MDB_txn* txn, MDB_cursor* cursor, NodeId sceneId,
                       const std::function<void(const Node&)>& visit) {
    auto from = codec::idKey(sceneId);
    MDB_val key = toVal(from), value;
    Node node;
    int rc = mdb_cursor_get(cursor, &key, &value, MDB_SET_RANGE);
    for (; rc == MDB_SUCCESS; rc = mdb_cursor_get(cursor, &key, &value, MDB_NEXT)) {
        NodeId id = codec::idFromKey(env.bytes(key), "node");
        decodeInScene(env, txn, id, [&] { codec::decodeNode(id, env.bytes(value), node); });
        if (node.scene != sceneId) return;
        visit(node);
    }
    endOfScan(env, rc, "reading the nodes of a scene");
}

void ReadTransaction::forEachNodeInScene(NodeId sceneId, const std::function<void(const Node&)>& visit) const {
    const Impl& state = live();
    TableCursor cursor(state, Table::Nodes);
    forEachStoredNode(*state.env, state.txn, cursor.cursor(), sceneId, visit);
}

std::optional<SceneIndex> ReadTransaction::sceneIndex(const SceneInfo& scene) const {
    const Impl& state = live();
    if (!state.env->has(Table::SceneIndex)) return std::nullopt;
    auto key = codec::idKey(scene.id);
    auto bytes = lookup(*state.env, state.txn, Table::SceneIndex, toVal(key), "reading a scene index");
    if (!bytes) return std::nullopt;
    const Environment& env = *state.env;
    SceneIndex index = decodeInScene(env, state.txn, scene.id, [&] {
        return codec::decodeSceneIndex(scene.id, *bytes,
                                       [&](void* into, std::string_view from) { env.copyOut(into, from); });
    });
    if (index.version != scene.version || index.entries.size() != scene.nodeCount + 1) return std::nullopt;
    return index;
}

std::vector<model::Relation> ReadTransaction::relationsOf(NodeId id) const {
    const Impl& state = live();
    return readDuplicates<model::Relation>(
        state, Table::Relations, id, codec::kRelationEntrySize, "reading relations", [&](std::string_view entry) {
            return decodeInScene(*state.env, state.txn, id, [&] { return codec::decodeRelationEntry(id, entry); });
        });
}

void ReadTransaction::forEachRelationInScene(NodeId sceneId,
                                             const std::function<void(const model::Relation&)>& visit) const {
    const Impl& state = live();
    TableCursor cursor(state, Table::Relations);
    scanSceneRelations(*state.env, state.txn, cursor.cursor(), sceneId, visit);
}

std::vector<model::Relation> ReadTransaction::relationsInScene(NodeId sceneId) const {
    std::vector<model::Relation> out;
    forEachRelationInScene(sceneId, [&](const model::Relation& r) { out.push_back(r); });
    return out;
}

std::vector<NodeId> ReadTransaction::nodesWithCategory(std::string_view category, NodeId sceneId,
                                                       std::size_t limit) const {
    const Impl& state = live();
    const Environment& env = *state.env;
    std::vector<NodeId> out;
    if (category.empty() || category.size() > env.maxKeySize()) return out;
    TableCursor cursor(state, Table::Labels);
    MDB_val key = toVal(category), value;
    auto idAt = [](const char* p) { return codec::readBigEndian64(reinterpret_cast<const std::uint8_t*>(p)); };

    if (sceneId == model::kNoNode) {
        int rc = cursor.get(key, value, MDB_SET_KEY);
        if (rc == MDB_NOTFOUND) return out;
        env.check(rc, "reading the label index");
        std::size_t count = duplicateCount(env, cursor.cursor());
        out.reserve(std::min(count, limit));
        // Entries sort by (scene, node); scenes are contiguous id blocks, so that is id order.
        forEachDuplicate(env, cursor.cursor(), value, count, labelEntrySize(category, value),
                         [&](std::string_view entry) {
                             if (out.size() == limit) return false;
                             out.push_back(idAt(entry.data() + 8));
                             return out.size() < limit;
                         });
        return out;
    }

    auto from = codec::labelPrefix(sceneId, 0);
    value = toVal(from);
    int rc = cursor.get(key, value, MDB_GET_BOTH_RANGE);
    for (; rc == MDB_SUCCESS; rc = cursor.get(key, value, MDB_NEXT_DUP)) {
        labelEntrySize(category, value);
        const char* entry = static_cast<const char*>(value.mv_data);
        if (idAt(entry) != sceneId || out.size() == limit) return out;
        out.push_back(idAt(entry + 8));
    }
    endOfScan(env, rc, "reading the label index");
    return out;
}

namespace {

std::vector<CategoryRow> categoryRowsOf(const ReadTransaction& read, const ReadTransaction::Impl& state,
                                        const std::vector<std::string>& keys, std::size_t limit);

}  // namespace

std::vector<CategoryRow> ReadTransaction::categoryRows(std::string_view category, std::size_t limit) const {
    return categoryRowsOf(*this, live(), labelKeys(category), limit);
}

void ReadTransaction::forEachCategoryRow(const std::vector<std::string>& keys, std::size_t limit,
                                         const std::function<void(const CategoryRow&)>& visit) const {
    const Impl& state = live();
    const Environment& env = *state.env;
    if (limit == 0) return;
    if (keys.size() == 1 && !keys.front().empty() && keys.front().size() <= env.maxKeySize()) {
        // One key (no name stored before names were canonical): its entries in order, as read.
        const std::string& name = keys.front();
        TableCursor cursor(state, Table::Labels);
        MDB_val key = toVal(name), value;
        int rc = cursor.get(key, value, MDB_SET_KEY);
        if (rc == MDB_NOTFOUND) return;
        env.check(rc, "reading the label index");
        const std::size_t size = labelEntrySize(name, value);
        if (size == codec::kLabelEntrySize) {
            const std::size_t count = duplicateCount(env, cursor.cursor());
            const std::uint32_t keyCrc = crc32c(name);
            std::size_t seen = 0;
            // The entries' checksums a chunk at a time, side by side, then each entry decoded.
            std::array<std::uint32_t, 16> checksums;
            forEachDuplicateBlock(env, cursor.cursor(), value, count, size, [&](const char* entries, std::size_t n) {
                for (std::size_t start = 0; start < n && seen < limit; start += checksums.size()) {
                    const std::size_t chunk = std::min({n - start, checksums.size(), limit - seen});
                    const char* first = entries + start * size;
                    codec::labelEntryChecksums(keyCrc, first, chunk, checksums.data());
                    for (std::size_t i = 0; i < chunk; ++i) {
                        const std::string_view entry(first + i * size, size);
                        visit(decodeInScene(env, state.txn, codec::labelEntryScene(entry), [&] {
                            return codec::decodeLabelEntryWithChecksum(name, entry, checksums[i]);
                        }));
                    }
                    seen += chunk;
                }
                return seen < limit;
            });
            return;
        }
    }
    for (const CategoryRow& row : categoryRowsOf(*this, state, keys, limit)) visit(row);
}

namespace {

std::vector<CategoryRow> categoryRowsOf(const ReadTransaction& read, const ReadTransaction::Impl& state,
                                        const std::vector<std::string>& keys, std::size_t limit) {
    const Environment& env = *state.env;
    std::vector<CategoryRow> out;
    for (const auto& name : keys) {
        if (name.empty() || name.size() > env.maxKeySize() || limit == 0) continue;
        TableCursor cursor(state, Table::Labels);
        MDB_val key = toVal(name), value;
        int rc = cursor.get(key, value, MDB_SET_KEY);
        if (rc == MDB_NOTFOUND) continue;
        env.check(rc, "reading the label index");
        const std::size_t count = duplicateCount(env, cursor.cursor()), size = labelEntrySize(name, value);
        const std::size_t before = out.size(), wanted = std::min(count, limit);
        const std::uint32_t keyCrc = crc32c(name);
        out.reserve(before + wanted);
        // Entries sort by (scene, node); scenes are contiguous id blocks, so that is id order.
        forEachDuplicate(env, cursor.cursor(), value, count, size, [&](std::string_view entry) {
            if (size == codec::kLabelEntrySize) {
                out.push_back(decodeInScene(env, state.txn, codec::labelEntryScene(entry),
                                            [&] { return codec::decodeLabelEntry(name, keyCrc, entry); }));
            } else {
                out.emplace_back().id = codec::labelEntryNode(entry);
            }
            return out.size() - before < wanted;
        });
    }
    if (keys.size() > 1) {
        std::sort(out.begin(), out.end(), [](const CategoryRow& a, const CategoryRow& b) { return a.id < b.id; });
        if (out.size() > limit) out.resize(limit);
    }
    // Entries of schema version 4 hold the ids alone: the rest comes from the records.
    Node node;
    for (CategoryRow& row : out) {
        if (row.scene != model::kNoNode) continue;
        if (!read.readNode(row.id, node))
            throw Error(ErrorKind::Storage, fmt::format("the label index names node #{}, which is not stored", row.id),
                        std::nullopt, "the database file is damaged; smql check names what is damaged");
        row = {node.id, node.scene, node.sourceId, node.geometry, node.box};
    }
    return out;
}

}  // namespace

std::vector<CategoryRow> ReadTransaction::categoryRowsInScene(std::string_view categoryKey, NodeId sceneId) const {
    std::vector<CategoryRow> out;
    const Impl& state = live();
    const Environment& env = *state.env;
    if (categoryKey.empty() || categoryKey.size() > env.maxKeySize()) return out;
    TableCursor cursor(state, Table::Labels);
    MDB_val key = toVal(categoryKey), value;
    auto from = codec::labelPrefix(sceneId, 0);
    value = toVal(from);
    int rc = cursor.get(key, value, MDB_GET_BOTH_RANGE);
    for (; rc == MDB_SUCCESS; rc = cursor.get(key, value, MDB_NEXT_DUP)) {
        const std::string_view entry = env.bytes(value);
        if (labelEntrySize(categoryKey, value) != codec::kLabelEntrySize || codec::labelEntryScene(entry) != sceneId)
            return out;
        out.push_back(
            decodeInScene(env, state.txn, sceneId, [&] { return codec::decodeLabelEntry(categoryKey, entry); }));
    }
    endOfScan(env, rc, "reading the label index");
    return out;
}

std::vector<std::string> ReadTransaction::labelKeys(std::string_view category) const {
    const Impl& state = live();
    std::vector<std::string> keys{model::categoryName(category)};
    for (const auto& [stored, canonical] : state.env->legacyLabels(state.txn))
        if (canonical == keys.front()) keys.push_back(stored);
    return keys;
}

std::vector<NodeId> ReadTransaction::nodesNamed(std::string_view category, std::size_t limit) const {
    auto keys = labelKeys(category);
    if (keys.size() == 1) return nodesWithCategory(keys.front(), model::kNoNode, limit);
    std::vector<NodeId> out;
    for (const auto& key : keys) {
        auto ids = nodesWithCategory(key, model::kNoNode, limit);
        out.insert(out.end(), ids.begin(), ids.end());
    }
    std::sort(out.begin(), out.end());
    if (out.size() > limit) out.resize(limit);
    return out;
}

std::uint64_t ReadTransaction::countWithCategory(std::string_view category) const {
    return countWithKeys(labelKeys(category));
}

std::uint64_t ReadTransaction::countWithKeys(const std::vector<std::string>& keys) const {
    const Impl& state = live();
    const Environment& env = *state.env;
    std::uint64_t count = 0;
    for (const auto& name : keys) {
        if (name.empty() || name.size() > env.maxKeySize()) continue;
        TableCursor cursor(state, Table::Labels);
        MDB_val key = toVal(name), value;
        int rc = cursor.get(key, value, MDB_SET_KEY);
        if (rc == MDB_NOTFOUND) continue;
        env.check(rc, "reading the label index");
        count += duplicateCount(env, cursor.cursor());
    }
    return count;
}

std::vector<std::pair<std::string, std::uint64_t>> ReadTransaction::categories() const {
    const Impl& state = live();
    const Environment& env = *state.env;
    TableCursor cursor(state, Table::Labels);
    std::vector<std::pair<std::string, std::uint64_t>> out;
    MDB_val key, value;
    int rc = cursor.get(key, value, MDB_FIRST);
    for (; rc == MDB_SUCCESS; rc = cursor.get(key, value, MDB_NEXT_NODUP))
        out.emplace_back(std::string(env.bytes(key)), duplicateCount(env, cursor.cursor()));
    endOfScan(env, rc, "listing categories");
    return out;
}

std::optional<NodeId> ReadTransaction::nodeBySourceId(NodeId sceneId, std::int64_t sourceId) const {
    const Impl& state = live();
    auto key = codec::sourceKey(sceneId, sourceId);
    auto bytes = lookup(*state.env, state.txn, Table::SourceIds, toVal(key), "looking up a source id");
    if (!bytes) return std::nullopt;
    return codec::idFromKey(*bytes, "source id index");
}

std::vector<ReadTransaction::BlobInfo> ReadTransaction::blobsOf(NodeId id) const {
    const Impl& state = live();
    const Environment& env = *state.env;
    TableCursor cursor(state, Table::Blobs);
    auto prefix = codec::idKey(id);
    std::string_view want(reinterpret_cast<const char*>(prefix.data()), prefix.size());
    std::vector<BlobInfo> out;
    MDB_val key = toVal(prefix), value;
    int rc = cursor.get(key, value, MDB_SET_RANGE);
    for (; rc == MDB_SUCCESS && env.bytes(key).substr(0, prefix.size()) == want;
         rc = cursor.get(key, value, MDB_NEXT)) {
        BlobInfo info;
        auto [name, mediaType] = decodeInScene(
            env, state.txn, id, [&] { return codec::peekBlob(env.bytes(key), env.bytes(value), info.size); });
        info.name = std::string(name);
        info.mediaType = std::string(mediaType);
        out.push_back(std::move(info));
    }
    endOfScan(env, rc, "listing blobs");
    return out;
}

std::optional<model::Blob> ReadTransaction::blob(NodeId id, std::string_view name) const {
    const Impl& state = live();
    std::string key = codec::blobKey(id, name);
    if (key.size() > state.env->maxKeySize()) return std::nullopt;
    auto bytes = lookup(*state.env, state.txn, Table::Blobs, toVal(key), "reading a blob");
    if (!bytes) return std::nullopt;
    return decodeInScene(*state.env, state.txn, id, [&] { return codec::decodeBlob(key, *bytes); });
}

std::optional<std::string> ReadTransaction::setting(std::string_view key) const {
    const Impl& state = live();
    if (!validSettingKey(*state.env, key)) return std::nullopt;
    auto bytes = lookup(*state.env, state.txn, Table::Meta, toVal(settingKey(key)), "reading a setting");
    if (!bytes) return std::nullopt;
    return std::string(*bytes);
}

std::vector<std::pair<std::string, std::string>> ReadTransaction::settings() const {
    const Impl& state = live();
    const Environment& env = *state.env;
    TableCursor cursor(state, Table::Meta);
    std::vector<std::pair<std::string, std::string>> out;
    MDB_val key = toVal(kSettingPrefix), value;
    int rc = cursor.get(key, value, MDB_SET_RANGE);
    for (; rc == MDB_SUCCESS; rc = cursor.get(key, value, MDB_NEXT)) {
        std::string_view name = env.bytes(key);
        if (!name.starts_with(kSettingPrefix)) return out;
        name.remove_prefix(kSettingPrefix.size());
        out.emplace_back(std::string(name), std::string(env.bytes(value)));
    }
    endOfScan(env, rc, "listing settings");
    return out;
}

std::vector<TableStats> ReadTransaction::tableStats() const {
    const Impl& state = live();
    std::vector<TableStats> out;
    for (std::size_t i = 0; i < kTableCount; ++i) {
        if (!state.env->has(static_cast<Table>(i))) continue;
        MDB_stat stat{};
        state.env->check(mdb_stat(state.txn, state.env->dbi(static_cast<Table>(i)), &stat), "reading table stats");
        out.push_back(
            {kTables[i].name, stat.ms_entries,
             std::uint64_t(stat.ms_branch_pages + stat.ms_leaf_pages + stat.ms_overflow_pages) * stat.ms_psize});
    }
    return out;
}

// -------------------------------------------------------- WriteTransaction

WriteTransaction::WriteTransaction(std::unique_ptr<Impl> impl) : ReadTransaction(std::move(impl)) {}
WriteTransaction::WriteTransaction(WriteTransaction&&) noexcept = default;
WriteTransaction& WriteTransaction::operator=(WriteTransaction&&) noexcept = default;
WriteTransaction::~WriteTransaction() = default;

void WriteTransaction::putSetting(std::string_view key, std::string_view value) {
    const Impl& state = live();
    const Environment& env = *state.env;
    if (!validSettingKey(env, key))
        throw Error(ErrorKind::Usage,
                    key.empty() ? std::string("a setting needs a name")
                                : fmt::format("setting name '{}...' is too long ({} bytes; at most {})",
                                              key.substr(0, 40), key.size(), env.maxKeySize() - kSettingPrefix.size()),
                    std::nullopt, "SHOW SETTINGS lists the settings in use");
    std::string fullKey = settingKey(key);
    MDB_val k = toVal(fullKey), v = toVal(value);
    env.check(mdb_put(state.txn, env.dbi(Table::Meta), &k, &v, 0), "storing a setting");
}

void WriteTransaction::eraseSetting(std::string_view key) {
    const Impl& state = live();
    const Environment& env = *state.env;
    if (!validSettingKey(env, key)) return;
    std::string fullKey = settingKey(key);
    MDB_val k = toVal(fullKey);
    int rc = mdb_del(state.txn, env.dbi(Table::Meta), &k, nullptr);
    if (rc != MDB_NOTFOUND) env.check(rc, "erasing a setting");
}

void WriteTransaction::commit() {
    Impl& state = live();  // asserts this is the first commit()
    // Again right before the commit: a transaction that began under the old
    // lock file must not overwrite what a writer under a new one committed.
    state.env->checkLockFile("committing");
    // LMDB frees the transaction whether or not the commit succeeds, so the
    // destructor must not abort it.
    MDB_txn* txn = std::exchange(state.txn, nullptr);
    state.env->check(mdb_txn_commit(txn), "committing");
}

}  // namespace smql::storage
