// SIMILAR TO: the built-in embedder on the Replica room's human labels, combined with metric
// predicates, placeholders, EXPLAIN, and the HNSW index of a large scene against the exact ranking.
#include <set>

#include <catch2/catch.hpp>

#include "engine/similar/embedding_index.hpp"
#include "engine/similar/text_embedder.hpp"
#include "engine_support.hpp"
#include "ingest/generate/room_generator.hpp"
#include "ingest/import/importers.hpp"

using namespace smql;
using smql::testing::categories;
using smql::testing::run;
using smql::testing::similarities;
using smql::testing::TempDir;

namespace {

std::unique_ptr<Engine> replicaEngine(const TempDir& dir) {
    auto engine = Engine::open(dir.path.string());
    engine->importScene(import::readReplica(testing::replicaRoom0(), "replica-room0"));
    return engine;
}

}  // namespace

TEST_CASE("The embedder ranks what words mean, not only how they are spelled", "[similar]") {
    auto node = [](std::string category, std::string color = "") {
        model::Node n;
        n.category = std::move(category);
        if (!color.empty()) n.attributes.push_back({"color", color});
        return n;
    };
    const auto sofa = similar::embedNode(node("sofa"));
    const auto lamp = similar::embedNode(node("lamp"));
    const auto redMug = similar::embedNode(node("mug", "red"));
    const auto blueMug = similar::embedNode(node("mug", "blue"));
    auto score = [](const similar::Vector& v, const char* query) {
        return similar::similarity(v, similar::embedQuery(query));
    };
    CHECK(score(sofa, "couch") > score(lamp, "couch"));                              // a WordNet synonym
    CHECK(score(sofa, "furniture") > score(lamp, "furniture"));                      // a hypernym
    CHECK(score(sofa, "something to sit on") > score(lamp, "something to sit on"));  // a definition
    CHECK(score(sofa, "sofaa") > score(lamp, "sofaa"));                              // a misspelling, by trigrams
    CHECK(score(redMug, "red mug") > score(blueMug, "red mug"));
    CHECK(score(redMug, "red mug") > score(sofa, "red mug"));
    // Unit vectors: a node is most similar to itself, and a scene node to nothing.
    CHECK(similar::similarity(sofa, sofa) == Approx(1.0).epsilon(1e-5));
    model::Node scene;
    scene.kind = model::NodeKind::Scene;
    scene.category = "room";
    CHECK(similar::isZero(similar::embedNode(scene)));
    CHECK(similar::isZero(similar::embedQuery("the of a")));
}

TEST_CASE("SIMILAR TO ranks the Replica room's objects by meaning", "[similar]") {
    TempDir dir;
    auto engine = replicaEngine(dir);

    auto couch = run(*engine, "FIND object SIMILAR TO 'couch' LIMIT 2");
    REQUIRE(couch.columns.back().name == "similarity");
    CHECK(categories(couch) == std::vector<std::string>{"sofa", "sofa"});

    auto sit = categories(run(*engine, "FIND object SIMILAR TO 'something to sit on' LIMIT 5"));
    REQUIRE(sit.size() == 5);
    const std::set<std::string> seats{"sofa", "chair", "stool", "cushion"};
    for (const auto& category : sit) CHECK(seats.count(category) == 1);

    CHECK(categories(run(*engine, "FIND object SIMILAR TO 'plnt' LIMIT 1")).front().find("plant") != std::string::npos);
    CHECK(categories(run(*engine, "FIND object SIMILAR TO 'pillow' LIMIT 1")).front() == "cushion");

    // Most similar first, every similarity positive.
    auto ranked = similarities(run(*engine, "FIND object SIMILAR TO 'furniture'"));
    REQUIRE(!ranked.empty());
    CHECK(std::is_sorted(ranked.rbegin(), ranked.rend()));
    CHECK(ranked.back() > 0);
}

TEST_CASE("SIMILAR TO combines with metric predicates, RETURN, PATH and placeholders", "[similar]") {
    TempDir dir;
    auto engine = replicaEngine(dir);

    // Only what is on a sofa, ranked: the cushions, then anything else lying there.
    auto onSofa = run(*engine, "FIND object WHERE on(sofa) SIMILAR TO 'pillow'");
    auto all = run(*engine, "FIND object WHERE on(sofa)");
    REQUIRE(!onSofa.rows.empty());
    CHECK(onSofa.rows.size() <= all.rows.size());
    CHECK(categories(onSofa).front() == "cushion");

    auto returned = run(*engine, "FIND object SIMILAR TO 'lamp' RETURN category, similarity LIMIT 1 PATH");
    REQUIRE(returned.columns.size() == 3);
    CHECK(returned.columns[1].name == "similarity");
    CHECK(std::get<std::string>(returned.rows.at(0)[0]) == "lamp");

    auto statement = engine->prepare("FIND object SIMILAR TO ? LIMIT 1");
    statement.bind(1, std::string("couch"));
    CHECK(categories(statement.execute()) == std::vector<std::string>{"sofa"});
    statement.bind(1, std::string("lamp"));
    CHECK(categories(statement.execute()) == std::vector<std::string>{"lamp"});
}

TEST_CASE("SIMILAR TO refuses what it cannot rank", "[similar]") {
    TempDir dir;
    auto engine = replicaEngine(dir);
    CHECK_THROWS_WITH(run(*engine, "FIND object SIMILAR TO 'chair' NEAREST TO door"),
                      Catch::Contains("SIMILAR TO and NEAREST TO both set an order"));
    CHECK_THROWS_WITH(run(*engine, "FIND object SIMILAR TO '  '"), Catch::Contains("needs words"));
    CHECK_THROWS_WITH(run(*engine, "FIND object SIMILAR TO 'a' SIMILAR TO 'b'"), Catch::Contains("given twice"));
    CHECK_THROWS_WITH(run(*engine, "FIND object RETURN similarity"), Catch::Contains("unknown column 'similarity'"));
    // Words the embedder does not read at all find nothing rather than everything.
    CHECK(run(*engine, "FIND object SIMILAR TO 'the of'").rows.empty());
}

TEST_CASE("A large target asks the embedding index, agreeing with the ranking of every candidate", "[similar]") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    engine->importScene(generate::generateRoom({.seed = 3, .objectCount = 600, .name = "hall"}));

    auto explain = [&](const std::string& statement) {
        std::string out;
        for (const auto& row : run(*engine, "EXPLAIN " + statement).rows) out += std::get<std::string>(row[0]) + "\n";
        return out;
    };
    CHECK_THAT(explain("FIND object SIMILAR TO 'red chair' LIMIT 10"),
               Catch::Contains("search of the embedding index"));
    // WHERE makes the plan rank every candidate: the same similarities must come out.
    CHECK_THAT(explain("FIND object WHERE height > 0 m SIMILAR TO 'red chair' LIMIT 10"),
               Catch::Contains("Top 10 by similarity"));
    auto indexed = similarities(run(*engine, "FIND object SIMILAR TO 'red chair' LIMIT 10"));
    auto exact = similarities(run(*engine, "FIND object WHERE height > 0 m SIMILAR TO 'red chair' LIMIT 10"));
    REQUIRE(indexed.size() == 10);
    CHECK(indexed == exact);
}

TEST_CASE("HNSW finds what an exact search of the distinct vectors finds", "[similar]") {
    // Described nodes: each a category and a description of its own, so most vectors are distinct.
    const std::vector<std::string> categories{"chair", "sofa", "lamp", "table", "mug", "plant", "book", "bed"};
    const std::vector<std::string> words{"wooden",  "metal",  "red",  "blue",  "old",  "small",   "window", "door",
                                         "kitchen", "office", "soft", "round", "tall", "striped", "glass",  "paper"};
    std::vector<similar::Vector> vectors;
    for (std::size_t i = 0; i < 3000; ++i) {
        model::Node node;
        node.category = categories[i % categories.size()];
        node.text = words[i % 16] + " " + words[(i / 16) % 16] + " " + words[(i / 256) % 16];
        vectors.push_back(similar::embedNode(node));
    }
    const similar::EmbeddingIndex exact(vectors, SIZE_MAX);
    const similar::EmbeddingIndex graph(vectors, 1000);
    REQUIRE(!exact.approximate());
    REQUIRE(graph.approximate());
    REQUIRE(graph.distinct() >= 1000);
    std::size_t found = 0, wanted = 0;
    for (const char* text : {"red chair", "old wooden table", "lamp by the window", "soft sofa", "glass mug"}) {
        const auto query = similar::embedQuery(text);
        auto truth = exact.mostSimilar(query, 10);
        auto answer = graph.mostSimilar(query, 10);
        REQUIRE(truth.size() >= 10);
        const float tenth = truth[9].similarity;
        wanted += 10;
        found += std::min<std::size_t>(10, std::count_if(answer.begin(), answer.end(),
                                                         [&](const auto& m) { return m.similarity >= tenth - 1e-6F; }));
        // Whatever HNSW returns is a real similarity, most similar first.
        for (std::size_t i = 0; i < answer.size(); ++i)
            CHECK(answer[i].similarity == Approx(exact.similarity(answer[i].position, query)));
    }
    CHECK(static_cast<double>(found) / static_cast<double>(wanted) >= 0.9);
}
