// The vectors of one scene's nodes in one space and the search SIMILAR TO runs on them: the
// built-in text embedder's (kDimensions floats, text_embedder.hpp) or the vectors an external model
// gave the nodes at ingest (their `embedding` blobs, model/embedding.hpp), of any length. Nodes that
// say the same (nine grey cushions) share one vector: the search runs over the distinct vectors and
// answers with every node of each, which keeps the search small and spares HNSW the many exact ties
// it handles badly. Up to kIndexedFrom distinct vectors are searched exactly; from there on an
// hnswlib graph (HNSW, inner product on unit vectors) answers top-k searches approximately, and the
// executor widens k until enough candidates pass its filters.
//
// The graph is built in memory when a scene is first searched and kept with its snapshot, not
// stored: building it costs about as much as a thousand exact scans (bench/similar_bench.cpp,
// docs/benchmarks.md), so below kIndexedFrom a one-statement `smql DB -c` is better served exactly,
// and above it only long sessions (the shell, an embedding application) repay it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "engine/similar/text_embedder.hpp"

namespace smql::similar {

// `vector` scaled to unit length (it must not be zero): how a stored or bound vector from an
// external model enters a search, whose similarity is then a dot product.
std::vector<float> unitVector(std::span<const float> vector);

class EmbeddingIndex {
public:
    static constexpr std::size_t kIndexedFrom = 20000;

    // `vectors` holds one vector of `dimensions` floats per node, by position (the executor's
    // slots), back to back: unit length, or zero for a node without one, which searches leave out.
    // Matches less similar than `least` are never answered. The HNSW graph is built when there are
    // `indexedFrom` distinct vectors or more.
    EmbeddingIndex(std::size_t dimensions, std::span<const float> vectors, float least,
                   std::size_t indexedFrom = kIndexedFrom);
    // The built-in text embedder's vectors, with its least similarity (kLeastSimilarity).
    explicit EmbeddingIndex(const std::vector<Vector>& vectors, std::size_t indexedFrom = kIndexedFrom);
    ~EmbeddingIndex();
    EmbeddingIndex(EmbeddingIndex&&) noexcept;
    EmbeddingIndex& operator=(EmbeddingIndex&&) noexcept;

    std::size_t dimensions() const { return dimensions_; }
    std::size_t size() const { return groupOf_.size(); }
    // Distinct non-zero vectors: what a search visits.
    std::size_t distinct() const { return groups_.size(); }
    float least() const { return least_; }
    bool hasVector(std::uint32_t position) const { return groupOf_[position] != kNoGroup; }
    // Cosine similarity of a position's vector and a unit-length `query` of dimensions() floats; 0
    // for a position without a vector.
    float similarity(std::uint32_t position, std::span<const float> query) const;
    // Whether searches go through the HNSW graph (approximate) rather than a scan (exact).
    bool approximate() const { return graph_ != nullptr; }

    struct Match {
        std::uint32_t position;
        float similarity;
    };
    // At least k positions (all of the last group found; fewer when fewer reach least()) most similar to
    // `query` first, ties by position. Exact without the graph; with it, HNSW's answer (ef = max(k, 128)).
    std::vector<Match> mostSimilar(std::span<const float> query, std::size_t k) const;

private:
    struct Group {
        std::vector<std::uint32_t> positions;  // ascending
    };
    struct Graph;
    static constexpr std::uint32_t kNoGroup = UINT32_MAX;
    // Groups the `count` vectors `vectorAt(position)` gives, keeps one copy of each distinct one, and
    // builds the graph from `indexedFrom` of them.
    template <class VectorAt>
    void group(std::size_t count, const VectorAt& vectorAt, std::size_t indexedFrom);
    std::span<const float> vectorOf(std::size_t group) const {
        return {groupVectors_.data() + group * dimensions_, dimensions_};
    }

    std::size_t dimensions_;
    float least_;
    std::vector<float> groupVectors_;  // the distinct vectors, back to back, by group: one scan runs over them
    std::vector<Group> groups_;
    std::vector<std::uint32_t> groupOf_;  // by position; kNoGroup for zero vectors
    std::unique_ptr<Graph> graph_;
};

}  // namespace smql::similar
