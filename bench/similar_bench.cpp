// smql_bench_similar: the search of SIMILAR TO against a scan of every node's vector, side by
// side. For each size it embeds the nodes of generated rooms, builds the index (distinct vectors,
// and the HNSW graph here at every size), and runs the same text queries three ways: a scan of
// every node's vector (what a table of vectors without an index does), the engine's exact scan of
// the distinct vectors, and HNSW. Medians, the ratio of the first to HNSW, and HNSW's recall of the
// exact top 10 (ties at the tenth place count as found).
// `make bench-similar` prints the Markdown table docs/benchmarks.md keeps ("SIMILAR TO").
#include <algorithm>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "bench/stats.hpp"
#include "engine/similar/embedding_index.hpp"
#include "engine/similar/text_embedder.hpp"
#include "ingest/generate/room_generator.hpp"

namespace smql::bench {

namespace {

constexpr std::size_t kTop = 10;

// What people type: categories, synonyms, colours, descriptions, misspellings.
const std::vector<std::string> kQueries = {
    "chair",
    "couch",
    "something to sit on",
    "red mug",
    "a lamp for reading",
    "blue cushion",
    "furniture",
    "plant",
    "tabel",
    "storage for books",
    "white cup",
    "soft thing",
    "screen",
    "green bottle",
    "kitchen appliance",
    "picture frame",
    "wooden table",
    "pillow",
    "container",
    "light",
};

// Words of the descriptions a capture's ingest writes ("a worn wooden chair by the window"): four
// of them per node make nearly every node's vector its own, as in a described real scene.
const std::vector<std::string> kDescriptionWords = {
    "worn",    "wooden",  "metal",   "glass",    "plastic", "leather", "fabric", "ceramic", "shiny",  "dusty",
    "small",   "large",   "tall",    "low",      "round",   "square",  "old",    "new",     "broken", "folded",
    "window",  "door",    "corner",  "wall",     "shelf",   "desk",    "floor",  "ceiling", "rug",    "stairs",
    "kitchen", "bedroom", "office",  "hallway",  "garden",  "bath",    "light",  "dark",    "bright", "striped",
    "pattern", "stacked", "open",    "closed",   "empty",   "full",    "soft",   "hard",    "heavy",  "light",
    "reading", "cooking", "working", "sleeping", "eating",  "storage", "decor",  "paper",   "books",  "flowers"};

struct Row {
    std::size_t nodes = 0;
    double embedMicrosPerNode = 0;
    double buildMillis = 0;
    double exactMicros = 0;
    double indexMicros = 0;
    double distinctMicros = 0;
    double recall = 0;
    std::size_t distinct = 0;
    bool described = false;
};

std::vector<similar::Vector> embeddedRooms(std::size_t nodes, bool described, double& micros) {
    std::vector<model::Node> all;
    std::uint64_t state = 42;  // a fixed linear congruential sequence: the same text every run
    auto nextWord = [&] {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return kDescriptionWords[(state >> 33) % kDescriptionWords.size()];
    };
    for (std::uint64_t seed = 1; all.size() < nodes; ++seed) {
        auto room = generate::generateRoom({.seed = seed, .objectCount = 2000, .name = "bench"});
        for (auto& node : room.nodes) {
            if (all.size() == nodes) break;
            if (described) node.text = fmt::format("{} {} {} {}", nextWord(), nextWord(), nextWord(), nextWord());
            all.push_back(std::move(node));
        }
    }
    auto started = Clock::now();
    std::vector<similar::Vector> vectors;
    vectors.reserve(all.size());
    for (const auto& node : all) vectors.push_back(similar::embedNode(node));
    micros = microsecondsSince(started);
    return vectors;
}

Row measure(std::size_t nodes, bool described, int repeats) {
    Row row;
    row.nodes = nodes;
    row.described = described;
    double embedMicros = 0;
    auto vectors = embeddedRooms(nodes, described, embedMicros);
    row.embedMicrosPerNode = embedMicros / static_cast<double>(nodes);
    auto started = Clock::now();
    similar::EmbeddingIndex indexed(vectors, 0);               // HNSW at every size, to show where it pays
    const similar::EmbeddingIndex scanned(vectors, SIZE_MAX);  // never HNSW: the distinct vectors scanned
    row.buildMillis = microsecondsSince(started) / 1000;

    std::vector<double> exactTimes, indexTimes, distinctTimes;
    double found = 0, wanted = 0;
    for (const auto& text : kQueries) {
        const similar::Vector query = similar::embedQuery(text);
        std::vector<similar::EmbeddingIndex::Match> exact;
        for (int r = 0; r < repeats; ++r) {
            auto t = Clock::now();
            // An exact top 10: every vector's similarity, then a partial sort.
            std::vector<similar::EmbeddingIndex::Match> all;
            all.reserve(vectors.size());
            for (std::size_t i = 0; i < vectors.size(); ++i) {
                const float s = similar::similarity(vectors[i], query);
                if (s > 0) all.push_back({static_cast<std::uint32_t>(i), s});
            }
            const std::size_t keep = std::min(kTop, all.size());
            std::partial_sort(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(keep), all.end(),
                              [](const auto& a, const auto& b) { return a.similarity > b.similarity; });
            all.resize(keep);
            exactTimes.push_back(microsecondsSince(t));
            exact = std::move(all);
        }
        for (int r = 0; r < repeats; ++r) {
            auto t = Clock::now();
            auto answer = scanned.mostSimilar(query, kTop);
            distinctTimes.push_back(microsecondsSince(t));
        }
        std::vector<similar::EmbeddingIndex::Match> approximate;
        for (int r = 0; r < repeats; ++r) {
            auto t = Clock::now();
            approximate = indexed.mostSimilar(query, kTop);
            indexTimes.push_back(microsecondsSince(t));
        }
        if (exact.empty()) continue;
        // Ties: any node as similar as the exact tenth counts as a right answer.
        const float tenth = exact.back().similarity;
        wanted += static_cast<double>(exact.size());
        const auto right = std::count_if(approximate.begin(), approximate.end(),
                                         [&](const auto& match) { return match.similarity >= tenth - 1e-6F; });
        found += static_cast<double>(std::min<std::size_t>(static_cast<std::size_t>(right), exact.size()));
    }
    row.exactMicros = median(exactTimes);
    row.indexMicros = median(indexTimes);
    row.distinctMicros = median(distinctTimes);
    row.recall = wanted > 0 ? found / wanted : 1.0;
    row.distinct = indexed.distinct();
    return row;
}

}  // namespace

}  // namespace smql::bench

int main(int argc, char** argv) {
    using namespace smql::bench;
    std::vector<std::size_t> sizes{2000, 10000, 50000};
    int repeats = 5;
    CLI::App app{"smql_bench_similar: SIMILAR TO's search (distinct vectors, HNSW) against a scan of every node"};
    app.add_option("--sizes", sizes, "node counts to measure (each from generated rooms)");
    app.add_option("--repeats", repeats, "timed runs of each query on each side")->check(CLI::PositiveNumber);
    CLI11_PARSE(app, argc, argv);
    fmt::print(
        "| nodes | text | distinct vectors | embed per node (µs) | HNSW build (ms) | top {} by scanning every node "
        "(µs) | "
        "top {} by scanning distinct vectors (µs) | top {} by HNSW (µs) | every node / HNSW | HNSW recall@{} |\n",
        kTop, kTop, kTop, kTop);
    fmt::print("|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (bool described : {false, true})
        for (std::size_t n : sizes) {
            Row row = measure(n, described, repeats);
            fmt::print("| {} | {} | {} | {:.1f} | {:.0f} | {:.0f} | {:.0f} | {:.0f} | {:.1f}x | {:.3f} |\n", row.nodes,
                       row.described ? "category, colour, description" : "category, colour", row.distinct,
                       row.embedMicrosPerNode, row.buildMillis, row.exactMicros, row.distinctMicros, row.indexMicros,
                       row.exactMicros / row.indexMicros, row.recall);
            std::cout.flush();
        }
    fmt::print("\n{} queries x {} runs each per size, on {} cores, {} build\n", kQueries.size(), repeats,
               std::thread::hardware_concurrency(), SMQL_BENCH_BUILD_TYPE);
    return 0;
}
