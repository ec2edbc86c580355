// What COLMAP's database.db holds after feature extraction and matching,
// read with the sqlite3 C API: the cameras, the images, which have features
// and which overlap. The COLMAP runner reads it to say why a reconstruction failed
// ("only 2 of 8 photos overlap enough") from facts rather than guesses.
#pragma once

#include <cstddef>
#include <string>
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

}  // namespace smql::ingest
