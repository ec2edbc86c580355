#include "engine/engine.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <optional>
#include <unordered_map>

#include <fmt/format.h>

#include "engine/binder/binder.hpp"
#include "engine/binder/shape_cache.hpp"
#include "engine/catalog/scene_snapshot.hpp"
#include "engine/exec/executor.hpp"
#include "engine/history/scene_update.hpp"
#include "engine/parser/normalise.hpp"
#include "engine/parser/parser.hpp"
#include "engine/planner/planner.hpp"
#include "model/category.hpp"
#include "model/error.hpp"
#include "model/instant.hpp"
#include "model/names.hpp"
#include "model/points.hpp"
#include "relations/hierarchy.hpp"
#include "storage/database.hpp"

namespace smql {

using catalog::SceneSnapshot;
using catalog::Slot;

namespace {

constexpr std::size_t kStatementCacheSize = 512;

// Decoded scenes kept in memory; the least recently used one goes first.
constexpr std::size_t kSnapshotCacheSize = 32;

}  // namespace

struct Engine::State {
    // Texts hashed and compared as views, so that looking one up copies nothing. A member, not a type of the
    // file's anonymous namespace: State is declared in engine.hpp, and a field of such a type would give it
    // internal linkage in part (GCC's -Wsubobject-linkage).
    struct TextHash {
        using is_transparent = void;
        std::size_t operator()(std::string_view text) const { return std::hash<std::string_view>{}(text); }
    };
    std::unique_ptr<storage::Database> db;
    catalog::Session session;
    struct CachedSnapshot {
        std::shared_ptr<const SceneSnapshot> snapshot;
        std::uint64_t lastUse = 0;
    };
    std::unordered_map<model::NodeId, CachedSnapshot> snapshots;
    std::uint64_t useCounter = 0;
    // The snapshots handed out in the running call, which read the nodes they have not decoded yet
    // through its transaction; when the call ends they read through none.
    std::vector<std::shared_ptr<const SceneSnapshot>> reading;
    struct ReadsEnd {
        explicit ReadsEnd(State& running) : state(running) {}
        ReadsEnd(const ReadsEnd&) = delete;
        ReadsEnd& operator=(const ReadsEnd&) = delete;
        ~ReadsEnd() {
            for (const auto& snapshot : state.reading) snapshot->readThrough(nullptr);
            state.reading.clear();
        }
        State& state;
    };
    std::unordered_map<std::string, std::shared_ptr<const std::vector<ast::Statement>>, TextHash, std::equal_to<>>
        statements;
    // Texts that differ from one seen before only in their literals (binder/shape_cache.hpp).
    binder::ShapeCache shapes{static_cast<std::size_t>(session.limits.shapeCache)};
    std::mutex mutex;
    // Set by interrupt() from any thread; the running statement polls it. Not under the mutex.
    std::atomic<bool> interrupt{false};

    struct Parsed {
        std::shared_ptr<const std::vector<ast::Statement>> statements;
        bool fromShape = false;  // made from a cached shape: the parser has not seen this text
    };

    // The statements of `text`: the parse of the same text before, else (with `shaped`) a cached
    // shape's statement with this text's literals, else the parser's, whose shape is then learned.
    Parsed parse(std::string_view text, bool shaped) {
        if (auto it = statements.find(text); it != statements.end()) return {it->second};
        std::optional<parser::StatementShape> shape;
        if (shaped && shapes.capacity() > 0) shape = parser::statementShape(text);
        if (shape)
            if (std::optional<ast::Statement> statement = shapes.statementOf(*shape, text)) {
                auto one = std::make_shared<std::vector<ast::Statement>>();
                one->push_back(std::move(*statement));
                return {std::move(one), true};
            }
        auto parsed = std::make_shared<const std::vector<ast::Statement>>(parser::parse(text));
        if (shape && parsed->size() == 1) shapes.learn(*shape, parsed->front());
        if (statements.size() >= kStatementCacheSize) statements.clear();
        statements.emplace(std::string(text), parsed);
        return {parsed};
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

    // The scene called `name`, or the current one when `name` is empty.
    model::SceneInfo sceneNamed(const storage::ReadTransaction& txn, const std::string& name) {
        if (name.empty()) return currentScene(txn);
        if (auto info = txn.sceneByName(name)) return *info;
        throw Error(ErrorKind::Binding, fmt::format("no scene named '{}'", name), std::nullopt,
                    "SHOW SCENES lists the scenes");
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

    // One statement through bind, plan and execute in its own read transaction; `values` fill
    // its placeholders (binder/parameters.hpp). `kept` owns the statement when it may run again (a
    // prepared statement, a parse the engine keeps): its plan is then kept (keptPlan). The caller
    // holds the mutex.
    ResultSet run(const ast::Statement& statement, const std::vector<std::optional<ParameterValue>>& values,
                  const std::shared_ptr<const ast::Statement>& kept = nullptr) {
        const std::optional<CatalogQuery> catalog = catalogQuery(statement, values);
        if (catalog && catalog->countOnly)
            if (const auto* remembered = categoryCounts.find(catalog->category(), db->lastCommittedTransaction()))
                return countAnswer(remembered->count);
        auto txn = db->beginRead();
        if (catalog && !catalog->countOnly)
            if (auto rs = rememberedFind(txn, *catalog)) return std::move(*rs);
        ReadsEnd readsEnd{*this};
        const bool keeps = kept && keepsPlan(statement);
        std::shared_ptr<const planner::Plan> plan = keeps ? keptPlan(statement, values, txn) : nullptr;
        if (!plan) {
            binder::Binder binder({txn, session, [&] { return snapshot(txn, currentScene(txn)); },
                                   [&](const std::string& instant) { return snapshotAsOf(txn, instant); },
                                   &categoryCounts});
            plan = std::make_shared<const planner::Plan>(
                planner::plan(std::make_shared<const binder::BoundStatement>(binder.bind(statement, values))));
            if (keeps) keepPlan(kept, values, plan);
        }
        storage::Database* writer = db->readOnly() ? nullptr : db.get();
        auto rs = exec::Executor(txn, session, *plan, &interrupt, writer).run();
        shapes.setCapacity(static_cast<std::size_t>(session.limits.shapeCache));  // SET shape_cache, at once
        return rs;
    }

    // Plans of statements a connection runs again (prepared, or a text it has parsed before), each as
    // bound for its values, in its scene (or across all scenes) and in one committed transaction: the
    // binder reads nothing else (the settings and limits are read when the plan runs), so a run that
    // matches one goes from its read transaction to the executor. A commit (of any process) drops them
    // all; a plan goes with its scene's snapshot when the snapshot cache lets that go, so kept plans
    // hold no scene the cache does not. Statements with AS OF, and those that change the session or
    // the data, are bound each time.
    struct KeptPlan {
        std::shared_ptr<const ast::Statement> statement;  // kept alive, so its address names it alone
        std::vector<std::optional<ParameterValue>> values;
        std::string sceneName;
        bool allScenes = false;
        std::shared_ptr<const planner::Plan> plan;
    };
    static constexpr std::size_t kKeptPlans = 256;
    std::vector<KeptPlan> keptPlans;  // the most recently kept last
    std::uint64_t keptPlansTransaction = 0;

    // Whether the kept plans were bound in `txn`'s committed transaction; if not, they are dropped and
    // what is kept from now on is `txn`'s.
    bool keepingFor(const storage::ReadTransaction& txn) {
        if (keptPlansTransaction == txn.transactionId()) return true;
        keptPlans.clear();
        keptPlansTransaction = txn.transactionId();
        return false;
    }

    static bool keepsPlan(const ast::Statement& statement) {
        if (const auto* find = std::get_if<ast::FindStmt>(&statement.body)) return !find->asOf;
        if (const auto* count = std::get_if<ast::CountStmt>(&statement.body)) return !count->asOf;
        return std::holds_alternative<ast::RelateStmt>(statement.body) ||
               std::holds_alternative<ast::CheckStmt>(statement.body);
    }

    std::shared_ptr<const planner::Plan> keptPlan(const ast::Statement& statement,
                                                  const std::vector<std::optional<ParameterValue>>& values,
                                                  const storage::ReadTransaction& txn) {
        if (!keepingFor(txn)) return nullptr;
        for (auto it = keptPlans.rbegin(); it != keptPlans.rend(); ++it) {
            if (it->statement.get() != &statement || it->values != values || it->sceneName != session.sceneName ||
                it->allScenes != session.allScenes)
                continue;
            // The scene's snapshot reads the nodes it has not decoded yet through this transaction, as
            // when the binder is handed it (snapshot()).
            if (const auto& scene = it->plan->statement->scene) {
                if (auto cached = snapshots.find(scene->info().id); cached != snapshots.end())
                    cached->second.lastUse = ++useCounter;
                scene->readThrough(&txn);
                reading.push_back(scene);
            }
            return it->plan;
        }
        return nullptr;
    }

    // After keptPlan looked for the statement in the same read transaction (so the kept plans are that
    // transaction's).
    void keepPlan(const std::shared_ptr<const ast::Statement>& statement,
                  const std::vector<std::optional<ParameterValue>>& values, std::shared_ptr<const planner::Plan> plan) {
        if (keptPlans.size() >= kKeptPlans) keptPlans.erase(keptPlans.begin());
        // The session as binding left it: a first statement names the most recent scene (currentScene).
        keptPlans.push_back({statement, values, session.sceneName, session.allScenes, std::move(plan)});
    }

    // The categories named across all scenes, with their label keys and counts as read in the last
    // committed transaction a statement saw (binder/category_counts.hpp). While no process has
    // committed since (the database's last committed transaction is still that one), the same
    // COUNT has the same answer, and it is given without a read transaction, binder or plan; a FIND
    // of the same category reads the label index at once, without the binder or a plan.
    binder::CategoryCounts categoryCounts;

    // A FIND or COUNT of one category across all scenes with nothing but a LIMIT: its category (its
    // text, or its bound value lower-cased as the binder does) and limit. Any other statement (AS OF,
    // WHERE, VIEW, NEAREST TO, ORDER BY, SIMILAR TO, PATH, RETURN, one scene, a value missing or of
    // another type) is not answered early, and the binder words whatever is wrong with it.
    struct CatalogQuery {
        std::string_view name;  // the statement's text or its bound value, which outlive the run
        std::string folded;     // the bound value lower-cased, when it was not
        std::optional<std::int64_t> limit;
        bool countOnly = false;
        std::string_view category() const { return folded.empty() ? name : std::string_view(folded); }
    };

    std::optional<CatalogQuery> catalogQuery(const ast::Statement& statement,
                                             const std::vector<std::optional<ParameterValue>>& values) const {
        if (!session.allScenes || values.size() != statement.parameterCount) return std::nullopt;
        std::size_t placeholders = 0;
        auto bound = [&]<class T>(const ast::Placeholder& placeholder, const T*) -> const T* {
            if (placeholder.nodeId || placeholder.index == 0 || placeholder.index > values.size() ||
                !values[placeholder.index - 1])
                return nullptr;
            ++placeholders;
            return std::get_if<T>(&*values[placeholder.index - 1]);
        };
        const ast::Ref* target = nullptr;
        CatalogQuery query;
        if (const auto* count = std::get_if<ast::CountStmt>(&statement.body)) {
            if (count->asOf || count->view || count->where) return std::nullopt;
            target = &count->target;
            query.countOnly = true;
        } else if (const auto* find = std::get_if<ast::FindStmt>(&statement.body)) {
            if (find->asOf || find->view || find->where || find->nearestTo || find->orderBy || find->similarTo ||
                find->path || !find->columns.empty())
                return std::nullopt;
            target = &find->target;
            query.limit = find->limit;
            if (find->limitParam) {
                const auto* limit = bound(*find->limitParam, static_cast<const std::int64_t*>(nullptr));
                if (!limit || *limit < 0) return std::nullopt;
                query.limit = *limit;
            }
        } else {
            return std::nullopt;
        }
        if (target->kind == ast::Ref::Kind::Name) {
            query.name = target->name;
        } else if (target->kind == ast::Ref::Kind::Param && target->side.empty()) {
            const auto* text = bound(target->placeholder, static_cast<const std::string*>(nullptr));
            if (!text || text->empty() || text->size() > parser::kMaxTextValue) return std::nullopt;
            if (std::any_of(text->begin(), text->end(), [](char c) { return c >= 'A' && c <= 'Z'; }))
                query.folded = parser::lowerCase(*text);
            else
                query.name = *text;
        } else {
            return std::nullopt;
        }
        // Every placeholder is one of these two (the others were ruled out above), each used once.
        if (placeholders != statement.parameterCount) return std::nullopt;
        return query;
    }

    // The rows of a FIND across all scenes whose category was bound in `txn`'s own committed transaction
    // (so its label keys and count are the ones the binder would work out again), read from the label
    // index as the executor reads them; none when it was not.
    std::optional<ResultSet> rememberedFind(const storage::ReadTransaction& txn, const CatalogQuery& query) const {
        const binder::CategoryCount* kept = categoryCounts.find(query.category(), txn.transactionId());
        if (!kept) return std::nullopt;
        return exec::catalogFind(txn, session, kept->keys.front(), kept->keys, query.limit, kept->count);
    }

    std::shared_ptr<const SceneSnapshot> snapshot(const storage::ReadTransaction& txn, const model::SceneInfo& info) {
        auto it = snapshots.find(info.id);
        if (it == snapshots.end() || it->second.snapshot->info().version != info.version) {
            if (it == snapshots.end() && snapshots.size() >= kSnapshotCacheSize) {
                auto oldest = std::min_element(snapshots.begin(), snapshots.end(), [](const auto& a, const auto& b) {
                    return a.second.lastUse < b.second.lastUse;
                });
                const SceneSnapshot* evicted = oldest->second.snapshot.get();
                std::erase_if(keptPlans,
                              [&](const KeptPlan& kept) { return kept.plan->statement->scene.get() == evicted; });
                snapshots.erase(oldest);
            }
            it = snapshots.insert_or_assign(info.id, CachedSnapshot{SceneSnapshot::load(txn, info), 0}).first;
        }
        it->second.lastUse = ++useCounter;
        it->second.snapshot->readThrough(&txn);
        reading.push_back(it->second.snapshot);
        return it->second.snapshot;
    }

    // The current scene as the memory held it at `instant`: the newest version captured at or
    // before it (the live one, or one from the history). Times compare in model::utcInstant's form.
    std::shared_ptr<const SceneSnapshot> snapshotAsOf(const storage::ReadTransaction& txn, const std::string& instant) {
        const model::SceneInfo live = currentScene(txn);
        if (model::comparableInstant(live.captureTime) <= instant) return snapshot(txn, live);
        auto versions = txn.history(live.name);
        for (auto v = versions.rbegin(); v != versions.rend(); ++v)
            if (model::comparableInstant(v->info.captureTime) <= instant) return SceneSnapshot::fromVersion(*v);
        const std::string& first = versions.empty() ? live.captureTime : versions.front().info.captureTime;
        throw Error(ErrorKind::Binding,
                    fmt::format("scene '{}' was first captured at {}: the memory holds nothing of it at {}", live.name,
                                first, instant),
                    std::nullopt, "SHOW CHANGES lists the updates of the scene and their times");
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
    State::Parsed parsed;
    try {
        parsed = state_->parse(text, true);
    } catch (const Error& e) {
        if (e.kind() != ErrorKind::Syntax) throw;
        // As sqlite3_exec: the statements before the one that does not parse run, then its error.
        for (const auto& statement : parser::parseBeforeError(text)) onResult(state_->run(statement, {}));
        throw;
    }
    if (parsed.fromShape) {
        // A statement from a shape reads and changes nothing (parser/normalise.hpp), so when it
        // fails it runs again from the parser's own reading, whose error names this text's
        // places: a shape's locations are those of its placeholder text.
        std::optional<ResultSet> result;
        try {
            result = state_->run(parsed.statements->front(), {});
        } catch (const Error& e) {
            if (e.kind() == ErrorKind::Interrupted) throw;
        }
        if (result) return onResult(std::move(*result));
        parsed = state_->parse(text, false);
    }
    for (const auto& statement : *parsed.statements)
        onResult(state_->run(statement, {}, std::shared_ptr<const ast::Statement>(parsed.statements, &statement)));
}

binder::ShapeCacheStats Engine::shapeCacheStats() const {
    std::lock_guard lock(state_->mutex);
    return state_->shapes.stats();
}

PreparedStatement Engine::prepare(std::string_view text) {
    std::shared_ptr<const std::vector<ast::Statement>> statements;
    {
        std::lock_guard lock(state_->mutex);
        // Not from a shape: the prepared statement's locations are its own text's.
        statements = state_->parse(text, false).statements;
    }
    if (statements->size() != 1)
        throw Error(ErrorKind::Usage,
                    fmt::format("a prepared statement is one statement; this text holds {}", statements->size()),
                    statements->at(1).where, "prepare each statement on its own");
    // Shares the cached parse: the AST is immutable, and values go into copies of it.
    return PreparedStatement(*this, std::shared_ptr<const ast::Statement>(statements, &statements->front()));
}

ResultSet Engine::executePrepared(const std::shared_ptr<const ast::Statement>& statement,
                                  const std::vector<std::optional<ParameterValue>>& values) {
    std::lock_guard lock(state_->mutex);
    state_->interrupt = false;  // as in execute(): only an interrupt during this run stops it
    return state_->run(*statement, values, statement);
}

PreparedStatement::PreparedStatement(Engine& engine, std::shared_ptr<const ast::Statement> statement)
    : engine_(&engine),
      statement_(std::move(statement)),
      slots_(binder::parameterSlots(*statement_)),
      values_(slots_.size()) {}

std::size_t PreparedStatement::parameterCount() const { return slots_.size(); }

void PreparedStatement::bind(std::size_t index, ParameterValue value) {
    if (index < 1 || index > slots_.size())
        throw Error(ErrorKind::Usage,
                    slots_.empty() ? fmt::format("no placeholder {}: the statement has none", index)
                                   : fmt::format("no placeholder {}: the statement has {} (1 to {})", index,
                                                 slots_.size(), slots_.size()),
                    std::nullopt, "placeholders are numbered from 1, in the order ? are written or by $n");
    if (auto why = binder::rejectedValue(slots_[index - 1], value))
        throw Error(ErrorKind::Usage, *why, slots_[index - 1].placeholder.where);
    values_[index - 1] = std::move(value);
}

void PreparedStatement::clearBindings() { std::fill(values_.begin(), values_.end(), std::nullopt); }

ResultSet PreparedStatement::execute() { return engine_->executePrepared(statement_, values_); }

const std::string& PreparedStatement::text() const { return statement_->text; }

model::NodeId Engine::importScene(model::SceneData scene) {
    std::lock_guard lock(state_->mutex);
    // Every write stores canonical category names (model/category.hpp), whoever made the scene:
    // an importer, ingest, or a program through the C API.
    model::canonicaliseCategories(scene);
    history::stampSeen(scene, model::utcNow());
    relations::assignParents(scene, state_->session.thresholds);
    auto txn = state_->db->beginWrite();
    auto id = txn.importScene(scene);
    txn.commit();
    state_->session.sceneName = scene.info.name;
    state_->session.allScenes = false;
    return id;
}

void Engine::checkIngestTarget(const std::string& name, const std::string& update) {
    std::lock_guard lock(state_->mutex);
    if (state_->db->readOnly())
        throw Error(ErrorKind::Storage, "the database is open read-only: an ingest cannot write its scene",
                    std::nullopt, "open it read-write");
    auto txn = state_->db->beginRead();
    if (!update.empty() && !txn.sceneByName(update))
        throw Error(ErrorKind::Binding, fmt::format("no scene named '{}' to update", update), std::nullopt,
                    "SHOW SCENES lists the scenes");
    if (update.empty() && txn.sceneByName(name))
        throw Error(ErrorKind::Input, fmt::format("a scene named '{}' already exists", name), std::nullopt,
                    fmt::format("choose another name (--scene), make the capture its next version (--update {}), "
                                "or remove the stored one first (DROP SCENE)",
                                name));
}

model::SceneData Engine::readScene(const std::string& name) {
    std::lock_guard lock(state_->mutex);
    auto txn = state_->db->beginRead();
    const model::SceneInfo info = state_->sceneNamed(txn, name);
    State::ReadsEnd readsEnd{*state_};
    auto snap = state_->snapshot(txn, info);
    model::SceneData out;
    out.info = info;
    for (const auto& n : snap->nodes()) {
        if (n.kind == model::NodeKind::Scene) continue;
        out.nodes.push_back(n);
        for (const auto& blob : txn.blobsOf(n.id))
            if (auto stored = txn.blob(n.id, blob.name)) out.blobs.push_back(std::move(*stored));
    }
    // The scene's own blobs (its points), under kNoNode as SceneData has them.
    for (const auto& blob : txn.blobsOf(info.id))
        if (auto stored = txn.blob(info.id, blob.name)) {
            stored->node = model::kNoNode;
            out.blobs.push_back(std::move(*stored));
        }
    out.relations = snap->storedRelations();
    return out;
}

std::string Engine::scenePoints(const std::string& name) {
    std::lock_guard lock(state_->mutex);
    auto txn = state_->db->beginRead();
    const model::SceneInfo info = state_->sceneNamed(txn, name);
    // The one blob, not the scene with every evidence crop.
    auto points = txn.blob(info.id, model::kPointsBlobName);
    if (!points)
        throw Error(ErrorKind::Input, fmt::format("scene '{}' holds no points", info.name), std::nullopt,
                    "points come from smql ingest of a capture; a scene imported from a layout has boxes only");
    model::readPointsPly(points->bytes);  // a damaged blob is refused, not handed on
    return std::move(points->bytes);
}

std::vector<model::Blob> Engine::evidence(model::NodeId node) {
    std::lock_guard lock(state_->mutex);
    auto txn = state_->db->beginRead();
    if (!txn.node(node))
        throw Error(ErrorKind::Binding, fmt::format("no node #{}", node), std::nullopt, "FIND lists node ids");
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
    for (auto& r : out.relations)
        r.subject = localId(r.subject), r.object = localId(r.object), r.frame = localId(r.frame);
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

void Engine::setAskTranslator(std::shared_ptr<const ask::Translator> translator) {
    std::lock_guard lock(state_->mutex);
    state_->session.askTranslator = std::move(translator);
}

std::string Engine::askTranslatorName() const {
    std::lock_guard lock(state_->mutex);
    return state_->session.askTranslator ? state_->session.askTranslator->name() : "built-in";
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
    // Camera frames and descriptions carry their kind as their category ("frame", "description"):
    // no kind of thing a person names, unless some thing is called so too (a picture frame).
    auto namesAThing = [&](const std::string& category) {
        for (model::NodeId id : txn.nodesWithCategory(category)) {
            auto node = txn.node(id);
            if (node && node->kind != model::NodeKind::Frame && node->kind != model::NodeKind::Description) return true;
        }
        return false;
    };
    // Names stored before they were canonical are listed as their canonical name, once.
    for (const auto& [name, count] : txn.categories())
        if (namesAThing(name)) out.push_back(model::categoryName(name));
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

Engine::SceneMap Engine::sceneMap(const std::string& name) {
    std::lock_guard lock(state_->mutex);
    auto txn = state_->db->beginRead();
    const model::SceneInfo info = state_->sceneNamed(txn, name);
    State::ReadsEnd readsEnd{*state_};
    auto snapshot = state_->snapshot(txn, info);
    const auto& guidance = snapshot->guidance();
    SceneMap map{
        {snapshot->info(), snapshot->nodes(), snapshot->storedRelations(), {}}, guidance.graph, guidance.space};
    return map;
}

// -------------------------------------------------------- updating a scene

std::string Engine::SceneUpdateReport::summary() const {
    return fmt::format(
        "updated scene '{}' as of {}: {} objects seen again where they were, {} moved, {} new, {} missing, {} not "
        "looked at; the version before is kept in the scene's history (SHOW CHANGES lists the changes)",
        scene, time, unchanged, moved, added, missing, unseen);
}

std::optional<std::string> Engine::SceneUpdateReport::warning() const {
    // Matching compares positions in the scene's frame (docs/history.md, "Frames"): a capture of another place, or
    // one started from another origin, finds nothing again where it was however little changed, and takes a thing
    // of the same kind, size and colour anywhere for one that moved: the five dining frames' scene updated with
    // TUM's office photos found 0 again in place, 2 "moved" (chairs), 10 new.
    constexpr std::size_t kFewest = 3;
    const std::size_t stored = moved + missing + unseen;
    if (unchanged > 0 || stored < kFewest || added < kFewest || added <= moved) return std::nullopt;
    return fmt::format(
        "none of the {} stored objects was seen again where it was, and {} of the {} captured are new: a capture "
        "of another place, or of this one started from another origin, reads so (the stored version is read AS OF "
        "a time before this update)",
        stored, added, added + moved);
}

Engine::SceneUpdateReport Engine::updateScene(const std::string& name, const model::SceneData& observed) {
    std::lock_guard lock(state_->mutex);
    // Reading in the write transaction is what makes updates exact: a second updater waits
    // for this one's commit before it reads the scene.
    auto txn = state_->db->beginWrite();
    std::string sceneName = name;
    if (sceneName.empty()) sceneName = state_->currentScene(state_->db->beginRead()).name;
    auto info = txn.sceneByName(sceneName);
    if (!info)
        throw Error(ErrorKind::Binding, fmt::format("no scene named '{}'", sceneName), std::nullopt,
                    "SHOW SCENES lists the scenes");
    const std::string time =
        observed.info.captureTime.empty() ? model::utcNow() : model::comparableInstant(observed.info.captureTime);
    if (!info->captureTime.empty() && time < model::comparableInstant(info->captureTime))
        throw Error(ErrorKind::Input,
                    fmt::format("the capture was taken at {}, before the stored version of scene '{}' ({})", time,
                                sceneName, info->captureTime),
                    std::nullopt, "updates go forward in time: update with captures newer than the scene");

    model::SceneData stored;
    stored.info = *info;
    txn.forEachNodeInScene(info->id, [&](const model::Node& n) { stored.nodes.push_back(n); });
    stored.relations = txn.relationsInScene(info->id);
    // A version stored before names were canonical matches the capture by canonical names, and the
    // next version is stored with them (the old records are erased by their stored keys).
    model::canonicaliseCategories(stored);
    model::SceneData capture = observed;
    model::canonicaliseCategories(capture);

    history::SceneUpdate update = history::planUpdate(stored, capture, time);
    relations::assignParents(update.next, state_->session.thresholds);
    auto replaced = txn.replaceScene(info->id, update.next, time, update.changes, update.carried);
    txn.commit();

    SceneUpdateReport report;
    report.scene = sceneName;
    report.time = time;
    report.version = replaced.superseded;
    report.unchanged = update.unchanged;
    report.moved = update.moved;
    report.added = update.added;
    report.missing = update.missing;
    report.unseen = update.unseen;
    report.changes = std::move(update.changes);
    // The ids of the new version, as replaceScene stored them: local id k is the k-th node of the
    // new block, which begins with the scene node.
    for (auto& change : report.changes)
        if (change.after != model::kNoNode) change.after = replaced.scene + change.after;
    return report;
}

bool statementComplete(std::string_view text) {
    return text.find_first_not_of(" \t\r\n") != std::string_view::npos && !parser::isIncomplete(text);
}

const std::vector<std::string>& languageKeywords() { return parser::keywords(); }

const std::vector<std::string>& referenceSides() { return parser::sides(); }

}  // namespace smql
