// smql_bench: builds a small and a large generated memory in smql and in
// SQLite, checks that both answer every benchmark query the same, times the
// query classes, imports and opens, and writes the markdown report.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "bench/data_set.hpp"
#include "bench/postgis_baseline.hpp"
#include "bench/report.hpp"
#include "bench/stats.hpp"
#include "bench/workload.hpp"
#include "model/error.hpp"

namespace smql::bench {

namespace {

namespace fs = std::filesystem;

struct Options {
    int scenes = 1000;
    int objects = 2000;
    int smallObjects = 200;
    WorkloadOptions workload;
    bool quick = false;
    std::string out;
    std::string directory;
    bool keep = false;
    bool postgis = true;
};

// The hand-written notes of an existing report: what follows the marker's line.
std::string keptNotes(const std::string& path) {
    std::ifstream in(path);
    if (!in) return {};
    std::stringstream text;
    text << in.rdbuf();
    std::string s = text.str();
    auto at = s.find(kNotesMarker);
    if (at == std::string::npos) return {};
    auto lineEnd = s.find('\n', at);
    return lineEnd == std::string::npos ? std::string() : s.substr(lineEnd + 1);
}

fs::path workDirectory(const std::string& requested) {
    if (!requested.empty()) {
        if (fs::exists(requested) && !fs::is_empty(requested))
            throw std::runtime_error(fmt::format("--dir {} is not empty; give a new or empty directory", requested));
        fs::create_directories(requested);
        return requested;
    }
    std::string pattern = (fs::temp_directory_path() / "smql-bench-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a temporary directory");
    return pattern;
}

int run(const Options& options, const std::string& commandLine) {
    auto started = Clock::now();
    Report report;
    report.machine = machineInfo();
    report.commandLine = commandLine;
    report.options = options.workload;

    // The PostgreSQL cluster lives for the whole run; its destructor stops it and removes it, also on errors.
    std::unique_ptr<PostgresServer> postgres;
    if (options.postgis) {
        std::string whyNot;
        postgres = startPostgres(whyNot);
        report.postgis = postgres ? postgres->version() : "PostGIS skipped: " + whyNot;
        if (!postgres) fmt::print("smql_bench: {}\n", report.postgis);
    } else {
        report.postgis = "PostGIS skipped (--no-postgis)";
    }
    fs::path work = workDirectory(options.directory);
    fmt::print("smql_bench: databases under {}\n", work.string());
    const DataSetSpec specs[] = {{"small", 1, options.smallObjects}, {"large", options.scenes, options.objects}};
    try {
        for (const auto& spec : specs) {
            fmt::print("{}: {} scene(s) x {} objects\n", spec.label, spec.scenes, spec.objectsPerScene);
            std::cout.flush();
            DataSetRun run;
            run.data = buildDataSet(spec, work / spec.label, postgres.get(), std::cout);
            run.result = runWorkload(run.data, options.workload, std::cout);
            report.runs.push_back(std::move(run));
        }
    } catch (...) {
        if (!options.keep) fs::remove_all(work);
        throw;
    }
    if (!options.keep) fs::remove_all(work);
    report.totalSeconds = microsecondsSince(started) / 1e6;

    std::string markdown = renderMarkdown(report);
    std::cout << '\n' << markdown;
    if (!options.out.empty()) {
        std::string notes = keptNotes(options.out);
        std::ofstream file(options.out, std::ios::trunc);
        file << markdown << (notes.empty() ? "\n" : notes);
        if (!file) throw std::runtime_error(fmt::format("cannot write {}", options.out));
        fmt::print("\nwrote {}\n", options.out);
    }
    return 0;
}

}  // namespace

}  // namespace smql::bench

int main(int argc, char** argv) {
    using smql::bench::Options;
    Options options;
    CLI::App app{"smql_bench: smql against a SQLite baseline on generated memories, side by side"};
    app.add_option("--scenes", options.scenes, "scenes in the large data set")->check(CLI::PositiveNumber);
    app.add_option("--objects", options.objects, "objects per scene in the large data set")->check(CLI::PositiveNumber);
    app.add_option("--small-objects", options.smallObjects, "objects in the one scene of the small data set")
        ->check(CLI::PositiveNumber);
    app.add_option("--queries", options.workload.queries, "timed executions per query class and system")
        ->check(CLI::PositiveNumber);
    app.add_option("--rounds", options.workload.rounds, "rounds the timed executions are split into (median of rounds)")
        ->check(CLI::PositiveNumber);
    app.add_option("--sample-scenes", options.workload.sampledScenes, "scenes the single-scene queries visit")
        ->check(CLI::PositiveNumber);
    app.add_option("--out", options.out, "write the markdown report to this file (docs/benchmarks.md)");
    app.add_option("--dir", options.directory, "build the databases here (default: a new temporary directory)");
    app.add_flag("--keep", options.keep, "keep the databases after the run");
    app.add_flag("--no-postgis{false}", options.postgis, "leave the PostGIS baseline out (no PostgreSQL cluster)");
    app.add_flag("--quick", options.quick, "tiny sizes and few queries, overriding the options above: a smoke test");
    CLI11_PARSE(app, argc, argv);
    if (options.quick) {
        options.scenes = 10;
        options.objects = 200;
        options.smallObjects = 60;
        options.workload.queries = 50;
        options.workload.rounds = 2;
        options.workload.sampledScenes = 3;
        options.workload.openRepeats = 3;
    }
    std::string commandLine = "smql_bench";
    for (int i = 1; i < argc; ++i) commandLine += std::string(" ") + argv[i];
    try {
        return smql::bench::run(options, commandLine);
    } catch (const smql::Error& e) {
        std::cerr << "smql_bench: smql error: " << e.what() << '\n';
    } catch (const std::exception& e) {
        std::cerr << "smql_bench: " << e.what() << '\n';
    }
    return 1;
}
