#include "engine/engine.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <optional>
#include <unordered_map>

#include <fmt/format.h>

#include "engine/binder/binder.hpp"
#include "model/error.hpp"
#include "engine/exec/executor.hpp"
#include "engine/exec/scene_snapshot.hpp"
#include "model/names.hpp"
#include "engine/parser/parser.hpp"
#include "engine/planner/planner.hpp"
#include "engine/relations/hierarchy.hpp"
#include "storage/database.hpp"

namespace smql {

using exec::SceneSnapshot;
using exec::Slot;

namespace {

constexpr std::size_t kStatementCacheSize = 512;
// Decoded scenes kept in memory; the least recently used one goes first.
constexpr std::size_t kSnapshotCacheSize = 32;

}  // namespace

struct Engine::State {
    std::unique_ptr<storage::Database> db;
    exec::Session session;
    struct CachedSnapshot {
        std::shared_ptr<const SceneSnapshot> snapshot;
        std::uint64_t lastUse = 0;
    };
    std::unordered_map<model::NodeId, CachedSnapshot> snapshots;
    std::uint64_t useCounter = 0;
    std::unordered_map<std::string, std::shared_ptr<const std::vector<ast::Statement>>> statements;
    std::mutex mutex;
    // Set by interrupt() from any thread; the running statement polls it. Not under the mutex.
    std::atomic<bool> interrupt{false};

    std::shared_ptr<const std::vector<ast::Statement>> parse(std::string_view text) {
        std::string key(text);
        if (auto it = statements.find(key); it != statements.end()) return it->second;
        auto parsed = std::make_shared<const std::vector<ast::Statement>>(parser::parse(text));
        if (statements.size() >= kStatementCacheSize) statements.clear();
        statements.emplace(std::move(key), parsed);
        return parsed;
    }

    // The current scene as of the last statement, and the snapshot id it was read in: while no write
    // has committed since, it is still right, and the statement skips the lookup.
    std::optional<model::SceneInfo> resolved;
    std::uint64_t resolvedInTransaction = 0;

    model::SceneInfo currentScene(const storage::ReadTransaction& txn) {
        if (resolved && resolved->name == session.sceneName && resolvedInTransaction == txn.transactionId())
            return *resolved;
        resolved = lookUpCurrentScene(txn);
        resolvedInTransaction = txn.transactionId();
        return *resolved;
    }

    model::SceneInfo lookUpCurrentScene(const storage::ReadTransaction& txn) {
        if (!session.sceneName.empty()) {
            if (auto info = txn.sceneByName(session.sceneName)) return *info;
            throw Error(ErrorKind::Binding, fmt::format("scene '{}' no longer exists", session.sceneName), std::nullopt,
                        "SHOW SCENES lists the scenes; USE SCENE 'name' picks one");
        }
        auto scenes = txn.scenes();
        if (scenes.empty())
            throw Error(ErrorKind::Binding, "the database holds no scene yet", std::nullopt,
                        "import or ingest a scene first (docs/formats.md lists the formats)");
        // The most recently imported scene, chosen once: later statements keep using it.
        const auto* latest = &scenes.front();
        for (const auto& s : scenes)
            if (s.id > latest->id) latest = &s;
        session.sceneName = latest->name;
        return *latest;
    }

    std::shared_ptr<const SceneSnapshot> snapshot(const storage::ReadTransaction& txn, const model::SceneInfo& info) {
        auto it = snapshots.find(info.id);
        if (it == snapshots.end() || it->second.snapshot->info().version != info.version) {
            if (it == snapshots.end() && snapshots.size() >= kSnapshotCacheSize) {
                auto oldest = std::min_element(snapshots.begin(), snapshots.end(), [](const auto& a, const auto& b) {
                    return a.second.lastUse < b.second.lastUse;
                });
                snapshots.erase(oldest);
            }
            it = snapshots.insert_or_assign(info.id, CachedSnapshot{SceneSnapshot::load(txn, info), 0}).first;
        }
        it->second.lastUse = ++useCounter;
        return it->second.snapshot;
    }
};

Engine::Engine(std::unique_ptr<State> state) : state_(std::move(state)) {}
Engine::~Engine() = default;

std::unique_ptr<Engine> Engine::open(const std::string& directory, bool readOnly) {
    auto state = std::make_unique<State>();
    storage::OpenOptions options;
    options.readOnly = readOnly;
    options.create = !readOnly;
    state->db = storage::Database::open(directory, options);
    return std::unique_ptr<Engine>(new Engine(std::move(state)));
}

storage::CheckReport Engine::check(const std::string& directory) { return storage::checkDatabase(directory); }

storage::Database& Engine::database() { return *state_->db; }

void Engine::interrupt() { state_->interrupt = true; }

std::vector<ResultSet> Engine::execute(std::string_view text) {
    std::vector<ResultSet> results;
    execute(text, [&](ResultSet&& rs) { results.push_back(std::move(rs)); });
    return results;
}

void Engine::execute(std::string_view text, const std::function<void(ResultSet&&)>& onResult) {
    std::lock_guard lock(state_->mutex);
    state_->interrupt = false;  // an interrupt stops the statements running when it comes, not later ones
    auto statements = state_->parse(text);
    for (const auto& statement : *statements) {
        auto start = std::chrono::steady_clock::now();
        auto txn = state_->db->beginRead();
        binder::Binder binder({txn, state_->session, [&] {
                                   return state_->snapshot(txn, state_->currentScene(txn));
                               }});
        auto plan = planner::plan(std::make_shared<const binder::BoundStatement>(binder.bind(statement)));
        auto rs = exec::Executor(txn, state_->session, plan, &state_->interrupt).run();
        rs.elapsedMicroseconds =
            std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
        onResult(std::move(rs));
    }
}

model::NodeId Engine::importScene(model::SceneData scene) {
    std::lock_guard lock(state_->mutex);
    relations::assignParents(scene, state_->session.thresholds);
    auto txn = state_->db->beginWrite();
    auto id = txn.importScene(scene);
    txn.commit();
    state_->session.sceneName = scene.info.name;
    state_->session.allScenes = false;
    return id;
}

model::SceneData Engine::readScene(const std::string& name) {
    std::lock_guard lock(state_->mutex);
    auto txn = state_->db->beginRead();
    auto info = name.empty() ? state_->currentScene(txn) : txn.sceneByName(name).value_or(model::SceneInfo{});
    if (info.id == model::kNoNode)
        throw Error(ErrorKind::Binding, fmt::format("no scene named '{}'", name), std::nullopt,
                    "SHOW SCENES lists the scenes");
    auto snap = state_->snapshot(txn, info);
    model::SceneData out;
    out.info = info;
    for (const auto& n : snap->nodes()) {
        if (n.kind == model::NodeKind::Scene) continue;
        out.nodes.push_back(n);
        for (const auto& blob : txn.blobsOf(n.id))
            if (auto stored = txn.blob(n.id, blob.name)) out.blobs.push_back(std::move(*stored));
    }
    out.relations = snap->storedRelations();
    return out;
}

std::vector<model::Blob> Engine::evidence(model::NodeId node) {
    std::lock_guard lock(state_->mutex);
    auto txn = state_->db->beginRead();
    if (!txn.node(node)) throw Error(ErrorKind::Binding, fmt::format("no node #{}", node), std::nullopt, "FIND lists node ids");
    std::vector<model::Blob> out;
    for (const auto& info : txn.blobsOf(node))
        if (auto blob = txn.blob(node, info.name)) out.push_back(std::move(*blob));
    return out;
}

model::SceneData Engine::exportScene(const std::string& name) {
    model::SceneData out = readScene(name);
    // Local ids 1..n in database-id order; the scene root is implied by parent 0.
    std::unordered_map<model::NodeId, model::NodeId> local;
    for (const auto& n : out.nodes) local.emplace(n.id, local.size() + 1);
    auto localId = [&](model::NodeId id) {
        auto it = local.find(id);
        return it == local.end() ? model::kNoNode : it->second;
    };
    for (auto& n : out.nodes) {
        n.id = localId(n.id);
        n.parent = localId(n.parent);
        n.scene = model::kNoNode;
    }
    for (auto& r : out.relations) r.subject = localId(r.subject), r.object = localId(r.object), r.frame = localId(r.frame);
    for (auto& b : out.blobs) b.node = localId(b.node);
    out.info.id = model::kNoNode;
    out.info.nodeCount = 0;
    out.info.version = 0;
    return out;
}

void Engine::updateNodes(const std::vector<model::Node>& nodes) {
    std::lock_guard lock(state_->mutex);
    auto txn = state_->db->beginWrite();
    txn.updateNodes(nodes);
    txn.commit();
}

std::string Engine::currentScene() const {
    std::lock_guard lock(state_->mutex);
    if (state_->session.allScenes) return "*";
    auto txn = state_->db->beginRead();
    auto scenes = txn.scenes();
    if (scenes.empty()) return {};
    return state_->currentScene(txn).name;
}

std::vector<std::string> Engine::knownCategories() const {
    std::lock_guard lock(state_->mutex);
    auto txn = state_->db->beginRead();
    std::vector<std::string> out;
    for (const auto& [name, count] : txn.categories()) out.push_back(name);
    return out;
}

// -------------------------------------------------------- refreshing a scene

Engine::SceneRefresh Engine::refreshScene(const std::string& name, const model::SceneData& observed,
                                          const ObjectMatcher& match) {
    std::lock_guard lock(state_->mutex);
    // Reading in the write transaction is what makes the counts exact: a
    // second refresher waits for this one's commit before it reads them.
    auto txn = state_->db->beginWrite();
    std::string sceneName = name;
    if (sceneName.empty()) sceneName = state_->currentScene(state_->db->beginRead()).name;
    auto info = txn.sceneByName(sceneName);
    if (!info)
        throw Error(ErrorKind::Binding, fmt::format("no scene named '{}'", sceneName), std::nullopt,
                    "SHOW SCENES lists the scenes");
    model::SceneData stored;
    stored.info = *info;
    txn.forEachNodeInScene(info->id, [&](const model::Node& n) {
        if (n.kind != model::NodeKind::Scene) stored.nodes.push_back(n);
    });

    std::unordered_map<model::NodeId, const model::Node*> storedById;
    for (const auto& n : stored.nodes) storedById.emplace(n.id, &n);
    std::vector<model::Node> updated;
    for (const auto& [storedId, observedId] : match(stored, observed)) {
        model::Node node = *storedById.at(storedId);
        auto set = [&](const std::string& attribute, const std::string& value) {
            auto it = std::find_if(node.attributes.begin(), node.attributes.end(),
                                   [&](const auto& a) { return a.name == attribute; });
            if (it == node.attributes.end()) node.attributes.push_back({attribute, value});
            else it->value = value;
        };
        const std::string* seen = node.attribute("captures");
        set("captures", std::to_string((seen ? std::stoi(*seen) : 1) + 1));
        set("last_seen_at", observed.info.captureTime);
        std::sort(node.attributes.begin(), node.attributes.end(),
                  [](const auto& a, const auto& b) { return a.name < b.name; });
        updated.push_back(std::move(node));
    }
    txn.updateNodes(updated);
    txn.commit();

    SceneRefresh out;
    out.seenAgain = updated.size();
    for (const auto& n : stored.nodes) out.storedObjects += n.kind == model::NodeKind::Object && !n.hidden;
    return out;
}

}  // namespace smql
