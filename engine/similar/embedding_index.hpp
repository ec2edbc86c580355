// The vectors of one scene's nodes and the search SIMILAR TO runs on them. Nodes that say the same
// (nine grey cushions) share one vector: the search runs over the distinct vectors and answers with
// every node of each, which keeps the search small and spares HNSW the many exact ties it handles
// badly. Up to kIndexedFrom distinct vectors are searched exactly; from there on an hnswlib graph
// (HNSW, inner product on unit vectors) answers top-k searches approximately, and the executor
// widens k until enough candidates pass its filters.
//
// The graph is built in memory when a scene is first searched and kept with its snapshot, not
// stored: building it costs about as much as a thousand exact scans (bench/similar_bench.cpp,
// docs/benchmarks.md), so below kIndexedFrom a one-statement `smql DB -c` is better served exactly,
// and above it only long sessions (the shell, an embedding application) repay it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "engine/similar/text_embedder.hpp"

namespace smql::similar {

class EmbeddingIndex {
public:
    static constexpr std::size_t kIndexedFrom = 20000;

    // One vector per node, by position (the executor's slots); zero vectors are left out of
    // searches. The HNSW graph is built when there are `indexedFrom` distinct vectors or more.
    explicit EmbeddingIndex(const std::vector<Vector>& vectors, std::size_t indexedFrom = kIndexedFrom);
    ~EmbeddingIndex();
    EmbeddingIndex(EmbeddingIndex&&) noexcept;
    EmbeddingIndex& operator=(EmbeddingIndex&&) noexcept;

    std::size_t size() const { return groupOf_.size(); }
    // Distinct non-zero vectors: what a search visits.
    std::size_t distinct() const { return groups_.size(); }
    float similarity(std::uint32_t position, const Vector& query) const;
    // Whether searches go through the HNSW graph (approximate) rather than a scan (exact).
    bool approximate() const { return graph_ != nullptr; }

    struct Match {
        std::uint32_t position;
        float similarity;
    };
    // At least k positions (all of the last group found; fewer when fewer reach kLeastSimilarity) most similar to
    // `query` first, ties by position. Exact without the graph; with it, HNSW's answer (ef = max(k, 128)).
    std::vector<Match> mostSimilar(const Vector& query, std::size_t k) const;

private:
    struct Group {
        Vector vector;
        std::vector<std::uint32_t> positions;  // ascending
    };
    struct Graph;
    static constexpr std::uint32_t kNoGroup = UINT32_MAX;
    std::vector<Group> groups_;
    std::vector<std::uint32_t> groupOf_;  // by position; kNoGroup for zero vectors
    std::unique_ptr<Graph> graph_;
};

}  // namespace smql::similar
