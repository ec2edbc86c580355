#include "engine/similar/embedding_index.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <mutex>
#include <queue>
#include <string_view>
#include <unordered_map>

#include <hnswlib/hnswlib.h>

namespace smql::similar {

namespace {

constexpr std::size_t kLinksPerNode = 16;  // hnswlib's M
constexpr std::size_t kBuildBeam = 200;    // ef_construction
constexpr std::size_t kSearchBeam = 128;   // the least ef of a search
constexpr std::size_t kSeed = 100;         // the same graph for the same vectors, run after run

std::string_view bytesOf(std::span<const float> v) {
    return {reinterpret_cast<const char*>(v.data()), v.size() * sizeof(float)};
}

}  // namespace

std::vector<float> unitVector(std::span<const float> vector) {
    double norm = 0;
    for (float x : vector) norm += static_cast<double>(x) * x;
    const double scale = 1 / std::sqrt(norm);
    std::vector<float> unit(vector.size());
    for (std::size_t i = 0; i < vector.size(); ++i) unit[i] = static_cast<float>(vector[i] * scale);
    return unit;
}

struct EmbeddingIndex::Graph {
    hnswlib::InnerProductSpace space;
    hnswlib::HierarchicalNSW<float> hnsw;
    // hnswlib's search is const, but its beam width (ef) is a member set before each search.
    std::mutex searching;
    Graph(std::size_t dimensions, std::size_t capacity)
        : space(dimensions), hnsw(&space, capacity, kLinksPerNode, kBuildBeam, kSeed) {}
};

template <class VectorAt>
void EmbeddingIndex::group(std::size_t count, const VectorAt& vectorAt, std::size_t indexedFrom) {
    groupOf_.assign(count, kNoGroup);
    std::unordered_map<std::string_view, std::uint32_t> groupByBytes;
    for (std::size_t i = 0; i < count; ++i) {
        const std::span<const float> vector = vectorAt(i);
        if (isZero(vector)) continue;
        auto [at, added] = groupByBytes.try_emplace(bytesOf(vector), static_cast<std::uint32_t>(groups_.size()));
        if (added) {
            groups_.emplace_back();
            groupVectors_.insert(groupVectors_.end(), vector.begin(), vector.end());
        }
        groups_[at->second].positions.push_back(static_cast<std::uint32_t>(i));
        groupOf_[i] = at->second;
    }
    if (groups_.size() < indexedFrom) return;
    graph_ = std::make_unique<Graph>(dimensions_, groups_.size());
    for (std::size_t g = 0; g < groups_.size(); ++g) graph_->hnsw.addPoint(vectorOf(g).data(), g);
}

EmbeddingIndex::EmbeddingIndex(std::size_t dimensions, std::span<const float> vectors, float least,
                               std::size_t indexedFrom)
    : dimensions_(dimensions), least_(least) {
    assert(dimensions > 0 && vectors.size() % dimensions == 0);
    group(
        vectors.size() / dimensions, [&](std::size_t i) { return vectors.subspan(i * dimensions, dimensions); },
        indexedFrom);
}

EmbeddingIndex::EmbeddingIndex(const std::vector<Vector>& vectors, std::size_t indexedFrom)
    : dimensions_(kDimensions), least_(kLeastSimilarity) {
    group(
        vectors.size(), [&](std::size_t i) { return std::span<const float>(vectors[i]); }, indexedFrom);
}

EmbeddingIndex::~EmbeddingIndex() = default;
EmbeddingIndex::EmbeddingIndex(EmbeddingIndex&&) noexcept = default;
EmbeddingIndex& EmbeddingIndex::operator=(EmbeddingIndex&&) noexcept = default;

float EmbeddingIndex::similarity(std::uint32_t position, std::span<const float> query) const {
    const std::uint32_t group = groupOf_[position];
    return group == kNoGroup ? 0.0F : similar::similarity(vectorOf(group), query);
}

std::vector<EmbeddingIndex::Match> EmbeddingIndex::mostSimilar(std::span<const float> query, std::size_t k) const {
    assert(query.size() == dimensions_);
    struct Found {
        std::uint32_t group;
        float similarity;
    };
    std::vector<Found> found;
    if (k == 0 || isZero(query) || groups_.empty()) return {};
    const std::size_t groupsWanted = std::min(k, groups_.size());
    if (!graph_) {
        found.reserve(groups_.size());
        for (std::size_t g = 0; g < groups_.size(); ++g)
            found.push_back({static_cast<std::uint32_t>(g), similar::similarity(vectorOf(g), query)});
    } else {
        std::priority_queue<std::pair<float, hnswlib::labeltype>> nearest;
        {
            std::lock_guard guard(graph_->searching);
            graph_->hnsw.setEf(std::max(groupsWanted, kSearchBeam));
            nearest = graph_->hnsw.searchKnn(query.data(), groupsWanted);
        }
        for (; !nearest.empty(); nearest.pop())  // inner-product distance: 1 - similarity
            found.push_back({static_cast<std::uint32_t>(nearest.top().second), 1.0F - nearest.top().first});
    }
    std::erase_if(found, [&](const Found& f) { return !(f.similarity >= least_); });
    if (found.size() > groupsWanted) {
        // Only the groups at least as similar as the k-th need sorting (those tied with it included).
        auto kth = found.begin() + static_cast<std::ptrdiff_t>(groupsWanted - 1);
        std::nth_element(found.begin(), kth, found.end(),
                         [](const Found& a, const Found& b) { return a.similarity > b.similarity; });
        const float kthSimilarity = kth->similarity;
        std::erase_if(found, [&](const Found& f) { return f.similarity < kthSimilarity; });
    }
    // Groups in order of similarity, ties by their first node; each brings all its nodes.
    std::sort(found.begin(), found.end(), [&](const Found& a, const Found& b) {
        return a.similarity != b.similarity ? a.similarity > b.similarity
                                            : groups_[a.group].positions.front() < groups_[b.group].positions.front();
    });
    std::vector<Match> out;
    for (std::size_t i = 0; i < found.size() && out.size() < k;) {
        // Groups equally similar merge, so their nodes come in position order.
        std::size_t end = i;
        std::vector<std::uint32_t> positions;
        for (; end < found.size() && found[end].similarity == found[i].similarity; ++end)
            positions.insert(positions.end(), groups_[found[end].group].positions.begin(),
                             groups_[found[end].group].positions.end());
        std::sort(positions.begin(), positions.end());
        for (std::uint32_t p : positions) out.push_back({p, found[i].similarity});
        i = end;
    }
    return out;
}

}  // namespace smql::similar
