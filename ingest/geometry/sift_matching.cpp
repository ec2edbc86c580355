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

// Of each row's nearest (a's row, b's row), in a's order, those that are also their column's nearest and pass
// there too (COLMAP's cross-check), or all of them without it. `best`, `second`, `nearest`: each of b's rows'.
template <typename Dot>
std::vector<std::pair<std::uint32_t, std::uint32_t>> crossChecked(
    std::vector<std::pair<std::uint32_t, std::uint32_t>> candidates, const Dot* best, const Dot* second,
    const std::int32_t* nearest, const SiftMatchOptions& options) {
    if (!options.crossCheck) return candidates;
    std::erase_if(candidates, [&](const auto& match) {
        const auto [i, j] = match;
        return nearest[j] != static_cast<std::int32_t>(i) ||
               !passes(static_cast<float>(best[j]), static_cast<float>(second[j]), options);
    });
    return candidates;
}

// The integer ways. The descriptors' bytes are multiplied as integers, the products summed into sixteen
// (AVX-512) or eight (AVX2) lanes of 32 bits, each lane one of b's rows, and each row's and column's nearest
// two are kept as the products come: no matrix of them is written, where the portable way writes a block of
// 1,024 of a's rows by all of b's (56 MB for Mip-NeRF 360's kitchen photos, 13,700 features each) and reads
// it three times. The sums are the dot products themselves, so every way gives the same matches.
//   - AVX-512 VNNI: vpdpbusd multiplies 64 bytes by 64 and sums them four at a time into sixteen lanes in one
//     instruction, four times the products of a float fused multiply-add of that width. Its second operand
//     is signed, so b's bytes go in less 128 and each product of a's row gets 128 times the row's sum back
//     (`corrections`): a.b = a.(b - 128) + 128 sum(a).
//   - AVX2: the bytes widened to 16 bits, vpmaddwd multiplies 16 by 16 and sums them two at a time into
//     eight lanes (products under 2^16, their sums exact).
// Either way b's rows are packed in groups, a row to a lane, each step's bytes of the group's rows side by side
// (64 or 32 bytes a step, 2,048 a group); rows past b's last are zeros, and their products are left out.
constexpr std::size_t kGroupBytes = 2048;
constexpr std::int32_t kNone = std::numeric_limits<std::int32_t>::min();

}  // namespace

// The types below are those of the ways' table (IntegerWay, which the header declares), so they are outside
// the file's anonymous namespace.

// Where the products go as they come: each of b's rows' best, second best and nearest of a's rows so far
// (keepNearest's rule, a's rows in order), and each of a block of a's rows' best, second best and nearest
// of b's rows so far in each lane (lane l of L sees b's rows l, l + L, ... in order).
struct NearestSoFar {
    std::int32_t* columnBest;
    std::int32_t* columnSecond;
    std::int32_t* columnNearest;
    std::int32_t* rowBest;  // a lane's worth a row
    std::int32_t* rowSecond;
    std::int32_t* rowNearest;
    void nextRows(std::size_t lanes) {
        rowBest += lanes;
        rowSecond += lanes;
        rowNearest += lanes;
    }
};

// A block of a's rows, as a way's products read them: `data` a row every `stride` bytes, and what each
// row's products get back (`corrections`); `first` the first row's index in a.
struct RowBlock {
    const std::uint8_t* data;
    std::size_t stride;
    const std::int32_t* corrections;
    std::int32_t first;
};

namespace {

// AVX-512 VNNI: the products of R of a's rows with C groups of b's rows from group `group` on, into `kept`;
// `rowsB` of b's rows are real. GCC 12's _mm512_max_epi32 starts from an undefined vector, which its own
// warnings then flag: the masked max over every lane is the same.
template <int R, int C>
struct VnniTile {
    __attribute__((target("avx512f,avx512bw,avx512vnni"))) static void run(const RowBlock& a, const std::int8_t* packed,
                                                                           std::size_t group, std::size_t rowsB,
                                                                           const NearestSoFar& kept) {
        constexpr std::size_t kLanes = 16;
        constexpr __mmask16 kAll = 0xFFFF;
        __m512i sum[R][C] = {};  // zeros
        const std::int8_t* groups = packed + group * kGroupBytes;
#pragma GCC unroll 8
        for (std::size_t step = 0; step < 32; ++step) {
            __m512i bs[C];
#pragma GCC unroll 4
            for (int c = 0; c < C; ++c) bs[c] = _mm512_loadu_si512(groups + c * kGroupBytes + step * 64);
#pragma GCC unroll 4
            for (int i = 0; i < R; ++i) {
                std::int32_t four;
                std::memcpy(&four, a.data + i * a.stride + step * 4, 4);
                const __m512i as = _mm512_set1_epi32(four);
#pragma GCC unroll 4
                for (int c = 0; c < C; ++c) sum[i][c] = _mm512_dpbusd_epi32(sum[i][c], as, bs[c]);
            }
        }
        const __m512i lanes = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
#pragma GCC unroll 4
        for (int c = 0; c < C; ++c) {
            const std::size_t column = (group + static_cast<std::size_t>(c)) * kLanes;
            const __mmask16 real =
                column + kLanes <= rowsB ? kAll : static_cast<__mmask16>((1u << (rowsB - column)) - 1);
            const __m512i columns = _mm512_add_epi32(_mm512_set1_epi32(static_cast<std::int32_t>(column)), lanes);
            __m512i best = _mm512_loadu_si512(kept.columnBest + column);
            __m512i second = _mm512_loadu_si512(kept.columnSecond + column);
            __m512i nearest = _mm512_loadu_si512(kept.columnNearest + column);
#pragma GCC unroll 4
            for (int i = 0; i < R; ++i) {
                const __m512i dot = _mm512_add_epi32(sum[i][c], _mm512_set1_epi32(a.corrections[i]));
                __mmask16 better = _mm512_cmpgt_epi32_mask(dot, best);
                second = _mm512_mask_mov_epi32(_mm512_maskz_max_epi32(kAll, second, dot), better, best);
                nearest = _mm512_mask_mov_epi32(nearest, better, _mm512_set1_epi32(a.first + i));
                best = _mm512_mask_mov_epi32(best, better, dot);

                std::int32_t* rowBest = kept.rowBest + i * kLanes;
                std::int32_t* rowSecond = kept.rowSecond + i * kLanes;
                const __m512i rowDot = _mm512_mask_mov_epi32(_mm512_set1_epi32(kNone), real, dot);
                const __m512i before = _mm512_loadu_si512(rowBest);
                better = _mm512_cmpgt_epi32_mask(rowDot, before);
                _mm512_storeu_si512(rowSecond, _mm512_mask_mov_epi32(
                                                   _mm512_maskz_max_epi32(kAll, _mm512_loadu_si512(rowSecond), rowDot),
                                                   better, before));
                _mm512_mask_storeu_epi32(kept.rowNearest + i * kLanes, better, columns);
                _mm512_mask_storeu_epi32(rowBest, better, rowDot);
            }
            _mm512_storeu_si512(kept.columnBest + column, best);
            _mm512_storeu_si512(kept.columnSecond + column, second);
            _mm512_storeu_si512(kept.columnNearest + column, nearest);
        }
    }
};

// Eight lanes of 32 bits, read and written where they lie.
__attribute__((target("avx2"))) inline __m256i load(const std::int32_t* p) {
    return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
}
__attribute__((target("avx2"))) inline void store(std::int32_t* p, __m256i v) {
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), v);
}

// AVX2: as VnniTile, eight lanes, the bytes as 16-bit words.
template <int R, int C>
struct Avx2Tile {
    __attribute__((target("avx2"))) static void run(const RowBlock& a, const std::int8_t* packed, std::size_t group,
                                                    std::size_t rowsB, const NearestSoFar& kept) {
        constexpr std::size_t kLanes = 8;
        __m256i sum[R][C] = {};  // zeros
        const std::int8_t* groups = packed + group * kGroupBytes;
#pragma GCC unroll 8
        for (std::size_t step = 0; step < 64; ++step) {
            __m256i bs[C];
#pragma GCC unroll 4
            for (int c = 0; c < C; ++c)
                bs[c] = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(groups + c * kGroupBytes + step * 32));
#pragma GCC unroll 4
            for (int i = 0; i < R; ++i) {
                std::int32_t two;
                std::memcpy(&two, a.data + i * a.stride + step * 4, 4);
                const __m256i as = _mm256_set1_epi32(two);
#pragma GCC unroll 4
                for (int c = 0; c < C; ++c) sum[i][c] = _mm256_add_epi32(sum[i][c], _mm256_madd_epi16(as, bs[c]));
            }
        }
        const __m256i lanes = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
#pragma GCC unroll 4
        for (int c = 0; c < C; ++c) {
            const std::size_t column = (group + static_cast<std::size_t>(c)) * kLanes;
            const __m256i real =
                _mm256_cmpgt_epi32(_mm256_set1_epi32(static_cast<std::int32_t>(rowsB - column)), lanes);
            const __m256i columns = _mm256_add_epi32(_mm256_set1_epi32(static_cast<std::int32_t>(column)), lanes);
            __m256i best = load(kept.columnBest + column);
            __m256i second = load(kept.columnSecond + column);
            __m256i nearest = load(kept.columnNearest + column);
#pragma GCC unroll 4
            for (int i = 0; i < R; ++i) {
                const __m256i dot = sum[i][c];
                __m256i better = _mm256_cmpgt_epi32(dot, best);
                second = _mm256_blendv_epi8(_mm256_max_epi32(second, dot), best, better);
                nearest = _mm256_blendv_epi8(nearest, _mm256_set1_epi32(a.first + i), better);
                best = _mm256_blendv_epi8(best, dot, better);

                std::int32_t* rowBest = kept.rowBest + i * kLanes;
                std::int32_t* rowSecond = kept.rowSecond + i * kLanes;
                std::int32_t* rowNearest = kept.rowNearest + i * kLanes;
                const __m256i rowDot = _mm256_blendv_epi8(_mm256_set1_epi32(kNone), dot, real);
                const __m256i before = load(rowBest);
                better = _mm256_cmpgt_epi32(rowDot, before);
                store(rowSecond, _mm256_blendv_epi8(_mm256_max_epi32(load(rowSecond), rowDot), before, better));
                store(rowNearest, _mm256_blendv_epi8(load(rowNearest), columns, better));
                store(rowBest, _mm256_blendv_epi8(before, rowDot, better));
            }
            store(kept.columnBest + column, best);
            store(kept.columnSecond + column, second);
            store(kept.columnNearest + column, nearest);
        }
    }
};

// A way's tiles over a block of a's rows against all of b's: 16 groups of b's rows (32 KB, held in the
// first-level cache) at a time, four of a's rows by `kGroups` groups a tile. The 6 pairs of Mip-NeRF 360's first
// 4 kitchen photos (20,600 features each), matched on one core: VNNI's way 2.35 s with 32 groups (64 KB) a slice,
// 1.97 s with 16 and 1.94 s with 8; AVX2's 4.85-4.93 s with any of them.
template <std::size_t kLanes, std::size_t kGroups, template <int, int> class Tile>
inline void products(RowBlock a, std::size_t rows, const std::int8_t* packed, std::size_t rowsB, NearestSoFar kept) {
    constexpr std::size_t kRows = 4, kSliceGroups = 16;
    const std::size_t groups = (rowsB + kLanes - 1) / kLanes;
    for (std::size_t from = 0; from < groups; from += kSliceGroups) {
        const std::size_t to = std::min(groups, from + kSliceGroups);
        RowBlock at = a;
        NearestSoFar into = kept;
        const auto tiles = [&](auto rowsAtOnce) {
            constexpr int kR = decltype(rowsAtOnce)::value;
            std::size_t g = from;
            for (; g + kGroups <= to; g += kGroups) Tile<kR, kGroups>::run(at, packed, g, rowsB, into);
            for (; g < to; ++g) Tile<kR, 1>::run(at, packed, g, rowsB, into);
            at.data += kR * at.stride;
            at.corrections += kR;
            at.first += kR;
            for (int r = 0; r < kR; ++r) into.nextRows(kLanes);
        };
        std::size_t r = 0;
        for (; r + kRows <= rows; r += kRows) tiles(std::integral_constant<int, kRows>{});
        for (; r < rows; ++r) tiles(std::integral_constant<int, 1>{});
    }
}

// b's rows packed for VnniTile: 16 to a group, a step the rows' next four bytes, each less 128.
void packForVnni(const std::uint8_t* b, std::size_t rowsB, std::vector<std::int8_t>& packed) {
    packed.assign((rowsB + 15) / 16 * kGroupBytes, 0);
    for (std::size_t j = 0; j < rowsB; ++j) {
        std::int8_t* lane = packed.data() + j / 16 * kGroupBytes + j % 16 * 4;
        for (std::size_t k = 0; k < 128; ++k)
            lane[k / 4 * 64 + k % 4] = static_cast<std::int8_t>(b[j * 128 + k] ^ 0x80);
    }
}

// b's rows packed for Avx2Tile: 8 to a group, a step the rows' next two bytes as 16-bit words.
void packForAvx2(const std::uint8_t* b, std::size_t rowsB, std::vector<std::int8_t>& packed) {
    packed.assign((rowsB + 7) / 8 * kGroupBytes, 0);
    for (std::size_t j = 0; j < rowsB; ++j) {
        std::int8_t* lane = packed.data() + j / 8 * kGroupBytes + j % 8 * 4;
        for (std::size_t k = 0; k < 128; ++k) {
            const std::int16_t word = b[j * 128 + k];
            std::memcpy(lane + k / 2 * 32 + k % 2 * 2, &word, 2);
        }
    }
}

// A block of a's rows as VnniTile reads them: the bytes, each row's products getting 128 times its sum back.
RowBlock vnniRows(const std::uint8_t* a, std::size_t rows, std::int32_t first, std::vector<std::int16_t>&,
                  std::vector<std::int32_t>& corrections) {
    corrections.resize(rows);
    for (std::size_t r = 0; r < rows; ++r) corrections[r] = 128 * std::accumulate(a + r * 128, a + r * 128 + 128, 0);
    return {a, 128, corrections.data(), first};
}

// ... as Avx2Tile reads them: widened to 16-bit words, nothing to get back.
RowBlock avx2Rows(const std::uint8_t* a, std::size_t rows, std::int32_t first, std::vector<std::int16_t>& words,
                  std::vector<std::int32_t>& corrections) {
    words.assign(a, a + rows * 128);
    corrections.assign(rows, 0);
    return {reinterpret_cast<const std::uint8_t*>(words.data()), 256, corrections.data(), first};
}

}  // namespace

// The integer ways, one table: lanes, how b's rows are packed and a's read, and the tiles.
struct IntegerWay {
    std::size_t lanes;
    void (*pack)(const std::uint8_t* b, std::size_t rowsB, std::vector<std::int8_t>& packed);
    RowBlock (*rowsOf)(const std::uint8_t* a, std::size_t rows, std::int32_t first, std::vector<std::int16_t>& words,
                       std::vector<std::int32_t>& corrections);
    void (*products)(RowBlock a, std::size_t rows, const std::int8_t* packed, std::size_t rowsB, NearestSoFar kept);
};

namespace {

const IntegerWay kVnniWay{16, packForVnni, vnniRows, products<16, 4, VnniTile>};
const IntegerWay kAvx2Way{8, packForAvx2, avx2Rows, products<8, 2, Avx2Tile>};

// The way `kernel` asks for on this processor; none for Eigen's.
const IntegerWay* integerWay(MatchKernel kernel) {
    static const bool vnni =
        __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vnni");
    static const bool avx2 = __builtin_cpu_supports("avx2");
    if (kernel == MatchKernel::Fastest && vnni) return &kVnniWay;
    if (kernel != MatchKernel::Portable && avx2) return &kAvx2Way;
    return nullptr;
}

}  // namespace

std::vector<std::pair<std::uint32_t, std::uint32_t>> SiftMatcher::match(const std::uint8_t* a, std::size_t rowsA,
                                                                        const std::uint8_t* b, std::size_t rowsB) {
    if (rowsA == 0 || rowsB == 0) return {};
    if (const IntegerWay* way = integerWay(options_.kernel)) return matchIntegers(*way, a, rowsA, b, rowsB);
    return matchPortable(a, rowsA, b, rowsB);
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> SiftMatcher::matchPortable(const std::uint8_t* a,
                                                                                std::size_t rowsA,
                                                                                const std::uint8_t* b,
                                                                                std::size_t rowsB) {
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
    return crossChecked(std::move(candidates), best_.data(), second_.data(), nearest_.data(), options_);
}

// Each block of a's rows' products with all of b's, their nearest kept as they come, then each row's lanes
// into its nearest.
std::vector<std::pair<std::uint32_t, std::uint32_t>> SiftMatcher::matchIntegers(
    const IntegerWay& way, const std::uint8_t* a, std::size_t rowsA, const std::uint8_t* b, std::size_t rowsB) {
    way.pack(b, rowsB, packed_);
    const std::size_t columns = packed_.size() / kGroupBytes * way.lanes;
    columns_.assign(3 * columns, 0);
    std::fill(columns_.begin() + static_cast<std::ptrdiff_t>(2 * columns), columns_.end(), -1);
    constexpr std::size_t kBlockRows = 256;
    const std::size_t lanes = kBlockRows * way.lanes;
    rows_.resize(3 * lanes);
    const NearestSoFar kept{columns_.data(), columns_.data() + columns, columns_.data() + 2 * columns,
                            rows_.data(),    rows_.data() + lanes,      rows_.data() + 2 * lanes};
    std::vector<std::pair<std::uint32_t, std::uint32_t>> candidates;
    for (std::size_t first = 0; first < rowsA; first += kBlockRows) {
        const std::size_t rows = std::min(kBlockRows, rowsA - first);
        std::fill(rows_.begin(), rows_.begin() + static_cast<std::ptrdiff_t>(2 * lanes), kNone);
        std::fill(rows_.begin() + static_cast<std::ptrdiff_t>(2 * lanes), rows_.end(), -1);
        way.products(way.rowsOf(a + first * 128, rows, static_cast<std::int32_t>(first), words_, corrections_), rows,
                     packed_.data(), rowsB, kept);
        // Each row's lanes into its best (the first of b's rows to give it, as the portable search takes) and the
        // largest of the rest: the other lanes' best and every lane's second.
        for (std::size_t r = 0; r < rows; ++r) {
            const std::int32_t* best = kept.rowBest + r * way.lanes;
            const std::int32_t* second = kept.rowSecond + r * way.lanes;
            const std::int32_t* nearest = kept.rowNearest + r * way.lanes;
            std::size_t lane = 0;
            for (std::size_t l = 1; l < way.lanes; ++l)
                if (best[l] > best[lane] || (best[l] == best[lane] && nearest[l] < nearest[lane])) lane = l;
            if (!(best[lane] > 0)) continue;  // no dot product above 0: no nearest (COLMAP's rule)
            std::int32_t rest = 0;
            for (std::size_t l = 0; l < way.lanes; ++l) rest = std::max({rest, second[l], l == lane ? 0 : best[l]});
            if (passes(static_cast<float>(best[lane]), static_cast<float>(rest), options_))
                candidates.emplace_back(static_cast<std::uint32_t>(first + r),
                                        static_cast<std::uint32_t>(nearest[lane]));
        }
    }
    return crossChecked(std::move(candidates), kept.columnBest, kept.columnSecond, kept.columnNearest, options_);
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
