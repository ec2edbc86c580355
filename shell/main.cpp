// The `smql` command: a shell over a database directory, and sub-commands.
//   smql DIR                       interactive shell
//   smql DIR -c 'STATEMENT;'       run statements, print, exit (non-zero on error)
//   smql DIR -f script.smql        run a script
//   smql import|export|demo|test|synth|ingest|check-ingest|check   see --help of each
#include <fstream>
#include <iostream>
#include <sstream>
#include <unistd.h>

#include <CLI/CLI.hpp>

#include "engine/error.hpp"
#include "engine/model/names.hpp"
#include "ingest/import/registry.hpp"
#include "shell/commands.hpp"
#include "shell/ingest_command.hpp"
#include "shell/session.hpp"

namespace {

constexpr const char* kVersion = "smql 0.1.0";

int runShell(int argc, char** argv) {
    CLI::App app{"smql: an embedded spatial memory engine. `smql DIR` opens the shell on a database directory;\n"
                 "sub-commands: import, export, ingest, check-ingest, check, synth, demo, test (smql COMMAND --help)."};
    std::string dir, command, script, format = "table";
    bool readOnly = false, timer = false;
    app.add_option("database", dir, "database directory (created if missing)")->required();
    auto* commandOption = app.add_option("-c,--command", command, "run these statements and exit");
    app.add_option("-f,--file", script, "run the statements of this file and exit")->check(CLI::ExistingFile);
    app.add_option("--format", format, "output format: table, json or csv")->check(CLI::IsMember({"table", "json", "csv"}));
    app.add_flag("--read-only", readOnly, "open the database read-only");
    app.add_flag("--timer", timer, "print each statement's time");
    app.set_version_flag("--version", kVersion);
    CLI11_PARSE(app, argc, argv);

    // `-c ""` (an unset variable in a script, say) would otherwise fall through
    // to reading standard input or the interactive shell and exit 0.
    if (commandOption->count() > 0 && command.find_first_not_of(" \t\r\n") == std::string::npos)
        throw smql::Error(smql::ErrorKind::Usage, "-c was given no statement", std::nullopt,
                          "write the statements after -c, as in smql DB -c 'SHOW SCENES'");
    auto outputFormat = smql::shell::parseFormat(format);
    auto engine = smql::Engine::open(dir, readOnly);
    if (command.empty() && script.empty()) {
        if (!isatty(STDIN_FILENO)) {
            // Piped input: run it as a script.
            std::stringstream text;
            text << std::cin.rdbuf();
            smql::shell::Session session(*engine, std::cout, std::cerr, outputFormat);
            session.setTimer(timer);
            return session.runStatements(text.str()) ? 0 : 1;
        }
        return smql::shell::runRepl(*engine, dir, outputFormat);
    }
    smql::shell::Session session(*engine, std::cout, std::cerr, outputFormat);
    session.setTimer(timer);
    if (!command.empty() && !session.runStatements(command)) return 1;
    if (!script.empty()) {
        std::ifstream in(script);
        std::stringstream text;
        text << in.rdbuf();
        if (!session.runStatements(text.str())) return 1;
    }
    return 0;
}

int runSubcommand(int argc, char** argv) {
    CLI::App app{"smql sub-commands"};
    app.require_subcommand(1);

    auto* import = app.add_subcommand("import", "import a scene layout file into a database (one transaction)");
    std::string importFormat, importFile, importDb, importScene;
    import->add_option("format", importFormat, smql::model::joinAlternatives(smql::import::formatNames()))
        ->required()
        ->check(CLI::IsMember(smql::import::formatNames()));
    import->add_option("file", importFile, "the file to import")->required();
    import->add_option("--db", importDb, "database directory (created if missing)")->required();
    import->add_option("--scene", importScene, "scene name (default: from the file, else the file's folder name)");

    auto* exportCmd = app.add_subcommand("export", "export a scene as JSON (export json), or a node's evidence crops "
                                                    "(export evidence '#id' DIR)");
    std::string exportFormat, exportDb, exportScene, exportOut;
    std::vector<std::string> exportEvidence;
    exportCmd->add_option("format", exportFormat, "json or evidence")->required()->check(CLI::IsMember({"json", "evidence"}));
    exportCmd->add_option("node_and_dir", exportEvidence, "for evidence: the node ('#42') and the folder to write to");
    exportCmd->add_option("--db", exportDb, "database directory")->required()->check(CLI::ExistingDirectory);
    exportCmd->add_option("--scene", exportScene, "scene name (default: the most recent)");
    exportCmd->add_option("-o,--output", exportOut, "output file (default: standard output)");

    auto* ingestCmd = app.add_subcommand("ingest", "turn a capture (RGB-D folder, TUM, nerfstudio, COLMAP ...) into a new scene");
    smql::shell::IngestArguments ingestArgs;
    bool ingestQuiet = false;
    std::optional<double> ingestScale;
    ingestCmd->add_option("capture", ingestArgs.capture, "capture folder or file")->required()->check(CLI::ExistingPath);
    ingestCmd->add_option("--db", ingestArgs.db, "database directory (created if missing)")->required();
    ingestCmd->add_option("--scene", ingestArgs.scene, "scene name (default: the capture's folder name)");
    ingestCmd->add_option("--geometry", ingestArgs.geometry, "given, colmap or auto (default)")
        ->check(CLI::IsMember({"given", "colmap", "auto"}));
    ingestCmd->add_option("--objects", ingestArgs.objects, "masks, detections, cluster or auto (default)")
        ->check(CLI::IsMember({"masks", "detections", "cluster", "auto"}));
    ingestCmd->add_option("--fps", ingestArgs.fps, "frames per second sampled from videos (default 1)")->check(CLI::PositiveNumber);
    ingestCmd->add_option("--scale", ingestScale, "metres per capture unit, overriding the estimate")->check(CLI::PositiveNumber);
    ingestCmd->add_flag("--quiet", ingestQuiet, "print nothing but errors");
    ingestCmd->add_option("--update", ingestArgs.update,
                          "refresh the last-seen time of the objects of this scene that the capture sees again, "
                          "instead of adding a new scene");
    ingestCmd->add_option("--log", ingestArgs.log, "progress as a bar (default), json lines, or quiet")
        ->check(CLI::IsMember({"bar", "json", "quiet"}));

    auto* check = app.add_subcommand("check-ingest", "compare an ingested scene with a synthetic capture's truth");
    std::string checkDb, checkTruth, checkScene, checkFormat = "table";
    check->add_option("database", checkDb, "database directory")->required()->check(CLI::ExistingDirectory);
    check->add_option("--truth", checkTruth, "truth.json of the capture (smql synth writes it)")->required()->check(CLI::ExistingFile);
    check->add_option("--scene", checkScene, "scene name (default: the most recent)");
    check->add_option("--format", checkFormat, "table or json")->check(CLI::IsMember({"table", "json"}));

    auto* demo = app.add_subcommand("demo", "build a sample memory of a generated room and query it");
    std::string demoDb;
    demo->add_option("--db", demoDb, "where to build it (default: a new folder under /tmp)");

    auto* test = app.add_subcommand("test", "run declarative query suites (*.smqlt)");
    std::vector<std::string> testFiles;
    test->add_option("files", testFiles, "suite files")->required()->check(CLI::ExistingFile);

    auto* synth = app.add_subcommand("synth", "write a synthetic RGB-D capture of a generated room, with ground truth");
    std::string synthOut;
    std::uint64_t synthSeed = 1;
    int synthFrames = 60, synthObjects = 24;
    bool synthForce = false;
    synth->add_option("--out", synthOut, "output folder (refused when not empty, unless --force)")->required();
    synth->add_option("--seed", synthSeed, "room and walk seed (default 1)");
    synth->add_option("--frames", synthFrames, "frames along the walk (default 60)")->check(CLI::Range(1, 100000));
    synth->add_option("--objects", synthObjects, "objects in the room (default 24)")->check(CLI::Range(1, 5000));
    synth->add_flag("--force", synthForce, "write into a non-empty folder, replacing an earlier capture's files");

    auto* checkDbCmd = app.add_subcommand("check", "verify a database: records and their checksums, scene trees, "
                                                   "indexes, lock file; exit status 1 when anything is wrong");
    std::string checkDbDir;
    checkDbCmd->add_option("database", checkDbDir, "database directory")->required()->check(CLI::ExistingDirectory);

    CLI11_PARSE(app, argc, argv);
    if (checkDbCmd->parsed()) return smql::shell::checkCommand(checkDbDir);
    if (import->parsed()) return smql::shell::importCommand(importFormat, importFile, importDb, importScene);
    if (exportCmd->parsed() && exportFormat == "evidence") {
        if (exportEvidence.size() != 2)
            throw smql::Error(smql::ErrorKind::Usage, "export evidence takes a node and a folder", std::nullopt,
                              "smql export evidence '#42' evidence/ --db DB");
        return smql::shell::exportEvidenceCommand(exportDb, exportEvidence[0], exportEvidence[1]);
    }
    if (exportCmd->parsed()) return smql::shell::exportCommand(exportFormat, exportDb, exportScene, exportOut);
    if (ingestCmd->parsed()) {
        ingestArgs.scale = ingestScale;
        if (ingestQuiet) ingestArgs.log = "quiet";
        return smql::shell::ingestCommand(ingestArgs);
    }
    if (check->parsed()) return smql::shell::checkIngestCommand(checkDb, checkTruth, checkScene, checkFormat);
    if (demo->parsed()) return smql::shell::demoCommand(demoDb);
    if (test->parsed()) return smql::shell::testCommand(testFiles);
    if (synth->parsed()) return smql::shell::synthCommand(synthOut, synthSeed, synthFrames, synthObjects, synthForce);
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        std::string first = argc > 1 ? argv[1] : "";
        if (first == "import" || first == "export" || first == "demo" || first == "test" || first == "synth" ||
            first == "ingest" || first == "check-ingest" || first == "check")
            return runSubcommand(argc, argv);
        return runShell(argc, argv);
    } catch (const smql::Error& e) {
        std::cerr << e.render() << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "smql: " << e.what() << "\n";
        return 1;
    }
}
