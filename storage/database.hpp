// The on-disk memory: one LMDB environment per database directory. LMDB types
// never leave storage/; callers see these classes and the model types.
//
// Contract: any number of ReadTransactions (each a consistent MVCC snapshot,
// never blocked by the writer) and at most one WriteTransaction at a time per
// process (LMDB serialises writers across processes). A WriteTransaction that
// is destroyed without commit() leaves the database exactly as it was.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "model/types.hpp"
#include "storage/scene_index.hpp"

namespace smql::storage {

// 2: every record and relation entry ends in a CRC32C (docs/storage.md).
// 3: the history table keeps the versions of a scene that updates replaced.
// 4: the scene_index table keeps each scene's table of contents (storage/scene_index.hpp).
// 5: a label entry carries the node's source id, geometry and box (codec::labelEntry), so a search of
//    a category across scenes reads no node record.
// 6: scene index records of format 2 (bounds in single precision), which an smql of version 5 would
//    take for damaged records; this smql reads format 1 too, so a version-5 database is read as it is.
inline constexpr std::uint32_t kSchemaVersion = 6;

struct OpenOptions {
    bool readOnly = false;
    bool create = true;                              // create the directory and database if missing
    std::uint64_t mapSize = std::uint64_t(1) << 38;  // virtual address space reserved (256 GiB); not disk
};

// Entries and pages of one sub-database, for SHOW/bench diagnostics of where
// the bytes of a database go.
struct TableStats {
    std::string name;
    std::uint64_t entries = 0;
    // Branch, leaf and overflow pages times the page size, as LMDB counts
    // them: for the DUPSORT tables (children, labels, relations) that is the
    // key tree only, without the pages of long duplicate lists.
    std::uint64_t bytes = 0;
};

// A node as a search of its category across scenes shows it (FIND c LIMIT n under USE SCENE '*'):
// read from the label index alone, whose entries carry these fields (docs/storage.md).
struct CategoryRow {
    model::NodeId id = model::kNoNode;
    model::NodeId scene = model::kNoNode;
    std::optional<std::int64_t> sourceId;
    model::GeometryKind geometry = model::GeometryKind::None;
    model::Box box;
    friend bool operator==(const CategoryRow&, const CategoryRow&) = default;
};

class ReadTransaction;
class WriteTransaction;

class Database {
public:
    // Throws smql::Error(ErrorKind::Storage) when the directory cannot be
    // opened, is not an smql database, or has another schema version.
    static std::unique_ptr<Database> open(const std::string& directory, const OpenOptions& options = {});
    ~Database();
    Database(const Database&) = delete;
    Database& operator=(const Database&) = delete;

    // Thread-safe: any thread may begin reads, each a snapshot of the last commit.
    ReadTransaction beginRead() const;
    // Blocks while another WriteTransaction (of any process) is open; the
    // transaction must stay on the thread that began it. Throws
    // smql::Error(Storage) on a read-only database.
    WriteTransaction beginWrite();

    const std::string& directory() const;
    bool readOnly() const;
    // Size of data.mdb on disk (the file grows with the data, not with mapSize).
    std::uint64_t fileSizeBytes() const;
    // The id of the last transaction committed to the database by any process (LMDB's
    // me_last_txnid, read from the meta pages without a transaction): a read transaction begun now
    // sees this commit, so an answer read in a transaction of this id (ReadTransaction::
    // transactionId) is still the answer while this returns the same id.
    std::uint64_t lastCommittedTransaction() const;

    struct Impl;

private:
    explicit Database(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

// The reads, which both kinds of transaction offer: LMDB has one transaction type with a read-only
// flag, and a WriteTransaction is a ReadTransaction that also writes (and reads what it wrote).
class ReadTransaction {
public:
    ReadTransaction(ReadTransaction&&) noexcept;
    ReadTransaction& operator=(ReadTransaction&&) noexcept;
    // A WriteTransaction is read through a reference; moved into a ReadTransaction it could no longer
    // be committed.
    ReadTransaction(WriteTransaction&&) = delete;
    ReadTransaction& operator=(WriteTransaction&&) = delete;
    ~ReadTransaction();

    std::uint64_t transactionId() const;

    std::vector<model::SceneInfo> scenes() const;
    std::optional<model::SceneInfo> scene(model::NodeId sceneId) const;
    std::optional<model::SceneInfo> sceneByName(std::string_view name) const;

    std::optional<model::Node> node(model::NodeId id) const;
    // node(), decoding into `into` so a loop reuses one Node's string capacity.
    // Returns false (leaving `into` untouched) when there is no such node.
    bool readNode(model::NodeId id, model::Node& into) const;
    // Nodes in the whole database, scene nodes included; O(1).
    std::uint64_t nodeCount() const;
    // Children in id order, which is the order the importer listed them in.
    std::vector<model::NodeId> children(model::NodeId parent) const;
    // Every node of a scene (the scene node itself included), in id order.
    void forEachNodeInScene(model::NodeId sceneId, const std::function<void(const model::Node&)>& visit) const;
    // The scene's table of contents as stored with it (storage/scene_index.hpp), when there is one
    // for the scene as `scene` describes it (its version and node count); nothing for a scene stored
    // before schema version 4 and not written since.
    std::optional<SceneIndex> sceneIndex(const model::SceneInfo& scene) const;
    // Relations whose subject or object is `id`: those with `id` as subject
    // first, then those with `id` as object.
    std::vector<model::Relation> relationsOf(model::NodeId id) const;
    // Every relation of a scene, once each.
    void forEachRelationInScene(model::NodeId sceneId, const std::function<void(const model::Relation&)>& visit) const;
    std::vector<model::Relation> relationsInScene(model::NodeId sceneId) const;

    // Label index: nodes with this exact category in every scene (or one), in
    // id order. Scene nodes (whose category is the scene name) and nodes with
    // an empty category are not in the index.
    std::vector<model::NodeId> nodesWithCategory(std::string_view category, model::NodeId sceneId = model::kNoNode,
                                                 std::size_t limit = SIZE_MAX) const;
    // The label keys that name `category` however it is written (model/category.hpp): its
    // canonical name, and names stored before names were canonical that fold to it.
    std::vector<std::string> labelKeys(std::string_view category) const;
    // Nodes of a category in every scene, by any of its spellings (labelKeys), in id order.
    std::vector<model::NodeId> nodesNamed(std::string_view category, std::size_t limit = SIZE_MAX) const;
    // nodesNamed's first `limit` nodes as rows, from the label index's entries without reading a node
    // record (one look-up and a page of entries at a time); a database of schema version 4 opened
    // read-only, whose entries hold the ids alone, is answered from the records. With `sceneId`, the
    // rows of that scene under this exact category key.
    std::vector<CategoryRow> categoryRows(std::string_view category, std::size_t limit = SIZE_MAX) const;
    // categoryRows by label keys already worked out (labelKeys: the name is folded once per
    // statement), each row handed to `visit` as it is read, in id order, with no list in between.
    void forEachCategoryRow(const std::vector<std::string>& keys, std::size_t limit,
                            const std::function<void(const CategoryRow&)>& visit) const;
    std::vector<CategoryRow> categoryRowsInScene(std::string_view categoryKey, model::NodeId sceneId) const;
    // How many nodes of every scene have this category, by any of its spellings (labelKeys): one
    // index lookup a key, no scan.
    std::uint64_t countWithCategory(std::string_view category) const;
    // The same by label keys already worked out (labelKeys).
    std::uint64_t countWithKeys(const std::vector<std::string>& keys) const;
    // Every distinct category with its node count, across all scenes, by name (byte order).
    std::vector<std::pair<std::string, std::uint64_t>> categories() const;
    std::optional<model::NodeId> nodeBySourceId(model::NodeId sceneId, std::int64_t sourceId) const;

    // Binary attachments of a node (evidence crops), by name.
    struct BlobInfo {
        std::string name;
        std::string mediaType;
        std::uint64_t size = 0;
    };
    std::vector<BlobInfo> blobsOf(model::NodeId id) const;
    std::optional<model::Blob> blob(model::NodeId id, std::string_view name) const;

    std::optional<std::string> setting(std::string_view key) const;
    std::vector<std::pair<std::string, std::string>> settings() const;

    // The versions of a scene that updates replaced, oldest first (empty for a scene never updated).
    std::vector<model::SceneVersion> history(std::string_view sceneName) const;

    std::vector<TableStats> tableStats() const;

    struct Impl;
    explicit ReadTransaction(std::unique_ptr<Impl> impl);

protected:
    // The transaction's state; asserts it is still open (only a WriteTransaction can be committed).
    Impl& live() const;

private:
    std::unique_ptr<Impl> impl_;
};

// Reads in a write transaction (all of ReadTransaction's) see its own writes: a read-modify-write
// change reads in the transaction it writes in, so another writer (which waits for this one) cannot
// interleave with it.
class WriteTransaction : public ReadTransaction {
public:
    WriteTransaction(WriteTransaction&&) noexcept;
    WriteTransaction& operator=(WriteTransaction&&) noexcept;
    ~WriteTransaction();  // aborts unless committed

    // Stores a whole scene: assigns database ids to the scene node and every
    // node of `data` (mapping local ids, parents and relation ends), fills
    // every index. Returns the new scene's id. Throws smql::Error(Input) when
    // a scene with the same name exists or local ids are inconsistent; those
    // checks run before the first write, so the transaction stays usable.
    // The scene gets one contiguous block of ids: the scene node, then the
    // nodes of `data` in list order (docs/storage.md relies on this).
    model::NodeId importScene(const model::SceneData& data);
    // Removes a scene with all its nodes, relations, index entries and history.
    // Ids are never reused. Throws smql::Error(Binding) when there is no such scene.
    void dropScene(model::NodeId sceneId);
    // Replaces a scene by a new version of the same place: the stored one (nodes,
    // relations, scene record) goes to the history table as the next version, with
    // `changes` (whose `after` ids are local ids of `data`, mapped here) and the time
    // `supersededAt`; `data` is stored as importScene stores a scene, under the same
    // name, with a new block of ids. The blobs of each stored node in `carried`
    // (stored id, local id in `data`) move to its new id.
    struct Replacement {
        model::NodeId scene = model::kNoNode;  // the new version's scene id
        std::uint64_t superseded = 0;          // the number the replaced version has in the history
    };
    Replacement replaceScene(model::NodeId sceneId, model::SceneData data, const std::string& supersededAt,
                             std::vector<model::ObjectChange> changes,
                             const std::vector<std::pair<model::NodeId, model::NodeId>>& carried = {});
    // Gives a scene (and its history) another name. Throws smql::Error(Binding) when
    // there is no such scene, smql::Error(Input) when the new name is taken or empty.
    void renameScene(model::NodeId sceneId, const std::string& newName);
    // Rewrites stored nodes in place (attributes, text, confidence, box): the
    // id, kind, scene, parent and category must stay as they are, since the
    // indexes hold them. Bumps the version of each scene touched. Throws
    // smql::Error(Input) for a node that does not exist or changes a fixed field.
    void updateNodes(const std::vector<model::Node>& nodes);
    // Throws smql::Error(Usage) for an empty key or one over 503 bytes (LMDB's key limit).
    void putSetting(std::string_view key, std::string_view value);
    // Erasing a setting that is not set does nothing.
    void eraseSetting(std::string_view key);

    void commit();

    explicit WriteTransaction(std::unique_ptr<Impl> impl);
};

}  // namespace smql::storage
