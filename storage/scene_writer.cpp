// WriteTransaction::importScene: a new scene's id block, its node records and every index.
#include <algorithm>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "model/category.hpp"
#include "model/error.hpp"
#include "storage/codec.hpp"
#include "storage/database.hpp"
#include "storage/database_internal.hpp"
#include "storage/scene_validation.hpp"

namespace smql::storage {

using model::Node;
using model::NodeId;
using model::SceneInfo;

namespace {

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
            auto entry = codec::labelEntry(category, sceneId_, idAt(i), data_.nodes[i]);
            put(env_, labels.get(), toVal(category), toVal(entry), 0, "storing a label");
            if (!model::isCategoryName(category)) env_.forgetLegacyLabels();
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

void storeSceneIndex(const Environment& env, MDB_txn* txn, NodeId sceneId, std::string& record) {
    auto info = readScene(env, txn, sceneId);
    if (!info) throw Error(ErrorKind::Storage, fmt::format("no scene with id {} to index", sceneId));
    // The records as a reader decodes them, so the index says what a scene loaded whole would.
    std::vector<Node> nodes;
    nodes.reserve(info->nodeCount + 1);
    {
        Cursor cursor(env, txn, Table::Nodes);
        forEachStoredNode(env, txn, cursor.get(), sceneId, [&](const Node& node) { nodes.push_back(node); });
    }
    codec::encodeSceneIndex(sceneId, SceneIndex::of(nodes, info->version), record);
    auto key = codec::idKey(sceneId);
    MDB_val k = toVal(key), v = toVal(record);
    env.check(mdb_put(txn, env.dbi(Table::SceneIndex), &k, &v, 0), "storing a scene index");
}

NodeId WriteTransaction::importScene(const model::SceneData& data) {
    Impl& state = live();
    const Environment& env = *state.env;
    MDB_txn* txn = state.txn;
    const std::string& name = data.info.name;

    // Everything that can be wrong with the input is found before the first write.
    auto position = validateScene(env, data);
    if (readSceneId(env, txn, name))
        throw Error(ErrorKind::Input, fmt::format("a scene named '{}' already exists", name), std::nullopt,
                    "choose another name, or remove the stored one first (DROP SCENE)");

    const NodeId sceneId = readNextId(env, txn);
    SceneWriter write(env, txn, state.record, data, std::move(position), sceneId);
    write.nodes();
    write.children();
    write.labels();
    write.sourceIds();
    write.relations();
    write.blobs();
    write.scene();
    storeSceneIndex(env, txn, sceneId, state.record);
    return sceneId;
}

}  // namespace smql::storage
