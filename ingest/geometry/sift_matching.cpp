#include "ingest/geometry/sift_matching.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <future>
#include <map>
#include <set>
#include <thread>

#include <immintrin.h>

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

// The dot products, a tile of R rows of `a` by C rows of `b` at a time (`n` to a row of `out`), in eight lanes of
// fused multiply-adds for processors with AVX2 and FMA. Debian builds for SSE2, where Eigen's product held
// the matching of Mip-NeRF 360's 25 kitchen photos (13,700 features each at the mean) to 320 s; this path
// matched them in 214 s, and TUM fr1/rpy's 100 frames in 4.2 s where they took 7.8, the same model to the
// byte (the ingest's "feature matching (smql)" step). The products and their sums are integers under 2^24,
// exact in floats, so this gives Eigen's bytes whatever the order of the additions. The tile's loops are unrolled so
// that its sums stay in registers (GCC's -O2 left them in memory, and the products took longer than Eigen's).
template <int R, int C>
__attribute__((target("avx2,fma"))) inline void dotTile(const float* a, const float* b, std::size_t n, float* out) {
    __m256 sum[R][C];
#pragma GCC unroll 4
    for (int i = 0; i < R; ++i)
#pragma GCC unroll 4
        for (int c = 0; c < C; ++c) sum[i][c] = _mm256_setzero_ps();
#pragma GCC unroll 16
    for (int k = 0; k < 128; k += 8) {
        __m256 bk[C];
#pragma GCC unroll 4
        for (int c = 0; c < C; ++c) bk[c] = _mm256_loadu_ps(b + c * 128 + k);
#pragma GCC unroll 4
        for (int i = 0; i < R; ++i) {
            const __m256 ak = _mm256_loadu_ps(a + i * 128 + k);
#pragma GCC unroll 4
            for (int c = 0; c < C; ++c) sum[i][c] = _mm256_fmadd_ps(ak, bk[c], sum[i][c]);
        }
    }
#pragma GCC unroll 4
    for (int i = 0; i < R; ++i)
#pragma GCC unroll 4
        for (int c = 0; c < C; ++c) {
            __m128 half = _mm_add_ps(_mm256_castps256_ps128(sum[i][c]), _mm256_extractf128_ps(sum[i][c], 1));
            half = _mm_add_ps(half, _mm_movehl_ps(half, half));
            half = _mm_add_ss(half, _mm_movehdup_ps(half));
            out[static_cast<std::size_t>(i) * n + static_cast<std::size_t>(c)] = _mm_cvtss_f32(half);
        }
}

// Row tiles of `a` against the `width` rows of `b` from `b`'s row `from` on (`n` columns to a row of `out`).
template <int R>
__attribute__((target("avx2,fma"))) inline void dotRows(const float* a, const float* b, std::size_t from,
                                                        std::size_t width, std::size_t n, float* out) {
    constexpr std::size_t kColumns = 3;
    std::size_t j = from;
    for (; j + kColumns <= from + width; j += kColumns) dotTile<R, kColumns>(a, b + j * 128, n, out + j);
    for (; j < from + width; ++j) dotTile<R, 1>(a, b + j * 128, n, out + j);
}

// `b` a slice at a time, each slice's 48 KB held in the first-level cache while every row of `a` meets it.
__attribute__((target("avx2,fma"))) void dotProductsAvx2(const float* a, std::size_t rows, const float* b,
                                                         std::size_t n, float* out) {
    constexpr std::size_t kRows = 4, kSlice = 96;
    for (std::size_t from = 0; from < n; from += kSlice) {
        const std::size_t width = std::min(kSlice, n - from);
        std::size_t r = 0;
        for (; r + kRows <= rows; r += kRows) dotRows<kRows>(a + r * 128, b, from, width, n, out + r * n);
        for (; r < rows; ++r) dotRows<1>(a + r * 128, b, from, width, n, out + r * n);
    }
}

}  // namespace

void descriptorDots(const float* a, std::size_t rows, const float* b, std::size_t n, float* out, bool portable) {
    static const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    if (avx2 && !portable) return dotProductsAvx2(a, rows, b, n, out);
    const Eigen::Map<const Floats> A(a, static_cast<Eigen::Index>(rows), 128), B(b, static_cast<Eigen::Index>(n), 128);
    Eigen::Map<Floats>(out, static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(n)).noalias() =
        A * B.transpose();
}

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
        descriptorDots(floatsA.data() + first * 128, rows, floatsB.data(), rowsB, dots_.data());
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
