// SIFT features matched between images for COLMAP, exactly, on the CPU. COLMAP 3.8's CPU matcher
// builds a FLANN forest for each image of each pair and searches it approximately: 296 frames at
// twice their size (1,300 features a frame), matched with 6 frames each, took it 112 s of a 6.8-minute
// ingest. Here every dot product of a pair's descriptors is taken, exactly (the bytes' products and sums
// are integers below 2^24: as integers, or as floats in a matrix product), and the best and second best
// of each row and column are kept: COLMAP's own brute-force rule
// (the distance and ratio tests on the angles between descriptors, mutual best), with the true nearest
// neighbours where FLANN's search may miss them. The matches go into COLMAP's database, where its
// matchers find them and only verify them (docs/ingest.md, "Geometry from COLMAP").
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace smql::ingest {

// How the matcher finds each descriptor's nearest; each way gives the same matches. The integer ways take
// the bytes' products as integers and keep each row's and column's nearest two as the products come:
// `Fastest` in AVX-512 VNNI where the processor has it, else as `Avx2`; `Avx2` in AVX2 where the processor has
// it, else as `Portable`. `Portable` is Eigen's product of the bytes as floats, then searched.
enum class MatchKernel { Fastest, Avx2, Portable };

// COLMAP's SiftMatchingOptions, as its matcher runs by default.
struct SiftMatchOptions {
    float maxRatio = 0.8f;     // best angle under this times the second best
    float maxDistance = 0.7f;  // best angle at most this (radians)
    bool crossCheck = true;    // each the other's best
    MatchKernel kernel = MatchKernel::Fastest;
};

// One of the matcher's integer ways (sift_matching.cpp).
struct IntegerWay;

// Matches two images' descriptors (rows of 128 bytes, as COLMAP stores them), pair after pair: its
// buffers grow to the largest pair and are kept. One a thread.
class SiftMatcher {
public:
    explicit SiftMatcher(const SiftMatchOptions& options = {}) : options_(options) {}
    // Pairs of row indices, in the order of `a`'s rows.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> match(const std::uint8_t* a, std::size_t rowsA,
                                                               const std::uint8_t* b, std::size_t rowsB);

private:
    std::vector<std::pair<std::uint32_t, std::uint32_t>> matchIntegers(const IntegerWay& way, const std::uint8_t* a,
                                                                       std::size_t rowsA, const std::uint8_t* b,
                                                                       std::size_t rowsB);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> matchPortable(const std::uint8_t* a, std::size_t rowsA,
                                                                       const std::uint8_t* b, std::size_t rowsB);

    SiftMatchOptions options_;
    // The integer ways: b's rows packed for the processor's products, a block of a's rows as 16-bit words
    // (AVX2) and what each row's products get back; each of b's rows' best, second best and nearest row of
    // a; a block of a's rows' best, second best and nearest of b's, by lane.
    std::vector<std::int8_t> packed_;
    std::vector<std::int16_t> words_;
    std::vector<std::int32_t> corrections_, columns_, rows_;
    // The portable way: the descriptors as floats, and their dot products; of each of b's rows, the largest
    // dot products with a's and the row of a that gives the largest.
    std::vector<float> a_, b_, dots_;
    std::vector<float> best_, second_;
    std::vector<std::int32_t> nearest_;
};

// The pairs (indices into the images in name order) COLMAP's sequential_matcher matches: each image
// with the `overlap - 1` after it and, with `quadratic`, those 2^k after it for k < overlap
// (SequentialFeatureMatcher::RunSequentialMatching, COLMAP 3.8). The smaller index first, each once.
std::vector<std::pair<std::size_t, std::size_t>> sequentialPairs(std::size_t images, int overlap, bool quadratic);

// What matchColmapPairs did.
struct ColmapMatching {
    std::size_t pairs = 0;    // pairs matched here
    std::size_t matched = 0;  // of them with at least one match
    double seconds = 0;
};

// Matches the pairs of the database's images named (relative to its image folder) that the database
// holds no matches of yet, on `threads` threads (0: every core), and writes them for COLMAP to verify.
// A name the database does not hold is skipped (COLMAP's matcher then says so).
ColmapMatching matchColmapPairs(const std::string& database,
                                const std::vector<std::pair<std::string, std::string>>& pairs, int threads,
                                const SiftMatchOptions& options = {});

}  // namespace smql::ingest
