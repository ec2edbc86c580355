#include "fleet/local/local_scenes.hpp"

#include <chrono>
#include <random>
#include <unordered_map>

#include <fmt/format.h>

#include "model/error.hpp"
#include "storage/database.hpp"

namespace smql::fleet {

namespace {

// Database ids -> local ids 1..n in the order of `nodes` (the scene node, when present, is left
// out: it is the root, parent 0).
class LocalIds {
public:
    explicit LocalIds(const std::vector<model::Node>& nodes) {
        for (const auto& n : nodes)
            if (n.kind != model::NodeKind::Scene) ids_.emplace(n.id, ids_.size() + 1);
    }
    model::NodeId operator()(model::NodeId id) const {
        auto it = ids_.find(id);
        return it == ids_.end() ? model::kNoNode : it->second;
    }

private:
    std::unordered_map<model::NodeId, model::NodeId> ids_;
};

// A scene's nodes and relations in local ids, as `smql export json` numbers them.
void renumber(model::SceneData& data, const LocalIds& local) {
    for (auto& n : data.nodes) {
        n.id = local(n.id);
        n.parent = local(n.parent);
        n.scene = model::kNoNode;
    }
    for (auto& r : data.relations) r.subject = local(r.subject), r.object = local(r.object), r.frame = local(r.frame);
    for (auto& b : data.blobs) b.node = local(b.node);
    data.info.id = model::kNoNode;
    data.info.nodeCount = 0;
    data.info.version = 0;
}

// A superseded version as it travels; `after` of its changes is mapped by the next version's ids.
SceneVersionData fromHistory(const model::SceneVersion& stored, const LocalIds& next) {
    SceneVersionData out;
    out.version = stored.number;
    out.data.info = stored.info;
    for (const auto& n : stored.nodes)
        if (n.kind != model::NodeKind::Scene) out.data.nodes.push_back(n);
    out.data.relations = stored.relations;
    LocalIds local(stored.nodes);
    renumber(out.data, local);
    out.supersededAt = stored.supersededAt;
    out.changes = stored.changes;
    for (auto& c : out.changes) c.before = local(c.before), c.after = next(c.after);
    return out;
}

std::string randomUuid() {
    std::random_device random;
    std::uniform_int_distribution<unsigned> byte(0, 255);
    unsigned char b[16];
    for (auto& x : b) x = static_cast<unsigned char>(byte(random));
    b[6] = static_cast<unsigned char>((b[6] & 0x0f) | 0x40);  // version 4: random
    b[8] = static_cast<unsigned char>((b[8] & 0x3f) | 0x80);  // RFC 4122 variant
    return fmt::format(
        "{:02x}{:02x}{:02x}{:02x}-{:02x}{:02x}-{:02x}{:02x}-{:02x}{:02x}-{:02x}{:02x}{:02x}{:02x}{:02x}{:02x}", b[0],
        b[1], b[2], b[3], b[4], b[5], b[6], b[7], b[8], b[9], b[10], b[11], b[12], b[13], b[14], b[15]);
}

}  // namespace

std::string PushReport::summary() const {
    return fmt::format("pushed {} scene version{} ({} nodes) of device {}; {} {} there already; {:.2f} s", sent,
                       sent == 1 ? "" : "s", nodes, device, present, present == 1 ? "was" : "were", seconds);
}

std::string deviceId(storage::Database& database) {
    if (auto stored = database.beginRead().setting(kDeviceSetting)) return *stored;
    if (database.readOnly())
        throw Error(ErrorKind::Storage,
                    fmt::format("database {} has no device id yet and is open read-only", database.directory()),
                    std::nullopt, "the first push makes the id and stores it: open the database read-write");
    auto txn = database.beginWrite();
    // Another process may have made it since the read: the write transaction reads what it committed.
    if (auto stored = txn.setting(kDeviceSetting)) return *stored;
    std::string id = randomUuid();
    txn.putSetting(kDeviceSetting, id);
    txn.commit();
    return id;
}

LocalSource localSource(storage::Database& database) {
    LocalSource source;
    source.device = deviceId(database);
    auto txn = database.beginRead();
    for (const auto& info : txn.scenes()) source.scenes.push_back({info.name, txn.history(info.name).size() + 1});
    source.read = [&database](const std::string& scene) { return readVersions(database, scene); };
    return source;
}

std::vector<SceneVersionData> readVersions(storage::Database& database, const std::string& scene) {
    auto txn = database.beginRead();
    auto info = txn.sceneByName(scene);
    if (!info) throw Error(ErrorKind::Binding, fmt::format("no scene named '{}' in {}", scene, database.directory()));
    SceneVersionData current;
    current.data.info = *info;
    txn.forEachNodeInScene(info->id, [&](const model::Node& n) {
        if (n.kind == model::NodeKind::Scene) return;
        current.data.nodes.push_back(n);
        for (const auto& blob : txn.blobsOf(n.id))
            if (auto stored = txn.blob(n.id, blob.name)) current.data.blobs.push_back(std::move(*stored));
    });
    current.data.relations = txn.relationsInScene(info->id);
    LocalIds currentIds(current.data.nodes);

    std::vector<model::SceneVersion> history = txn.history(scene);
    std::vector<SceneVersionData> out;
    out.reserve(history.size() + 1);
    for (std::size_t i = 0; i < history.size(); ++i) {
        const LocalIds next = i + 1 < history.size() ? LocalIds(history[i + 1].nodes) : currentIds;
        out.push_back(fromHistory(history[i], next));
    }
    renumber(current.data, currentIds);
    current.version = history.size() + 1;
    out.push_back(std::move(current));
    return out;
}

void storePulled(storage::Database& database, const SceneVersionData& version) {
    auto txn = database.beginWrite();
    txn.importScene(version.data);
    txn.commit();
}

}  // namespace smql::fleet
