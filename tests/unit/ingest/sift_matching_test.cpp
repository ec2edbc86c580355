// The features COLMAP's matchers would match, matched by the ingest first (sift_matching.hpp): held to
// COLMAP's own matcher on real photos, to its sequential matcher's choice of pairs, and to its rule on
// descriptors made to test it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>

#include <fmt/format.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "ingest/geometry/colmap_database.hpp"
#include "ingest/geometry/sift_matching.hpp"
#include "scratch_dir.hpp"

using namespace smql::ingest;
using smql::ingest::test::ScratchDir;
namespace fs = std::filesystem;

namespace {

// COLMAP's features of the images in `images` (one camera, as the ingest gives a known one), in `database`.
void extractFeatures(const fs::path& images, const fs::path& database) {
    const std::string command = fmt::format(
        "QT_QPA_PLATFORM=offscreen colmap feature_extractor --database_path '{}' --image_path '{}' "
        "--ImageReader.single_camera 1 --ImageReader.camera_model PINHOLE --ImageReader.camera_params "
        "518,519,325.5,253.5 --SiftExtraction.use_gpu 0 > '{}.log' 2>&1",
        database.string(), images.string(), database.string());
    REQUIRE(std::system(command.c_str()) == 0);
}

// One of COLMAP's matchers run on the database (matching the pairs it holds no matches of, verifying all).
void runMatcher(const fs::path& database, const std::string& matcher, const std::string& options = "") {
    const std::string command = fmt::format(
        "QT_QPA_PLATFORM=offscreen colmap {} --database_path '{}' --SiftMatching.use_gpu 0 {} >> '{}.log' "
        "2>&1",
        matcher, database.string(), options, database.string());
    REQUIRE(std::system(command.c_str()) == 0);
}

std::vector<std::string> imageNames(const fs::path& database) {
    std::vector<std::string> names;
    for (const auto& image : readColmapImages(database.string())) names.push_back(image.name);
    std::sort(names.begin(), names.end());
    return names;
}

// Descriptors as COLMAP stores them: unit vectors scaled to 512, truncated to bytes.
std::vector<std::uint8_t> descriptors(cv::RNG& rng, int rows) {
    std::vector<std::uint8_t> out;
    for (int r = 0; r < rows; ++r) {
        std::vector<double> v(128);
        double norm = 0;
        for (auto& x : v) {
            x = rng.uniform(0.0, 1.0);
            norm += x * x;
        }
        for (auto x : v) out.push_back(static_cast<std::uint8_t>(std::min(255.0, 512.0 * x / std::sqrt(norm))));
    }
    return out;
}

}  // namespace

TEST_CASE("descriptors are matched by COLMAP's rule: nearest, unambiguous, each the other's") {
    cv::RNG rng(20261204);
    const int rows = 1100;  // more than a block of rows (1,024)
    const std::vector<std::uint8_t> a = descriptors(rng, rows);
    // b: a's rows in reverse order, each moved a little, and rows that resemble none of them.
    std::vector<std::uint8_t> b;
    for (int r = rows - 1; r >= 0; --r)
        for (int k = 0; k < 128; ++k)
            b.push_back(static_cast<std::uint8_t>(std::clamp(a[r * 128 + k] + rng.uniform(-3, 4), 0, 255)));
    const std::vector<std::uint8_t> other = descriptors(rng, 10);
    b.insert(b.end(), other.begin(), other.end());

    SiftMatcher matcher;
    auto matches = matcher.match(a.data(), rows, b.data(), b.size() / 128);
    REQUIRE(matches.size() == static_cast<std::size_t>(rows));
    for (const auto& [i, j] : matches) CHECK(j == static_cast<std::uint32_t>(rows - 1) - i);

    // Row 0 of a twice in b: no row of b is nearer to it than the other copy, so it has no match.
    std::vector<std::uint8_t> twice(a.begin(), a.begin() + 128);
    twice.insert(twice.end(), a.begin(), a.begin() + 128);
    CHECK(matcher.match(a.data(), rows, twice.data(), 2).empty());
    // Kept where each need only be the other's nearest one way: the ratio test still drops the tie.
    SiftMatcher oneWay({.crossCheck = false});
    CHECK(oneWay.match(a.data(), rows, twice.data(), 2).empty());
    // None where nothing is near (the angle's limit), and none of no descriptors.
    SiftMatcher strict({.maxDistance = 0.01f});
    CHECK(strict.match(a.data(), rows, other.data(), 10).empty());
    CHECK(matcher.match(a.data(), 0, b.data(), b.size() / 128).empty());
}

TEST_CASE("the pairs matched are COLMAP's sequential matcher's, with and without its farther pairs") {
    // 18 drawn images (more than 16, so that the pairs 16 on are there), their features, and the pairs
    // COLMAP's sequential_matcher writes: each pair it matched has a row in `matches`, matches or none.
    ScratchDir dir;
    const fs::path images = dir.path / "images";
    fs::create_directories(images);
    cv::RNG rng(7);
    for (int n = 0; n < 18; ++n) {
        cv::Mat image(120, 160, CV_8UC3, cv::Scalar(128, 128, 128));
        for (int s = 0; s < 30; ++s)
            cv::circle(image, {rng.uniform(0, 160), rng.uniform(0, 120)}, rng.uniform(3, 15),
                       cv::Scalar(rng.uniform(0, 256), rng.uniform(0, 256), rng.uniform(0, 256)), cv::FILLED);
        cv::imwrite((images / fmt::format("f{:02}.png", n)).string(), image);
    }
    const fs::path features = dir.path / "features.db";
    extractFeatures(images, features);
    for (const bool quadratic : {false, true}) {
        const fs::path database = dir.path / fmt::format("sequential-{}.db", quadratic);
        fs::copy_file(features, database);
        runMatcher(database, "sequential_matcher",
                   fmt::format("--SequentialMatching.overlap 5 --SequentialMatching.quadratic_overlap {}", quadratic));
        std::map<long long, std::string> names;
        for (const auto& image : readColmapImages(database.string())) names[image.id] = image.name;
        std::set<std::pair<std::string, std::string>> theirs, ours;
        for (const auto& pair : readColmapMatches(database.string()))
            theirs.insert(std::minmax(names[pair.first], names[pair.second]));
        const auto sorted = imageNames(database);
        for (const auto& [a, b] : sequentialPairs(sorted.size(), 5, quadratic)) ours.emplace(sorted[a], sorted[b]);
        INFO("quadratic " << quadratic);
        CHECK(ours.size() == (quadratic ? 74u : 62u));
        CHECK(ours == theirs);
    }
}

TEST_CASE("real photos' features matched here: COLMAP's own matches, and its verification finds the same overlap") {
    // The five real photos of ../shared/data/rgbd-dining, matched all against all by COLMAP's
    // exhaustive_matcher, and by matchColmapPairs with COLMAP then verifying them.
    ScratchDir dir;
    const fs::path images = dir.path / "images";
    fs::create_directories(images);
    for (int n = 1; n <= 5; ++n)
        fs::copy_file(fmt::format("{}/rgbd-dining/color/{}.png", SMQL_SHARED_DATA, n),
                      images / fmt::format("{}.png", n));
    const fs::path theirs = dir.path / "theirs.db", ours = dir.path / "ours.db";
    extractFeatures(images, theirs);
    fs::copy_file(theirs, ours);
    runMatcher(theirs, "exhaustive_matcher");

    std::vector<std::pair<std::string, std::string>> pairs;
    const auto names = imageNames(ours);
    for (std::size_t a = 0; a < names.size(); ++a)
        for (std::size_t b = a + 1; b < names.size(); ++b) pairs.emplace_back(names[a], names[b]);
    const ColmapMatching matched = matchColmapPairs(ours.string(), pairs, 0);
    CHECK(matched.pairs == 10);
    CHECK(matched.matched >= 9);
    // Matched again, nothing is left to match.
    CHECK(matchColmapPairs(ours.string(), pairs, 0).pairs == 0);
    const auto written = readColmapMatches(ours.string());
    runMatcher(ours, "exhaustive_matcher");
    // COLMAP only verified them: the matches it keeps are ours (it empties a pair's under 15).
    const auto kept = readColmapMatches(ours.string());
    REQUIRE(kept.size() == written.size());
    for (std::size_t p = 0; p < kept.size(); ++p)
        if (written[p].matches.size() >= 15) CHECK(kept[p].matches == written[p].matches);

    // COLMAP's CPU matcher searches FLANN's trees, which may miss a nearest neighbour; the ingest's is
    // exact. So nearly all of its matches are among ours, and ours are about as many.
    const auto theirMatches = readColmapMatches(theirs.string()), ourMatches = readColmapMatches(ours.string());
    REQUIRE(theirMatches.size() == 10);
    REQUIRE(ourMatches.size() == 10);
    std::size_t theirTotal = 0, ourTotal = 0, shared = 0;
    for (std::size_t p = 0; p < 10; ++p) {
        REQUIRE(theirMatches[p].first == ourMatches[p].first);
        REQUIRE(theirMatches[p].second == ourMatches[p].second);
        const std::set<std::pair<std::uint32_t, std::uint32_t>> mine(ourMatches[p].matches.begin(),
                                                                     ourMatches[p].matches.end());
        for (const auto& m : theirMatches[p].matches) shared += mine.count(m);
        theirTotal += theirMatches[p].matches.size();
        ourTotal += ourMatches[p].matches.size();
    }
    INFO("COLMAP's matches " << theirTotal << ", ours " << ourTotal << ", shared " << shared);
    REQUIRE(theirTotal > 500);
    CHECK(shared >= 0.95 * static_cast<double>(theirTotal));
    CHECK(ourTotal <= 1.1 * static_cast<double>(theirTotal));
    // The same photos overlap, linked the same way.
    const auto theirSummary = readColmapDatabase(theirs.string()), ourSummary = readColmapDatabase(ours.string());
    CHECK(ourSummary.overlappingPairs == theirSummary.overlappingPairs);
    CHECK(ourSummary.largestOverlapGroup == theirSummary.largestOverlapGroup);
}
