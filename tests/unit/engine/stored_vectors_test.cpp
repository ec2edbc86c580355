// SIMILAR TO with a bound vector: the nodes ranked by the embeddings an external model gave them
// (their `embedding` blobs), beside the built-in text embedder's space; the checks on the vector,
// the scene and the stored blobs; and HNSW over vectors of a length other than the text embedder's.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

#include <catch2/catch.hpp>

#include "engine/similar/embedding_index.hpp"
#include "engine_support.hpp"
#include "ingest/generate/room_generator.hpp"
#include "ingest/import/importers.hpp"
#include "model/embedding.hpp"

using namespace smql;
using smql::testing::categories;
using smql::testing::run;
using smql::testing::similarities;
using smql::testing::TempDir;

namespace {

model::Node object(model::NodeId id, std::string category, double x, double height) {
    model::Node n;
    n.id = id;
    n.kind = model::NodeKind::Object;
    n.category = std::move(category);
    n.geometry = model::GeometryKind::Box;
    n.box.center = {x, 0, height / 2};
    n.box.size = {0.2, 0.2, height};
    return n;
}

// A shelf of six things with hand-made 4-dimensional embeddings, not all of unit length; the
// lamp has none. Against (1, 0, 0, 0): mug 1, cup 0.994, bowl 0.707, book 0, plant -1.
model::SceneData shelf() {
    model::SceneData scene;
    scene.info.name = "shelf";
    scene.nodes = {object(1, "book", 0, 0.3), object(2, "mug", 1, 0.1),   object(3, "plant", 2, 0.4),
                   object(4, "cup", 3, 0.12), object(5, "bowl", 4, 0.08), object(6, "lamp", 5, 0.5)};
    const std::vector<std::pair<model::NodeId, std::vector<float>>> vectors{
        {1, {0, 1, 0, 0}}, {2, {2, 0, 0, 0}}, {3, {-1, 0, 0, 0}}, {4, {0.9F, 0.1F, 0, 0}}, {5, {0.5F, 0.5F, 0, 0}}};
    for (const auto& [node, vector] : vectors) scene.blobs.push_back(model::embeddingBlob(node, vector));
    return scene;
}

ResultSet similarTo(Engine& engine, const std::string& statement, std::vector<float> vector) {
    auto prepared = engine.prepare(statement);
    prepared.bind(1, std::move(vector));
    return prepared.execute();
}

std::string explained(Engine& engine, const std::string& statement, ParameterValue value) {
    auto prepared = engine.prepare("EXPLAIN " + statement);
    prepared.bind(1, std::move(value));
    std::string out;
    for (const auto& row : prepared.execute().rows) out += std::get<std::string>(row[0]) + "\n";
    return out;
}

// Deterministic vectors of `dimensions` values in [-1, 1): the same scene every run.
std::vector<float> pseudoRandom(std::uint64_t& state, std::size_t dimensions) {
    std::vector<float> v(dimensions);
    for (float& x : v) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        x = static_cast<float>((state >> 40) % 2000) / 1000.0F - 1.0F;
    }
    return v;
}

}  // namespace

TEST_CASE("A bound vector ranks the nodes by their stored embeddings, most similar first", "[similar][vectors]") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    engine->importScene(shelf());

    // Every node with an embedding, negative cosines too; the lamp has none and is left out.
    auto all = similarTo(*engine, "FIND object SIMILAR TO ?", {2, 0, 0, 0});
    REQUIRE(all.columns.back().name == "similarity");
    CHECK(categories(all) == std::vector<std::string>{"mug", "cup", "bowl", "book", "plant"});
    CHECK(similarities(all) == std::vector<double>{1.0, 0.994, 0.707, 0.0, -1.0});

    CHECK(categories(similarTo(*engine, "FIND object SIMILAR TO ? LIMIT 2", {1, 0, 0, 0})) ==
          std::vector<std::string>{"mug", "cup"});
    CHECK(categories(similarTo(*engine, "FIND object SIMILAR TO ? LIMIT 3", {0, 1, 0, 0})) ==
          std::vector<std::string>{"book", "bowl", "cup"});
    // WHERE filters first (the mug and the bowl are low), then the rest are ranked.
    CHECK(categories(similarTo(*engine, "FIND object WHERE height > 0.11 m SIMILAR TO ?", {1, 0, 0, 0})) ==
          std::vector<std::string>{"cup", "book", "plant"});
    auto returned = similarTo(*engine, "FIND object SIMILAR TO ? RETURN category, similarity LIMIT 1", {0, 0, 0, 1});
    REQUIRE(returned.rows.size() == 1);
    CHECK(std::get<double>(returned.rows[0][1]) == 0.0);

    // The same scene's text search stays in the built-in embedder's space.
    CHECK(categories(run(*engine, "FIND object SIMILAR TO 'plant' LIMIT 1")) == std::vector<std::string>{"plant"});

    // EXPLAIN says which space it searches.
    CHECK_THAT(explained(*engine, "FIND object SIMILAR TO ? LIMIT 3", std::vector<float>{1, 0, 0, 0}),
               Catch::Contains("Top 3 by similarity to the bound vector (4 dimensions) in the space of the nodes' "
                               "stored embeddings: exact, each candidate's vector, nodes without one left out"));
    CHECK_THAT(explained(*engine, "FIND object SIMILAR TO ? LIMIT 3", std::string("cup")),
               Catch::Contains("Top 3 by similarity to 'cup' in the built-in text embedder's space"));
}

TEST_CASE("Nodes with the same embedding tie in id order", "[similar][vectors]") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    model::SceneData scene;
    scene.info.name = "pair";
    scene.nodes = {object(1, "chair", 0, 0.9), object(2, "stool", 1, 0.5), object(3, "chair", 2, 0.9)};
    for (model::NodeId id : {3, 1}) scene.blobs.push_back(model::embeddingBlob(id, std::vector<float>{0.6F, 0.8F}));
    scene.blobs.push_back(model::embeddingBlob(2, std::vector<float>{1, 0}));
    engine->importScene(scene);
    auto rs = similarTo(*engine, "FIND object SIMILAR TO ?", {0.6F, 0.8F});
    REQUIRE(rs.rows.size() == 3);
    CHECK(categories(rs) == std::vector<std::string>{"chair", "chair", "stool"});
    CHECK(std::get<std::int64_t>(rs.rows[0][0]) < std::get<std::int64_t>(rs.rows[1][0]));
}

TEST_CASE("A bound vector is refused where the scene cannot compare it", "[similar][vectors]") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    engine->importScene(shelf());

    auto failure = [&](const std::string& statement, ParameterValue value) {
        try {
            auto prepared = engine->prepare(statement);
            prepared.bind(1, std::move(value));
            prepared.execute();
        } catch (const Error& e) {
            CHECK(e.kind() == ErrorKind::Usage);
            return e.message() + " | " + e.hint();
        }
        FAIL("no error");
        return std::string();
    };
    CHECK_THAT(failure("FIND object SIMILAR TO ?", std::vector<float>{1, 0, 0}),
               Catch::Contains("the scene's embeddings have 4 dimensions; the bound vector has 3"));
    CHECK_THAT(failure("FIND object SIMILAR TO ?", std::vector<float>{0, 0, 0, 0}),
               Catch::Contains("every value is 0"));
    CHECK_THAT(failure("FIND object SIMILAR TO ?", std::vector<float>{1, NAN, 0, 0}), Catch::Contains("not a finite"));
    // A vector only goes where SIMILAR TO's query goes: refused when bound elsewhere.
    CHECK_THAT(failure("FIND ? SIMILAR TO 'cup'", std::vector<float>{1, 0, 0, 0}),
               Catch::Contains("stands for a name, not a vector"));
    CHECK_THAT(failure("FIND object LIMIT ?", std::vector<float>{1}),
               Catch::Contains("stands for LIMIT's whole number, not a vector"));
    CHECK_THAT(failure("FIND object WHERE height > ?", std::vector<float>{1}),
               Catch::Contains("stands for a value, not a vector"));
    CHECK_THAT(failure("FIND object SIMILAR TO ?", std::int64_t{3}),
               Catch::Contains("stands for SIMILAR TO's text or vector, not an integer"));

    // A scene whose nodes have no embeddings: nothing to compare with, and where they would come from.
    engine->importScene(import::readReplica(testing::replicaRoom0(), "replica-room0"));
    const std::string none = failure("FIND object SIMILAR TO ?", std::vector<float>{1, 0, 0, 0});
    CHECK_THAT(none, Catch::Contains("scene 'replica-room0' has no stored embeddings"));
    CHECK_THAT(none, Catch::Contains("\"embedding\" field at ingest"));
}

TEST_CASE("Storage refuses embeddings that are malformed or of two lengths", "[similar][vectors]") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    auto refused = [&](model::SceneData scene) {
        try {
            engine->importScene(std::move(scene));
        } catch (const Error& e) {
            CHECK(e.kind() == ErrorKind::Input);
            return e.message();
        }
        FAIL("imported");
        return std::string();
    };
    model::SceneData mixed = shelf();
    mixed.blobs.push_back(model::embeddingBlob(6, std::vector<float>{1, 0, 0}));
    CHECK_THAT(refused(mixed), Catch::Contains("the embedding of node 6 has 3 dimensions, that of node 1 has 4"));

    model::SceneData typed = shelf();
    typed.blobs[0].mediaType = "image/jpeg";
    CHECK_THAT(refused(typed), Catch::Contains("the embedding of node 1: media type 'image/jpeg'"));
    model::SceneData cut = shelf();
    cut.blobs[0].bytes.pop_back();
    CHECK_THAT(refused(cut), Catch::Contains("15 bytes are not a whole number of floats"));
    CHECK(run(*engine, "SHOW SCENES").rows.empty());
}

TEST_CASE("Stored embeddings travel with the scene's JSON and rank the same after", "[similar][vectors]") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    engine->importScene(shelf());
    const auto path = dir.path / "shelf.json";
    std::ofstream(path) << import::writeSceneJson(engine->exportScene("shelf"));
    run(*engine, "DROP SCENE shelf");
    engine->importScene(import::readSceneJson(path.string(), ""));
    CHECK(categories(similarTo(*engine, "FIND object SIMILAR TO ?", {1, 0, 0, 0})) ==
          std::vector<std::string>{"mug", "cup", "bowl", "book", "plant"});
}

TEST_CASE("A large scene's stored embeddings are searched through the index, as the exact ranking says",
          "[similar][vectors]") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    auto room = generate::generateRoom({.seed = 3, .objectCount = 600, .name = "hall"});
    std::uint64_t state = 7;
    for (const auto& node : room.nodes)
        if (node.kind == model::NodeKind::Object)
            room.blobs.push_back(model::embeddingBlob(node.id, pseudoRandom(state, 24)));
    engine->importScene(room);

    const std::vector<float> query = pseudoRandom(state, 24);
    CHECK_THAT(explained(*engine, "FIND object SIMILAR TO ? LIMIT 10", query),
               Catch::Contains("in the space of the nodes' stored embeddings: search of the embedding index"));
    auto indexed = similarities(similarTo(*engine, "FIND object SIMILAR TO ? LIMIT 10", query));
    auto exact = similarities(similarTo(*engine, "FIND object WHERE height > 0 m SIMILAR TO ? LIMIT 10", query));
    REQUIRE(indexed.size() == 10);
    CHECK(indexed == exact);
}

TEST_CASE("HNSW over vectors of another length finds what the exact search finds", "[similar][vectors]") {
    constexpr std::size_t kLength = 24;
    std::uint64_t state = 11;
    std::vector<float> vectors;
    for (std::size_t i = 0; i < 3000; ++i) {
        const auto unit = similar::unitVector(pseudoRandom(state, kLength));
        vectors.insert(vectors.end(), unit.begin(), unit.end());
    }
    const float least = std::numeric_limits<float>::lowest();
    const similar::EmbeddingIndex exact(kLength, vectors, least, SIZE_MAX);
    const similar::EmbeddingIndex graph(kLength, vectors, least, 1000);
    REQUIRE(!exact.approximate());
    REQUIRE(graph.approximate());
    REQUIRE(graph.dimensions() == kLength);
    std::size_t found = 0, wanted = 0;
    for (int q = 0; q < 10; ++q) {
        const auto query = similar::unitVector(pseudoRandom(state, kLength));
        auto truth = exact.mostSimilar(query, 10);
        auto answer = graph.mostSimilar(query, 10);
        REQUIRE(truth.size() == 10);
        const float tenth = truth[9].similarity;
        wanted += 10;
        found += std::min<std::size_t>(10, std::count_if(answer.begin(), answer.end(),
                                                         [&](const auto& m) { return m.similarity >= tenth - 1e-6F; }));
        for (const auto& match : answer)
            CHECK(match.similarity == Approx(exact.similarity(match.position, query)).margin(1e-5));
    }
    CHECK(static_cast<double>(found) / static_cast<double>(wanted) >= 0.9);
}
