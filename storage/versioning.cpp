// Versions of a scene: replacing it by its next version (the stored one goes to the history table),
// dropping and renaming it, updating nodes in place, and reading its history.
#include <cstring>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <fmt/format.h>

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

[[noreturn]] void noSuchScene(NodeId sceneId) {
    throw Error(ErrorKind::Binding, fmt::format("no scene with id {}", sceneId), std::nullopt,
                "SHOW SCENES lists the scenes of the database");
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

// Deletes a node's label entry, found by its ids (the entry's first 16 bytes, of either size).
void eraseLabel(const Environment& env, MDB_txn* txn, std::string_view category, NodeId sceneId, NodeId nodeId) {
    Cursor cursor(env, txn, Table::Labels);
    auto ids = codec::labelPrefix(sceneId, nodeId);
    MDB_val key = toVal(category), value = toVal(ids);
    int rc = mdb_cursor_get(cursor.get(), &key, &value, MDB_GET_BOTH_RANGE);
    if (rc == MDB_NOTFOUND) return;
    env.check(rc, "dropping a label");
    if (value.mv_size < ids.size() || std::memcmp(value.mv_data, ids.data(), ids.size()) != 0) return;
    env.check(mdb_cursor_del(cursor.get(), 0), "dropping a label");
}

// Deletes a scene's nodes, relations, index entries and records; its history stays.
void eraseScene(const Environment& env, MDB_txn* txn, const SceneInfo& scene) {
    const NodeId sceneId = scene.id;

    // What the index entries are keyed by, copied out of the map before any
    // delete can move the pages it points into.
    struct Doomed {
        NodeId id;
        std::string category;
        std::optional<std::int64_t> sourceId;
        bool labelled;
    };
    std::vector<Doomed> doomed;
    doomed.reserve(scene.nodeCount + 1);
    {
        Cursor nodes(env, txn, Table::Nodes);
        forEachStoredNode(env, txn, nodes.get(), sceneId, [&](const Node& node) {
            bool labelled = node.kind != model::NodeKind::Scene && !node.category.empty();
            doomed.push_back({node.id, labelled ? node.category : std::string(), node.sourceId, labelled});
        });
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
        if (node.labelled) eraseLabel(env, txn, node.category, sceneId, node.id);
        if (node.sourceId) {
            auto source = codec::sourceKey(sceneId, *node.sourceId);
            erase(Table::SourceIds, toVal(source), nullptr);
        }
    }
    auto key = codec::idKey(sceneId);
    erase(Table::Scenes, toVal(key), nullptr);
    erase(Table::SceneNames, toVal(scene.name), nullptr);
    erase(Table::SceneIndex, toVal(key), nullptr);
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

void eraseHistory(const Environment& env, MDB_txn* txn, std::string_view sceneName) {
    std::vector<std::string> keys;
    scanHistory(env, txn, sceneName, [&](std::string_view key, std::string_view) { keys.emplace_back(key); });
    for (const auto& key : keys) {
        MDB_val k = toVal(key);
        env.check(mdb_del(txn, env.dbi(Table::History), &k, nullptr), "erasing the history of a scene");
    }
}

}  // namespace

std::vector<model::SceneVersion> ReadTransaction::history(std::string_view sceneName) const {
    const Impl& state = live();
    std::vector<model::SceneVersion> out;
    scanHistory(*state.env, state.txn, sceneName, [&](std::string_view key, std::string_view value) {
        try {
            out.push_back(codec::decodeVersion(key, value));
        } catch (const codec::CorruptRecord& e) {
            throw Error(ErrorKind::Storage,
                        fmt::format("corrupt record in the history of scene '{}' of database {}: {}", sceneName,
                                    state.env->directory(), e.detail()),
                        std::nullopt, e.hint());
        }
    });
    return out;
}

void WriteTransaction::dropScene(NodeId sceneId) {
    const Impl& state = live();
    auto info = readScene(*state.env, state.txn, sceneId);
    if (!info) noSuchScene(sceneId);
    eraseScene(*state.env, state.txn, *info);
    eraseHistory(*state.env, state.txn, info->name);
}

WriteTransaction::Replacement WriteTransaction::replaceScene(NodeId sceneId, model::SceneData data,
                                                             const std::string& supersededAt,
                                                             std::vector<model::ObjectChange> changes,
                                                             const std::vector<std::pair<NodeId, NodeId>>& carried) {
    Impl& state = live();
    const Environment& env = *state.env;
    MDB_txn* txn = state.txn;
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
    codec::encodeVersion(key, superseded, state.record);
    MDB_val k = toVal(key), v = toVal(state.record);
    env.check(mdb_put(txn, env.dbi(Table::History), &k, &v, MDB_NOOVERWRITE), "storing a version of a scene");
    return {newScene, superseded.number};
}

void WriteTransaction::renameScene(NodeId sceneId, const std::string& newName) {
    Impl& state = live();
    const Environment& env = *state.env;
    MDB_txn* txn = state.txn;
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
    codec::encodeScene(*info, state.record);
    MDB_val k = toVal(key), v = toVal(state.record);
    env.check(mdb_put(txn, env.dbi(Table::Scenes), &k, &v, 0), "renaming a scene");
    MDB_val oldKey = toVal(oldName);
    env.check(mdb_del(txn, env.dbi(Table::SceneNames), &oldKey, nullptr), "renaming a scene");
    MDB_val newKey = toVal(newName), idVal = toVal(key);
    env.check(mdb_put(txn, env.dbi(Table::SceneNames), &newKey, &idVal, MDB_NOOVERWRITE), "renaming a scene");
    auto bytes = lookup(env, txn, Table::Nodes, toVal(key), "reading a node");
    if (!bytes) throw Error(ErrorKind::Storage, fmt::format("scene '{}' has no scene node", oldName));
    Node sceneNode = decodeInScene(env, txn, sceneId, [&] { return codec::decodeNode(sceneId, *bytes); });
    sceneNode.category = newName;
    codec::encodeNode(sceneNode, state.record);
    v = toVal(state.record);
    env.check(mdb_put(txn, env.dbi(Table::Nodes), &k, &v, 0), "renaming a scene");

    // The history moves with the name: each record is sealed with its key, so it is re-encoded.
    std::vector<model::SceneVersion> versions;
    scanHistory(env, txn, oldName,
                [&](std::string_view hk, std::string_view hv) { versions.push_back(codec::decodeVersion(hk, hv)); });
    eraseHistory(env, txn, oldName);
    for (auto& version : versions) {
        std::string hk = codec::historyKey(newName, version.number);
        codec::encodeVersion(hk, version, state.record);
        MDB_val hkv = toVal(hk), hvv = toVal(state.record);
        env.check(mdb_put(txn, env.dbi(Table::History), &hkv, &hvv, MDB_NOOVERWRITE), "renaming a scene");
    }
    storeSceneIndex(env, txn, sceneId, state.record);
}

void WriteTransaction::updateNodes(const std::vector<Node>& nodes) {
    Impl& state = live();
    const Environment& env = *state.env;
    MDB_txn* txn = state.txn;
    std::set<NodeId> scenes;
    // The label entries the update changes (they carry the box): old and new, per node.
    struct Relabel {
        const Node* node;
        codec::LabelEntry before, after;
    };
    std::vector<Relabel> labels;
    // Check every node before the first write, so a refused update writes nothing.
    for (const Node& node : nodes) {
        auto key = codec::idKey(node.id);
        auto bytes = lookup(env, txn, Table::Nodes, toVal(key), "reading a node");
        if (!bytes) importError(fmt::format("node #{} does not exist", node.id));
        checkBox(node, [&] { return fmt::format("node #{}", node.id); });
        Node stored = decodeInScene(env, txn, node.id, [&] { return codec::decodeNode(node.id, *bytes); });
        if (stored.kind != node.kind || stored.scene != node.scene || stored.parent != node.parent ||
            stored.category != node.category || stored.sourceId != node.sourceId ||
            stored.kind == model::NodeKind::Scene)
            importError(
                fmt::format("node #{}: an update may change attributes, text, confidence and the box, not its "
                            "kind, scene, parent, category or source id",
                            node.id));
        scenes.insert(node.scene);
        if (!node.category.empty()) {
            auto before = codec::labelEntry(node.category, node.scene, node.id, stored);
            auto after = codec::labelEntry(node.category, node.scene, node.id, node);
            if (before != after) labels.push_back({&node, before, after});
        }
    }
    for (const Relabel& label : labels) {
        eraseLabel(env, txn, label.node->category, label.node->scene, label.node->id);
        MDB_val k = toVal(label.node->category), v = toVal(label.after);
        env.check(mdb_put(txn, env.dbi(Table::Labels), &k, &v, 0), "updating a label");
    }
    for (const Node& node : nodes) {
        codec::encodeNode(node, state.record);
        auto key = codec::idKey(node.id);
        MDB_val k = toVal(key), v = toVal(state.record);
        env.check(mdb_put(txn, env.dbi(Table::Nodes), &k, &v, 0), "updating a node");
    }
    // A new version tells every cached snapshot of these scenes to reload.
    for (NodeId sceneId : scenes) {
        auto info = readScene(env, txn, sceneId);
        if (!info) continue;
        ++info->version;
        codec::encodeScene(*info, state.record);
        auto key = codec::idKey(sceneId);
        MDB_val k = toVal(key), v = toVal(state.record);
        env.check(mdb_put(txn, env.dbi(Table::Scenes), &k, &v, 0), "updating a scene's version");
        storeSceneIndex(env, txn, sceneId, state.record);
    }
}

}  // namespace smql::storage
