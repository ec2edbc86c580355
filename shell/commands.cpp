#include "shell/commands.hpp"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <fmt/format.h>

#include "engine/engine.hpp"
#include "engine/error.hpp"
#include "engine/format.hpp"
#include "ingest/synth/synth.hpp"
#include "shell/ingest_command.hpp"
#include "ingest/import/importers.hpp"
#include "ingest/import/registry.hpp"
#include "shell/session.hpp"

namespace smql::shell {

namespace fs = std::filesystem;

namespace {

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::string summary(const model::SceneData& scene) {
    std::size_t anchors = 0, objects = 0, hidden = 0;
    for (const auto& n : scene.nodes) {
        anchors += n.kind == model::NodeKind::Anchor;
        objects += n.kind == model::NodeKind::Object && !n.hidden;
        hidden += n.hidden;
    }
    return fmt::format("{} nodes: {} anchors, {} objects, {} hidden", scene.nodes.size(), anchors, objects, hidden);
}

}  // namespace

int importCommand(const std::string& format, const std::string& file, const std::string& dbDir,
                  const std::string& sceneName) {
    auto start = std::chrono::steady_clock::now();
    // Read and validate the whole file before the database is touched.
    model::SceneData scene = import::read(format, file, sceneName);
    auto engine = Engine::open(dbDir);
    engine->importScene(scene);
    std::cout << fmt::format("imported scene '{}' ({}) into {} in {:.1f} ms\n", scene.info.name, summary(scene), dbDir,
                             millisecondsSince(start));
    return 0;
}

int exportCommand(const std::string&, const std::string& dbDir, const std::string& sceneName,
                  const std::string& outFile) {
    auto engine = Engine::open(dbDir, /*readOnly=*/true);
    std::string json = import::writeSceneJson(engine->exportScene(sceneName));
    if (outFile.empty()) {
        std::cout << json << "\n";
        return 0;
    }
    std::ofstream out(outFile);
    out << json << "\n";
    if (!out)
        throw Error(ErrorKind::Usage, fmt::format("cannot write {}", outFile), std::nullopt, "check the folder exists");
    std::cerr << fmt::format("exported scene to {}\n", outFile);
    return 0;
}

int demoCommand(const std::string& dbDirOption) {
    std::string workDir = dbDirOption;
    if (workDir.empty()) {
        std::string pattern = (fs::temp_directory_path() / "smql-demo-XXXXXX").string();
        if (!mkdtemp(pattern.data())) throw Error(ErrorKind::Usage, "cannot create a folder under /tmp");
        workDir = pattern;
    }
    std::string capture = (fs::path(workDir) / "capture").string();
    std::string memory = (fs::path(workDir) / "memory").string();
    std::cout << "smql demo: a synthetic RGB-D walk through a generated room (no external data),\n"
                 "ingested into a metric memory, then queried.\n\n";
    auto synth = synth::writeSynth(capture, {.seed = 7, .frames = 40, .objects = 24, .force = true});
    std::cout << fmt::format("1. captured {} frames of a {} into {} in {:.1f} s\n\n", synth.scene.poses.size(),
                             "generated room", capture, synth.totalSeconds);
    std::cout << "2. smql ingest " << capture << " --db " << memory << "\n";
    IngestArguments ingest;
    ingest.capture = capture;
    ingest.db = memory;
    ingest.scene = "demo-room";
    if (fs::exists(memory)) fs::remove_all(memory);  // a fresh memory each run
    ingestCommand(ingest);

    std::cout << "\n3. queries\n\n";
    auto engine = Engine::open(memory);
    Session session(*engine, std::cout, std::cerr, OutputFormat::Table);
    session.setTimer(true);
    // Queries that hold for any generated room: whatever furniture the seed chose.
    const char* examples[] = {
        "SHOW TREE",
        "FIND object WHERE on(object) PATH",
        "FIND object WHERE color = 'red' PATH",
        "FIND object NEAREST TO door LIMIT 3",
        "COUNT object WHERE near(wall.left, 1 m)",
        "RELATE (FIND object WHERE on(object) LIMIT 1) TO (FIND object NEAREST TO (FIND object WHERE on(object) LIMIT 1) LIMIT 1)",
        "DESCRIBE (FIND object WHERE on(object) LIMIT 1)",
        "EXPLAIN FIND object WHERE on(object) AND near(window, 2 m)",
    };
    bool ok = true;
    for (const char* statement : examples) {
        std::cout << "smql> " << statement << ";\n";
        ok &= session.runStatements(statement);
        std::cout << "\n";
    }
    std::cout << fmt::format("Explore it yourself: smql {}\n", memory);
    return ok ? 0 : 1;
}

}  // namespace smql::shell
