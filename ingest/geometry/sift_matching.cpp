#include "ingest/geometry/sift_matching.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <future>
#include <map>
#include <set>
#include <thread>

#include <Eigen/Core>

#include "ingest/geometry/colmap_database.hpp"

namespace smql::ingest {

namespace {

using Floats = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

Eigen::Map<Floats> asFloats(const std::uint8_t* data, std::size_t rows, std::vector<float>& buffer) {
    using Bytes = Eigen::Matrix<std::uint8_t, Eigen::Dynamic, 128, Eigen::RowMajor>;
    buffer.resize(std::max(buffer.size(), rows * 128));
    Eigen::Map<Floats> out(buffer.data(), static_cast<Eigen::Index>(rows), 128);
    out = Eigen::Map<const Bytes>(data, static_cast<Eigen::Index>(rows), 128).cast<float>();
    return out;
}

// COLMAP's descriptors are unit vectors scaled to 512: a dot product gives the angle between two. The
// best passes when its angle is within the distance and under the ratio times the second best's; a tie
// with the best is the second best too (COLMAP's FindBestMatchesOneWayBruteForce), and fails.
bool passes(float best, float second, const SiftMatchOptions& options) {
    constexpr float kNorm = 1.0f / (512.0f * 512.0f);
    const float bestAngle = std::acos(std::min(kNorm * best, 1.0f));
    if (bestAngle > options.maxDistance) return false;
    return bestAngle < options.maxRatio * std::acos(std::min(kNorm * second, 1.0f));
}

// One row of dot products (row `i` of a) into each column's best and second best so far: selects
// without branches, which the compiler vectorises (asked for its full cost model, as GCC's -O2 leaves
// this loop scalar), also compiled for AVX2, chosen when the processor has it.
#if !defined(__clang__)
__attribute__((optimize("vect-cost-model=dynamic")))
#endif
__attribute__((target_clones("avx2", "default"))) void
keepNearest(const float* row, std::size_t n, std::int32_t i, float* best, float* second, std::int32_t* nearest) {
    for (std::size_t j = 0; j < n; ++j) {
        const float dot = row[j];
        const bool better = dot > best[j];
        second[j] = better ? best[j] : std::max(second[j], dot);
        nearest[j] = better ? i : nearest[j];
        best[j] = better ? dot : best[j];
    }
}

}  // namespace

std::vector<std::pair<std::uint32_t, std::uint32_t>> SiftMatcher::match(const std::uint8_t* a, std::size_t rowsA,
                                                                        const std::uint8_t* b, std::size_t rowsB) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
    if (rowsA == 0 || rowsB == 0) return out;
    const Eigen::Map<Floats> floatsA = asFloats(a, rowsA, a_), floatsB = asFloats(b, rowsB, b_);
    if (options_.crossCheck) {
        best_.assign(rowsB, 0.0f);
        second_.assign(rowsB, 0.0f);
        nearest_.assign(rowsB, -1);
    }
    // The dot products a block of a's rows at a time: two frames of 8,192 features (COLMAP's most) would
    // take 268 MB at once. The rows' nearest are kept as candidates until the columns' are all known.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> candidates;
    constexpr std::size_t kBlockRows = 1024;
    for (std::size_t first = 0; first < rowsA; first += kBlockRows) {
        const std::size_t rows = std::min(kBlockRows, rowsA - first);
        dots_.resize(std::max(dots_.size(), rows * rowsB));
        Eigen::Map<Floats> dots(dots_.data(), static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(rowsB));
        dots.noalias() =
            floatsA.middleRows(static_cast<Eigen::Index>(first), static_cast<Eigen::Index>(rows)) * floatsB.transpose();
        if (options_.crossCheck)
            for (std::size_t r = 0; r < rows; ++r)
                keepNearest(dots_.data() + r * rowsB, rowsB, static_cast<std::int32_t>(first + r), best_.data(),
                            second_.data(), nearest_.data());
        for (Eigen::Index r = 0; r < dots.rows(); ++r) {
            auto row = dots.row(r);
            Eigen::Index j = 0;
            const float best = row.maxCoeff(&j);
            if (!(best > 0)) continue;  // no dot product above 0: no nearest (COLMAP's rule)
            row(j) = -1;                // the second best: the largest of the others (a tie with the best is one)
            const float second = std::max(row.maxCoeff(), 0.0f);
            if (passes(best, second, options_))
                candidates.emplace_back(static_cast<std::uint32_t>(first + static_cast<std::size_t>(r)),
                                        static_cast<std::uint32_t>(j));
        }
    }
    for (const auto& [i, j] : candidates)
        if (!options_.crossCheck ||
            (nearest_[j] == static_cast<std::int32_t>(i) && passes(best_[j], second_[j], options_)))
            out.emplace_back(i, j);
    return out;
}

std::vector<std::pair<std::size_t, std::size_t>> sequentialPairs(std::size_t images, int overlap, bool quadratic) {
    std::set<std::pair<std::size_t, std::size_t>> pairs;
    for (std::size_t first = 0; first < images; ++first)
        for (int k = 0; k < std::min(overlap, 31); ++k) {
            if (first + static_cast<std::size_t>(k) >= images) break;
            if (k > 0) pairs.emplace(first, first + static_cast<std::size_t>(k));
            const std::size_t farther = first + (std::size_t{1} << k);
            if (quadratic && farther < images) pairs.emplace(first, farther);
        }
    return {pairs.begin(), pairs.end()};
}

ColmapMatching matchColmapPairs(const std::string& database,
                                const std::vector<std::pair<std::string, std::string>>& pairs, int threads,
                                const SiftMatchOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    std::map<std::string, long long> ids;
    for (const auto& image : readColmapImages(database)) ids.emplace(image.name, image.id);
    std::set<std::pair<long long, long long>> done;
    for (const auto& matched : readColmapMatches(database)) done.emplace(matched.first, matched.second);
    std::vector<std::pair<long long, long long>> todo;
    for (const auto& [first, second] : pairs) {
        const auto a = ids.find(first), b = ids.find(second);
        if (a == ids.end() || b == ids.end() || a->second == b->second) continue;
        const auto pair = std::minmax(a->second, b->second);
        if (done.insert(pair).second) todo.push_back(pair);
    }
    ColmapMatching out;
    if (todo.empty()) return out;

    std::map<long long, ColmapDescriptors> descriptors;
    for (auto& d : readColmapDescriptors(database)) descriptors.emplace(d.image, std::move(d));
    const ColmapDescriptors none;
    auto of = [&](long long image) -> const ColmapDescriptors& {
        const auto found = descriptors.find(image);
        return found == descriptors.end() ? none : found->second;
    };
    std::vector<ColmapPairMatches> matched(todo.size());
    std::atomic<std::size_t> next{0};
    auto work = [&] {
        SiftMatcher matcher(options);
        for (std::size_t k; (k = next++) < todo.size();) {
            const auto& [first, second] = todo[k];
            const ColmapDescriptors &a = of(first), &b = of(second);
            matched[k] = {first, second, matcher.match(a.data.data(), a.rows, b.data.data(), b.rows)};
        }
    };
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const std::size_t helpers =
        std::min<std::size_t>(todo.size(), threads > 0 ? static_cast<std::size_t>(threads) : cores) - 1;
    std::vector<std::future<void>> running;
    for (std::size_t h = 0; h < helpers; ++h) running.push_back(std::async(std::launch::async, work));
    work();
    for (auto& r : running) r.get();
    writeColmapMatches(database, matched);

    out.pairs = todo.size();
    out.matched = static_cast<std::size_t>(
        std::count_if(matched.begin(), matched.end(), [](const ColmapPairMatches& m) { return !m.matches.empty(); }));
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

}  // namespace smql::ingest
