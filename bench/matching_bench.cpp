// smql_bench_matching: the ingest's feature matching (ingest/geometry/sift_matching.hpp) against COLMAP's own
// matcher on the CPU, side by side on the same features. It reads the database of a COLMAP work folder the
// ingest kept (`smql ingest PHOTOS --colmap-dir DIR`: DIR/database.db, its features extracted as the ingest
// extracts them), keeps its first --images images by name and no matches, and matches them all against all,
// in rounds, each way on a fresh copy:
//   - COLMAP's exhaustive_matcher alone, on every core: it matches (FLANN's trees) and verifies each pair;
//   - smql's matching in each of its ways (MatchKernel) on every core, then COLMAP's exhaustive_matcher on one,
//     which then only verifies (the ingest's way).
// Medians over the rounds, the matches each way finds (smql's ways must agree, or the run fails), the pairs
// COLMAP's verification then finds overlapping, and the ratio of COLMAP's time to each. `make bench-matching` runs it
// on ../shared's real photos and prints the Markdown table docs/benchmarks.md keeps ("Feature matching").
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <sqlite3.h>
#include <unistd.h>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "bench/stats.hpp"
#include "ingest/geometry/colmap_database.hpp"
#include "ingest/geometry/sift_matching.hpp"

namespace smql::bench {

namespace {

namespace fs = std::filesystem;
using ingest::MatchKernel;

struct Way {
    std::string name;
    std::optional<MatchKernel> kernel;  // none: COLMAP's matcher alone
};

const std::vector<Way> kWays = {
    {"COLMAP's exhaustive_matcher (FLANN), matching and verifying on every core", std::nullopt},
    {"smql, AVX-512 VNNI's products (where the processor has it), then COLMAP verifying on one core",
     MatchKernel::Fastest},
    {"smql, AVX2's products (where the processor has it), then COLMAP verifying on one core", MatchKernel::Avx2},
    {"smql, Eigen's product, then COLMAP verifying on one core", MatchKernel::Portable},
};

void exec(sqlite3* db, const std::string& sql) {
    char* error = nullptr;
    if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error) != SQLITE_OK) {
        const std::string what = error ? error : "?";
        sqlite3_free(error);
        throw std::runtime_error(fmt::format("{}: {}", sql, what));
    }
}

// The database with the first `images` images by name, their features, and no matches.
void keepFirstImages(const fs::path& database, std::size_t images) {
    auto all = ingest::readColmapImages(database.string());
    std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
    sqlite3* db = nullptr;
    if (sqlite3_open(database.c_str(), &db) != SQLITE_OK) throw std::runtime_error("cannot open " + database.string());
    try {
        exec(db, "BEGIN; DELETE FROM matches; DELETE FROM two_view_geometries;");
        for (std::size_t i = images; i < all.size(); ++i)
            for (const char* table : {"images", "keypoints", "descriptors"})
                exec(db, fmt::format("DELETE FROM {} WHERE image_id = {};", table, all[i].id));
        exec(db, "COMMIT; VACUUM;");
    } catch (...) {
        sqlite3_close(db);
        throw;
    }
    sqlite3_close(db);
}

std::size_t matchesIn(const fs::path& database) {
    std::size_t total = 0;
    for (const auto& pair : ingest::readColmapMatches(database.string())) total += pair.matches.size();
    return total;
}

// COLMAP's exhaustive_matcher on `threads` threads (-1: every core, its default).
double runColmapMatcher(const fs::path& database, const std::string& colmap, int threads) {
    const auto start = Clock::now();
    const std::string command = fmt::format(
        "QT_QPA_PLATFORM=offscreen {} exhaustive_matcher --database_path '{}' --SiftMatching.use_gpu 0 "
        "--SiftMatching.num_threads {} > '{}.log' 2>&1",
        colmap, database.string(), threads, database.string());
    if (std::system(command.c_str()) != 0)
        throw std::runtime_error(fmt::format("{} failed (see {}.log)", command, database.string()));
    return microsecondsSince(start) / 1e6;
}

struct Measured {
    std::vector<double> matching, verifying, total;
    std::size_t matches = 0;      // found by the way's matching (COLMAP's: as its verification leaves them)
    std::size_t overlapping = 0;  // pairs COLMAP's verification keeps 15 matches of or more
};

}  // namespace

int run(int argc, char** argv) {
    CLI::App app{"smql_bench_matching: the ingest's feature matching against COLMAP's matcher, side by side"};
    std::string database, colmap = "colmap", name;
    std::size_t images = 10, rounds = 3;
    app.add_option("database", database, "a COLMAP work folder's database.db (smql ingest PHOTOS --colmap-dir DIR)")
        ->required()
        ->check(CLI::ExistingFile);
    app.add_option("--images", images, "the first images by name, matched all against all (default 10)");
    app.add_option("--rounds", rounds, "rounds, each way once a round (default 3)");
    app.add_option("--name", name, "what the table calls the photos (default: the database's folder)");
    app.add_option("--colmap", colmap, "COLMAP's command (default colmap)");
    CLI11_PARSE(app, argc, argv);
    if (name.empty()) name = fs::path(database).parent_path().filename().string();

    const fs::path work = fs::temp_directory_path() / fmt::format("smql-bench-matching-{}", ::getpid());
    fs::create_directories(work);
    const fs::path source = work / "source.db";
    fs::copy_file(database, source);
    keepFirstImages(source, images);
    const auto kept = ingest::readColmapImages(source.string());
    std::vector<std::pair<std::string, std::string>> pairs;
    for (std::size_t a = 0; a < kept.size(); ++a)
        for (std::size_t b = a + 1; b < kept.size(); ++b) pairs.emplace_back(kept[a].name, kept[b].name);
    std::size_t features = 0;
    for (const auto& d : ingest::readColmapDescriptors(source.string())) features += d.rows;

    std::map<std::string, Measured> measured;
    for (std::size_t round = 0; round < rounds; ++round)
        for (const Way& way : kWays) {
            const fs::path copy = work / "round.db";
            fs::remove(copy);
            fs::copy_file(source, copy);
            Measured& m = measured[way.name];
            double matching = 0;
            if (way.kernel) {
                matching = ingest::matchColmapPairs(copy.string(), pairs, 0, {.kernel = *way.kernel}).seconds;
                const std::size_t found = matchesIn(copy);
                if (round > 0 && found != m.matches)
                    throw std::runtime_error(fmt::format("{}: {} matches, {} before", way.name, found, m.matches));
                m.matches = found;
            }
            // After smql's matching, verification on one thread, as the ingest runs it (its RANSAC's draws then
            // repeat: colmap_runner.cpp, kRepeatableThreads); COLMAP's matcher alone on every core.
            const double verifying = runColmapMatcher(copy, colmap, way.kernel ? 1 : -1);
            if (!way.kernel) {
                matching = verifying;
                m.matches = matchesIn(copy);
            }
            m.matching.push_back(matching);
            m.verifying.push_back(way.kernel ? verifying : 0);
            m.total.push_back(way.kernel ? matching + verifying : verifying);
            m.overlapping = ingest::readColmapDatabase(copy.string()).overlappingPairs;
        }
    fs::remove_all(work);

    // The smql ways must find the same matches.
    std::size_t smqlMatches = 0;
    for (const Way& way : kWays)
        if (way.kernel) {
            const std::size_t found = measured[way.name].matches;
            if (smqlMatches && found != smqlMatches)
                throw std::runtime_error(
                    fmt::format("{} found {} matches where another way found {}", way.name, found, smqlMatches));
            smqlMatches = found;
        }

    const double colmapTotal = median(measured[kWays[0].name].total);
    std::cout << fmt::format(
        "{}: {} images, {} pairs all against all, {:.0f} features an image at the mean; {} rounds, medians (s)\n\n",
        name, kept.size(), pairs.size(), static_cast<double>(features) / static_cast<double>(kept.size()), rounds);
    std::cout << "| way | matching | verification | both | COLMAP / this (both) | matches | pairs overlapping |\n";
    std::cout << "|---|---:|---:|---:|---:|---:|---:|\n";
    for (const Way& way : kWays) {
        Measured& m = measured[way.name];
        const double total = median(m.total);
        std::cout << fmt::format("| {} | {:.2f} | {} | {:.2f} | {:.2f}x | {} | {} |\n", way.name, median(m.matching),
                                 way.kernel ? fmt::format("{:.2f}", median(m.verifying)) : std::string("(in it)"),
                                 total, colmapTotal / total, m.matches, m.overlapping);
    }
    return 0;
}

}  // namespace smql::bench

int main(int argc, char** argv) {
    try {
        return smql::bench::run(argc, argv);
    } catch (const std::exception& e) {
        std::cerr << "smql_bench_matching: " << e.what() << "\n";
        return 1;
    }
}
