// One predicate, one answer: for every predicate and every plan shape, the rows of
// `FIND node WHERE p(y)` are exactly the nodes x for which `CHECK x p y` answers yes, and
// `WHERE p` and `WHERE NOT p` partition the scene's nodes (query partitioning, as SQLancer's
// tests do). Run on the Replica room, a generated room and a slice of the real layouts in
// ../shared/data/real-layouts (every tenth room; SMQL_DIFFERENTIAL_ROOMS=all for all 238). On the
// same rooms, on and in, the tree and ASK must agree (TreeAgreement).
#include <catch2/catch.hpp>

#include <cstdlib>
#include <iostream>
#include <map>
#include <set>

#include <fmt/format.h>

#include "engine_support.hpp"
#include "ingest/generate/room_generator.hpp"
#include "ingest/import/importers.hpp"
#include "relations/predicates.hpp"

using namespace smql;
using namespace smql::testing;

namespace {

using Ids = std::set<std::int64_t>;

Ids ids(const ResultSet& rs) {
    Ids out;
    const int id = rs.columnIndex("id");
    for (const auto& row : rs.rows) out.insert(std::get<std::int64_t>(row[id]));
    return out;
}

std::string listed(const Ids& set) {
    std::string out;
    for (auto id : set) out += fmt::format("{}#{}", out.empty() ? "" : " ", id);
    return out.empty() ? "(none)" : out;
}

// At most `most` of `all`, spread evenly over it.
std::vector<std::int64_t> spread(const std::vector<std::int64_t>& all, std::size_t most) {
    std::vector<std::int64_t> out;
    const std::size_t step = std::max<std::size_t>(1, all.size() / most);
    for (std::size_t i = 0; i < all.size() && out.size() < most; i += step) out.push_back(all[i]);
    return out;
}

class Differential {
public:
    explicit Differential(Engine& engine) : engine_(engine) {}

    std::size_t statements = 0;
    std::vector<std::string> disagreements;

    // Every predicate of the table over the current scene's nodes.
    void scene(const std::string& name) {
        run(fmt::format("USE SCENE '{}'", name));
        auto nodeSet = ids(run("FIND node"));
        nodes_.assign(nodeSet.begin(), nodeSet.end());
        name_ = name;
        for (const auto& spec : relations::predicates()) {
            const std::string p(spec.name());
            if (spec.arity == 2) {
                auto refs = spread(nodes_, 4);
                for (std::size_t i = 0; i + 1 < refs.size(); ++i)
                    compare(fmt::format("{}(#{}, #{})", p, refs[i], refs[i + 1]),
                            fmt::format("{} #{} AND #{}", p, refs[i], refs[i + 1]), refs[i]);
                continue;
            }
            for (auto y : spread(nodes_, 6)) {
                compare(fmt::format("{}(#{})", p, y), fmt::format("{} #{}", p, y), y);
                if (spec.takesDistance)
                    compare(fmt::format("{}(#{}, 1.5 m)", p, y), fmt::format("{} #{} 1.5 m", p, y), y);
            }
            // A category as the reference: it holds for x when it holds for some node of it.
            categoryReference(p);
        }
    }

private:
    ResultSet run(const std::string& statement) {
        ++statements;
        return engine_.execute(statement).back();
    }

    void disagree(const std::string& what, const Ids& want, const Ids& got) {
        if (want == got) return;
        disagreements.push_back(
            fmt::format("{}: {}: CHECK says {}, the statement {}", name_, what, listed(want), listed(got)));
    }

    // The nodes for which CHECK answers yes.
    Ids checked(const std::string& check) {
        Ids yes;
        for (auto x : nodes_) {
            auto rs = run(fmt::format("CHECK #{} {}", x, check));
            if (std::get<std::string>(rs.rows.at(0).at(0)) == "yes") yes.insert(x);
        }
        return yes;
    }

    // `term` as FIND and COUNT see it in each plan shape, against `check` per node.
    void compare(const std::string& term, const std::string& check, std::int64_t reference) {
        const Ids yes = checked(check);
        disagree("FIND node WHERE " + term, yes, ids(run("FIND node WHERE " + term)));
        disagree("scan: WHERE " + term + " OR " + term, yes,
                 ids(run(fmt::format("FIND node WHERE {} OR {}", term, term))));
        // The reference as a sub-query: `p(#y)` -> `p((FIND #y))`.
        std::string sub = term;
        const auto hash = sub.find('#');
        const auto end = sub.find_first_of(",)", hash);
        sub = sub.substr(0, hash) + "(FIND " + sub.substr(hash, end - hash) + ")" + sub.substr(end);
        disagree("sub-query: WHERE " + sub, yes, ids(run("FIND node WHERE " + sub)));
        disagree("nearest first: WHERE " + term, yes,
                 ids(run(fmt::format("FIND node WHERE {} ORDER BY distance(#{}) LIMIT 100000", term, reference))));
        auto count = run("COUNT node WHERE " + term);
        if (std::get<std::int64_t>(count.rows.at(0).at(0)) != static_cast<std::int64_t>(yes.size()))
            disagreements.push_back(fmt::format("{}: COUNT node WHERE {}: {} where CHECK says {}", name_, term,
                                                std::get<std::int64_t>(count.rows.at(0).at(0)), yes.size()));
        Ids rest(nodes_.begin(), nodes_.end());
        for (auto x : yes) rest.erase(x);
        disagree("partition: WHERE NOT " + term, rest, ids(run("FIND node WHERE NOT " + term)));
    }

    // p(category): the union of CHECK's yes over the category's nodes.
    void categoryReference(const std::string& p) {
        auto category = run(fmt::format("FIND #{}", nodes_[nodes_.size() / 2]));
        const std::string name = std::get<std::string>(category.rows.at(0).at(1));
        Ids yes;
        for (auto y : ids(run(fmt::format("FIND '{}'", name)))) {
            Ids one = checked(fmt::format("{} #{}", p, y));
            yes.insert(one.begin(), one.end());
        }
        disagree(fmt::format("FIND node WHERE {}('{}')", p, name), yes,
                 ids(run(fmt::format("FIND node WHERE {}('{}')", p, name))));
    }

    Engine& engine_;
    std::vector<std::int64_t> nodes_;
    std::string name_;
};

std::string layouts(const char* file) { return std::string(SMQL_SHARED_DATA) + "/real-layouts/" + file; }

// The Replica room and every tenth real layout (every one when SMQL_DIFFERENTIAL_ROOMS=all), and
// `more`, stored in `engine`: their names.
std::vector<std::string> realScenes(Engine& engine, const std::vector<model::SceneData>& more = {}) {
    std::vector<std::string> scenes;
    auto add = [&](const model::SceneData& scene) {
        engine.importScene(scene);
        scenes.push_back(scene.info.name);
    };
    add(import::readReplica(replicaRoom0(), "replica-room0"));
    for (const auto& scene : more) add(scene);
    const bool all =
        std::getenv("SMQL_DIFFERENTIAL_ROOMS") && std::string(std::getenv("SMQL_DIFFERENTIAL_ROOMS")) == "all";
    for (const char* file : {"scannet_meta_info_val.json", "arkitscenes_meta_info_val.json"}) {
        auto rooms = import::readVsiBenchAll(layouts(file));
        for (std::size_t i = 0; i < rooms.size(); i += all ? 1 : 10) add(rooms[i]);
    }
    return scenes;
}

}  // namespace

TEST_CASE("FIND, COUNT and CHECK answer every predicate alike, in every plan shape", "[differential]") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    const auto scenes = realScenes(*engine, {generate::generateRoom({.seed = 7, .name = "generated-7"})});
    Differential differential(*engine);
    for (const auto& name : scenes) differential.scene(name);
    std::cout << fmt::format("differential: {} statements over {} scenes, {} disagreements\n", differential.statements,
                             scenes.size(), differential.disagreements.size());
    for (std::size_t i = 0; i < differential.disagreements.size() && i < 20; ++i)
        std::cout << "  " << differential.disagreements[i] << "\n";
    CHECK(differential.disagreements.empty());
}

namespace {

// on and in, the tree and ASK: one rule (docs/relations.md, "The tree"). For every object a of a
// scene: its parent, when a thing, carries it (on or in holds); every thing a is on or in is on a's
// path, unless a rests on it and on its parent side by side (a board over two trestles: neither
// carries the other, and the tree holds one); and ASK's "what is on the X?" names what on(X) finds.
struct TreeAgreement {
    std::size_t objects = 0, sideBySide = 0, asked = 0;
    std::vector<std::string> disagreements, besideEachOther;

    void scene(Engine& engine, const std::string& name) {
        engine.execute(fmt::format("USE SCENE '{}'", name));
        std::map<std::int64_t, std::int64_t> parent;  // object -> parent id (0: none)
        std::map<std::int64_t, std::string> category;
        const ResultSet found = engine.execute("FIND object RETURN id, category, parent").back();
        for (const auto& row : found.rows) {
            const auto id = std::get<std::int64_t>(row[0]);
            category[id] = std::get<std::string>(row[1]);
            const auto* text = std::get_if<std::string>(&row[2]);
            const auto hash = text ? text->rfind('#') : std::string::npos;
            parent[id] = hash == std::string::npos ? 0 : std::stoll(text->substr(hash + 1));
        }
        auto ancestors = [&](std::int64_t a) {
            std::set<std::int64_t> out;
            for (auto it = parent.find(a); it != parent.end() && it->second != 0 && out.insert(it->second).second;)
                it = parent.find(it->second);
            return out;
        };
        std::map<std::int64_t, Ids> carries;  // b -> the things on or in it
        for (const auto& [b, unused] : parent)
            carries[b] = ids(engine.execute(fmt::format("FIND object WHERE on(#{}) OR in(#{})", b, b)).back());
        for (const auto& [a, p] : parent) {
            ++objects;
            const std::string what = fmt::format("{}: {}#{}", name, category[a], a);
            if (parent.count(p) && !carries[p].count(a))
                disagreements.push_back(
                    fmt::format("{} hangs under {}#{}, which it is not on or in", what, category[p], p));
            const auto path = ancestors(a);
            for (const auto& [b, on] : carries) {
                if (!on.count(a) || path.count(b)) continue;
                const bool besideParent = parent.count(p) && carries[p].count(a) && !ancestors(b).count(p);
                if (besideParent) {
                    ++sideBySide;
                    besideEachOther.push_back(
                        fmt::format("{} on {}#{} and {}#{}", what, category[p], p, category[b], b));
                    continue;
                }
                disagreements.push_back(
                    fmt::format("{} is on or in {}#{}, which is not on its path", what, category[b], b));
            }
        }
        // ASK, for the categories one thing of the scene has.
        std::map<std::string, int> seen;
        for (const auto& [id, c] : category) ++seen[c];
        for (const auto& [b, c] : category) {
            if (seen[c] != 1) continue;
            ++asked;
            const Ids on = ids(engine.execute(fmt::format("FIND object WHERE on(#{})", b)).back());
            const auto answer = engine.execute(fmt::format("ASK 'what is on the {}?'", c)).back();
            if (answer.columnIndex("id") >= 0 && ids(answer) != on)
                disagreements.push_back(fmt::format("{}: ASK 'what is on the {}?' names {}, on(#{}) finds {}", name, c,
                                                    listed(ids(answer)), b, listed(on)));
        }
    }
};

}  // namespace

TEST_CASE("on, in, the tree and ASK agree on every object", "[differential][tree]") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    const auto scenes = realScenes(*engine);
    TreeAgreement agreement;
    for (const auto& name : scenes) agreement.scene(*engine, name);
    std::cout << fmt::format(
        "tree: {} objects over {} scenes, {} resting on two things side by side, {} ASKs, {} disagreements\n",
        agreement.objects, scenes.size(), agreement.sideBySide, agreement.asked, agreement.disagreements.size());
    for (const auto& pair : agreement.besideEachOther) std::cout << "  side by side: " << pair << "\n";
    for (std::size_t i = 0; i < agreement.disagreements.size() && i < 20; ++i)
        std::cout << "  " << agreement.disagreements[i] << "\n";
    CHECK(agreement.disagreements.empty());
    CHECK(agreement.objects > 250);
}
