// What COLMAP's database.db holds after feature extraction and matching,
// read with the sqlite3 C API: the cameras, the images, which have features
// and which overlap. The COLMAP runner reads it to say why a reconstruction failed
// ("only 2 of 8 photos overlap enough") from facts rather than guesses, and
// matches the features itself (sift_matching.hpp): the descriptors read, the
// matches written for COLMAP to verify. Once the features are extracted, it
// settles what COLMAP leaves to chance (the images' numbers, descriptors never
// written), so that the same photos are matched alike on every run.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
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
    // Each image in such a pair, by name, with its group (any number that is the same for the images of one
    // group): where a walk taken in order parts, the images before and after lie in different groups.
    std::map<std::string, std::int64_t> overlapGroup;
    std::set<std::string> featureless;  // images without a keypoint (a blank wall; a dark or blurred photo)
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

// Numbers the images 1, 2, ... in the order of their names, their keypoints and descriptors with them.
// COLMAP's feature_extractor numbers each image as its threads finish it, so the numbers change from run to
// run, and with them the order the matcher and the mapper take the images in (TUM's 17 office photos: two
// photos swapped in one run of three, and its model differed). Throws smql::Error(Input) when the database
// holds matches already, whose pairs are named by those numbers.
void numberColmapImagesByName(const std::string& path);

// Zeroes the descriptors COLMAP 3.8's SIFT on the CPU leaves unwritten, and returns how many: VLFeat
// describes no keypoint whose centre rounds onto its octave's last row or past its last column
// (vl_sift_calc_keypoint_descriptor's bounds), and COLMAP keeps what the memory held there: bytes that look
// like a descriptor, or a spike of 255. Of TUM fr1/rpy's 100 frames, 26 such keypoints of 160,888, 10 to 14 of
// them different between any two of four extractions, and a pair matched from them kept 23 matches in one run
// and 22 in the next. A zero descriptor matches nothing (sift_matching.hpp), so every run matches the same.
// `octaveResolution`: COLMAP's SiftExtraction.octave_resolution.
std::size_t clearUnwrittenDescriptors(const std::string& path, int octaveResolution = 3);

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
// A pair of images the `matches` table holds (the smaller id first), and how many matches it has.
struct ColmapPairCount {
    long long first = 0, second = 0;
    std::size_t matches = 0;
};
// The pairs of the `matches` table with `minMatches` matches or more and no verified geometry yet (no row in
// `two_view_geometries`), in the table's order.
std::vector<ColmapPairCount> readUnverifiedPairs(const std::string& path, std::size_t minMatches);
// Written to the `matches` table in one transaction (a pair it holds already is left as it is), where
// COLMAP's matchers find them and only verify them: its matcher skips the features of a pair
// with matches and no verified geometry (SiftFeatureMatcher::Match, COLMAP 3.8).
void writeColmapMatches(const std::string& path, const std::vector<ColmapPairMatches>& pairs);

}  // namespace smql::ingest
