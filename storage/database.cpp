#include "storage/database.hpp"

#include <algorithm>
#include <cassert>
#include <filesystem>
#include <set>
#include <unordered_map>
#include <utility>

#include <fmt/format.h>

#include "model/embedding.hpp"
#include "model/error.hpp"
#include "storage/codec.hpp"
#include "storage/lmdb_env.hpp"

namespace smql::storage {

using model::Node;
using model::NodeId;
using model::SceneInfo;

struct Database::Impl {
    std::shared_ptr<Environment> env;
    std::string directory;
    bool readOnly;
};

struct ReadTransaction::Impl {
    Impl(std::shared_ptr<Environment> environment, MDB_txn* transaction)
        : env(std::move(environment)), txn(transaction) {}
    ~Impl() {
        for (MDB_cursor* cursor : cursors)
            if (cursor) mdb_cursor_close(cursor);
        env->endReader(txn);
    }
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;

    std::shared_ptr<Environment> env;  // keeps the environment open while the snapshot lives
    MDB_txn* txn;
    // One cursor per table, kept for the transaction's life: opening a cursor
    // allocates, and lookups such as children() run many times per query.
    mutable std::array<MDB_cursor*, kTableCount> cursors{};
    mutable std::array<bool, kTableCount> cursorBusy{};
};

struct WriteTransaction::Impl {
    Impl(std::shared_ptr<Environment> environment, MDB_txn* transaction)
        : env(std::move(environment)), txn(transaction) {}
    ~Impl() {
        if (txn) mdb_txn_abort(txn);
    }
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;

    std::shared_ptr<Environment> env;
    MDB_txn* txn;        // null once committed
    std::string record;  // encode buffer, reused across records
};

namespace {

constexpr std::string_view kImportHint = "fix the importer or the file it read";

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

// Runs `decode` and reports a corrupt record as "corrupt record in scene X":
// which scene is damaged is what a user needs to restore or re-import.
template <class Decode>
auto decodeInScene(const Environment& env, MDB_txn* txn, NodeId id, Decode&& decode) -> decltype(decode()) {
    try {
        return decode();
    } catch (const codec::CorruptRecord& e) {
        throw Error(ErrorKind::Storage,
                    fmt::format("corrupt record in scene {} of database {}: {}", sceneNameFor(env, txn, id),
                                env.directory(), e.detail()),
                    std::nullopt, e.hint());
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

std::string settingKey(std::string_view key) {
    std::string full;
    full.reserve(kSettingPrefix.size() + key.size());
    full.append(kSettingPrefix).append(key);
    return full;
}

bool validSettingKey(const Environment& env, std::string_view key) {
    return !key.empty() && kSettingPrefix.size() + key.size() <= env.maxKeySize();
}

std::size_t duplicateCount(const Environment& env, MDB_cursor* cursor) {
    std::size_t count = 0;
    env.check(mdb_cursor_count(cursor, &count), "counting index entries");
    return count;
}

// Calls visit(entry) for each duplicate of the key `cursor` was just
// positioned on, reading the fixed-size entries a page at a time straight from
// the map; visit returns false to stop. `first` is the value the positioning
// call returned and `count` the key's duplicate count.
template <class Visit>
void forEachDuplicate(const Environment& env, MDB_cursor* cursor, const MDB_val& first, std::size_t count,
                      std::size_t entrySize, Visit&& visit) {
    if (first.mv_size != entrySize)
        throw Error(ErrorKind::Storage,
                    fmt::format("corrupt index entry: {} bytes instead of {}", first.mv_size, entrySize), std::nullopt,
                    "the database file is damaged; restore it from a backup");
    // A key with a single value has no duplicate page for MDB_GET_MULTIPLE to return.
    if (count == 1) {
        visit(env.bytes(first));
        return;
    }
    MDB_val key, block;
    int rc = mdb_cursor_get(cursor, &key, &block, MDB_GET_MULTIPLE);
    while (rc == MDB_SUCCESS) {
        const char* entries = static_cast<const char*>(block.mv_data);
        for (std::size_t at = 0; at + entrySize <= block.mv_size; at += entrySize)
            if (!visit(std::string_view(entries + at, entrySize))) return;
        rc = mdb_cursor_get(cursor, &key, &block, MDB_NEXT_MULTIPLE);
    }
    if (rc != MDB_NOTFOUND) env.fail(rc, "reading index entries");
}

// Borrows the transaction's cached cursor for a table, or opens a private one
// when the cached one is in use further up the stack (a visitor calling back
// into the same transaction).
class TableCursor {
public:
    TableCursor(const ReadTransaction::Impl& txn, Table table) : txn_(txn), slot_(static_cast<std::size_t>(table)) {
        if (txn.cursors[slot_] && txn.cursorBusy[slot_]) {
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

void endOfScan(const Environment& env, int rc, std::string_view operation) {
    if (rc != MDB_SUCCESS && rc != MDB_NOTFOUND) env.fail(rc, operation);
}

[[noreturn]] void importError(std::string message) {
    throw Error(ErrorKind::Input, std::move(message), std::nullopt, std::string(kImportHint));
}

// Deletes every blob of a node: its keys are one range starting with the node's id.
void eraseBlobs(const Environment& env, MDB_txn* txn, NodeId node) {
    Cursor cursor(env, txn, Table::Blobs);
    auto prefix = codec::idKey(node);
    std::string_view want(reinterpret_cast<const char*>(prefix.data()), prefix.size());
    for (;;) {
        MDB_val key = toVal(prefix), value;
        int rc = mdb_cursor_get(cursor.get(), &key, &value, MDB_SET_RANGE);
        if (rc == MDB_NOTFOUND) return;
        env.check(rc, "dropping blobs");
        if (env.bytes(key).substr(0, prefix.size()) != want) return;
        env.check(mdb_cursor_del(cursor.get(), 0), "dropping a blob");
    }
}

// Names key the name index and, followed by a zero byte and a version number, the history table.
void checkSceneName(const Environment& env, std::string_view name) {
    if (name.empty())
        throw Error(ErrorKind::Input, "a scene needs a name", std::nullopt, "give the scene a name when importing it");
    const std::size_t longest = env.maxKeySize() - codec::historyKey("", 0).size();
    if (name.size() > longest)
        throw Error(ErrorKind::Input,
                    fmt::format("scene name '{}...' is too long ({} bytes; at most {})", name.substr(0, 40),
                                name.size(), longest),
                    std::nullopt, "choose a shorter name");
    if (name.find('\0') != std::string_view::npos)
        throw Error(ErrorKind::Input, "a scene name cannot hold a NUL character", std::nullopt, "choose another name");
}

// Checks a scene's local ids before anything is written, and returns the
// position of each local id in data.nodes (its database id is sceneId + 1 + position).
std::unordered_map<NodeId, std::size_t> validateScene(const Environment& env, const model::SceneData& data) {
    const std::string& name = data.info.name;
    checkSceneName(env, name);

    std::unordered_map<NodeId, std::size_t> position;
    position.reserve(data.nodes.size());
    for (std::size_t i = 0; i < data.nodes.size(); ++i) {
        const Node& node = data.nodes[i];
        if (node.id == model::kNoNode)
            importError(fmt::format("scene '{}': node #{} has local id 0; local ids start at 1", name, i + 1));
        auto [it, inserted] = position.emplace(node.id, i);
        if (!inserted)
            importError(fmt::format("scene '{}': local id {} is used by node #{} and node #{}", name, node.id,
                                    it->second + 1, i + 1));
        if (node.kind == model::NodeKind::Scene)
            importError(fmt::format("scene '{}': node {} has kind scene; the import creates the scene node itself",
                                    name, node.id));
        if (node.category.find('\0') != std::string::npos)
            importError(fmt::format("scene '{}': the category of node {} contains a NUL character", name, node.id));
        if (node.category.size() > env.maxKeySize())
            importError(fmt::format("scene '{}': the category of node {} is {} bytes long; at most {}", name, node.id,
                                    node.category.size(), env.maxKeySize()));
    }

    std::unordered_map<std::int64_t, NodeId> bySourceId;
    for (const Node& node : data.nodes) {
        if (node.parent != model::kNoNode && !position.contains(node.parent))
            importError(fmt::format("scene '{}': node {} has parent {}, which is not a node of the scene", name,
                                    node.id, node.parent));
        if (node.sourceId) {
            auto [it, inserted] = bySourceId.emplace(*node.sourceId, node.id);
            if (!inserted)
                importError(fmt::format("scene '{}': source id {} is used by node {} and node {}", name, *node.sourceId,
                                        it->second, node.id));
        }
    }

    // The parents must form a tree under the scene node: walk up from every
    // node once, marking nodes on the current walk to catch cycles.
    enum class Mark : std::uint8_t { Unseen, OnWalk, Done };
    std::vector<Mark> marks(data.nodes.size(), Mark::Unseen);
    std::vector<std::size_t> walk;
    for (std::size_t start = 0; start < data.nodes.size(); ++start) {
        walk.clear();
        std::size_t at = start;
        while (marks[at] == Mark::Unseen) {
            marks[at] = Mark::OnWalk;
            walk.push_back(at);
            NodeId parent = data.nodes[at].parent;
            if (parent == model::kNoNode) break;
            at = position.at(parent);
            if (marks[at] == Mark::OnWalk)
                importError(fmt::format("scene '{}': the parents of node {} form a cycle", name, data.nodes[at].id));
        }
        for (std::size_t i : walk) marks[i] = Mark::Done;
    }

    std::set<std::pair<NodeId, std::string_view>> blobNames;
    std::optional<std::pair<NodeId, std::size_t>> embeddings;  // the first node with one, and its length
    for (const model::Blob& blob : data.blobs) {
        if (!position.contains(blob.node))
            importError(fmt::format("scene '{}': blob '{}' belongs to node {}, which is not a node of the scene", name,
                                    blob.name, blob.node));
        if (blob.name.empty() || blob.name.size() + sizeof(NodeId) > env.maxKeySize() || blob.mediaType.size() > 255)
            importError(
                fmt::format("scene '{}': blob '{}' of node {} needs a name of 1 to {} bytes and a media type "
                            "of at most 255",
                            name, blob.name.substr(0, 40), blob.node, env.maxKeySize() - sizeof(NodeId)));
        if (!blobNames.emplace(blob.node, blob.name).second)
            importError(fmt::format("scene '{}': node {} has two blobs named '{}'", name, blob.node, blob.name));
        if (blob.name != model::kEmbeddingBlob) continue;
        // SIMILAR TO compares a bound vector with every node's: one model's vectors, one length.
        std::size_t dimensions = 0;
        try {
            dimensions = model::readEmbedding(blob).size();
        } catch (const Error& e) {
            importError(fmt::format("scene '{}': the embedding of node {}: {}", name, blob.node, e.message()));
        }
        if (!embeddings) embeddings = {blob.node, dimensions};
        if (embeddings->second != dimensions)
            importError(
                fmt::format("scene '{}': the embedding of node {} has {} dimensions, that of node {} has {}; "
                            "a scene's embeddings come from one model",
                            name, blob.node, dimensions, embeddings->first, embeddings->second));
    }

    for (std::size_t i = 0; i < data.relations.size(); ++i) {
        const model::Relation& r = data.relations[i];
        for (NodeId end : {r.subject, r.object})
            if (!position.contains(end))
                importError(
                    fmt::format("scene '{}': relation #{} ({}) refers to node {}, which is not a node of "
                                "the scene",
                                name, i + 1, model::toString(r.type), end));
        if (r.frame != model::kNoNode && !position.contains(r.frame))
            importError(
                fmt::format("scene '{}': relation #{} ({}) was seen from frame {}, which is not a node of "
                            "the scene",
                            name, i + 1, model::toString(r.type), r.frame));
    }
    return position;
}

std::uint64_t readNextId(const Environment& env, MDB_txn* txn) {
    auto bytes = lookup(env, txn, Table::Meta, toVal(kNextIdKey), "reading the next id");
    if (!bytes)
        throw Error(ErrorKind::Storage,
                    fmt::format("database {} is damaged: its meta table has no next id", env.directory()), std::nullopt,
                    "restore it from a backup, or import its scenes again into a new database");
    return codec::decodeU64(*bytes, "next id");
}

void put(const Environment& env, MDB_cursor* cursor, MDB_val key, MDB_val value, unsigned flags,
         std::string_view operation) {
    env.check(mdb_cursor_put(cursor, &key, &value, flags), operation);
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
    WriteTransaction write(std::make_unique<WriteTransaction::Impl>(impl_->env, txn));
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

// --------------------------------------------------------- ReadTransaction

ReadTransaction::ReadTransaction(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
ReadTransaction::ReadTransaction(ReadTransaction&&) noexcept = default;
ReadTransaction& ReadTransaction::operator=(ReadTransaction&&) noexcept = default;
ReadTransaction::~ReadTransaction() = default;

std::uint64_t ReadTransaction::transactionId() const { return mdb_txn_id(impl_->txn); }

std::vector<SceneInfo> ReadTransaction::scenes() const {
    const Environment& env = *impl_->env;
    TableCursor cursor(*impl_, Table::Scenes);
    std::vector<SceneInfo> out;
    MDB_val key, value;
    int rc = cursor.get(key, value, MDB_FIRST);
    for (; rc == MDB_SUCCESS; rc = cursor.get(key, value, MDB_NEXT)) {
        NodeId id = codec::idFromKey(env.bytes(key), "scene");
        out.push_back(decodeInScene(env, impl_->txn, id, [&] { return codec::decodeScene(id, env.bytes(value)); }));
    }
    endOfScan(env, rc, "listing scenes");
    return out;
}

std::optional<SceneInfo> ReadTransaction::scene(NodeId sceneId) const {
    return readScene(*impl_->env, impl_->txn, sceneId);
}

namespace {

// Scene ids are contiguous blocks (the scene node first), so a scene's nodes are the run of node
// records from its id on that carry its id as their scene. `step(key, value, op)` moves a cursor
// over the nodes table: a read transaction's cached one or a write transaction's own.
template <class Step>
void scanSceneNodes(const Environment& env, MDB_txn* txn, Step&& step, NodeId sceneId,
                    const std::function<void(const Node&)>& visit) {
    auto from = codec::idKey(sceneId);
    MDB_val key = toVal(from), value;
    Node node;
    int rc = step(key, value, MDB_SET_RANGE);
    for (; rc == MDB_SUCCESS; rc = step(key, value, MDB_NEXT)) {
        NodeId id = codec::idFromKey(env.bytes(key), "node");
        decodeInScene(env, txn, id, [&] { codec::decodeNode(id, env.bytes(value), node); });
        if (node.scene != sceneId) return;
        visit(node);
    }
    endOfScan(env, rc, "reading the nodes of a scene");
}

std::optional<SceneInfo> sceneNamed(const Environment& env, MDB_txn* txn, std::string_view name) {
    auto id = readSceneId(env, txn, name);
    if (!id) return std::nullopt;
    return readScene(env, txn, *id);
}

}  // namespace

std::optional<SceneInfo> ReadTransaction::sceneByName(std::string_view name) const {
    return sceneNamed(*impl_->env, impl_->txn, name);
}

bool ReadTransaction::readNode(NodeId id, Node& into) const {
    auto key = codec::idKey(id);
    auto bytes = lookup(*impl_->env, impl_->txn, Table::Nodes, toVal(key), "reading a node");
    if (!bytes) return false;
    decodeInScene(*impl_->env, impl_->txn, id, [&] { codec::decodeNode(id, *bytes, into); });
    return true;
}

std::optional<Node> ReadTransaction::node(NodeId id) const {
    std::optional<Node> out;
    auto key = codec::idKey(id);
    auto bytes = lookup(*impl_->env, impl_->txn, Table::Nodes, toVal(key), "reading a node");
    if (bytes) decodeInScene(*impl_->env, impl_->txn, id, [&] { codec::decodeNode(id, *bytes, out.emplace()); });
    return out;
}

std::uint64_t ReadTransaction::nodeCount() const {
    MDB_stat stat{};
    impl_->env->check(mdb_stat(impl_->txn, impl_->env->dbi(Table::Nodes), &stat), "counting nodes");
    return stat.ms_entries;
}

namespace {

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

std::vector<NodeId> ReadTransaction::children(NodeId parent) const {
    return readDuplicates<NodeId>(
        *impl_, Table::Children, parent, sizeof(NodeId), "reading children", [](std::string_view entry) {
            return codec::readBigEndian64(reinterpret_cast<const std::uint8_t*>(entry.data()));
        });
}

void ReadTransaction::forEachNodeInScene(NodeId sceneId, const std::function<void(const Node&)>& visit) const {
    TableCursor cursor(*impl_, Table::Nodes);
    scanSceneNodes(
        *impl_->env, impl_->txn,
        [&](MDB_val& key, MDB_val& value, MDB_cursor_op op) { return cursor.get(key, value, op); }, sceneId, visit);
}

std::vector<model::Relation> ReadTransaction::relationsOf(NodeId id) const {
    return readDuplicates<model::Relation>(
        *impl_, Table::Relations, id, codec::kRelationEntrySize, "reading relations", [&](std::string_view entry) {
            return decodeInScene(*impl_->env, impl_->txn, id, [&] { return codec::decodeRelationEntry(id, entry); });
        });
}

namespace {

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

// A scene's superseded versions: the history keys with its name as prefix, oldest first.
void scanHistory(const Environment& env, MDB_txn* txn, std::string_view sceneName,
                 const std::function<void(std::string_view key, std::string_view value)>& visit) {
    Cursor cursor(env, txn, Table::History);
    const std::string prefix = codec::historyPrefix(sceneName);
    MDB_val key = toVal(prefix), value;
    int rc = mdb_cursor_get(cursor.get(), &key, &value, MDB_SET_RANGE);
    for (; rc == MDB_SUCCESS && env.bytes(key).starts_with(prefix);
         rc = mdb_cursor_get(cursor.get(), &key, &value, MDB_NEXT))
        visit(env.bytes(key), env.bytes(value));
    endOfScan(env, rc, "reading the history of a scene");
}

}  // namespace

void ReadTransaction::forEachRelationInScene(NodeId sceneId,
                                             const std::function<void(const model::Relation&)>& visit) const {
    TableCursor cursor(*impl_, Table::Relations);
    scanSceneRelations(*impl_->env, impl_->txn, cursor.cursor(), sceneId, visit);
}

std::vector<model::SceneVersion> ReadTransaction::history(std::string_view sceneName) const {
    std::vector<model::SceneVersion> out;
    scanHistory(*impl_->env, impl_->txn, sceneName, [&](std::string_view key, std::string_view value) {
        try {
            out.push_back(codec::decodeVersion(key, value));
        } catch (const codec::CorruptRecord& e) {
            throw Error(ErrorKind::Storage,
                        fmt::format("corrupt record in the history of scene '{}' of database {}: {}", sceneName,
                                    impl_->env->directory(), e.detail()),
                        std::nullopt, e.hint());
        }
    });
    return out;
}

std::vector<NodeId> ReadTransaction::nodesWithCategory(std::string_view category, NodeId sceneId,
                                                       std::size_t limit) const {
    const Environment& env = *impl_->env;
    std::vector<NodeId> out;
    if (category.empty() || category.size() > env.maxKeySize()) return out;
    TableCursor cursor(*impl_, Table::Labels);
    MDB_val key = toVal(category), value;
    auto idAt = [](const char* p) { return codec::readBigEndian64(reinterpret_cast<const std::uint8_t*>(p)); };

    if (sceneId == model::kNoNode) {
        int rc = cursor.get(key, value, MDB_SET_KEY);
        if (rc == MDB_NOTFOUND) return out;
        env.check(rc, "reading the label index");
        std::size_t count = duplicateCount(env, cursor.cursor());
        out.reserve(std::min(count, limit));
        // Entries sort by (scene, node); scenes are contiguous id blocks, so that is id order.
        forEachDuplicate(env, cursor.cursor(), value, count, codec::kLabelEntrySize, [&](std::string_view entry) {
            if (out.size() == limit) return false;
            out.push_back(idAt(entry.data() + 8));
            return out.size() < limit;
        });
        return out;
    }

    auto from = codec::labelEntry(sceneId, 0);
    value = toVal(from);
    int rc = cursor.get(key, value, MDB_GET_BOTH_RANGE);
    for (; rc == MDB_SUCCESS; rc = cursor.get(key, value, MDB_NEXT_DUP)) {
        if (value.mv_size != codec::kLabelEntrySize)
            throw Error(ErrorKind::Storage, fmt::format("corrupt label index entry for '{}'", category), std::nullopt,
                        "the database file is damaged; restore it from a backup");
        const char* entry = static_cast<const char*>(value.mv_data);
        if (idAt(entry) != sceneId || out.size() == limit) return out;
        out.push_back(idAt(entry + 8));
    }
    endOfScan(env, rc, "reading the label index");
    return out;
}

std::uint64_t ReadTransaction::countWithCategory(std::string_view category) const {
    const Environment& env = *impl_->env;
    if (category.empty() || category.size() > env.maxKeySize()) return 0;
    TableCursor cursor(*impl_, Table::Labels);
    MDB_val key = toVal(category), value;
    int rc = cursor.get(key, value, MDB_SET_KEY);
    if (rc == MDB_NOTFOUND) return 0;
    env.check(rc, "reading the label index");
    return duplicateCount(env, cursor.cursor());
}

std::vector<std::pair<std::string, std::uint64_t>> ReadTransaction::categories() const {
    const Environment& env = *impl_->env;
    TableCursor cursor(*impl_, Table::Labels);
    std::vector<std::pair<std::string, std::uint64_t>> out;
    MDB_val key, value;
    int rc = cursor.get(key, value, MDB_FIRST);
    for (; rc == MDB_SUCCESS; rc = cursor.get(key, value, MDB_NEXT_NODUP))
        out.emplace_back(std::string(env.bytes(key)), duplicateCount(env, cursor.cursor()));
    endOfScan(env, rc, "listing categories");
    return out;
}

std::optional<NodeId> ReadTransaction::nodeBySourceId(NodeId sceneId, std::int64_t sourceId) const {
    auto key = codec::sourceKey(sceneId, sourceId);
    auto bytes = lookup(*impl_->env, impl_->txn, Table::SourceIds, toVal(key), "looking up a source id");
    if (!bytes) return std::nullopt;
    return codec::idFromKey(*bytes, "source id index");
}

std::vector<ReadTransaction::BlobInfo> ReadTransaction::blobsOf(NodeId id) const {
    const Environment& env = *impl_->env;
    TableCursor cursor(*impl_, Table::Blobs);
    auto prefix = codec::idKey(id);
    std::string_view want(reinterpret_cast<const char*>(prefix.data()), prefix.size());
    std::vector<BlobInfo> out;
    MDB_val key = toVal(prefix), value;
    int rc = cursor.get(key, value, MDB_SET_RANGE);
    for (; rc == MDB_SUCCESS && env.bytes(key).substr(0, prefix.size()) == want;
         rc = cursor.get(key, value, MDB_NEXT)) {
        BlobInfo info;
        auto [name, mediaType] = decodeInScene(
            env, impl_->txn, id, [&] { return codec::peekBlob(env.bytes(key), env.bytes(value), info.size); });
        info.name = std::string(name);
        info.mediaType = std::string(mediaType);
        out.push_back(std::move(info));
    }
    endOfScan(env, rc, "listing blobs");
    return out;
}

std::optional<model::Blob> ReadTransaction::blob(NodeId id, std::string_view name) const {
    std::string key = codec::blobKey(id, name);
    if (key.size() > impl_->env->maxKeySize()) return std::nullopt;
    auto bytes = lookup(*impl_->env, impl_->txn, Table::Blobs, toVal(key), "reading a blob");
    if (!bytes) return std::nullopt;
    return decodeInScene(*impl_->env, impl_->txn, id, [&] { return codec::decodeBlob(key, *bytes); });
}

std::optional<std::string> ReadTransaction::setting(std::string_view key) const {
    if (!validSettingKey(*impl_->env, key)) return std::nullopt;
    auto bytes = lookup(*impl_->env, impl_->txn, Table::Meta, toVal(settingKey(key)), "reading a setting");
    if (!bytes) return std::nullopt;
    return std::string(*bytes);
}

std::vector<std::pair<std::string, std::string>> ReadTransaction::settings() const {
    const Environment& env = *impl_->env;
    TableCursor cursor(*impl_, Table::Meta);
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
    std::vector<TableStats> out;
    for (std::size_t i = 0; i < kTableCount; ++i) {
        MDB_stat stat{};
        impl_->env->check(mdb_stat(impl_->txn, impl_->env->dbi(static_cast<Table>(i)), &stat), "reading table stats");
        out.push_back(
            {kTables[i].name, stat.ms_entries,
             std::uint64_t(stat.ms_branch_pages + stat.ms_leaf_pages + stat.ms_overflow_pages) * stat.ms_psize});
    }
    return out;
}

// -------------------------------------------------------- WriteTransaction

WriteTransaction::WriteTransaction(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
WriteTransaction::WriteTransaction(WriteTransaction&&) noexcept = default;
WriteTransaction& WriteTransaction::operator=(WriteTransaction&&) noexcept = default;
WriteTransaction::~WriteTransaction() = default;

namespace {

// The records and index entries of a new scene, one writer per table, each in the order that lets
// LMDB append (MDB_APPEND, MDB_APPENDDUP) where the keys allow it. `position` maps the scene's local
// ids to positions in `data.nodes`; node i gets the database id sceneId + 1 + i.
class SceneWriter {
public:
    SceneWriter(const Environment& env, MDB_txn* txn, std::string& record, const model::SceneData& data,
                std::unordered_map<NodeId, std::size_t> position, NodeId sceneId)
        : env_(env), txn_(txn), record_(record), data_(data), position_(std::move(position)), sceneId_(sceneId) {}

    // Nodes: ids above every existing key, in ascending order, so MDB_APPEND fills pages completely
    // and skips the search.
    void nodes() {
        Cursor nodes(env_, txn_, Table::Nodes);
        Node sceneNode;
        sceneNode.id = sceneId_;
        sceneNode.kind = model::NodeKind::Scene;
        sceneNode.scene = sceneId_;
        sceneNode.category = data_.info.name;
        codec::encodeNode(sceneNode, record_);
        auto key = codec::idKey(sceneId_);
        put(env_, nodes.get(), toVal(key), toVal(record_), MDB_APPEND, "storing the scene node");
        Node mapped;
        for (std::size_t i = 0; i < data_.nodes.size(); ++i) {
            mapped = data_.nodes[i];
            mapped.id = idAt(i);
            mapped.scene = sceneId_;
            mapped.parent = databaseId(data_.nodes[i].parent);
            codec::encodeNode(mapped, record_);
            key = codec::idKey(mapped.id);
            put(env_, nodes.get(), toVal(key), toVal(record_), MDB_APPEND, "storing a node");
        }
    }

    // Children: (parent, child) sorted, so each parent's duplicates append (MDB_APPENDDUP) and the
    // key searches walk the tree in order.
    void children() {
        std::vector<std::pair<NodeId, NodeId>> edges;
        edges.reserve(data_.nodes.size());
        for (std::size_t i = 0; i < data_.nodes.size(); ++i)
            edges.emplace_back(databaseId(data_.nodes[i].parent), idAt(i));
        std::sort(edges.begin(), edges.end());
        Cursor children(env_, txn_, Table::Children);
        for (const auto& [parent, child] : edges) {
            auto key = codec::idKey(parent), value = codec::idKey(child);
            put(env_, children.get(), toVal(key), toVal(value), MDB_APPENDDUP, "storing a child link");
        }
    }

    // Label index: categories interleave with other scenes' keys, so plain puts.
    void labels() {
        Cursor labels(env_, txn_, Table::Labels);
        for (std::size_t i = 0; i < data_.nodes.size(); ++i) {
            const std::string& category = data_.nodes[i].category;
            if (category.empty()) continue;
            auto entry = codec::labelEntry(sceneId_, idAt(i));
            put(env_, labels.get(), toVal(category), toVal(entry), 0, "storing a label");
        }
    }

    // Source ids: keys start with the new (largest) scene id, so sorted keys append.
    void sourceIds() {
        std::vector<std::pair<codec::SourceKey, NodeId>> sources;
        for (std::size_t i = 0; i < data_.nodes.size(); ++i)
            if (data_.nodes[i].sourceId)
                sources.emplace_back(codec::sourceKey(sceneId_, *data_.nodes[i].sourceId), idAt(i));
        std::sort(sources.begin(), sources.end());
        Cursor index(env_, txn_, Table::SourceIds);
        for (const auto& [key, id] : sources) {
            auto value = codec::idKey(id);
            put(env_, index.get(), toVal(key), toVal(value), MDB_APPEND, "storing a source id");
        }
    }

    // Relations: one entry under each end, sorted so duplicates append; identical relations
    // collapse into one entry.
    void relations() {
        std::vector<std::pair<NodeId, codec::RelationEntry>> entries;
        entries.reserve(2 * data_.relations.size());
        for (const model::Relation& local : data_.relations) {
            model::Relation r = local;
            r.subject = databaseId(local.subject);
            r.object = databaseId(local.object);
            r.frame = local.frame == model::kNoNode ? model::kNoNode : databaseId(local.frame);
            entries.emplace_back(r.subject, codec::encodeRelationEntry(r, codec::RelationSide::Subject));
            entries.emplace_back(r.object, codec::encodeRelationEntry(r, codec::RelationSide::Object));
        }
        std::sort(entries.begin(), entries.end());
        entries.erase(std::unique(entries.begin(), entries.end()), entries.end());
        Cursor relations(env_, txn_, Table::Relations);
        for (const auto& [id, entry] : entries) {
            auto key = codec::idKey(id);
            put(env_, relations.get(), toVal(key), toVal(entry), MDB_APPENDDUP, "storing a relation");
        }
    }

    // Blobs: keys start with the new node ids, so sorted keys append.
    void blobs() {
        std::vector<std::pair<std::string, const model::Blob*>> blobs;
        for (const model::Blob& blob : data_.blobs)
            blobs.emplace_back(codec::blobKey(databaseId(blob.node), blob.name), &blob);
        std::sort(blobs.begin(), blobs.end());
        Cursor table(env_, txn_, Table::Blobs);
        for (const auto& [key, blob] : blobs) {
            codec::encodeBlob(key, *blob, record_);
            put(env_, table.get(), toVal(key), toVal(record_), MDB_APPEND, "storing a blob");
        }
    }

    // The scene's record, its name, and the next free id.
    void scene() {
        SceneInfo info = data_.info;
        info.id = sceneId_;
        info.nodeCount = data_.nodes.size();
        info.version = 1;
        codec::encodeScene(info, record_);
        auto key = codec::idKey(sceneId_);
        Cursor scenes(env_, txn_, Table::Scenes);
        put(env_, scenes.get(), toVal(key), toVal(record_), MDB_NOOVERWRITE, "storing the scene");
        Cursor names(env_, txn_, Table::SceneNames);
        put(env_, names.get(), toVal(info.name), toVal(key), MDB_NOOVERWRITE, "storing the scene name");
        std::string nextId = codec::encodeU64(sceneId_ + 1 + data_.nodes.size());
        Cursor meta(env_, txn_, Table::Meta);
        put(env_, meta.get(), toVal(kNextIdKey), toVal(nextId), 0, "storing the next id");
    }

private:
    NodeId idAt(std::size_t i) const { return sceneId_ + 1 + i; }
    NodeId databaseId(NodeId local) const {
        return local == model::kNoNode ? sceneId_ : sceneId_ + 1 + position_.at(local);
    }

    const Environment& env_;
    MDB_txn* txn_;
    std::string& record_;
    const model::SceneData& data_;
    const std::unordered_map<NodeId, std::size_t> position_;
    const NodeId sceneId_;
};

}  // namespace

NodeId WriteTransaction::importScene(const model::SceneData& data) {
    assert(impl_->txn && "WriteTransaction used after commit()");
    const Environment& env = *impl_->env;
    MDB_txn* txn = impl_->txn;
    const std::string& name = data.info.name;

    // Everything that can be wrong with the input is found before the first write.
    auto position = validateScene(env, data);
    if (readSceneId(env, txn, name))
        throw Error(ErrorKind::Input, fmt::format("a scene named '{}' already exists", name), std::nullopt,
                    "choose another name, or remove the stored one first (DROP SCENE)");

    const NodeId sceneId = readNextId(env, txn);
    SceneWriter write(env, txn, impl_->record, data, std::move(position), sceneId);
    write.nodes();
    write.children();
    write.labels();
    write.sourceIds();
    write.relations();
    write.blobs();
    write.scene();
    return sceneId;
}

namespace {

[[noreturn]] void noSuchScene(NodeId sceneId) {
    throw Error(ErrorKind::Binding, fmt::format("no scene with id {}", sceneId), std::nullopt,
                "SHOW SCENES lists the scenes of the database");
}

// Deletes a scene's nodes, relations, index entries and records; its history stays.
void eraseScene(const Environment& env, MDB_txn* txn, const SceneInfo& scene) {
    const NodeId sceneId = scene.id;
    const SceneInfo* info = &scene;

    // What the index entries are keyed by, copied out of the map before any
    // delete can move the pages it points into.
    struct Doomed {
        NodeId id;
        std::string category;
        std::optional<std::int64_t> sourceId;
        bool labelled;
    };
    std::vector<Doomed> doomed;
    doomed.reserve(info->nodeCount + 1);
    {
        Cursor nodes(env, txn, Table::Nodes);
        auto from = codec::idKey(sceneId);
        MDB_val key = toVal(from), value;
        Node node;
        int rc = mdb_cursor_get(nodes.get(), &key, &value, MDB_SET_RANGE);
        for (; rc == MDB_SUCCESS; rc = mdb_cursor_get(nodes.get(), &key, &value, MDB_NEXT)) {
            NodeId id = codec::idFromKey(env.bytes(key), "node");
            decodeInScene(env, txn, id, [&] { codec::decodeNode(id, env.bytes(value), node); });
            if (node.scene != sceneId) break;
            bool labelled = node.kind != model::NodeKind::Scene && !node.category.empty();
            doomed.push_back({node.id, labelled ? node.category : std::string(), node.sourceId, labelled});
        }
        endOfScan(env, rc, "reading the nodes of a scene");
    }

    auto erase = [&](Table table, MDB_val key, MDB_val* value) {
        int rc = mdb_del(txn, env.dbi(table), &key, value);
        if (rc != MDB_NOTFOUND) env.check(rc, "dropping a scene");
    };
    for (const Doomed& node : doomed) {
        auto key = codec::idKey(node.id);
        erase(Table::Nodes, toVal(key), nullptr);
        erase(Table::Children, toVal(key), nullptr);
        erase(Table::Relations, toVal(key), nullptr);
        eraseBlobs(env, txn, node.id);
        if (node.labelled) {
            auto entry = codec::labelEntry(sceneId, node.id);
            MDB_val value = toVal(entry);
            erase(Table::Labels, toVal(node.category), &value);
        }
        if (node.sourceId) {
            auto source = codec::sourceKey(sceneId, *node.sourceId);
            erase(Table::SourceIds, toVal(source), nullptr);
        }
    }
    auto key = codec::idKey(sceneId);
    erase(Table::Scenes, toVal(key), nullptr);
    erase(Table::SceneNames, toVal(info->name), nullptr);
}

void eraseHistory(const Environment& env, MDB_txn* txn, std::string_view sceneName) {
    std::vector<std::string> keys;
    scanHistory(env, txn, sceneName, [&](std::string_view key, std::string_view) { keys.emplace_back(key); });
    for (const auto& key : keys) {
        MDB_val k = toVal(key);
        env.check(mdb_del(txn, env.dbi(Table::History), &k, nullptr), "erasing the history of a scene");
    }
}

}  // namespace

void WriteTransaction::dropScene(NodeId sceneId) {
    assert(impl_->txn && "WriteTransaction used after commit()");
    auto info = readScene(*impl_->env, impl_->txn, sceneId);
    if (!info) noSuchScene(sceneId);
    eraseScene(*impl_->env, impl_->txn, *info);
    eraseHistory(*impl_->env, impl_->txn, info->name);
}

WriteTransaction::Replacement WriteTransaction::replaceScene(NodeId sceneId, model::SceneData data,
                                                             const std::string& supersededAt,
                                                             std::vector<model::ObjectChange> changes,
                                                             const std::vector<std::pair<NodeId, NodeId>>& carried) {
    assert(impl_->txn && "WriteTransaction used after commit()");
    const Environment& env = *impl_->env;
    MDB_txn* txn = impl_->txn;
    auto info = readScene(env, txn, sceneId);
    if (!info) noSuchScene(sceneId);
    if (data.info.name != info->name)
        throw Error(ErrorKind::Usage,
                    fmt::format("a new version of scene '{}' cannot be named '{}'", info->name, data.info.name),
                    std::nullopt, "RENAME SCENE gives a scene another name");

    model::SceneVersion superseded;
    superseded.info = *info;
    forEachNodeInScene(sceneId, [&](const Node& n) { superseded.nodes.push_back(n); });
    superseded.relations = relationsInScene(sceneId);
    superseded.supersededAt = supersededAt;
    superseded.number = 1;
    scanHistory(env, txn, info->name, [&](std::string_view key, std::string_view) {
        superseded.number =
            codec::readBigEndian64(reinterpret_cast<const std::uint8_t*>(key.data()) + key.size() - 8) + 1;
    });

    // importScene gives the i-th node of `data` the id newScene + 1 + i.
    std::unordered_map<NodeId, std::size_t> position;
    for (std::size_t i = 0; i < data.nodes.size(); ++i) position.emplace(data.nodes[i].id, i);
    std::vector<std::optional<std::size_t>> afterPosition;
    for (const auto& change : changes) {
        afterPosition.emplace_back();
        if (change.after == model::kNoNode) continue;
        auto at = position.find(change.after);
        if (at == position.end())
            throw Error(ErrorKind::Input,
                        fmt::format("a change names local node {}, which the new version lacks", change.after),
                        std::nullopt, std::string(kImportHint));
        afterPosition.back() = at->second;
    }

    for (const auto& [storedId, local] : carried) {
        Cursor cursor(env, txn, Table::Blobs);
        auto prefix = codec::idKey(storedId);
        std::string_view want(reinterpret_cast<const char*>(prefix.data()), prefix.size());
        MDB_val key = toVal(want), value;
        int rc = mdb_cursor_get(cursor.get(), &key, &value, MDB_SET_RANGE);
        for (; rc == MDB_SUCCESS && env.bytes(key).starts_with(want);
             rc = mdb_cursor_get(cursor.get(), &key, &value, MDB_NEXT)) {
            model::Blob blob =
                decodeInScene(env, txn, storedId, [&] { return codec::decodeBlob(env.bytes(key), env.bytes(value)); });
            blob.node = local;
            data.blobs.push_back(std::move(blob));
        }
        endOfScan(env, rc, "reading the evidence of a node");
    }

    eraseScene(env, txn, *info);
    const NodeId newScene = importScene(data);
    for (std::size_t i = 0; i < changes.size(); ++i)
        if (afterPosition[i]) changes[i].after = newScene + 1 + *afterPosition[i];
    superseded.changes = std::move(changes);

    std::string key = codec::historyKey(info->name, superseded.number);
    codec::encodeVersion(key, superseded, impl_->record);
    MDB_val k = toVal(key), v = toVal(impl_->record);
    env.check(mdb_put(txn, env.dbi(Table::History), &k, &v, MDB_NOOVERWRITE), "storing a version of a scene");
    return {newScene, superseded.number};
}

void WriteTransaction::renameScene(NodeId sceneId, const std::string& newName) {
    assert(impl_->txn && "WriteTransaction used after commit()");
    const Environment& env = *impl_->env;
    MDB_txn* txn = impl_->txn;
    auto info = readScene(env, txn, sceneId);
    if (!info) noSuchScene(sceneId);
    checkSceneName(env, newName);
    if (newName == info->name) return;
    if (readSceneId(env, txn, newName))
        throw Error(ErrorKind::Input, fmt::format("a scene named '{}' already exists", newName), std::nullopt,
                    "choose another name, or remove the stored one first (DROP SCENE)");
    const std::string oldName = info->name;

    // The scene record (a new version, so cached snapshots reload with the new name),
    // the name index and the scene node, whose category is the scene's name.
    info->name = newName;
    ++info->version;
    auto key = codec::idKey(sceneId);
    codec::encodeScene(*info, impl_->record);
    MDB_val k = toVal(key), v = toVal(impl_->record);
    env.check(mdb_put(txn, env.dbi(Table::Scenes), &k, &v, 0), "renaming a scene");
    MDB_val oldKey = toVal(oldName);
    env.check(mdb_del(txn, env.dbi(Table::SceneNames), &oldKey, nullptr), "renaming a scene");
    MDB_val newKey = toVal(newName), idVal = toVal(key);
    env.check(mdb_put(txn, env.dbi(Table::SceneNames), &newKey, &idVal, MDB_NOOVERWRITE), "renaming a scene");
    auto bytes = lookup(env, txn, Table::Nodes, toVal(key), "reading a node");
    if (!bytes) throw Error(ErrorKind::Storage, fmt::format("scene '{}' has no scene node", oldName));
    Node sceneNode = decodeInScene(env, txn, sceneId, [&] { return codec::decodeNode(sceneId, *bytes); });
    sceneNode.category = newName;
    codec::encodeNode(sceneNode, impl_->record);
    v = toVal(impl_->record);
    env.check(mdb_put(txn, env.dbi(Table::Nodes), &k, &v, 0), "renaming a scene");

    // The history moves with the name: each record is sealed with its key, so it is re-encoded.
    std::vector<model::SceneVersion> versions;
    scanHistory(env, txn, oldName,
                [&](std::string_view hk, std::string_view hv) { versions.push_back(codec::decodeVersion(hk, hv)); });
    eraseHistory(env, txn, oldName);
    for (auto& version : versions) {
        std::string hk = codec::historyKey(newName, version.number);
        codec::encodeVersion(hk, version, impl_->record);
        MDB_val hkv = toVal(hk), hvv = toVal(impl_->record);
        env.check(mdb_put(txn, env.dbi(Table::History), &hkv, &hvv, MDB_NOOVERWRITE), "renaming a scene");
    }
}

std::vector<model::Relation> WriteTransaction::relationsInScene(NodeId sceneId) const {
    assert(impl_->txn && "WriteTransaction used after commit()");
    std::vector<model::Relation> out;
    Cursor cursor(*impl_->env, impl_->txn, Table::Relations);
    scanSceneRelations(*impl_->env, impl_->txn, cursor.get(), sceneId,
                       [&](const model::Relation& r) { out.push_back(r); });
    return out;
}

void WriteTransaction::updateNodes(const std::vector<Node>& nodes) {
    assert(impl_->txn && "WriteTransaction used after commit()");
    const Environment& env = *impl_->env;
    MDB_txn* txn = impl_->txn;
    std::set<NodeId> scenes;
    // Check every node before the first write, so a refused update writes nothing.
    for (const Node& node : nodes) {
        auto key = codec::idKey(node.id);
        auto bytes = lookup(env, txn, Table::Nodes, toVal(key), "reading a node");
        if (!bytes) importError(fmt::format("node #{} does not exist", node.id));
        Node stored = decodeInScene(env, txn, node.id, [&] { return codec::decodeNode(node.id, *bytes); });
        if (stored.kind != node.kind || stored.scene != node.scene || stored.parent != node.parent ||
            stored.category != node.category || stored.sourceId != node.sourceId ||
            stored.kind == model::NodeKind::Scene)
            importError(
                fmt::format("node #{}: an update may change attributes, text, confidence and the box, not its "
                            "kind, scene, parent, category or source id",
                            node.id));
        scenes.insert(node.scene);
    }
    for (const Node& node : nodes) {
        codec::encodeNode(node, impl_->record);
        auto key = codec::idKey(node.id);
        MDB_val k = toVal(key), v = toVal(impl_->record);
        env.check(mdb_put(txn, env.dbi(Table::Nodes), &k, &v, 0), "updating a node");
    }
    // A new version tells every cached snapshot of these scenes to reload.
    for (NodeId sceneId : scenes) {
        auto info = readScene(env, txn, sceneId);
        if (!info) continue;
        ++info->version;
        codec::encodeScene(*info, impl_->record);
        auto key = codec::idKey(sceneId);
        MDB_val k = toVal(key), v = toVal(impl_->record);
        env.check(mdb_put(txn, env.dbi(Table::Scenes), &k, &v, 0), "updating a scene's version");
    }
}

std::optional<SceneInfo> WriteTransaction::sceneByName(std::string_view name) const {
    assert(impl_->txn && "WriteTransaction used after commit()");
    return sceneNamed(*impl_->env, impl_->txn, name);
}

void WriteTransaction::forEachNodeInScene(NodeId sceneId, const std::function<void(const Node&)>& visit) const {
    assert(impl_->txn && "WriteTransaction used after commit()");
    Cursor cursor(*impl_->env, impl_->txn, Table::Nodes);
    scanSceneNodes(
        *impl_->env, impl_->txn,
        [&](MDB_val& key, MDB_val& value, MDB_cursor_op op) { return mdb_cursor_get(cursor.get(), &key, &value, op); },
        sceneId, visit);
}

void WriteTransaction::putSetting(std::string_view key, std::string_view value) {
    assert(impl_->txn && "WriteTransaction used after commit()");
    const Environment& env = *impl_->env;
    if (!validSettingKey(env, key))
        throw Error(ErrorKind::Usage,
                    key.empty() ? std::string("a setting needs a name")
                                : fmt::format("setting name '{}...' is too long ({} bytes; at most {})",
                                              key.substr(0, 40), key.size(), env.maxKeySize() - kSettingPrefix.size()),
                    std::nullopt, "SHOW SETTINGS lists the settings in use");
    std::string fullKey = settingKey(key);
    MDB_val k = toVal(fullKey), v = toVal(value);
    env.check(mdb_put(impl_->txn, env.dbi(Table::Meta), &k, &v, 0), "storing a setting");
}

void WriteTransaction::eraseSetting(std::string_view key) {
    assert(impl_->txn && "WriteTransaction used after commit()");
    const Environment& env = *impl_->env;
    if (!validSettingKey(env, key)) return;
    std::string fullKey = settingKey(key);
    MDB_val k = toVal(fullKey);
    int rc = mdb_del(impl_->txn, env.dbi(Table::Meta), &k, nullptr);
    if (rc != MDB_NOTFOUND) env.check(rc, "erasing a setting");
}

void WriteTransaction::commit() {
    assert(impl_->txn && "WriteTransaction committed twice");
    // Again right before the commit: a transaction that began under the old
    // lock file must not overwrite what a writer under a new one committed.
    impl_->env->checkLockFile("committing");
    // LMDB frees the transaction whether or not the commit succeeds.
    MDB_txn* txn = std::exchange(impl_->txn, nullptr);
    impl_->env->check(mdb_txn_commit(txn), "committing");
}

}  // namespace smql::storage
