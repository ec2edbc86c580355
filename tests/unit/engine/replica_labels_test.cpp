// Real human labels (ReplicaSSG relationships of Replica room_0): every `on`
// and `in` pair but one (named in the test) must be named first by RELATE and
// found by the matching predicate; recall and precision of on, in and near
// against the labels are reported (docs/relations.md gives them).
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "engine_support.hpp"
#include "ingest/import/importers.hpp"

using namespace smql;
using namespace smql::testing;

namespace {

struct Label {
    std::int64_t subject, object;
    std::string predicate;
};

std::vector<Label> labelsOf(const nlohmann::json& relationships) {
    std::vector<Label> labels;
    for (const auto& r : relationships)
        labels.push_back({r[0].get<std::int64_t>(), r[1].get<std::int64_t>(), r[3].get<std::string>()});
    return labels;
}

std::vector<Label> readLabels() {
    std::ifstream in(replicaRelations());
    return labelsOf(nlohmann::json::parse(in).at("relationships"));
}

}  // namespace

TEST_CASE("Replica room0: RELATE names the labelled on/in relation first") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    engine->importScene(import::readReplica(replicaRoom0(), "room0"));
    auto labels = readLabels();
    REQUIRE(labels.size() == 25);

    int supportPairs = 0, namedFirst = 0, nearPairs = 0, nearFound = 0;
    for (const auto& label : labels) {
        std::string relate = fmt::format("RELATE src#{} TO src#{}", label.subject, label.object);
        auto rs = run(*engine, relate);
        int rel = rs.columnIndex("relation");
        if (label.predicate == "near") {
            ++nearPairs;
            for (const auto& row : rs.rows) nearFound += std::get<std::string>(row[rel]) == "near";
            continue;
        }
        ++supportPairs;
        INFO(relate << " -> " << rs.message);
        // Lamp 6 on table 7 among them: a 0.9 x 2.55 m box over sofa 9 and the side tables, whose floor they
        // take (docs/relations.md, "A box whose floor other things take").
        bool first = !rs.rows.empty() && std::get<std::string>(rs.rows.front()[rel]) == label.predicate;
        namedFirst += first;
        CHECK(first);

        // The predicate finds the subject among the nodes of its category.
        auto subject = run(*engine, fmt::format("DESCRIBE src#{}", label.subject));
        std::string category;
        for (const auto& row : subject.rows)
            if (std::get<std::string>(row[1]) == "category") category = std::get<std::string>(row[2]);
        auto found = run(*engine, fmt::format("FIND '{}' WHERE {}(src#{})", category, label.predicate, label.object));
        bool hit = false;
        for (const auto& row : found.rows)
            hit |= typeOf(row[2]) == ValueType::Integer && std::get<std::int64_t>(row[2]) == label.subject;
        CHECK(hit);
    }
    CHECK(supportPairs == 17);
    CHECK(namedFirst == 17);
    std::cout << fmt::format("Replica room0 labels: {}/{} on/in pairs named first; near pairs found: {}/{} = {:.2f}\n",
                             namedFirst, supportPairs, nearFound, nearPairs,
                             nearPairs ? double(nearFound) / nearPairs : 0.0);
    CHECK(nearFound * 2 >= nearPairs);  // at least half of the labelled near pairs
}

TEST_CASE("Replica room0: cushions on the sofa with their paths") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    engine->importScene(import::readReplica(replicaRoom0(), "room0"));
    auto rs = run(*engine, "FIND cushion WHERE on(sofa) PATH");
    // Labelled: 8, 70, 18, 71 on sofa 9; 13, 5, 32 on sofa 77.
    std::set<std::int64_t> sources;
    int path = rs.columnIndex("path");
    REQUIRE(path >= 0);
    for (const auto& row : rs.rows) {
        auto source = std::get<std::int64_t>(row[2]);
        sources.insert(source);
        auto text = std::get<std::string>(row[path]);
        INFO(text);
        CHECK(text.rfind("room0 / ", 0) == 0);
        // Each hangs below its sofa, cushion 32 too, though it also rests on the blanket draped over
        // sofa 77's arm (the higher of two things it rests on side by side is its parent).
        CHECK(text.find("sofa#") != std::string::npos);
    }
    for (std::int64_t s : {8, 70, 18, 71, 13, 5, 32}) CHECK(sources.count(s) == 1);
    // The cushions on chairs are not on a sofa.
    CHECK(sources.count(72) == 0);
    CHECK(sources.count(69) == 0);
}

namespace {

// Agreement of one predicate with the labels of that predicate. Recall: the labelled pairs the
// predicate finds. The labels are positive and sparse, so precision is taken over the pairs the
// labels speak of: each labelled subject against every node a label of that predicate names
// (subjects and objects); a predicted pair there that is not labelled counts against it.
struct Agreement {
    int labelled = 0, found = 0, predicted = 0, predictedLabelled = 0;
    double recall() const { return labelled ? double(found) / labelled : 0.0; }
    double precision() const { return predicted ? double(predictedLabelled) / predicted : 0.0; }
};

Agreement agreement(Engine& engine, const std::vector<Label>& labels, const std::string& predicate) {
    std::set<std::pair<std::int64_t, std::int64_t>> pairs;
    std::set<std::int64_t> subjects, named;
    for (const auto& l : labels)
        if (l.predicate == predicate) {
            pairs.insert({l.subject, l.object});
            subjects.insert(l.subject);
            named.insert(l.subject);
            named.insert(l.object);
        }
    Agreement a;
    a.labelled = static_cast<int>(pairs.size());
    for (std::int64_t object : named) {
        auto rs = run(engine, fmt::format("FIND node WHERE {}(src#{})", predicate, object));
        int source = rs.columnIndex("source_id");
        for (const auto& row : rs.rows) {
            if (typeOf(row[source]) != ValueType::Integer) continue;
            std::int64_t subject = std::get<std::int64_t>(row[source]);
            bool labelled = pairs.count({subject, object}) == 1;
            a.found += labelled;
            if (subjects.count(subject) && named.count(object)) {
                ++a.predicted;
                a.predictedLabelled += labelled;
            }
        }
    }
    return a;
}

}  // namespace

TEST_CASE("Replica room0: agreement of on, in and near with the human labels") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    engine->importScene(import::readReplica(replicaRoom0(), "room0"));
    auto labels = readLabels();
    for (const std::string predicate : {"on", "in", "near"}) {
        Agreement a = agreement(*engine, labels, predicate);
        std::cout << fmt::format("Replica room0 {:>4}: recall {}/{} = {:.2f}, precision {}/{} = {:.2f}\n", predicate,
                                 a.found, a.labelled, a.recall(), a.predictedLabelled, a.predicted, a.precision());
        CHECK(a.labelled > 0);
        // Every labelled pair (the arc lamp on its table too: docs/relations.md), and floors under the precision
        // measured when the rules were written.
        CHECK(a.found == a.labelled);
        CHECK(a.precision() >= 0.7);
        // near, with the crowd, calls no other pair of them near.
        if (predicate == "near") CHECK(a.precision() >= 0.9);
        // on: the arc lamp's box, spread over sofa 9 and its cushions, carries none of them.
        if (predicate == "on") CHECK(a.precision() >= 0.9);
    }
    CHECK(run(*engine, "FIND object WHERE on(lamp)").rows.empty());
    const auto cushionOn = run(*engine, "ASK 'what is the cushion on?'");
    CHECK_THAT(cushionOn.message, Catch::Contains("cushion#") && !Catch::Contains("lamp"));
}

// Hidden from the unit_engine run: the ctest unit_relations_replicassg runs it where ReplicaSSG's labels are
// there (docs/relations.md, "Agreement with people").
TEST_CASE("ReplicaSSG: on, in and near find every labelled pair of each Replica room there", "[.][replicassg]") {
    // ReplicaSSG's labels of all 18 Replica scenes (Howardkhh/ReplicaSSG, files/relationships.json), and each
    // scene's layout where it is there: replica-<scene, underscores dropped>/info_semantic.json beside the
    // labels' file or in the shared data.
    const char* given = std::getenv("SMQL_REPLICASSG");
    const std::filesystem::path file =
        given ? given : std::filesystem::path(SMQL_SHARED_DATA) / "replicassg" / "relationships.json";
    std::ifstream in(file);
    REQUIRE(in);
    const auto scans = nlohmann::json::parse(in).at("scans");
    int rooms = 0;
    for (const auto& scan : scans) {
        std::string folder = "replica-" + scan.at("scan").get<std::string>();
        std::erase(folder, '_');
        std::filesystem::path layout = file.parent_path() / folder / "info_semantic.json";
        if (!std::filesystem::exists(layout))
            layout = std::filesystem::path(SMQL_SHARED_DATA) / folder / "info_semantic.json";
        if (!std::filesystem::exists(layout)) continue;
        ++rooms;
        TempDir dir;
        auto engine = Engine::open(dir.path.string());
        engine->importScene(import::readReplica(layout.string(), "room"));
        const auto labels = labelsOf(scan.at("relationships"));
        for (const std::string predicate : {"on", "in", "near"}) {
            const Agreement a = agreement(*engine, labels, predicate);
            if (a.labelled == 0) continue;
            std::cout << fmt::format("{} {:>4}: recall {}/{} = {:.2f}, precision {}/{} = {:.2f}\n", folder, predicate,
                                     a.found, a.labelled, a.recall(), a.predictedLabelled, a.predicted, a.precision());
            INFO(folder << " " << predicate);
            // Every labelled pair.
            CHECK(a.found == a.labelled);
            // near without the crowd called 8 of 22 pairs near in room_0; with it, 8 of 8 (docs/relations.md).
            if (predicate == "near") CHECK(a.precision() >= 0.85);
        }
    }
    CHECK(rooms > 0);
}
