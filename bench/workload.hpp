// The query classes of the benchmark, run on one data set by both systems:
// every distinct query is first answered by both and the answers compared
// (a mismatch throws), then each class is timed query by query.
#pragma once

#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "bench/data_set.hpp"
#include "bench/stats.hpp"
#include "engine/binder/shape_cache.hpp"

namespace smql::bench {

// The shape of the queries (docs/benchmarks.md's method section states them).
inline constexpr int kRelatePairsPerScene = 8;
inline constexpr int kNearestLimit = 5;
inline constexpr int kCategoryLimit = 100;

struct WorkloadOptions {
    int queries = 2000;      // timed executions per query class and system
    int rounds = 5;          // the executions split into rounds; percentiles are the median over rounds
    int sampledScenes = 10;  // scenes the single-scene classes run in, spread over the data set
    int openRepeats = 11;    // opens timed per system (the median is reported)
};

struct ClassResult {
    std::string name;                    // the query, as the report shows it
    bool twoPredicateFind = false;       // what the FIND latency target is about
    Percentiles smqlFresh;               // new statement text each time: parse, bind, plan, run
    Percentiles smqlRepeated;            // the same texts again: the engine's parse cache answers the parse
    Percentiles smqlPrepared;            // Engine::prepare once, then bind and execute: the baselines' way
    std::vector<Percentiles> baselines;  // per WorkloadResult::baselineNames
    // What a new text costs before the binder, p50 in microseconds over the class's first query:
    // ANTLR's parse into the AST, and the hand-written scan that finds the text's statement shape.
    double parseMicros = 0;
    double shapeScanMicros = 0;
    std::size_t verified = 0;  // distinct queries compared before timing (every timed answer is compared too)
    double meanAnswer = 0;     // mean rows per answer (the count itself for COUNT)
};

// Medians over WorkloadOptions::openRepeats, in microseconds.
struct OpenTimes {
    double smqlOpen = 0;
    double smqlFirstQuery = 0;  // open + USE SCENE + the first FIND (which loads the scene)
    double sqliteOpen = 0;      // open + pragmas + preparing the statements
    double sqliteFirstQuery = 0;
};

struct WorkloadResult {
    std::vector<ClassResult> classes;
    std::vector<std::string> baselineNames;  // "SQLite", then "PostGIS" when it took part
    // The first FIND after USE SCENE: smql loads the scene into memory then. Over rounds that each
    // visit every sampled scene cold, as the other classes' percentiles are over rounds; the
    // baselines' one sample per scene (p50Low and p50High the fastest and the slowest of them).
    Percentiles smqlSceneSwitch;
    std::vector<Percentiles> baselineSceneSwitch;
    OpenTimes open;
    binder::ShapeCacheStats shapes;  // the engine's statement shapes at the end of the timed queries
};

WorkloadResult runWorkload(const DataSet& data, const WorkloadOptions& options, std::ostream& progress);

}  // namespace smql::bench
