// The `smql` command: a shell over a database directory, and sub-commands.
//   smql DIR                       interactive shell
//   smql DIR -c 'STATEMENT;'       run statements, print, exit (non-zero on error)
//   smql DIR -f script.smql        run a script
//   smql import|export|demo|test   see --help of each
#include <fstream>
#include <iostream>
#include <sstream>
#include <unistd.h>

#include <CLI/CLI.hpp>

#include "engine/error.hpp"
#include "shell/commands.hpp"
#include "shell/session.hpp"

namespace {

constexpr const char* kVersion = "smql 0.1.0";

int runShell(int argc, char** argv) {
    CLI::App app{"smql: an embedded spatial memory engine. `smql DIR` opens the shell on a database directory;\n"
                 "sub-commands: import, export, demo, test (smql COMMAND --help)."};
    std::string dir, command, script, format = "table";
    bool readOnly = false, timer = false;
    app.add_option("database", dir, "database directory (created if missing)")->required();
    app.add_option("-c,--command", command, "run these statements and exit");
    app.add_option("-f,--file", script, "run the statements of this file and exit")->check(CLI::ExistingFile);
    app.add_option("--format", format, "output format: table, json or csv")->check(CLI::IsMember({"table", "json", "csv"}));
    app.add_flag("--read-only", readOnly, "open the database read-only");
    app.add_flag("--timer", timer, "print each statement's time");
    app.set_version_flag("--version", kVersion);
    CLI11_PARSE(app, argc, argv);

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
    import->add_option("format", importFormat, "replica, spatiallm or json")
        ->required()
        ->check(CLI::IsMember({"replica", "spatiallm", "json"}));
    import->add_option("file", importFile, "the file to import")->required();
    import->add_option("--db", importDb, "database directory (created if missing)")->required();
    import->add_option("--scene", importScene, "scene name (default: from the file, else the file's folder name)");

    auto* exportCmd = app.add_subcommand("export", "export a scene in the smql JSON scene format");
    std::string exportFormat, exportDb, exportScene, exportOut;
    exportCmd->add_option("format", exportFormat, "json")->required()->check(CLI::IsMember({"json"}));
    exportCmd->add_option("--db", exportDb, "database directory")->required()->check(CLI::ExistingDirectory);
    exportCmd->add_option("--scene", exportScene, "scene name (default: the most recent)");
    exportCmd->add_option("-o,--output", exportOut, "output file (default: standard output)");

    auto* demo = app.add_subcommand("demo", "build a sample memory of a generated room and query it");
    std::string demoDb;
    demo->add_option("--db", demoDb, "where to build it (default: a new folder under /tmp)");

    auto* test = app.add_subcommand("test", "run declarative query suites (*.smqlt)");
    std::vector<std::string> testFiles;
    test->add_option("files", testFiles, "suite files")->required()->check(CLI::ExistingFile);

    CLI11_PARSE(app, argc, argv);
    if (import->parsed()) return smql::shell::importCommand(importFormat, importFile, importDb, importScene);
    if (exportCmd->parsed()) return smql::shell::exportCommand(exportFormat, exportDb, exportScene, exportOut);
    if (demo->parsed()) return smql::shell::demoCommand(demoDb);
    if (test->parsed()) return smql::shell::testCommand(testFiles);
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        std::string first = argc > 1 ? argv[1] : "";
        if (first == "import" || first == "export" || first == "demo" || first == "test") return runSubcommand(argc, argv);
        return runShell(argc, argv);
    } catch (const smql::Error& e) {
        std::cerr << e.render() << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "smql: " << e.what() << "\n";
        return 1;
    }
}
