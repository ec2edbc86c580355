#include "bench/workload.hpp"

#include <algorithm>
#include <array>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

#include <fmt/format.h>
#include <fmt/ostream.h>
#include <fmt/ranges.h>

#include "bench/postgis_baseline.hpp"
#include "bench/sqlite_baseline.hpp"
#include "engine/engine.hpp"
#include "engine/parser/normalise.hpp"
#include "engine/parser/parser.hpp"
#include "model/error.hpp"
#include "storage/database.hpp"

namespace smql::bench {

using relations::Predicate;

namespace {

// Surfaces that carry small things in the generated rooms, most common first:
// a scene's FIND uses the first it has.
constexpr std::array<std::string_view, 4> kSurfaces = {"table", "desk", "counter", "sofa"};
constexpr std::array<std::string_view, 10> kSmallCategories = {"mug",    "book", "lamp", "plant", "laptop",
                                                               "bottle", "bowl", "vase", "clock", "cushion"};

enum class AnswerColumn { Id, Relation, Count };

// A query as text, and as a prepared statement with the values its placeholders are bound to
// (the same query: the answers of both are compared). A node id cannot be a placeholder, so
// RELATE's prepared form is its text, prepared once per pair as an application would.
struct Query {
    std::string text;
    AnswerColumn column;
    std::function<Answer(Baseline&)> baseline;
    std::string prepared;
    std::vector<ParameterValue> values;
};

// Classes in report order; the single-scene ones come first.
enum ClassIndex { kFindWindow, kFindChair, kRelate, kNearest, kCategoryAll, kCountAll, kClassCount };
constexpr int kSingleSceneClasses = kCategoryAll;

const std::array<const char*, kClassCount> kClassNames = {
    "FIND on(table) AND near(window, 1.5 m)", "FIND on(table) AND near(chair, 1 m)",   "RELATE #a TO #b",
    "FIND object NEAREST TO door LIMIT 5",    "FIND <category> LIMIT 100, all scenes", "COUNT <category>, all scenes"};

Answer smqlAnswer(const ResultSet& rs, AnswerColumn column) {
    Answer out;
    const char* name = column == AnswerColumn::Id ? "id" : column == AnswerColumn::Relation ? "relation" : "count";
    int index = rs.columnIndex(name);
    if (index < 0) throw std::runtime_error(fmt::format("smql answer has no column '{}'", name));
    for (const auto& row : rs.rows) {
        const Value& v = row[static_cast<std::size_t>(index)];
        if (column == AnswerColumn::Relation) {
            const auto* p = relations::predicateNamed(std::get<std::string>(v));
            if (!p)
                throw std::runtime_error(
                    fmt::format("smql answered an unknown relation '{}'", std::get<std::string>(v)));
            out.push_back(static_cast<std::int64_t>(p->predicate));
        } else {
            out.push_back(std::get<std::int64_t>(v));
        }
    }
    return out;
}

std::string showAnswer(const Answer& a, AnswerColumn column) {
    if (column != AnswerColumn::Relation) return fmt::format("[{}]", fmt::join(a, ", "));
    std::vector<std::string_view> names;
    for (auto code : a) names.push_back(relations::toString(static_cast<Predicate>(code)));
    return fmt::format("[{}]", fmt::join(names, ", "));
}

// Throws unless a baseline's answer to `query` equals smql's.
void requireEqual(const Answer& ours, const Answer& theirs, const Baseline& baseline, const Query& query,
                  const std::string& where) {
    if (ours != theirs)
        throw std::runtime_error(fmt::format("answers differ in {} for `{}`:\n  smql:   {}\n  {}: {}", where,
                                             query.text, showAnswer(ours, query.column), baseline.name(),
                                             showAnswer(theirs, query.column)));
}

using Baselines = std::vector<std::unique_ptr<Baseline>>;

// Runs `query` on every system and throws unless the answers are equal.
// Returns the answer and each system's time for this (first) run.
struct Checked {
    Answer answer;
    double smqlMicros;
    std::vector<double> baselineMicros;
};
Checked check(Engine& engine, Baselines& baselines, const Query& query, const std::string& where) {
    auto t = Clock::now();
    auto results = engine.execute(query.text);
    Checked out{{}, microsecondsSince(t), {}};
    out.answer = smqlAnswer(results.back(), query.column);
    for (auto& baseline : baselines) {
        t = Clock::now();
        Answer theirs = query.baseline(*baseline);
        out.baselineMicros.push_back(microsecondsSince(t));
        requireEqual(out.answer, theirs, *baseline, query, where);
    }
    return out;
}

double answerSize(const Answer& a, AnswerColumn column) {
    return column == AnswerColumn::Count ? static_cast<double>(a.front()) : static_cast<double>(a.size());
}

struct SceneQueries {
    std::string name;
    std::array<std::vector<Query>, kSingleSceneClasses> byClass;
};

// The nodes of scene `name` but its scene node, read from storage (not loaded into the engine).
std::vector<model::Node> storedNodes(Engine& engine, const std::string& name) {
    std::vector<model::Node> nodes;
    auto txn = engine.database().beginRead();
    txn.forEachNodeInScene(txn.sceneByName(name).value().id, [&](const model::Node& n) {
        if (n.kind != model::NodeKind::Scene) nodes.push_back(n);
    });
    return nodes;
}

// Parses `find` with no scene in use: across all scenes a FIND with WHERE is refused after parsing, and the
// engine keeps the parsed text, so the FIND run after a USE SCENE times the scene's load and its work.
void parseAcrossScenes(Engine& engine, const Query& find) {
    engine.execute("USE SCENE '*'");
    try {
        engine.execute(find.text);
    } catch (const Error&) {
    }
}

// The single-scene queries of one scene: its nodes decide the FIND's surface
// and the RELATE pairs (half of them a small thing and what it rests on, half random).
SceneQueries sceneQueries(Engine& engine, int sceneIndex) {
    SceneQueries out;
    out.name = sceneName(sceneIndex);
    const std::vector<model::Node> nodes = storedNodes(engine, out.name);
    auto has = [&](std::string_view category) {
        return std::any_of(nodes.begin(), nodes.end(), [&](const model::Node& n) { return n.category == category; });
    };

    auto surface = std::find_if(kSurfaces.begin(), kSurfaces.end(), has);
    if (surface == kSurfaces.end() || !has("window") || !has("door") || !has("chair"))
        throw std::runtime_error(fmt::format(
            "scene {} lacks a table-like surface, a window, a door or a chair; give it more objects (--objects)",
            out.name));
    PredicateTerm on{Predicate::On, std::string(*surface), std::nullopt};
    for (const auto& [c, near] : {std::pair{kFindWindow, PredicateTerm{Predicate::Near, "window", 1.5}},
                                  std::pair{kFindChair, PredicateTerm{Predicate::Near, "chair", 1.0}}}) {
        const PredicateTerm& term = near;  // a lambda captures a variable, not a structured binding (clang 14)
        out.byClass[c].push_back(
            {fmt::format("FIND object WHERE on({}) AND near({}, {} m)", *surface, term.category, *term.nearDistance),
             AnswerColumn::Id,
             [on, term](Baseline& s) { return s.findObjects(on, term); },
             "FIND object WHERE on(?) AND near(?, ?)",
             {std::string(*surface), term.category, Length{*term.nearDistance}}});
    }

    std::vector<const model::Node*> objects;
    std::vector<std::pair<model::NodeId, model::NodeId>> resting;
    std::unordered_map<model::NodeId, const model::Node*> byId;
    for (const auto& n : nodes) byId.emplace(n.id, &n);
    for (const auto& n : nodes) {
        if (n.kind != model::NodeKind::Object) continue;
        objects.push_back(&n);
        auto parent = byId.find(n.parent);
        if (parent != byId.end() && parent->second->kind == model::NodeKind::Object)
            resting.emplace_back(n.id, n.parent);
    }
    std::mt19937_64 rng(static_cast<std::uint64_t>(sceneIndex) + 1);
    std::shuffle(resting.begin(), resting.end(), rng);
    std::vector<std::pair<model::NodeId, model::NodeId>> pairs(
        resting.begin(), resting.begin() + std::min<std::size_t>(resting.size(), kRelatePairsPerScene / 2));
    std::uniform_int_distribution<std::size_t> anyObject(0, objects.size() - 1), anyNode(0, nodes.size() - 1);
    while (pairs.size() < kRelatePairsPerScene) {
        model::NodeId a = objects[anyObject(rng)]->id, b = nodes[anyNode(rng)].id;
        if (a != b) pairs.emplace_back(a, b);
    }
    for (const auto& pair : pairs) {
        model::NodeId a = pair.first, b = pair.second;
        std::string text = fmt::format("RELATE #{} TO #{}", a, b);
        out.byClass[kRelate].push_back(
            {text, AnswerColumn::Relation, [a, b](Baseline& s) { return s.relate(a, b); }, text, {}});
    }

    out.byClass[kNearest].push_back({fmt::format("FIND object NEAREST TO door LIMIT {}", kNearestLimit),
                                     AnswerColumn::Id,
                                     [](Baseline& s) { return s.nearestObjects("door", kNearestLimit); },
                                     "FIND object NEAREST TO ? LIMIT ?",
                                     {std::string("door"), std::int64_t{kNearestLimit}}});
    return out;
}

std::array<std::vector<Query>, kClassCount - kSingleSceneClasses> allSceneQueries() {
    std::array<std::vector<Query>, kClassCount - kSingleSceneClasses> out;
    for (std::string_view c : kSmallCategories) {
        std::string category(c);
        out[0].push_back({fmt::format("FIND {} LIMIT {}", category, kCategoryLimit),
                          AnswerColumn::Id,
                          [category](Baseline& s) { return s.findCategoryAll(category, kCategoryLimit); },
                          "FIND ? LIMIT ?",
                          {category, std::int64_t{kCategoryLimit}}});
        out[1].push_back({fmt::format("COUNT {}", category),
                          AnswerColumn::Count,
                          [category](Baseline& s) { return s.countCategoryAll(category); },
                          "COUNT ?",
                          {category}});
    }
    return out;
}

// Samples per class, system and round, and what the checks saw.
struct ClassSamples {
    std::vector<std::vector<double>> smqlFresh, smqlRepeated, smqlPrepared;
    std::vector<std::vector<std::vector<double>>> baselines;  // per baseline, per round
    std::size_t verified = 0;
    double answerTotal = 0;
};

// Answers each query on every system and compares (which also warms them).
void verify(Engine& engine, Baselines& baselines, const std::vector<Query>& queries, const std::string& where,
            ClassSamples& samples) {
    for (const auto& q : queries) {
        auto checked = check(engine, baselines, q, where);
        ++samples.verified;
        samples.answerTotal += answerSize(checked.answer, q.column);
    }
}

// The engine's prepared statements, one per prepared text, made before the timing as an
// application prepares its statements once.
class PreparedStatements {
public:
    explicit PreparedStatements(Engine& engine) : engine_(engine) {}
    PreparedStatement& of(const Query& query) {
        auto it = statements_.find(query.prepared);
        if (it == statements_.end()) it = statements_.emplace(query.prepared, engine_.prepare(query.prepared)).first;
        return it->second;
    }

private:
    Engine& engine_;
    std::unordered_map<std::string, PreparedStatement> statements_;
};

// Binds the query's values and runs its prepared statement.
ResultSet runPrepared(PreparedStatement& statement, const Query& query) {
    for (std::size_t k = 0; k < query.values.size(); ++k) statement.bind(k + 1, query.values[k]);
    return statement.execute();
}

// Times `reps` executions per system, cycling through the queries. smql runs
// each query three times over: as fresh text (a numbered comment makes every text
// new, so the engine never saw it verbatim), as the repeated text (whose parse the
// engine has cached) and as a prepared statement with its values bound (as the
// baselines run). Each fresh answer is checked against the prepared answer and every
// baseline's answer of the same execution, outside the timed calls.
void timeQueries(Engine& engine, PreparedStatements& prepared, Baselines& baselines, const std::vector<Query>& queries,
                 int reps, int round, const std::string& where, ClassSamples& samples) {
    static std::uint64_t freshTexts = 0;
    std::vector<Answer> answers;
    for (int i = 0; i < reps; ++i) {
        const auto& q = queries[static_cast<std::size_t>(i) % queries.size()];
        std::string text = fmt::format("{} -- fresh text {}", q.text, ++freshTexts);
        auto t = Clock::now();
        auto results = engine.execute(text);
        samples.smqlFresh[round].push_back(microsecondsSince(t));
        answers.push_back(smqlAnswer(results.back(), q.column));
    }
    for (int i = 0; i < reps; ++i) {
        const auto& q = queries[static_cast<std::size_t>(i) % queries.size()];
        auto t = Clock::now();
        engine.execute(q.text);
        samples.smqlRepeated[round].push_back(microsecondsSince(t));
    }
    for (int i = 0; i < reps; ++i) {
        const auto& q = queries[static_cast<std::size_t>(i) % queries.size()];
        PreparedStatement& statement = prepared.of(q);
        auto t = Clock::now();
        ResultSet rs = runPrepared(statement, q);
        samples.smqlPrepared[round].push_back(microsecondsSince(t));
        if (smqlAnswer(rs, q.column) != answers[static_cast<std::size_t>(i)])
            throw std::runtime_error(fmt::format("smql's prepared `{}` answers {} in {}, its text `{}` answers {}",
                                                 q.prepared, showAnswer(smqlAnswer(rs, q.column), q.column), where,
                                                 q.text, showAnswer(answers[static_cast<std::size_t>(i)], q.column)));
    }
    for (std::size_t b = 0; b < baselines.size(); ++b) {
        for (int i = 0; i < reps; ++i) {
            const auto& q = queries[static_cast<std::size_t>(i) % queries.size()];
            auto t = Clock::now();
            Answer theirs = q.baseline(*baselines[b]);
            samples.baselines[b][round].push_back(microsecondsSince(t));
            requireEqual(answers[static_cast<std::size_t>(i)], theirs, *baselines[b], q, where);
        }
    }
}

// The median over rounds of each round's p50 and p99, so a burst of load on
// the machine during one round does not move the result; max is the largest sample.
Percentiles overRounds(std::vector<std::vector<double>>& rounds) {
    std::vector<double> p50s, p99s;
    Percentiles out;
    out.p50Low = std::numeric_limits<double>::infinity();
    for (auto& samples : rounds) {
        if (samples.empty()) continue;
        auto p = percentiles(samples);
        p50s.push_back(p.p50);
        p99s.push_back(p.p99);
        out.max = std::max(out.max, p.max);
        out.p50Low = std::min(out.p50Low, p.p50);
        out.p50High = std::max(out.p50High, p.p50);
    }
    if (p50s.empty()) out.p50Low = 0;
    out.p50 = median(p50s);
    out.p99 = median(p99s);
    return out;
}

// The p50 of ANTLR's parse and of the shape scan of `text`, each with a new comment per run as the
// fresh texts have.
std::pair<double, double> measureText(const std::string& text) {
    constexpr int kRuns = 1000;
    std::vector<double> parse, scan;
    for (int i = 0; i < kRuns; ++i) {
        const std::string fresh = fmt::format("{} -- text {}", text, i);
        auto t = Clock::now();
        parser::parse(fresh);
        parse.push_back(microsecondsSince(t));
        t = Clock::now();
        if (!parser::statementShape(fresh)) throw std::runtime_error(fmt::format("`{}` has no statement shape", text));
        scan.push_back(microsecondsSince(t));
    }
    return {median(parse), median(scan)};
}

OpenTimes measureOpen(const DataSet& data, const Query& firstQuery, const std::string& firstScene, int repeats) {
    std::vector<double> smqlOpen, smqlFirst, sqliteOpen, sqliteFirst;
    const std::string use = fmt::format("USE SCENE '{}'", firstScene);
    for (int r = 0; r < repeats; ++r) {
        auto t = Clock::now();
        auto engine = Engine::open(data.smqlDirectory.string());
        smqlOpen.push_back(microsecondsSince(t));
        engine->execute(use);
        engine->execute(firstQuery.text);
        smqlFirst.push_back(microsecondsSince(t));
        engine.reset();

        t = Clock::now();
        SqliteBaseline sqlite(data.sqliteFile.string(), false);
        sqliteOpen.push_back(microsecondsSince(t));
        sqlite.useScene(firstScene);
        firstQuery.baseline(sqlite);
        sqliteFirst.push_back(microsecondsSince(t));
    }
    return {median(smqlOpen), median(smqlFirst), median(sqliteOpen), median(sqliteFirst)};
}

// The first FIND after USE SCENE in `rounds` rounds, each visiting every scene of `scenes` cold (a
// newly opened engine has loaded none): before each, the scene's nodes are read and freed and the
// FIND parsed with no scene in use, as for the first visit in runWorkload, so the time is the load
// of the scene and the FIND's work. Each answer must be `answers`' (the one checked against the
// baselines there) for its scene.
std::vector<std::vector<double>> measureColdScenes(const DataSet& data, const std::vector<SceneQueries>& scenes,
                                                   const std::vector<Answer>& answers, int rounds) {
    std::vector<std::vector<double>> out(rounds);
    for (auto& round : out) {
        auto engine = Engine::open(data.smqlDirectory.string());
        for (std::size_t s = 0; s < scenes.size(); ++s) {
            const SceneQueries& scene = scenes[s];
            const Query& find = scene.byClass[kFindWindow].front();
            storedNodes(*engine, scene.name);  // read and freed, as sceneQueries does before the first visit
            parseAcrossScenes(*engine, find);
            engine->execute(fmt::format("USE SCENE '{}'", scene.name));
            const auto t = Clock::now();
            auto results = engine->execute(find.text);
            round.push_back(microsecondsSince(t));
            if (smqlAnswer(results.back(), find.column) != answers[s])
                throw std::runtime_error(
                    fmt::format("smql's `{}` in {} answers {} in a newly opened database, {} before", find.text,
                                scene.name, showAnswer(smqlAnswer(results.back(), find.column), find.column),
                                showAnswer(answers[s], find.column)));
        }
    }
    return out;
}

}  // namespace

WorkloadResult runWorkload(const DataSet& data, const WorkloadOptions& options, std::ostream& progress) {
    WorkloadResult result;
    const int rounds = std::max(1, options.rounds);
    const int sampled = std::clamp(options.sampledScenes, 1, data.spec.scenes);
    // Executions per class, system, scene and round: at least options.queries in all.
    const int perSceneRound = (options.queries + sampled * rounds - 1) / (sampled * rounds);
    const int perRound = (options.queries + rounds - 1) / rounds;
    std::vector<SceneQueries> scenes;
    std::array<ClassSamples, kClassCount> samples;
    std::vector<std::vector<double>> baselineSwitch;
    std::vector<Answer> firstAnswers;  // each scene's first FIND's
    {
        auto engine = Engine::open(data.smqlDirectory.string());
        Baselines baselines;
        baselines.push_back(std::make_unique<SqliteBaseline>(data.sqliteFile.string(), false));
        if (!data.postgisConnection.empty())
            baselines.push_back(std::make_unique<PostgisBaseline>(data.postgisConnection, false));
        for (const auto& b : baselines) result.baselineNames.push_back(b->name());
        baselineSwitch.resize(baselines.size());
        PreparedStatements prepared(*engine);
        for (auto& s : samples) {
            s.smqlFresh.resize(rounds);
            s.smqlRepeated.resize(rounds);
            s.smqlPrepared.resize(rounds);
            s.baselines.assign(baselines.size(), std::vector<std::vector<double>>(rounds));
        }
        auto useScene = [&](const std::string& name) {
            engine->execute(fmt::format("USE SCENE '{}'", name));
            for (auto& b : baselines) b->useScene(name);
        };
        for (int k = 0; k < sampled; ++k) {
            int index = static_cast<int>(static_cast<long long>(k) * data.spec.scenes / sampled);
            const auto& scene = scenes.emplace_back(sceneQueries(*engine, index));
            const Query& find = scene.byClass[kFindWindow].front();
            parseAcrossScenes(*engine, find);
            useScene(scene.name);
            std::string where = fmt::format("{} scene {}", data.spec.label, scene.name);
            auto first = check(*engine, baselines, find, where);
            firstAnswers.push_back(first.answer);
            for (std::size_t b = 0; b < baselines.size(); ++b) baselineSwitch[b].push_back(first.baselineMicros[b]);
            for (int c = 0; c < kSingleSceneClasses; ++c) {
                verify(*engine, baselines, scene.byClass[c], where, samples[c]);
                for (const Query& q : scene.byClass[c]) prepared.of(q);
            }
        }
        // Rounds outside, scenes inside: each round spans every scene, and the rounds spread over the run.
        for (int r = 0; r < rounds; ++r) {
            for (const auto& scene : scenes) {
                useScene(scene.name);
                std::string where = fmt::format("{} scene {}", data.spec.label, scene.name);
                for (int c = 0; c < kSingleSceneClasses; ++c)
                    timeQueries(*engine, prepared, baselines, scene.byClass[c], perSceneRound, r, where, samples[c]);
            }
        }
        fmt::print(progress, "  {}: single-scene queries done in {} scene(s)\n", data.spec.label, sampled);
        progress.flush();

        engine->execute("USE SCENE '*'");
        auto across = allSceneQueries();
        const std::string where = data.spec.label + " (all scenes)";
        for (int c = kSingleSceneClasses; c < kClassCount; ++c) {
            verify(*engine, baselines, across[c - kSingleSceneClasses], where, samples[c]);
            for (const Query& q : across[c - kSingleSceneClasses]) prepared.of(q);
        }
        for (int r = 0; r < rounds; ++r)
            for (int c = kSingleSceneClasses; c < kClassCount; ++c)
                timeQueries(*engine, prepared, baselines, across[c - kSingleSceneClasses], perRound, r, where,
                            samples[c]);
        fmt::print(progress, "  {}: all-scene queries done\n", data.spec.label);
        progress.flush();
        result.shapes = engine->shapeCacheStats();
    }
    // smql and SQLite are closed now, so each open below starts from nothing but the OS page cache. One round
    // goes first and is not counted, as every other class runs its queries once before the timing: the first
    // after the systems close was the slowest in every run (110-124 us at the median, the next 84-87, on the
    // large set in two runs), a cost of the process's, not of a scene's.
    auto cold = measureColdScenes(data, scenes, firstAnswers, rounds + 1);
    cold.erase(cold.begin());
    result.smqlSceneSwitch = overRounds(cold);
    result.open =
        measureOpen(data, scenes.front().byClass[kFindWindow].front(), scenes.front().name, options.openRepeats);

    for (int c = 0; c < kClassCount; ++c) {
        ClassResult r;
        r.name = kClassNames[c];
        r.twoPredicateFind = c == kFindWindow || c == kFindChair;
        r.smqlFresh = overRounds(samples[c].smqlFresh);
        r.smqlRepeated = overRounds(samples[c].smqlRepeated);
        r.smqlPrepared = overRounds(samples[c].smqlPrepared);
        for (auto& b : samples[c].baselines) r.baselines.push_back(overRounds(b));
        const std::string first = c < kSingleSceneClasses ? scenes.front().byClass[c].front().text
                                                          : allSceneQueries()[c - kSingleSceneClasses].front().text;
        std::tie(r.parseMicros, r.shapeScanMicros) = measureText(first);
        r.verified = samples[c].verified;
        r.meanAnswer = samples[c].verified ? samples[c].answerTotal / static_cast<double>(samples[c].verified) : 0;
        result.classes.push_back(std::move(r));
    }
    auto sceneSwitch = [](std::vector<double>& samples) {
        Percentiles p = percentiles(samples);  // sorts them
        p.p50Low = samples.empty() ? 0 : samples.front();
        p.p50High = p.max;
        return p;
    };
    for (auto& b : baselineSwitch) result.baselineSceneSwitch.push_back(sceneSwitch(b));
    return result;
}

}  // namespace smql::bench
