// Scratch directories and scene builders shared by the storage tests.
#pragma once

#include <lmdb.h>
#include <stdlib.h>

#include <filesystem>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "model/geometry.hpp"
#include "model/types.hpp"
#include "storage/codec.hpp"
#include "storage/crc32c.hpp"
#include "storage/database.hpp"
#include "storage/lmdb_env.hpp"
#include "storage/scene_index.hpp"

namespace smql::storage::testing {

// Changes one table of the database at `path` straight through LMDB, as damage, a bug elsewhere or
// another smql would: `edit` gets the write transaction and the table, and what it did is committed.
template <typename Edit>
void editTable(const std::string& path, const char* table, Edit&& edit) {
    MDB_env* env = nullptr;
    REQUIRE(mdb_env_create(&env) == 0);
    REQUIRE(mdb_env_set_maxdbs(env, kMaxTables) == 0);
    REQUIRE(mdb_env_open(env, path.c_str(), 0, 0644) == 0);
    MDB_txn* txn = nullptr;
    REQUIRE(mdb_txn_begin(env, nullptr, 0, &txn) == 0);
    MDB_dbi dbi;
    REQUIRE(mdb_dbi_open(txn, table, 0, &dbi) == 0);
    edit(txn, dbi);
    REQUIRE(mdb_txn_commit(txn) == 0);
    mdb_env_close(env);
}

// Every node record of a scene, in id order, as the store reads them.
inline std::vector<model::Node> nodesOf(const ReadTransaction& txn, model::NodeId sceneId) {
    std::vector<model::Node> nodes;
    txn.forEachNodeInScene(sceneId, [&](const model::Node& n) { nodes.push_back(n); });
    return nodes;
}

// Makes the label entries of the database at `path` what an smql before schema version 5 wrote:
// the two ids alone.
inline void narrowLabels(const std::string& path) {
    editTable(path, "labels", [](MDB_txn* txn, MDB_dbi) {
        MDB_dbi labels;
        REQUIRE(mdb_dbi_open(txn, "labels", MDB_DUPSORT | MDB_DUPFIXED, &labels) == 0);
        std::vector<std::pair<std::string, std::string>> entries;
        MDB_cursor* cursor = nullptr;
        REQUIRE(mdb_cursor_open(txn, labels, &cursor) == 0);
        MDB_val key, value;
        for (int rc = mdb_cursor_get(cursor, &key, &value, MDB_FIRST); rc == 0;
             rc = mdb_cursor_get(cursor, &key, &value, MDB_NEXT))
            entries.emplace_back(std::string(static_cast<const char*>(key.mv_data), key.mv_size),
                                 std::string(static_cast<const char*>(value.mv_data), codec::kIdsOnlyLabelEntrySize));
        mdb_cursor_close(cursor);
        REQUIRE(mdb_drop(txn, labels, 0) == 0);
        for (const auto& [category, ids] : entries) {
            MDB_val k = toVal(category), v = toVal(ids);
            REQUIRE(mdb_put(txn, labels, &k, &v, 0) == 0);
        }
    });
}

inline void setStoredSchemaVersion(const std::string& path, std::uint64_t version) {
    editTable(path, "meta", [&](MDB_txn* txn, MDB_dbi meta) {
        std::string bytes = codec::encodeU64(version);
        MDB_val key = toVal(kSchemaVersionKey), value = toVal(bytes);
        REQUIRE(mdb_put(txn, meta, &key, &value, 0) == 0);
    });
}

// A scene index record as an smql before schema version 6 wrote it (format 1): the bounds as
// doubles, exactly model::worldAabb of each box, packed by them.
inline std::string formatOneSceneIndex(model::NodeId sceneId, const std::vector<model::Node>& nodes,
                                       std::uint64_t version) {
    const SceneIndex rounded = SceneIndex::of(nodes, version);  // the categories and codes, in order
    std::vector<model::Aabb> bounds;
    std::vector<std::uint32_t> order;
    for (std::uint32_t s = 0; s < nodes.size(); ++s) {
        bounds.push_back(model::worldAabb(nodes[s].box));
        if (nodes[s].kind != model::NodeKind::Scene && nodes[s].geometry != model::GeometryKind::None)
            order.push_back(s);
    }
    const std::vector<model::Aabb> blocks = packTiles(bounds, order);
    std::string out;
    auto varint = [&](std::uint64_t v) {
        for (; v >= 0x80; v >>= 7) out.push_back(static_cast<char>((v & 0x7f) | 0x80));
        out.push_back(static_cast<char>(v));
    };
    auto raw = [&](const void* data, std::size_t size) { out.append(static_cast<const char*>(data), size); };
    out.push_back(1);
    raw(&version, 8);
    varint(rounded.categories.size());
    for (const auto& category : rounded.categories) {
        varint(category.size());
        out += category;
    }
    varint(nodes.size());
    varint(order.size());
    varint(blocks.size());
    for (std::size_t s = 0; s < nodes.size(); ++s) {
        const SceneIndexEntry& e = rounded.entries[s];
        raw(&bounds[s], sizeof(model::Aabb));
        raw(&e.category, 4);
        raw(&e.kind, 1);
        raw(&e.geometry, 1);
        raw(&e.hidden, 1);
        raw(&e.reserved, 1);
    }
    raw(order.data(), order.size() * 4);
    raw(blocks.data(), blocks.size() * sizeof(model::Aabb));
    const codec::IdKey key = codec::idKey(sceneId);
    const std::uint32_t crc = crc32c(out, crc32c({reinterpret_cast<const char*>(key.data()), key.size()}));
    raw(&crc, 4);
    return out;
}

// Makes the database at `path` what an smql of schema version 5 wrote: scene indexes of format 1.
inline void asSchemaVersion5(const std::string& path) {
    std::vector<std::pair<codec::IdKey, std::string>> records;
    {
        auto db = Database::open(path, {.readOnly = true});
        auto read = db->beginRead();
        for (const model::SceneInfo& info : read.scenes())
            records.emplace_back(codec::idKey(info.id),
                                 formatOneSceneIndex(info.id, nodesOf(read, info.id), info.version));
    }
    editTable(path, "scene_index", [&](MDB_txn* txn, MDB_dbi index) {
        for (const auto& [id, record] : records) {
            MDB_val key{id.size(), const_cast<std::uint8_t*>(id.data())}, value = toVal(record);
            REQUIRE(mdb_put(txn, index, &key, &value, 0) == 0);
        }
    });
    setStoredSchemaVersion(path, 5);
}

// Makes the database at `path` what an smql of schema version 4 wrote: scene indexes of format 1,
// label entries of the ids alone.
inline void asSchemaVersion4(const std::string& path) {
    asSchemaVersion5(path);
    narrowLabels(path);
    setStoredSchemaVersion(path, 4);
}

// Makes the database at `path` what an smql of schema version 3 wrote: no scene index table, label
// entries of the ids alone, and that version in the meta table.
inline void asSchemaVersion3(const std::string& path) {
    narrowLabels(path);
    editTable(path, "meta", [](MDB_txn* txn, MDB_dbi meta) {
        std::string three = codec::encodeU64(3);
        MDB_val key = toVal(kSchemaVersionKey), value = toVal(three);
        REQUIRE(mdb_put(txn, meta, &key, &value, 0) == 0);
        MDB_dbi index;
        REQUIRE(mdb_dbi_open(txn, "scene_index", 0, &index) == 0);
        REQUIRE(mdb_drop(txn, index, 1) == 0);
    });
}

// A fresh directory under the system temp dir, removed with everything in it.
class TempDir {
public:
    TempDir() {
        std::string pattern = (std::filesystem::temp_directory_path() / "smql-storage-XXXXXX").string();
        if (!::mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
        path_ = pattern;
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    std::string path() const { return path_.string(); }
    std::string sub(const std::string& name) const { return (path_ / name).string(); }

private:
    std::filesystem::path path_;
};

inline model::Node localNode(model::NodeId id, model::NodeKind kind, model::NodeId parent, std::string category) {
    model::Node node;
    node.id = id;
    node.kind = kind;
    node.parent = parent;
    node.category = std::move(category);
    return node;
}

// A scene of `count` nodes with local ids 1..count: node 1 is a room holding
// up to 3000 objects directly (more than a page of child entries), the rest
// hang one below another. Categories cycle through five names; node 2 is
// `near` the next 2000 nodes (many relation entries under one key).
inline model::SceneData largeScene(std::string name, std::size_t count, std::string extraCategory = {}) {
    static const char* kCategories[] = {"chair", "table", "lamp", "book", "cup"};
    model::SceneData data;
    data.info.name = std::move(name);
    data.info.source = "test:large";
    data.nodes.reserve(count);
    data.nodes.push_back(localNode(1, model::NodeKind::Room, model::kNoNode, "room"));
    for (std::size_t i = 2; i <= count; ++i) {
        model::NodeId parent = i <= 3001 ? 1 : i - 3000;
        std::string category = !extraCategory.empty() && i % 7 == 0 ? extraCategory : kCategories[i % 5];
        model::Node node = localNode(i, model::NodeKind::Object, parent, std::move(category));
        node.geometry = model::GeometryKind::Box;
        node.box = {{double(i) * 0.01, 1, 0.5}, {0.2, 0.2, 0.2}, 0};
        node.attributes = {{"color", i % 2 ? "red" : "blue"}};
        node.sourceId = std::int64_t(i) * 10;
        node.text = "object number " + std::to_string(i);
        data.nodes.push_back(std::move(node));
    }
    for (std::size_t i = 3; i <= count && i <= 2002; ++i)
        data.relations.push_back({2, i, model::RelationType::Near, 0.5f, 1, model::kNoNode});
    return data;
}

inline std::size_t countCategory(const model::SceneData& data, std::string_view category) {
    std::size_t n = 0;
    for (const auto& node : data.nodes) n += node.category == category;
    return n;
}

// Stores `data` in a write transaction of its own, committed; returns the scene's id.
inline model::NodeId importCommitted(Database& db, const model::SceneData& data) {
    auto txn = db.beginWrite();
    model::NodeId id = txn.importScene(data);
    txn.commit();
    return id;
}

}  // namespace smql::storage::testing
