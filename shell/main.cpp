// The `smql` command: a shell over a database directory, and sub-commands.
//   smql DIR                       interactive shell
//   smql DIR -c 'STATEMENT;'       run statements, print, exit (non-zero on error)
//   smql DIR -f script.smql        run a script
//   smql import|export|demo|test|synth|ingest|check-ingest   see --help of each
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <unistd.h>

#include <fmt/format.h>

#include "engine/error.hpp"
#include "engine/model/names.hpp"
#include "ingest/import/registry.hpp"
#include "shell/commands.hpp"
#include "shell/cli.hpp"
#include "shell/session.hpp"

namespace {

namespace fs = std::filesystem;

constexpr const char* kVersion = "smql 0.1.0";

int runShell(int argc, char** argv) {
    CLI::App app{"smql: an embedded spatial memory engine. `smql DIR` opens the shell on a database directory;\n"
                 "sub-commands: import, export, ingest, check-ingest, synth, demo, test (smql COMMAND --help)."};
    std::string dir, command, script, format = "table";
    bool readOnly = false, timer = false;
    app.add_option("database", dir, "database directory (created if missing)")->required();
    app.add_option("-c,--command", command, "run these statements and exit");
    app.add_option("-f,--file", script, "run the statements of this file and exit")->check(CLI::ExistingFile);
    app.add_option("--format", format, "output format: table, json or csv")->check(CLI::IsMember({"table", "json", "csv"}));
    app.add_flag("--read-only", readOnly, "open the database read-only");
    app.add_flag("--timer", timer, "print each statement's time");
    app.set_version_flag("--version", kVersion);
    if (auto status = smql::shell::parseArguments(app, argc, argv)) return *status;

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

// The capture commands live in smql-ingest beside this program (see shell/ingest_main.cpp): it
// replaces this process, so its output, exit status and Ctrl-C behave as if it were smql itself.
int runIngestTool(char** argv) {
    std::error_code error;
    fs::path self = fs::read_symlink("/proc/self/exe", error);
    fs::path tool = (error ? fs::path(argv[0]) : self).parent_path() / "smql-ingest";
    execv(tool.c_str(), argv);
    throw smql::Error(smql::ErrorKind::Usage, fmt::format("cannot run {}: {}", tool.string(), std::strerror(errno)),
                      std::nullopt, "smql-ingest is built and installed next to smql (cmake --build build --target smql-ingest)");
}

int runSubcommand(int argc, char** argv) {
    CLI::App app{"smql sub-commands"};
    app.name("smql");
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

    auto* test = app.add_subcommand("test", "run declarative query suites (*.smqlt)");
    std::vector<std::string> testFiles;
    test->add_option("files", testFiles, "suite files")->required()->check(CLI::ExistingFile);

    if (auto status = smql::shell::parseArguments(app, argc, argv)) return *status;
    if (import->parsed()) return smql::shell::importCommand(importFormat, importFile, importDb, importScene);
    if (exportCmd->parsed() && exportFormat == "evidence") {
        if (exportEvidence.size() != 2)
            throw smql::Error(smql::ErrorKind::Usage, "export evidence takes a node and a folder", std::nullopt,
                              "smql export evidence '#42' evidence/ --db DB");
        return smql::shell::exportEvidenceCommand(exportDb, exportEvidence[0], exportEvidence[1]);
    }
    if (exportCmd->parsed()) return smql::shell::exportCommand(exportFormat, exportDb, exportScene, exportOut);
    return smql::shell::testCommand(testFiles);
}

}  // namespace

int main(int argc, char** argv) {
    try {
        std::string first = argc > 1 ? argv[1] : "";
        if (first == "ingest" || first == "check-ingest" || first == "synth" || first == "demo")
            return runIngestTool(argv);
        if (first == "import" || first == "export" || first == "test") return runSubcommand(argc, argv);
        return runShell(argc, argv);
    } catch (const smql::Error& e) {
        std::cerr << e.render() << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "smql: " << e.what() << "\n";
        return 1;
    }
}
