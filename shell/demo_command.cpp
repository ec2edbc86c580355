// `smql demo [--db DIR]`: a synthetic RGB-D walk through a generated room, ingested into a new
// database and queried, so a first run needs no external data.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>

#include <fmt/format.h>

#include "engine/engine.hpp"
#include "ingest/synth/synth.hpp"
#include "model/error.hpp"
#include "shell/ingest_command.hpp"
#include "shell/session.hpp"

namespace smql::shell {

namespace fs = std::filesystem;

namespace {

std::string newTempFolder(const std::string& prefix) {
    std::string pattern = (fs::temp_directory_path() / (prefix + "-XXXXXX")).string();
    if (!mkdtemp(pattern.data()))
        throw Error(ErrorKind::Usage,
                    fmt::format("cannot create a folder under {}", fs::temp_directory_path().string()));
    return pattern;
}

}  // namespace

int demoCommand(const std::string& dbDirOption) {
    // The demo builds a database of its own: adding its scene to a database the user already has
    // would mix a generated room into their data.
    if (!dbDirOption.empty() && fs::exists(dbDirOption) &&
        (!fs::is_directory(dbDirOption) || !fs::is_empty(dbDirOption)))
        throw Error(ErrorKind::Usage, fmt::format("{} exists and is not an empty folder", dbDirOption), std::nullopt,
                    "smql demo --db names the database to build: a new or empty folder");
    std::string workDir = newTempFolder("smql-demo");
    std::string capture = (fs::path(workDir) / "capture").string();
    std::string memory = dbDirOption.empty() ? (fs::path(workDir) / "memory").string() : dbDirOption;
    std::cout << "smql demo: a synthetic RGB-D walk through a generated room (no external data),\n"
                 "ingested into a metric memory, then queried.\n\n";
    auto synth = synth::writeSynth(capture, {.seed = 7, .frames = 40, .objects = 24, .force = true});
    std::cout << fmt::format("1. captured {} frames of a {} into {} in {:.1f} s\n\n", synth.scene.poses.size(),
                             "generated room", capture, synth.totalSeconds);
    std::cout << "2. smql ingest " << capture << " --db " << memory << "\n";
    IngestArguments ingest;
    ingest.request.capture = capture;
    ingest.request.scene = "demo-room";
    ingest.db = memory;
    ingestCommand(ingest);
    // The frames have done their work: what stays is the memory (a few MB, for exploring), never
    // the capture's images, run after run.
    std::error_code ignored;
    fs::remove_all(dbDirOption.empty() ? fs::path(capture) : fs::path(workDir), ignored);

    std::cout << "\n3. queries\n\n";
    SessionOptions options;
    options.timer = true;
    options.fitTerminal = isatty(STDOUT_FILENO);
    Session session(Engine::open(memory), std::cout, std::cerr, options);
    // Queries that hold for any generated room: whatever furniture the seed chose.
    const char* examples[] = {
        "SHOW TREE",
        "FIND object WHERE on(object) PATH",
        "FIND object WHERE color = 'red' PATH",
        "FIND object NEAREST TO door LIMIT 3",
        "COUNT object WHERE near(wall.left, 1 m)",
        "RELATE (FIND object WHERE on(object) LIMIT 1) TO (FIND object NEAREST TO (FIND object WHERE on(object) LIMIT "
        "1) LIMIT 1)",
        "DESCRIBE (FIND object WHERE on(object) LIMIT 1)",
        "EXPLAIN FIND object WHERE on(object) AND near(window, 2 m)",
        // English, from where the viewer stands: the scene's viewpoint.
        "ASK 'what is the closest thing to me?'",
        "ASK 'what kind of room is this?'",
        "ASK 'how many people can sit here?'",
    };
    bool ok = true;
    for (const char* statement : examples) {
        std::cout << "smql> " << statement << ";\n";
        ok &= session.runScript(statement);
        std::cout << "\n";
    }
    std::cout << fmt::format("Explore it yourself: smql {}\n", memory);
    return ok ? 0 : 1;
}

}  // namespace smql::shell
