// What COLMAP's database.db holds after feature extraction and matching,
// read with the sqlite3 C API: the cameras, the images, which have features
// and which overlap. The COLMAP runner reads it to say why a reconstruction failed
// ("only 2 of 8 photos overlap enough") from facts rather than guesses, and
// matches the features itself (sift_matching.hpp): the descriptors read, the
// matches written for COLMAP to verify.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace smql::ingest {

struct ColmapDatabaseSummary {
    struct Camera {
        std::string model;  // PINHOLE, SIMPLE_RADIAL ...
        int width = 0, height = 0;
        std::vector<double> params;  // COLMAP's order (PINHOLE: fx, fy, cx, cy; pixel centres at +0.5)
    };
    std::vector<Camera> cameras;
    std::size_t images = 0;
    std::size_t imagesWithFeatures = 0;   // at least one keypoint
    std::size_t overlappingPairs = 0;     // image pairs with at least `minMatches` verified matches
    std::size_t overlappingImages = 0;    // images in at least one such pair
    std::size_t largestOverlapGroup = 0;  // images in the largest group linked through such pairs
};

// Throws smql::Error(Input) naming the file when it is not a COLMAP database.
// `minMatches`: the verified (inlier) matches a pair needs to count, the
// mapper's --Mapper.min_num_matches.
ColmapDatabaseSummary readColmapDatabase(const std::string& path, int minMatches = 15);

// An image as the database numbers it: what a model given to COLMAP (given
// poses to triangulate with) must name it and its camera.
struct ColmapDatabaseImage {
    long long id = 0;
    long long camera = 0;
    std::string name;  // relative to the image folder
};
std::vector<ColmapDatabaseImage> readColmapImages(const std::string& path);

// One image's SIFT descriptors as COLMAP stores them: `rows` of 128 bytes each.
struct ColmapDescriptors {
    long long image = 0;
    std::size_t rows = 0;
    std::vector<std::uint8_t> data;  // rows x 128, row by row
};
std::vector<ColmapDescriptors> readColmapDescriptors(const std::string& path);

// Feature matches of two images: each the index of a feature of `first` and of one of `second`.
struct ColmapPairMatches {
    long long first = 0, second = 0;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> matches;
};
// The `matches` table: every pair a matcher matched (the smaller id first), with its matches.
std::vector<ColmapPairMatches> readColmapMatches(const std::string& path);
// Written to the `matches` table in one transaction (a pair it holds already is left as it is), where
// COLMAP's matchers find them and only verify them: its matcher skips the features of a pair
// with matches and no verified geometry (SiftFeatureMatcher::Match, COLMAP 3.8).
void writeColmapMatches(const std::string& path, const std::vector<ColmapPairMatches>& pairs);

}  // namespace smql::ingest
