#include "shell/eval_command.hpp"

#include <filesystem>
#include <fstream>
#include <iostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/engine.hpp"
#include "engine/eval/evaluation.hpp"
#include "ingest/import/importers.hpp"
#include "shell/output_file.hpp"
#include "storage/output_guard.hpp"

namespace smql::shell {

namespace fs = std::filesystem;

namespace {

void writeFile(const fs::path& path, const std::string& text, const std::string& database) {
    storage::refuseDatabaseFile(path.string(), database);
    std::ofstream out(path);
    out << text;
    checkWritten(out, path.string());
}

}  // namespace

int evalCommand(const EvalOptions& options) {
    auto engine = Engine::open(options.db, /*readOnly=*/true);
    eval::EvalReport report = eval::evaluate(*engine, {.suite = options.suite, .scene = options.scene});
    if (!options.writeSuite.empty()) {
        fs::create_directories(options.writeSuite);
        writeFile(fs::path(options.writeSuite) / "truth.json", import::writeSceneJson(report.truth), options.db);
        writeFile(fs::path(options.writeSuite) / "eval-suite.json", report.suiteJson, options.db);
    }

    std::cout << "| task | metric | value | episodes | median query µs |\n|---|---|---:|---:|---:|\n";
    nlohmann::ordered_json metrics = nlohmann::ordered_json::array();
    for (const auto& m : report.metrics) {
        std::cout << fmt::format("| {} | {} | {:.3f} | {} | {:.1f} |\n", m.task, m.metric, m.value, m.episodes,
                                 m.medianMicroseconds);
        metrics.push_back({{"task", m.task},
                           {"metric", m.metric},
                           {"value", m.value},
                           {"episodes", m.episodes},
                           {"median_us", m.medianMicroseconds}});
    }
    if (!options.jsonOut.empty())
        writeFile(options.jsonOut,
                  nlohmann::ordered_json{{"suite", options.suite.empty() ? "generated" : options.suite},
                                         {"database", options.db},
                                         {"scene", report.scene},
                                         {"metrics", metrics}}
                          .dump(2) +
                      "\n",
                  options.db);
    return 0;
}

}  // namespace smql::shell
