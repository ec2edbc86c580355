#include "bench/workload.hpp"

#include <algorithm>
#include <array>
#include <functional>
#include <random>
#include <stdexcept>
#include <unordered_map>

#include <fmt/format.h>
#include <fmt/ostream.h>
#include <fmt/ranges.h>

#include "bench/sqlite_baseline.hpp"
#include "engine/engine.hpp"
#include "model/error.hpp"
#include "storage/database.hpp"

namespace smql::bench {

using relations::Predicate;

namespace {

// Surfaces that carry small things in the generated rooms, most common first:
// a scene's FIND uses the first it has.
constexpr std::array<std::string_view, 4> kSurfaces = {"table", "desk", "counter", "sofa"};
constexpr std::array<std::string_view, 10> kSmallCategories = {"mug",  "book",  "lamp",  "plant", "laptop",
                                                               "bottle", "bowl", "vase", "clock", "cushion"};

enum class AnswerColumn { Id, Relation, Count };

struct Query {
    std::string text;
    AnswerColumn column;
    std::function<Answer(SqliteBaseline&)> sqlite;
};

// Classes in report order; the single-scene ones come first.
enum ClassIndex { kFindWindow, kFindChair, kRelate, kNearest, kCategoryAll, kCountAll, kClassCount };
constexpr int kSingleSceneClasses = kCategoryAll;

const std::array<const char*, kClassCount> kClassNames = {"FIND on(table) AND near(window, 1.5 m)",
                                                          "FIND on(table) AND near(chair, 1 m)",
                                                          "RELATE #a TO #b",
                                                          "FIND object NEAREST TO door LIMIT 5",
                                                          "FIND <category> LIMIT 100, all scenes",
                                                          "COUNT <category>, all scenes"};

Answer smqlAnswer(const ResultSet& rs, AnswerColumn column) {
    Answer out;
    const char* name = column == AnswerColumn::Id ? "id" : column == AnswerColumn::Relation ? "relation" : "count";
    int index = rs.columnIndex(name);
    if (index < 0) throw std::runtime_error(fmt::format("smql answer has no column '{}'", name));
    for (const auto& row : rs.rows) {
        const Value& v = row[static_cast<std::size_t>(index)];
        if (column == AnswerColumn::Relation) {
            const auto* p = relations::predicateNamed(std::get<std::string>(v));
            if (!p) throw std::runtime_error(fmt::format("smql answered an unknown relation '{}'", std::get<std::string>(v)));
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

// Runs `query` on both systems and throws unless the answers are equal.
// Returns the answer and each system's time for this (first) run.
struct Checked {
    Answer answer;
    double smqlMicros;
    double sqliteMicros;
};
Checked check(Engine& engine, SqliteBaseline& sqlite, const Query& query, const std::string& where) {
    auto t = Clock::now();
    auto results = engine.execute(query.text);
    double smqlMicros = microsecondsSince(t);
    t = Clock::now();
    Answer theirs = query.sqlite(sqlite);
    double sqliteMicros = microsecondsSince(t);
    Answer ours = smqlAnswer(results.back(), query.column);
    if (ours != theirs)
        throw std::runtime_error(fmt::format("answers differ in {} for `{}`:\n  smql:   {}\n  sqlite: {}", where,
                                             query.text, showAnswer(ours, query.column),
                                             showAnswer(theirs, query.column)));
    return {std::move(ours), smqlMicros, sqliteMicros};
}

double answerSize(const Answer& a, AnswerColumn column) {
    return column == AnswerColumn::Count ? static_cast<double>(a.front()) : static_cast<double>(a.size());
}

struct SceneQueries {
    std::string name;
    std::array<std::vector<Query>, kSingleSceneClasses> byClass;
};

// The single-scene queries of one scene: its nodes decide the FIND's surface
// and the RELATE pairs (half of them a small thing and what it rests on, half random).
SceneQueries sceneQueries(Engine& engine, int sceneIndex) {
    SceneQueries out;
    out.name = sceneName(sceneIndex);
    std::vector<model::Node> nodes;
    {
        auto txn = engine.database().beginRead();
        auto info = txn.sceneByName(out.name).value();
        txn.forEachNodeInScene(info.id, [&](const model::Node& n) {
            if (n.kind != model::NodeKind::Scene) nodes.push_back(n);
        });
    }
    auto has = [&](std::string_view category) {
        return std::any_of(nodes.begin(), nodes.end(), [&](const model::Node& n) { return n.category == category; });
    };

    auto surface = std::find_if(kSurfaces.begin(), kSurfaces.end(), has);
    if (surface == kSurfaces.end() || !has("window") || !has("door") || !has("chair"))
        throw std::runtime_error(fmt::format(
            "scene {} lacks a table-like surface, a window, a door or a chair; give it more objects (--objects)",
            out.name));
    PredicateTerm on{Predicate::On, std::string(*surface), std::nullopt};
    for (auto [c, term] : {std::pair{kFindWindow, PredicateTerm{Predicate::Near, "window", 1.5}},
                           std::pair{kFindChair, PredicateTerm{Predicate::Near, "chair", 1.0}}}) {
        out.byClass[c].push_back({fmt::format("FIND object WHERE on({}) AND near({}, {} m)", *surface, term.category,
                                              *term.nearDistance),
                                  AnswerColumn::Id, [on, term](SqliteBaseline& s) { return s.findObjects(on, term); }});
    }

    std::vector<const model::Node*> objects;
    std::vector<std::pair<model::NodeId, model::NodeId>> resting;
    std::unordered_map<model::NodeId, const model::Node*> byId;
    for (const auto& n : nodes) byId.emplace(n.id, &n);
    for (const auto& n : nodes) {
        if (n.kind != model::NodeKind::Object) continue;
        objects.push_back(&n);
        auto parent = byId.find(n.parent);
        if (parent != byId.end() && parent->second->kind == model::NodeKind::Object) resting.emplace_back(n.id, n.parent);
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
    for (auto [a, b] : pairs)
        out.byClass[kRelate].push_back({fmt::format("RELATE #{} TO #{}", a, b), AnswerColumn::Relation,
                                        [a, b](SqliteBaseline& s) { return s.relate(a, b); }});

    out.byClass[kNearest].push_back({fmt::format("FIND object NEAREST TO door LIMIT {}", kNearestLimit), AnswerColumn::Id,
                                     [](SqliteBaseline& s) { return s.nearestObjects("door", kNearestLimit); }});
    return out;
}

std::array<std::vector<Query>, kClassCount - kSingleSceneClasses> allSceneQueries() {
    std::array<std::vector<Query>, kClassCount - kSingleSceneClasses> out;
    for (std::string_view c : kSmallCategories) {
        std::string category(c);
        out[0].push_back({fmt::format("FIND {} LIMIT {}", category, kCategoryLimit), AnswerColumn::Id,
                          [category](SqliteBaseline& s) { return s.findCategoryAll(category, kCategoryLimit); }});
        out[1].push_back({fmt::format("COUNT {}", category), AnswerColumn::Count,
                          [category](SqliteBaseline& s) { return s.countCategoryAll(category); }});
    }
    return out;
}

// Samples per class, system and round, and what the checks saw.
struct ClassSamples {
    std::vector<std::vector<double>> smql, sqlite;
    std::size_t verified = 0;
    double answerTotal = 0;
};

// Answers each query on both systems and compares (which also warms both).
void verify(Engine& engine, SqliteBaseline& sqlite, const std::vector<Query>& queries, const std::string& where,
            ClassSamples& samples) {
    for (const auto& q : queries) {
        auto checked = check(engine, sqlite, q, where);
        ++samples.verified;
        samples.answerTotal += answerSize(checked.answer, q.column);
    }
}

// Times `reps` executions per system, cycling through the queries.
void timeQueries(Engine& engine, SqliteBaseline& sqlite, const std::vector<Query>& queries, int reps,
          std::vector<double>& smqlSamples, std::vector<double>& sqliteSamples) {
    for (int i = 0; i < reps; ++i) {
        const auto& q = queries[static_cast<std::size_t>(i) % queries.size()];
        auto t = Clock::now();
        engine.execute(q.text);
        smqlSamples.push_back(microsecondsSince(t));
    }
    for (int i = 0; i < reps; ++i) {
        const auto& q = queries[static_cast<std::size_t>(i) % queries.size()];
        auto t = Clock::now();
        q.sqlite(sqlite);
        sqliteSamples.push_back(microsecondsSince(t));
    }
}

// The median over rounds of each round's p50 and p99, so a burst of load on
// the machine during one round does not move the result; max is the largest sample.
Percentiles overRounds(std::vector<std::vector<double>>& rounds) {
    std::vector<double> p50s, p99s;
    Percentiles out;
    for (auto& samples : rounds) {
        if (samples.empty()) continue;
        auto p = percentiles(samples);
        p50s.push_back(p.p50);
        p99s.push_back(p.p99);
        out.max = std::max(out.max, p.max);
    }
    out.p50 = median(p50s);
    out.p99 = median(p99s);
    return out;
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
        firstQuery.sqlite(sqlite);
        sqliteFirst.push_back(microsecondsSince(t));
    }
    return {median(smqlOpen), median(smqlFirst), median(sqliteOpen), median(sqliteFirst)};
}

}  // namespace

WorkloadResult runWorkload(const DataSet& data, const WorkloadOptions& options, std::ostream& progress) {
    WorkloadResult result;
    const int rounds = std::max(1, options.rounds);
    std::array<ClassSamples, kClassCount> samples;
    for (auto& s : samples) s.smql.resize(rounds), s.sqlite.resize(rounds);
    std::vector<double> smqlSwitch, sqliteSwitch;
    const int sampled = std::clamp(options.sampledScenes, 1, data.spec.scenes);
    // Executions per class, system, scene and round: at least options.queries in all.
    const int perSceneRound = (options.queries + sampled * rounds - 1) / (sampled * rounds);
    const int perRound = (options.queries + rounds - 1) / rounds;
    std::vector<SceneQueries> scenes;
    {
        auto engine = Engine::open(data.smqlDirectory.string());
        SqliteBaseline sqlite(data.sqliteFile.string(), false);
        for (int k = 0; k < sampled; ++k) {
            int index = static_cast<int>(static_cast<long long>(k) * data.spec.scenes / sampled);
            const auto& scene = scenes.emplace_back(sceneQueries(*engine, index));
            const Query& find = scene.byClass[kFindWindow].front();
            // Parse the FIND once without loading a scene (across all scenes a FIND with WHERE is refused
            // after parsing, and the engine keeps the parsed text), so the first FIND below times the scene load.
            engine->execute("USE SCENE '*'");
            try {
                engine->execute(find.text);
            } catch (const Error&) {
            }
            engine->execute(fmt::format("USE SCENE '{}'", scene.name));
            sqlite.useScene(scene.name);
            std::string where = fmt::format("{} scene {}", data.spec.label, scene.name);
            auto first = check(*engine, sqlite, find, where);
            smqlSwitch.push_back(first.smqlMicros);
            sqliteSwitch.push_back(first.sqliteMicros);
            for (int c = 0; c < kSingleSceneClasses; ++c) verify(*engine, sqlite, scene.byClass[c], where, samples[c]);
        }
        // Rounds outside, scenes inside: each round spans every scene, and the rounds spread over the run.
        for (int r = 0; r < rounds; ++r) {
            for (const auto& scene : scenes) {
                engine->execute(fmt::format("USE SCENE '{}'", scene.name));
                sqlite.useScene(scene.name);
                for (int c = 0; c < kSingleSceneClasses; ++c)
                    timeQueries(*engine, sqlite, scene.byClass[c], perSceneRound, samples[c].smql[r], samples[c].sqlite[r]);
            }
        }
        fmt::print(progress, "  {}: single-scene queries done in {} scene(s)\n", data.spec.label, sampled);
        progress.flush();

        engine->execute("USE SCENE '*'");
        auto across = allSceneQueries();
        for (int c = kSingleSceneClasses; c < kClassCount; ++c)
            verify(*engine, sqlite, across[c - kSingleSceneClasses], data.spec.label + " (all scenes)", samples[c]);
        for (int r = 0; r < rounds; ++r)
            for (int c = kSingleSceneClasses; c < kClassCount; ++c)
                timeQueries(*engine, sqlite, across[c - kSingleSceneClasses], perRound, samples[c].smql[r], samples[c].sqlite[r]);
        fmt::print(progress, "  {}: all-scene queries done\n", data.spec.label);
        progress.flush();
    }
    // Both databases are closed now, so each open below starts from nothing but the OS page cache.
    result.open = measureOpen(data, scenes.front().byClass[kFindWindow].front(), scenes.front().name, options.openRepeats);

    for (int c = 0; c < kClassCount; ++c) {
        ClassResult r;
        r.name = kClassNames[c];
        r.twoPredicateFind = c == kFindWindow || c == kFindChair;
        r.smql = overRounds(samples[c].smql);
        r.sqlite = overRounds(samples[c].sqlite);
        r.verified = samples[c].verified;
        r.meanAnswer = samples[c].verified ? samples[c].answerTotal / static_cast<double>(samples[c].verified) : 0;
        result.classes.push_back(std::move(r));
    }
    result.smqlSceneSwitch = percentiles(smqlSwitch);
    result.sqliteSceneSwitch = percentiles(sqliteSwitch);
    return result;
}

}  // namespace smql::bench
