#include "engine/engine.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <optional>
#include <unordered_map>

#include <fmt/format.h>

#include "engine/binder/binder.hpp"
#include "engine/error.hpp"
#include "engine/exec/executor.hpp"
#include "engine/exec/scene_snapshot.hpp"
#include "engine/model/names.hpp"
#include "engine/parser/parser.hpp"
#include "engine/planner/planner.hpp"
#include "engine/relations/hierarchy.hpp"
#include "storage/database.hpp"

namespace smql {

using exec::SceneSnapshot;
using exec::Slot;

namespace {

// "*" or "all": FIND and COUNT by category and attributes across every scene.
bool isAllScenes(std::string_view name) { return name == "*" || name == "all"; }

constexpr std::size_t kStatementCacheSize = 512;
// Decoded scenes kept in memory; the least recently used one goes first.
constexpr std::size_t kSnapshotCacheSize = 32;

}  // namespace

struct Engine::State {
    std::unique_ptr<storage::Database> db;
    relations::Thresholds thresholds;
    std::string sceneName;  // empty until chosen: USE SCENE, an import, or the most recent scene
    bool allScenes = false;
    struct CachedSnapshot {
        std::shared_ptr<const SceneSnapshot> snapshot;
        std::uint64_t lastUse = 0;
    };
    std::unordered_map<model::NodeId, CachedSnapshot> snapshots;
    std::uint64_t useCounter = 0;
    std::unordered_map<std::string, std::shared_ptr<const std::vector<ast::Statement>>> statements;
    std::mutex mutex;

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
        if (resolved && resolved->name == sceneName && resolvedInTransaction == txn.transactionId()) return *resolved;
        resolved = lookUpCurrentScene(txn);
        resolvedInTransaction = txn.transactionId();
        return *resolved;
    }

    model::SceneInfo lookUpCurrentScene(const storage::ReadTransaction& txn) {
        if (!sceneName.empty()) {
            if (auto info = txn.sceneByName(sceneName)) return *info;
            throw Error(ErrorKind::Binding, fmt::format("scene '{}' no longer exists", sceneName), std::nullopt,
                        "SHOW SCENES lists the scenes; USE SCENE 'name' picks one");
        }
        auto scenes = txn.scenes();
        if (scenes.empty())
            throw Error(ErrorKind::Binding, "the database holds no scene yet", std::nullopt,
                        "import one: smql import replica info_semantic.json --db DIR (or smql demo)");
        // The most recently imported scene, chosen once: later statements keep using it.
        const auto* latest = &scenes.front();
        for (const auto& s : scenes)
            if (s.id > latest->id) latest = &s;
        sceneName = latest->name;
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

storage::Database& Engine::database() { return *state_->db; }

namespace {

struct StatementRunner {
    Engine::State& state;
    const storage::ReadTransaction& txn;

    binder::Binder binderFor(const SceneSnapshot& scene) const {
        binder::BindContext ctx{
            scene, state.thresholds,
            [this](const std::string& category) { return !txn.nodesWithCategory(category).empty(); },
            [this, &scene](const ast::FindStmt& find) {
                auto bound = binderFor(scene).bindFind(find);
                auto plan = planner::planFind(bound, scene, state.thresholds);
                std::vector<Slot> slots;
                for (const auto& hit : exec::Executor(scene, state.thresholds).find(plan)) slots.push_back(hit.slot);
                std::sort(slots.begin(), slots.end());
                return slots;
            }};
        return binder::Binder(std::move(ctx));
    }

    ResultSet run(const ast::Statement& statement) {
        return std::visit([&](const auto& body) { return runBody(body, statement); }, statement.body);
    }

    std::shared_ptr<const SceneSnapshot> scene() { return state.snapshot(txn, state.currentScene(txn)); }

    ResultSet runBody(const ast::FindStmt& find, const ast::Statement&) {
        if (state.allScenes) return findAcrossScenes(find.target, find.where ? &*find.where : nullptr, find.limit, false);
        auto snap = scene();
        auto bound = binderFor(*snap).bindFind(find);
        auto plan = planner::planFind(bound, *snap, state.thresholds);
        return exec::Executor(*snap, state.thresholds).findRows(plan);
    }

    ResultSet runBody(const ast::CountStmt& count, const ast::Statement&) {
        if (state.allScenes)
            return findAcrossScenes(count.target, count.where ? &*count.where : nullptr, std::nullopt, true);
        auto snap = scene();
        auto bound = binderFor(*snap).bindCount(count);
        auto plan = planner::planFind(bound, *snap, state.thresholds);
        return exec::Executor(*snap, state.thresholds).findRows(plan);
    }

    ResultSet runBody(const ast::RelateStmt& relate, const ast::Statement&) {
        auto snap = scene();
        auto bound = binderFor(*snap).bindRelate(relate);
        return exec::Executor(*snap, state.thresholds).relate(bound);
    }

    ResultSet runBody(const ast::DescribeStmt& describe, const ast::Statement&) {
        auto snap = scene();
        auto nodes = binderFor(*snap).bindRef(describe.target, relations::viewFrame(snap->info().viewpoint));
        auto rs = exec::Executor(*snap, state.thresholds).describe(nodes);
        // Evidence lives in the blob table, not in the snapshot: list it from the transaction.
        for (Slot slot : nodes.slots) {
            auto id = snap->node(slot).id;
            for (const auto& blob : txn.blobsOf(id))
                rs.rows.push_back({static_cast<std::int64_t>(id), std::string("evidence"),
                                   fmt::format("{} ({}, {} bytes)", blob.name, blob.mediaType, blob.size)});
        }
        return rs;
    }

    ResultSet runBody(const ast::ShowStmt& show, const ast::Statement&) {
        switch (show.what) {
            case ast::ShowStmt::What::Scenes: return showScenes();
            case ast::ShowStmt::What::Settings: return showSettings();
            case ast::ShowStmt::What::Tree: {
                auto snap = scene();
                std::optional<Slot> root;
                if (show.root) {
                    auto nodes = binderFor(*snap).bindRef(*show.root, relations::viewFrame(snap->info().viewpoint));
                    if (nodes.slots.size() != 1)
                        throw Error(ErrorKind::Binding,
                                    fmt::format("SHOW TREE needs one node; {} names {}", nodes.description,
                                                nodes.slots.size()),
                                    show.root->where, "use #id or src#id");
                    root = nodes.slots.front();
                }
                return exec::Executor(*snap, state.thresholds).tree(root);
            }
        }
        return {};
    }

    ResultSet runBody(const ast::UseStmt& use, const ast::Statement&) {
        ResultSet rs;
        if (isAllScenes(use.scene)) {
            state.allScenes = true;
            rs.message = "using all scenes: FIND and COUNT by category and attributes";
            return rs;
        }
        if (!txn.sceneByName(use.scene)) {
            std::vector<std::string> names;
            for (const auto& s : txn.scenes()) names.push_back(s.name);
            auto close = model::nearestNames(use.scene, names);
            throw Error(ErrorKind::Binding, fmt::format("no scene named '{}'", use.scene), use.where,
                        close.empty() ? "SHOW SCENES lists the scenes" : "did you mean " + model::joinAlternatives(close) + "?");
        }
        state.sceneName = use.scene;
        state.allScenes = false;
        rs.message = fmt::format("using scene '{}'", use.scene);
        return rs;
    }

    ResultSet runBody(const ast::SetStmt& set, const ast::Statement&) {
        const auto* setting = relations::findSetting(set.name);
        if (!setting) {
            std::vector<std::string> names;
            for (const auto& s : relations::settingsCatalogue()) names.push_back(s.name);
            auto close = model::nearestNames(set.name, names);
            throw Error(ErrorKind::Binding, fmt::format("unknown setting '{}'", set.name), set.where,
                        close.empty() ? "SHOW SETTINGS lists them" : "did you mean " + model::joinAlternatives(close) + "?");
        }
        double value = 0;
        if (const auto* d = std::get_if<ast::Distance>(&set.value)) {
            if (setting->unit != relations::SettingUnit::Metres)
                throw Error(ErrorKind::Binding, fmt::format("{} is a ratio, not a distance", setting->name), set.where,
                            fmt::format("SET {} = 0.5", setting->name));
            value = d->metres;
        } else if (const auto* number = std::get_if<double>(&set.value)) {
            value = *number;  // a bare number for a distance setting is taken as metres
        } else {
            throw Error(ErrorKind::Binding, fmt::format("{} takes a number", setting->name), set.where,
                        setting->unit == relations::SettingUnit::Metres ? fmt::format("SET {} = 0.8 m", setting->name)
                                                                        : fmt::format("SET {} = 0.5", setting->name));
        }
        bool ratio = setting->unit == relations::SettingUnit::Ratio;
        if (!std::isfinite(value) || value < 0 || (ratio && value > 1) || (!ratio && value > 100))
            throw Error(ErrorKind::Binding, fmt::format("{} out of range for {}", value, setting->name), set.where,
                        ratio ? "ratios lie in [0, 1]" : "distances lie in [0, 100] m");
        state.thresholds.*(setting->field) = value;
        ResultSet rs;
        rs.message = fmt::format("{} = {}{}", setting->name, value, ratio ? "" : " m");
        return rs;
    }

    ResultSet runBody(const ast::ExplainStmt& explain, const ast::Statement&) {
        ResultSet rs;
        rs.columns = {{"plan", ValueType::Text}};
        const auto& inner = *explain.inner;
        auto snap = scene();
        auto binder = binderFor(*snap);
        std::optional<binder::BoundFind> bound;
        if (const auto* find = std::get_if<ast::FindStmt>(&inner.body)) bound = binder.bindFind(*find);
        if (const auto* count = std::get_if<ast::CountStmt>(&inner.body)) bound = binder.bindCount(*count);
        if (!bound) {
            rs.rows.push_back({std::string("Evaluate the statement directly (no plan choices)")});
            return rs;
        }
        auto plan = planner::planFind(*bound, *snap, state.thresholds);
        for (auto& line : plan.explain()) rs.rows.push_back({std::move(line)});
        return rs;
    }

    ResultSet showScenes() {
        ResultSet rs;
        rs.columns = {{"name", ValueType::Text},  {"id", ValueType::Integer},   {"nodes", ValueType::Integer},
                      {"source", ValueType::Text}, {"viewpoint", ValueType::Text}, {"current", ValueType::Text}};
        auto scenes = txn.scenes();
        std::optional<model::NodeId> current;
        if (!scenes.empty() && !state.allScenes) current = state.currentScene(txn).id;
        for (const auto& s : scenes) {
            std::string vp = fmt::format("({:.2f}, {:.2f}, {:.2f}) facing {:.0f} deg", s.viewpoint.position.x,
                                         s.viewpoint.position.y, s.viewpoint.position.z,
                                         s.viewpoint.facingYaw * 180.0 / M_PI);
            rs.rows.push_back({s.name, static_cast<std::int64_t>(s.id), static_cast<std::int64_t>(s.nodeCount), s.source,
                               vp, std::string(current && *current == s.id ? "*" : "")});
        }
        return rs;
    }

    ResultSet showSettings() {
        ResultSet rs;
        rs.columns = {{"name", ValueType::Text}, {"value", ValueType::Real}, {"unit", ValueType::Text},
                      {"meaning", ValueType::Text}};
        for (const auto& s : relations::settingsCatalogue())
            rs.rows.push_back({s.name, state.thresholds.*(s.field),
                               std::string(s.unit == relations::SettingUnit::Metres ? "m" : "ratio"), s.meaning});
        return rs;
    }

    // Category search over every scene through the label index: no snapshot is loaded.
    ResultSet findAcrossScenes(const ast::Ref& target, const ast::Expr* where, std::optional<std::int64_t> limit,
                               bool countOnly) {
        if (target.kind != ast::Ref::Kind::Name)
            throw Error(ErrorKind::Binding, "across all scenes, FIND and COUNT take a category", target.where,
                        "USE SCENE 'name' to query one scene by id, side or sub-query");
        if (where)
            throw Error(ErrorKind::Binding, "across all scenes, FIND and COUNT take no WHERE", where->where,
                        "metric predicates need one scene: USE SCENE 'name'");
        std::uint64_t total = txn.countWithCategory(target.name);
        if (total == 0) {
            std::vector<std::string> names;
            for (const auto& [name, count] : txn.categories()) names.push_back(name);
            auto close = model::nearestNames(target.name, names);
            throw Error(ErrorKind::Binding, fmt::format("unknown category '{}' in any scene", target.name),
                        target.where, close.empty() ? "" : "did you mean " + model::joinAlternatives(close) + "?");
        }
        ResultSet rs;
        if (countOnly) {
            rs.columns = {{"count", ValueType::Integer}};
            rs.rows.push_back({static_cast<std::int64_t>(total)});
            return rs;
        }
        auto ids = txn.nodesWithCategory(target.name, model::kNoNode,
                                         limit ? static_cast<std::size_t>(*limit) : SIZE_MAX);
        rs.columns = {{"id", ValueType::Integer},
                      {"category", ValueType::Text},
                      {"scene", ValueType::Integer},
                      {"source_id", ValueType::Integer},
                      {"box", ValueType::Box}};
        rs.rows.reserve(ids.size());
        model::Node node;
        for (auto id : ids) {
            if (!txn.readNode(id, node)) continue;
            rs.rows.push_back({static_cast<std::int64_t>(node.id), node.category, static_cast<std::int64_t>(node.scene),
                               node.sourceId ? Value(*node.sourceId) : Value(std::monostate{}),
                               node.geometry == model::GeometryKind::None ? Value(std::monostate{}) : Value(node.box)});
        }
        return rs;
    }
};

}  // namespace

std::vector<ResultSet> Engine::execute(std::string_view text) {
    std::vector<ResultSet> results;
    execute(text, [&](ResultSet&& rs) { results.push_back(std::move(rs)); });
    return results;
}

void Engine::execute(std::string_view text, const std::function<void(ResultSet&&)>& onResult) {
    std::lock_guard lock(state_->mutex);
    auto statements = state_->parse(text);
    for (const auto& statement : *statements) {
        auto start = std::chrono::steady_clock::now();
        auto txn = state_->db->beginRead();
        StatementRunner runner{*state_, txn};
        auto rs = runner.run(statement);
        rs.elapsedMicroseconds =
            std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
        onResult(std::move(rs));
    }
}

model::NodeId Engine::importScene(model::SceneData scene) {
    std::lock_guard lock(state_->mutex);
    relations::assignParents(scene, state_->thresholds);
    auto txn = state_->db->beginWrite();
    auto id = txn.importScene(scene);
    txn.commit();
    state_->sceneName = scene.info.name;
    state_->allScenes = false;
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
    if (state_->allScenes) return "*";
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

}  // namespace smql
