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
#include <sqlite3.h>
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

// COLMAP's features of the images in `images` (one camera, as the ingest gives a known one: the dining
// photos' by default), in `database`; `options` are more of feature_extractor's.
void extractFeatures(const fs::path& images, const fs::path& database,
                     const std::string& camera = "518,519,325.5,253.5", const std::string& options = "") {
    const std::string command = fmt::format(
        "QT_QPA_PLATFORM=offscreen colmap feature_extractor --database_path '{}' --image_path '{}' "
        "--ImageReader.single_camera 1 --ImageReader.camera_model PINHOLE --ImageReader.camera_params {} "
        "--SiftExtraction.use_gpu 0 {} > '{}.log' 2>&1",
        database.string(), images.string(), camera, options, database.string());
    REQUIRE(std::system(command.c_str()) == 0);
}

// The five real photos of ../shared/data/rgbd-dining, copied into `dir`'s images/, which is returned.
fs::path diningPhotos(const ScratchDir& dir) {
    const fs::path images = dir.path / "images";
    fs::create_directories(images);
    for (int n = 1; n <= 5; ++n)
        fs::copy_file(fmt::format("{}/rgbd-dining/color/{}.png", SMQL_SHARED_DATA, n),
                      images / fmt::format("{}.png", n));
    return images;
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
    const fs::path images = diningPhotos(dir);
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

TEST_CASE("images are numbered by their names, their features with them, whatever order COLMAP's threads gave") {
    // The five real dining photos' features, renumbered as two threads may leave them (the third photo
    // finished last), then numbered again by name: each photo keeps its own keypoints and descriptors.
    ScratchDir dir;
    const fs::path images = diningPhotos(dir);
    const fs::path database = dir.path / "database.db";
    extractFeatures(images, database);
    auto descriptorsByName = [&] {
        std::map<long long, std::string> names;
        for (const auto& image : readColmapImages(database.string())) names[image.id] = image.name;
        std::map<std::string, std::vector<std::uint8_t>> out;
        for (auto& d : readColmapDescriptors(database.string())) out[names.at(d.image)] = std::move(d.data);
        return out;
    };
    const auto before = descriptorsByName();
    REQUIRE(before.size() == 5);
    // COLMAP's threads number the photos in the order they finish, which load on the machine changes: numbered by
    // name first, so that the renumbering below leaves the third photo first on every run.
    numberColmapImagesByName(database.string());
    sqlite3* db = nullptr;
    REQUIRE(sqlite3_open(database.string().c_str(), &db) == SQLITE_OK);
    for (const char* table : {"images", "keypoints", "descriptors"})
        REQUIRE(sqlite3_exec(db, fmt::format("UPDATE {} SET image_id = image_id + 10", table).c_str(), nullptr, nullptr,
                             nullptr) == SQLITE_OK);
    for (const char* table : {"images", "keypoints", "descriptors"})
        REQUIRE(sqlite3_exec(db, fmt::format("UPDATE {} SET image_id = 5 WHERE image_id = 13", table).c_str(), nullptr,
                             nullptr, nullptr) == SQLITE_OK);
    sqlite3_close(db);
    REQUIRE(readColmapImages(database.string()).front().name == "3.png");

    numberColmapImagesByName(database.string());
    const auto numbered = readColmapImages(database.string());
    REQUIRE(numbered.size() == 5);
    for (std::size_t i = 0; i < numbered.size(); ++i) {
        CHECK(numbered[i].id == static_cast<long long>(i + 1));
        CHECK(numbered[i].name == fmt::format("{}.png", i + 1));
    }
    CHECK(descriptorsByName() == before);
    CHECK(readColmapDatabase(database.string()).imagesWithFeatures == 5);

    // Once pairs are matched under the numbers, they stay.
    runMatcher(database, "exhaustive_matcher");
    CHECK_THROWS_WITH(numberColmapImagesByName(database.string()), Catch::Contains("once matched"));
}

TEST_CASE(
    "descriptors COLMAP's SIFT leaves unwritten, at an octave's last row, are zeroed; the others keep their bytes") {
    // Ten real frames of TUM fr1/rpy: the keypoints on their bottom row (y within half a pixel of it, where the
    // first octave, the frames doubled, ends) are among those VLFeat does not describe; those a few pixels up
    // are described and keep their bytes.
    ScratchDir dir;
    const fs::path images = dir.path / "images";
    fs::create_directories(images);
    std::vector<fs::path> frames;
    for (const auto& entry : fs::directory_iterator(fmt::format("{}/captures/tum-fr1-rpy/rgb", SMQL_SHARED_DATA)))
        frames.push_back(entry.path());
    std::sort(frames.begin(), frames.end());
    REQUIRE(frames.size() >= 100);
    for (std::size_t i = 0; i < 100; i += 10) fs::copy_file(frames[i], images / frames[i].filename());
    const fs::path database = dir.path / "database.db";
    extractFeatures(images, database, "517.3,516.5,319.1,255.8", "--SiftExtraction.first_octave -1");

    // Each image's keypoints' (x, y) and descriptors, read with the sqlite3 C API.
    auto read = [&] {
        std::map<long long, std::pair<std::vector<float>, std::vector<std::uint8_t>>> out;
        sqlite3* db = nullptr;
        REQUIRE(sqlite3_open(database.string().c_str(), &db) == SQLITE_OK);
        sqlite3_stmt* rows = nullptr;
        REQUIRE(sqlite3_prepare_v2(db,
                                   "SELECT k.image_id, k.rows, k.data, d.data FROM keypoints k JOIN descriptors d "
                                   "USING (image_id) WHERE k.cols = 6",
                                   -1, &rows, nullptr) == SQLITE_OK);
        while (sqlite3_step(rows) == SQLITE_ROW) {
            const auto n = static_cast<std::size_t>(sqlite3_column_int64(rows, 1));
            const auto* k = static_cast<const float*>(sqlite3_column_blob(rows, 2));
            const auto* d = static_cast<const std::uint8_t*>(sqlite3_column_blob(rows, 3));
            auto& [keypoints, descriptors] = out[sqlite3_column_int64(rows, 0)];
            for (std::size_t i = 0; i < n; ++i) {
                keypoints.push_back(k[6 * i]);
                keypoints.push_back(k[6 * i + 1]);
            }
            descriptors.assign(d, d + n * 128);
        }
        sqlite3_finalize(rows);
        sqlite3_close(db);
        return out;
    };
    const auto before = read();
    REQUIRE(before.size() == 10);
    const std::size_t cleared = clearUnwrittenDescriptors(database.string());
    const auto after = read();
    std::size_t bottom = 0, bottomKept = 0, inside = 0, insideChanged = 0, zeroed = 0;
    for (const auto& [image, features] : after) {
        const auto& [keypoints, descriptors] = features;
        for (std::size_t i = 0; i < keypoints.size() / 2; ++i) {
            const auto first = descriptors.begin() + static_cast<std::ptrdiff_t>(128 * i);
            const bool zero = std::all_of(first, first + 128, [](std::uint8_t b) { return b == 0; });
            zeroed += zero;
            if (keypoints[2 * i + 1] > 479.5f) {
                ++bottom;
                bottomKept += !zero;
            } else if (keypoints[2 * i + 1] < 470.0f && keypoints[2 * i] < 630.0f) {
                ++inside;
                insideChanged += !std::equal(first, first + 128,
                                             before.at(image).second.begin() + static_cast<std::ptrdiff_t>(128 * i));
            }
        }
    }
    INFO(bottom << " keypoints on the bottom row, " << inside << " inside, " << cleared << " cleared");
    CHECK(bottom > 0);
    CHECK(bottomKept == 0);
    CHECK(inside > 10000);
    CHECK(insideChanged == 0);
    CHECK(zeroed == cleared);
    CHECK(cleared < 20);
    // The same keypoints are found again: clearing is idempotent.
    CHECK(clearUnwrittenDescriptors(database.string()) == cleared);
}

TEST_CASE("each way of finding the nearest gives the same matches: AVX-512 VNNI's, AVX2's, Eigen's") {
    const auto matchesBy = [](MatchKernel kernel, bool crossCheck, const std::vector<std::uint8_t>& a,
                              const std::vector<std::uint8_t>& b) {
        SiftMatcher matcher({.crossCheck = crossCheck, .kernel = kernel});
        return matcher.match(a.data(), a.size() / 128, b.data(), b.size() / 128);
    };
    const auto sameByEach = [&](const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
        std::size_t matched = 0;
        for (const bool crossCheck : {true, false}) {
            const auto portable = matchesBy(MatchKernel::Portable, crossCheck, a, b);
            CHECK(matchesBy(MatchKernel::Avx2, crossCheck, a, b) == portable);
            CHECK(matchesBy(MatchKernel::Fastest, crossCheck, a, b) == portable);
            matched += portable.size();
        }
        return matched;
    };

    // Made descriptors, in sizes that leave every remainder of the integer ways (blocks of 256 of a's rows, four
    // at a time; b's in groups of 16 or 8, four or two groups at a time, 16 to a slice): b holds a's rows moved a
    // little, in another order, some twice (ties), and rows like none of them.
    cv::RNG rng(20261206);
    for (const auto& [rows, n] : {std::pair{1, 1}, {5, 17}, {70, 300}, {1030, 530}}) {
        const std::vector<std::uint8_t> a = descriptors(rng, rows);
        std::vector<std::uint8_t> b = descriptors(rng, n);
        for (int j = 0; j < n; ++j) {
            if (j < rows && j % 5 != 4) {  // a's row (j * 11) % rows, moved a little: a row of its own each
                const int from = (j * 11) % rows;
                for (int k = 0; k < 128; ++k)
                    b[j * 128 + k] =
                        static_cast<std::uint8_t>(std::clamp(a[from * 128 + k] + rng.uniform(-4, 5), 0, 255));
            } else if (j >= rows && j % 3 == 0) {  // a row of b again, further on: a tie
                std::copy_n(b.begin() + (j - rows) * 128, 128, b.begin() + j * 128);
            }
        }
        INFO(rows << " x " << n);
        const std::size_t matched = sameByEach(a, b);
        if (rows > 1) CHECK(matched > 0);
    }

    // Real features: the five dining photos', every pair of them.
    ScratchDir dir;
    const fs::path database = dir.path / "features.db";
    extractFeatures(diningPhotos(dir), database);
    const auto features = readColmapDescriptors(database.string());
    REQUIRE(features.size() == 5);
    std::size_t matched = 0;
    for (std::size_t p = 0; p < features.size(); ++p)
        for (std::size_t q = p + 1; q < features.size(); ++q) matched += sameByEach(features[p].data, features[q].data);
    CHECK(matched > 1000);
}
