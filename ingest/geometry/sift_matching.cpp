#include "ingest/geometry/sift_matching.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <future>
#include <limits>
#include <map>
#include <numeric>
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
// fused multiply-adds for processors with AVX2 and FMA and without AVX-512 VNNI (the bytes' way, below). Debian
// builds for SSE2, where Eigen's product held the matching of Mip-NeRF 360's 25 kitchen photos (13,700 features
// each at the mean) to 320 s; this path matched them in 214 s, and TUM fr1/rpy's 100 frames in 4.2 s where they
// took 7.8, the same model to the byte (the ingest's "feature matching (smql)" step). The products and their sums are
// integers under 2^24, exact in floats, so this gives Eigen's bytes whatever the order of the additions. The tile's
// loops are unrolled so that its sums stay in registers (GCC's -O2 left them in memory, and the products took longer
// than Eigen's).
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

// The bytes' own way, for processors with AVX-512 VNNI, whose vpdpbusd multiplies 64 bytes by 64 and sums them
// four at a time into sixteen integers in one instruction, four times the products of a float fused
// multiply-add of that width. Its second operand is signed, so b's bytes go in less 128 (packColumns) and
// each product of a's row gets 128 times the row's sum back (`corrections`): a.b = a.(b - 128) + 128 sum(a).
// The integers are the dot products themselves, as the floats are, so the matches are the same.
constexpr std::size_t kGroupLanes = 16;           // b's rows side by side in a product
constexpr std::size_t kQuads = 128 / 4;           // a descriptor's bytes, four to a lane
constexpr std::size_t kGroupBytes = kQuads * 64;  // a group of 16 of b's rows, packed
constexpr std::int32_t kNone = std::numeric_limits<std::int32_t>::min();
// Every lane: GCC 12's _mm512_max_epi32 starts from an undefined vector, which its own warnings then flag.
constexpr __mmask16 kAllLanes = 0xFFFF;

// b's rows in groups of sixteen, each group's quads one after another, a quad's 64 bytes the sixteen rows'
// four bytes side by side; rows past b's last are zeros (their products are left out).
void packColumns(const std::uint8_t* b, std::size_t rowsB, std::vector<std::int8_t>& packed) {
    const std::size_t groups = (rowsB + kGroupLanes - 1) / kGroupLanes;
    packed.assign(groups * kGroupBytes, 0);
    for (std::size_t j = 0; j < rowsB; ++j) {
        std::int8_t* lane = packed.data() + (j / kGroupLanes) * kGroupBytes + (j % kGroupLanes) * 4;
        for (std::size_t q = 0; q < kQuads; ++q)
            for (std::size_t t = 0; t < 4; ++t)
                lane[q * 64 + t] = static_cast<std::int8_t>(b[j * 128 + q * 4 + t] ^ 0x80);
    }
}

// Where the products go as they come: each of b's rows' best, second best and nearest of a's rows so far
// (keepNearest's rule, a's rows in order), and each of a block of a's rows' best, second best and nearest
// of b's rows so far in each of sixteen lanes (lane l sees b's rows l, l + 16, ... in order).
struct NearestSoFar {
    std::int32_t* columnBest;
    std::int32_t* columnSecond;
    std::int32_t* columnNearest;
    std::int32_t* rowBest;  // 16 a row
    std::int32_t* rowSecond;
    std::int32_t* rowNearest;
};

// The products of R of a's rows (`first` the first's index, `corrections` theirs) with C groups of b's rows
// from group `group` on, kept in `kept`; `rowsB` of b's rows are real.
template <int R, int C>
__attribute__((target("avx512f,avx512bw,avx512vnni"))) inline void byteTile(const std::uint8_t* a, std::int32_t first,
                                                                            const std::int32_t* corrections,
                                                                            const std::int8_t* packed,
                                                                            std::size_t group, std::size_t rowsB,
                                                                            const NearestSoFar& kept) {
    __m512i sum[R][C];
#pragma GCC unroll 4
    for (int i = 0; i < R; ++i)
#pragma GCC unroll 4
        for (int c = 0; c < C; ++c) sum[i][c] = _mm512_setzero_si512();
    const std::int8_t* groups = packed + group * kGroupBytes;
#pragma GCC unroll 8
    for (std::size_t q = 0; q < kQuads; ++q) {
        __m512i bq[C];
#pragma GCC unroll 4
        for (int c = 0; c < C; ++c) bq[c] = _mm512_loadu_si512(groups + c * kGroupBytes + q * 64);
#pragma GCC unroll 4
        for (int i = 0; i < R; ++i) {
            std::int32_t quad;
            std::memcpy(&quad, a + i * 128 + q * 4, 4);
            const __m512i aq = _mm512_set1_epi32(quad);
#pragma GCC unroll 4
            for (int c = 0; c < C; ++c) sum[i][c] = _mm512_dpbusd_epi32(sum[i][c], aq, bq[c]);
        }
    }
    const __m512i lanes = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    const __m512i none = _mm512_set1_epi32(kNone);
#pragma GCC unroll 4
    for (int c = 0; c < C; ++c) {
        const std::size_t column = (group + static_cast<std::size_t>(c)) * kGroupLanes;
        const __mmask16 real =
            column + kGroupLanes <= rowsB ? kAllLanes : static_cast<__mmask16>((1u << (rowsB - column)) - 1);
        const __m512i columns = _mm512_add_epi32(_mm512_set1_epi32(static_cast<std::int32_t>(column)), lanes);
        __m512i best = _mm512_loadu_si512(kept.columnBest + column);
        __m512i second = _mm512_loadu_si512(kept.columnSecond + column);
        __m512i nearest = _mm512_loadu_si512(kept.columnNearest + column);
#pragma GCC unroll 4
        for (int i = 0; i < R; ++i) {
            const __m512i dot = _mm512_add_epi32(sum[i][c], _mm512_set1_epi32(corrections[i]));
            __mmask16 better = _mm512_cmpgt_epi32_mask(dot, best);
            second = _mm512_mask_mov_epi32(_mm512_maskz_max_epi32(kAllLanes, second, dot), better, best);
            nearest = _mm512_mask_mov_epi32(nearest, better, _mm512_set1_epi32(first + i));
            best = _mm512_mask_mov_epi32(best, better, dot);

            std::int32_t* row = kept.rowBest + i * kGroupLanes;
            const __m512i rowDot = _mm512_mask_mov_epi32(none, real, dot);
            const __m512i rowBest = _mm512_loadu_si512(row);
            better = _mm512_cmpgt_epi32_mask(rowDot, rowBest);
            std::int32_t* rowSecond = kept.rowSecond + i * kGroupLanes;
            std::int32_t* rowNearest = kept.rowNearest + i * kGroupLanes;
            _mm512_storeu_si512(rowSecond, _mm512_mask_mov_epi32(
                                               _mm512_maskz_max_epi32(kAllLanes, _mm512_loadu_si512(rowSecond), rowDot),
                                               better, rowBest));
            _mm512_mask_storeu_epi32(rowNearest, better, columns);
            _mm512_mask_storeu_epi32(row, better, rowDot);
        }
        _mm512_storeu_si512(kept.columnBest + column, best);
        _mm512_storeu_si512(kept.columnSecond + column, second);
        _mm512_storeu_si512(kept.columnNearest + column, nearest);
    }
}

// R of a's rows against b's groups [from, to), four groups at a time.
template <int R>
__attribute__((target("avx512f,avx512bw,avx512vnni"))) inline void byteRows(const std::uint8_t* a, std::int32_t first,
                                                                            const std::int32_t* corrections,
                                                                            const std::int8_t* packed, std::size_t from,
                                                                            std::size_t to, std::size_t rowsB,
                                                                            const NearestSoFar& kept) {
    constexpr std::size_t kGroups = 4;
    std::size_t g = from;
    for (; g + kGroups <= to; g += kGroups) byteTile<R, kGroups>(a, first, corrections, packed, g, rowsB, kept);
    for (; g < to; ++g) byteTile<R, 1>(a, first, corrections, packed, g, rowsB, kept);
}

// A block of `rows` of a's rows (`first` the first's index) against all of b's, 32 groups (64 KB, held in
// the second-level cache) at a time, four of a's rows at a time.
__attribute__((target("avx512f,avx512bw,avx512vnni"))) void byteProducts(const std::uint8_t* a, std::size_t rows,
                                                                         std::int32_t first,
                                                                         const std::int32_t* corrections,
                                                                         const std::int8_t* packed, std::size_t rowsB,
                                                                         NearestSoFar kept) {
    constexpr std::size_t kRows = 4, kSliceGroups = 32;
    const std::size_t groups = (rowsB + kGroupLanes - 1) / kGroupLanes;
    for (std::size_t from = 0; from < groups; from += kSliceGroups) {
        const std::size_t to = std::min(groups, from + kSliceGroups);
        NearestSoFar at = kept;
        std::size_t r = 0;
        for (; r + kRows <= rows; r += kRows) {
            byteRows<kRows>(a + r * 128, first + static_cast<std::int32_t>(r), corrections + r, packed, from, to, rowsB,
                            at);
            at.rowBest += kRows * kGroupLanes;
            at.rowSecond += kRows * kGroupLanes;
            at.rowNearest += kRows * kGroupLanes;
        }
        for (; r < rows; ++r) {
            byteRows<1>(a + r * 128, first + static_cast<std::int32_t>(r), corrections + r, packed, from, to, rowsB,
                        at);
            at.rowBest += kGroupLanes;
            at.rowSecond += kGroupLanes;
            at.rowNearest += kGroupLanes;
        }
    }
}

bool hasByteProducts() {
    static const bool has =
        __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vnni");
    return has;
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
    if (rowsA == 0 || rowsB == 0) return {};
    if (options_.kernel == MatchKernel::Fastest && hasByteProducts()) return matchBytes(a, rowsA, b, rowsB);
    return matchFloats(a, rowsA, b, rowsB);
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> SiftMatcher::matchFloats(const std::uint8_t* a, std::size_t rowsA,
                                                                              const std::uint8_t* b,
                                                                              std::size_t rowsB) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
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
        descriptorDots(floatsA.data() + first * 128, rows, floatsB.data(), rowsB, dots_.data(),
                       options_.kernel == MatchKernel::Portable);
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

// Each of a's rows' nearest found as the products come (byteProducts), a block of rows at a time: the products
// are never written out, where the floats' way writes and reads a block of 1,024 rows by all of b's (56 MB for
// Mip-NeRF 360's kitchen photos, 13,700 features each).
std::vector<std::pair<std::uint32_t, std::uint32_t>> SiftMatcher::matchBytes(const std::uint8_t* a, std::size_t rowsA,
                                                                             const std::uint8_t* b, std::size_t rowsB) {
    packColumns(b, rowsB, packed_);
    const std::size_t columns = packed_.size() / kGroupBytes * kGroupLanes;
    columns_.assign(3 * columns, 0);
    std::fill(columns_.begin() + static_cast<std::ptrdiff_t>(2 * columns), columns_.end(), -1);
    constexpr std::size_t kBlockRows = 256;
    rows_.resize(3 * kBlockRows * kGroupLanes);
    const NearestSoFar kept{columns_.data(),
                            columns_.data() + columns,
                            columns_.data() + 2 * columns,
                            rows_.data(),
                            rows_.data() + kBlockRows * kGroupLanes,
                            rows_.data() + 2 * kBlockRows * kGroupLanes};
    std::vector<std::int32_t> corrections(kBlockRows);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> candidates;
    for (std::size_t first = 0; first < rowsA; first += kBlockRows) {
        const std::size_t rows = std::min(kBlockRows, rowsA - first);
        for (std::size_t r = 0; r < rows; ++r) {
            const std::uint8_t* row = a + (first + r) * 128;
            corrections[r] = 128 * std::accumulate(row, row + 128, 0);
        }
        std::fill(rows_.begin(), rows_.begin() + static_cast<std::ptrdiff_t>(2 * kBlockRows * kGroupLanes), kNone);
        std::fill(rows_.begin() + static_cast<std::ptrdiff_t>(2 * kBlockRows * kGroupLanes), rows_.end(), -1);
        byteProducts(a + first * 128, rows, static_cast<std::int32_t>(first), corrections.data(), packed_.data(), rowsB,
                     kept);
        // Each row's lanes into its best (the first of b's rows to give it, as the floats' search takes) and the
        // largest of the rest: the other lanes' best and every lane's second.
        for (std::size_t r = 0; r < rows; ++r) {
            const std::int32_t* best = kept.rowBest + r * kGroupLanes;
            const std::int32_t* second = kept.rowSecond + r * kGroupLanes;
            const std::int32_t* nearest = kept.rowNearest + r * kGroupLanes;
            std::size_t lane = 0;
            for (std::size_t l = 1; l < kGroupLanes; ++l)
                if (best[l] > best[lane] || (best[l] == best[lane] && nearest[l] < nearest[lane])) lane = l;
            if (!(best[lane] > 0)) continue;  // no dot product above 0: no nearest (COLMAP's rule)
            std::int32_t rest = 0;
            for (std::size_t l = 0; l < kGroupLanes; ++l) rest = std::max({rest, second[l], l == lane ? 0 : best[l]});
            if (passes(static_cast<float>(best[lane]), static_cast<float>(rest), options_))
                candidates.emplace_back(static_cast<std::uint32_t>(first + r),
                                        static_cast<std::uint32_t>(nearest[lane]));
        }
    }
    std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
    for (const auto& [i, j] : candidates)
        if (!options_.crossCheck ||
            (kept.columnNearest[j] == static_cast<std::int32_t>(i) &&
             passes(static_cast<float>(kept.columnBest[j]), static_cast<float>(kept.columnSecond[j]), options_)))
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
