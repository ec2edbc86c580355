// The `smql` command: a shell over a database directory, and sub-commands.
//   smql DIR                       interactive shell
//   smql DIR 'STATEMENTS'          run statements, print, exit (also -c; -f FILE for a script)
//   smql import|export|check|test  here; ingest|check-ingest|synth|demo in smql-ingest;
//   smql fleet|push|pull, smql URL in smql-fleet
// Options follow sqlite3's where they mean the same (-json, -csv, -header, -cmd, -bail, -echo).
#include <unistd.h>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>
#include <utility>

#include <fmt/format.h>

#include "ingest/import/registry.hpp"
#include "model/error.hpp"
#include "model/names.hpp"
#include "shell/cli.hpp"
#include "shell/commands.hpp"
#include "shell/eval_command.hpp"
#include "shell/interrupt.hpp"
#include "shell/repl.hpp"
#include "shell/session.hpp"

namespace {

namespace fs = std::filesystem;

constexpr const char* kVersion = "smql 0.1.0";

// sqlite3 users write long options with one dash (-csv, -header, -cmd). CLI11 would read `-csv` as
// `-c sv`, so a single-dash word that names a long option becomes that option before parsing.
std::vector<std::string> longOptionsWithOneDash(const CLI::App& app, int argc, char** argv) {
    std::set<std::string, std::less<>> longNames;
    for (const CLI::Option* option : app.get_options())
        for (const std::string& name : option->get_lnames()) longNames.insert(name);
    std::vector<std::string> args(argv, argv + argc);
    for (std::size_t i = 1; i < args.size(); ++i) {
        if (args[i] == "--") break;
        const std::string& arg = args[i];
        if (arg.size() > 2 && arg[0] == '-' && arg[1] != '-' && longNames.contains(std::string_view(arg).substr(1)))
            args[i] = "-" + arg;
    }
    return args;
}

// The sub-commands and the program that runs each: one table, from which the dispatch in main() and
// the check for a mistyped one come.
enum class Runs { Ingest, Fleet, Here };
constexpr std::pair<std::string_view, Runs> kSubcommands[] = {
    {"ingest", Runs::Ingest}, {"check-ingest", Runs::Ingest}, {"synth", Runs::Ingest}, {"demo", Runs::Ingest},
    {"map", Runs::Ingest},    {"guide", Runs::Ingest},        {"view", Runs::Ingest},  {"fleet", Runs::Fleet},
    {"push", Runs::Fleet},    {"pull", Runs::Fleet},          {"import", Runs::Here},  {"export", Runs::Here},
    {"test", Runs::Here},     {"check", Runs::Here},          {"eval", Runs::Here}};

std::optional<Runs> subcommand(std::string_view name) {
    for (const auto& [word, runs] : kSubcommands)
        if (word == name) return runs;
    return std::nullopt;
}

// Two words one typing slip apart: one letter changed, added or dropped, or two neighbours swapped.
bool oneSlipApart(std::string_view a, std::string_view b) {
    if (a.size() > b.size()) std::swap(a, b);
    if (b.size() - a.size() > 1) return false;
    std::size_t i = 0;
    while (i < a.size() && a[i] == b[i]) ++i;
    if (a.size() == b.size())
        return i == a.size() || a.substr(i + 1) == b.substr(i + 1) ||
               (i + 1 < a.size() && a[i] == b[i + 1] && a[i + 1] == b[i] && a.substr(i + 2) == b.substr(i + 2));
    return a.substr(i) == b.substr(i + 1);
}

// A database name that does not exist and is a sub-command mistyped (`smql exprot json`) would make
// a database of the typo: refused, naming the sub-command.
void refuseMistypedSubcommand(const std::string& dir) {
    std::error_code ec;
    if (dir.size() < 4 || dir.find('/') != std::string::npos || fs::exists(dir, ec)) return;
    for (const auto& [word, runs] : kSubcommands)
        if (oneSlipApart(dir, word))
            throw smql::Error(
                smql::ErrorKind::Usage, fmt::format("'{}' is no sub-command, and no database of that name exists", dir),
                std::nullopt,
                fmt::format("did you mean smql {}? To make a new database of that name, write ./{}", word, dir));
}

// A database in a fresh temporary folder, removed with everything in it when the shell ends.
struct TransientDatabase {
    fs::path path;
    TransientDatabase() {
        std::string pattern = (fs::temp_directory_path() / "smql-XXXXXX").string();
        if (!mkdtemp(pattern.data()))
            throw smql::Error(smql::ErrorKind::Storage,
                              fmt::format("cannot make a temporary database folder: {}", std::strerror(errno)),
                              std::nullopt, "set TMPDIR to a folder you can write, or name a database");
        path = pattern;
    }
    TransientDatabase(const TransientDatabase&) = delete;
    TransientDatabase& operator=(const TransientDatabase&) = delete;
    ~TransientDatabase() {
        std::error_code ignored;
        fs::remove_all(path, ignored);
    }
};

std::string subcommandList() {
    std::string out;
    for (const auto& [word, runs] : kSubcommands) out += (out.empty() ? "" : ", ") + std::string(word);
    return out;
}

int runShell(int argc, char** argv) {
    CLI::App app{
        fmt::format("smql: an embedded spatial memory engine.\n"
                    "`smql DIR` opens the shell on the database in DIR; `smql DIR 'STATEMENTS'` runs them and exits; "
                    "`smql` or `smql :memory:`, a transient database.\n"
                    "Sub-commands: {} (smql COMMAND --help).\n"
                    "Long options may be written with one dash, as in sqlite3 (-csv, -header, -cmd).",
                    subcommandList())};
    app.name("smql");
    std::string dir, command, script, mode = "table";
    std::vector<std::string> statements, startup;
    smql::shell::SessionOptions options;
    app.add_option("database", dir,
                   "database directory (created if missing); none: a transient database, removed at exit");
    app.add_option("statements", statements, "statements to run, then exit (as -c)");
    auto* commandOption = app.add_option("-c,--command", command, "run these statements and exit");
    app.add_option("-f,--file", script, "run the statements of this file and exit")->check(CLI::ExistingFile);
    app.add_option("--cmd", startup,
                   "run this statement or meta command first (repeatable; then the shell or the input)")
        ->allow_extra_args(false);
    const std::vector<std::string> modes = smql::shell::outputModeNames();
    app.add_option("--format,--mode", mode, "output mode (default table)")->check(CLI::IsMember(modes));
    for (const std::string& name : modes)
        app.add_flag_callback(
            "--" + name, [&mode, name] { mode = name; }, "same as --format " + name);
    app.add_flag_callback(
        "--tabs", [&mode] { mode = "tsv"; }, "same as --format tsv (sqlite3's name)");
    app.add_option("--separator", options.output.separator, "what list mode puts between values (default |)");
    app.add_flag_callback(
        "--header,--headers", [&options] { options.output.headers = true; }, "print column names (the default)");
    app.add_flag_callback(
        "--noheader,--noheaders", [&options] { options.output.headers = false; }, "no column names");
    app.add_flag("--bail", options.bail, "stop at the first error: after a --cmd, and in the interactive shell");
    app.add_flag("--echo", options.echo, "print each statement before its result");
    app.add_flag("--read-only,--readonly", options.readOnly, "open the database read-only");
    app.add_flag("--safe", options.safe,
                 "safe mode, for statements from someone else: no meta command reads or writes files or opens "
                 "another database (docs/shell.md, \"Untrusted input\")");
    app.add_flag("--timer", options.timer, "print each statement's time on standard error");
    app.set_version_flag("--version", kVersion);
    std::vector<std::string> args = longOptionsWithOneDash(app, argc, argv);
    std::vector<char*> rewritten;
    for (auto& a : args) rewritten.push_back(a.data());
    if (auto status = smql::shell::parseArguments(app, static_cast<int>(rewritten.size()), rewritten.data()))
        return *status;

    // `-c ""` (an unset variable in a script, say) would otherwise fall through
    // to reading standard input or the interactive shell and exit 0.
    if (commandOption->count() > 0 && !smql::shell::holdsStatement(command))
        throw smql::Error(smql::ErrorKind::Usage, "-c was given no statement", std::nullopt,
                          "write the statements after -c, as in smql DB -c 'SHOW SCENES'");
    options.output.mode = smql::shell::parseOutputMode(mode);
    options.fitTerminal = isatty(STDOUT_FILENO);
    // No database named: as sqlite3 opens one in memory, smql opens one in a temporary folder that
    // is removed when the shell ends.
    // `:memory:`, as sqlite3 names it, is that transient database too.
    std::optional<TransientDatabase> transient;
    if (dir.empty() || dir == ":memory:") dir = transient.emplace().path.string();
    refuseMistypedSubcommand(dir);
    options.database = dir;
    bool noScript = command.empty() && statements.empty() && script.empty();
    bool interactive = noScript && isatty(STDIN_FILENO);
    // Piped input is read whole before Ctrl-C is caught: an interrupted read would run half a script.
    std::string piped;
    if (noScript && !interactive) {
        std::stringstream text;
        text << std::cin.rdbuf();
        piped = text.str();
    }
    smql::shell::interrupt::install();
    smql::shell::Session session(smql::Engine::open(dir, options.readOnly), std::cout, std::cerr, options);

    bool failed = false;
    for (const auto& text : startup) {
        if (session.runScript(text)) continue;
        if (options.bail) return 1;
        failed = true;
    }
    if (interactive && transient)
        std::cout << "Connected to a transient database, removed at exit. Use \".open DIR\" to open a "
                     "database that stays.\n";
    if (interactive) return smql::shell::runRepl(session, dir) != 0 || failed ? 1 : 0;

    // Scripts stop at their first error: later statements may depend on the ones before.
    auto fails = [&](const std::string& text) { return !session.quitRequested() && !session.runScript(text); };
    if (!command.empty() && fails(command)) return 1;
    for (const auto& text : statements)
        if (fails(text)) return 1;
    if (!script.empty()) {
        const std::string text = smql::shell::readScriptFile(script);
        if (!smql::shell::holdsStatement(text))
            throw smql::Error(smql::ErrorKind::Usage, fmt::format("{} holds no statement", script), std::nullopt,
                              "a script holds statements separated by ';' (blank lines and -- comments aside)");
        if (fails(text)) return 1;
    }
    if (noScript && fails(piped)) return 1;
    return failed ? 1 : 0;
}

// The capture commands live in smql-ingest beside this program (see shell/ingest_main.cpp), the
// fleet commands in smql-fleet (shell/fleet_main.cpp): it replaces this process, so its output,
// exit status and Ctrl-C behave as if it were smql itself.
int runTool(const char* name, char** argv) {
    std::error_code error;
    fs::path self = fs::read_symlink("/proc/self/exe", error);
    fs::path tool = (error ? fs::path(argv[0]) : self).parent_path() / name;
    execv(tool.c_str(), argv);
    throw smql::Error(
        smql::ErrorKind::Usage, fmt::format("cannot run {}: {}", tool.string(), std::strerror(errno)), std::nullopt,
        fmt::format("{} is built and installed next to smql (cmake --build build --target {})", name, name));
}

int runSubcommand(int argc, char** argv) {
    CLI::App app{"smql sub-commands"};
    app.name("smql");
    app.require_subcommand(1);

    auto* import = app.add_subcommand("import", "import a scene layout file into a database (one transaction)");
    std::string importFormat, importFile, importDb, importScene, importUpdate;
    import->add_option("format", importFormat, smql::model::joinAlternatives(smql::import::readableFormats()))
        ->required()
        ->check(CLI::IsMember(smql::import::readableFormats()));
    import->add_option("file", importFile, "the file to import")->required();
    import->add_option("--db", importDb, "database directory (created if missing)")->required();
    import->add_option("--scene", importScene, "scene name (default: from the file, else the file's folder name)");
    import->add_option("--update", importUpdate,
                       "a scene of the same place: the file becomes its next version (docs/history.md)");
    bool importAll = false;
    import->add_flag("--all", importAll, "every scene of a file that holds several (vsibench), each under its name")
        ->excludes("--scene")
        ->excludes("--update");

    auto* exportCmd = app.add_subcommand("export",
                                         "export a scene as a file (export json), or a node's evidence crops "
                                         "(export evidence '#id' DIR)");
    std::string exportFormat, exportDb, exportScene, exportOut;
    std::vector<std::string> exportEvidence;
    std::vector<std::string> exportFormats = smql::import::writableFormats();
    exportFormats.emplace_back("html");  // the view's page as one file (docs/view.md)
    exportFormats.emplace_back("evidence");
    exportCmd->add_option("format", exportFormat, smql::model::joinAlternatives(exportFormats))
        ->required()
        ->check(CLI::IsMember(exportFormats));
    exportCmd->add_option("node_and_dir", exportEvidence, "for evidence: the node ('#42') and the folder to write to");
    exportCmd->add_option("--db", exportDb, "database directory")->required()->check(CLI::ExistingDirectory);
    exportCmd->add_option("--scene", exportScene, "scene name (default: the most recent)");
    exportCmd->add_option("-o,--output", exportOut, "output file (default: standard output)");
    bool exportPoints = false;
    exportCmd->add_flag("--points", exportPoints,
                        "with ply: the capture's coloured points instead of the boxes (docs/formats.md)");

    auto* test = app.add_subcommand("test", "run declarative query suites (*.smqlt)");
    std::vector<std::string> testFiles;
    test->add_option("files", testFiles, "suite files")->required()->check(CLI::ExistingFile);

    auto* checkDbCmd = app.add_subcommand("check",
                                          "verify a database: records and their checksums, scene trees, "
                                          "indexes, lock file; exit status 1 when anything is wrong");
    std::string checkDbDir;
    checkDbCmd->add_option("database", checkDbDir, "database directory")->required()->check(CLI::ExistingDirectory);
    std::string salvageInto;
    checkDbCmd->add_option("--salvage", salvageInto,
                           "copy every scene that verifies into this new database (docs/storage.md, \"Recovery\")");

    auto* eval = app.add_subcommand("eval", "score a memory on an evaluation suite (docs/eval.md)");
    smql::shell::EvalOptions evalOptions;
    eval->add_option("suite", evalOptions.suite,
                     "the suite (eval-suite.json, as smql synth writes it); without one, the scene is its own "
                     "truth and the suite is generated from it")
        ->check(CLI::ExistingFile);
    eval->add_option("--db", evalOptions.db, "the database holding the memory")
        ->required()
        ->check(CLI::ExistingDirectory);
    eval->add_option("--scene", evalOptions.scene,
                     "the memory's scene (default: the suite's scene name, else the database's only scene)");
    eval->add_option("--json", evalOptions.jsonOut, "also write the metrics to this JSON file");
    eval->add_option("--write-suite", evalOptions.writeSuite,
                     "write the generated suite and its truth (eval-suite.json, truth.json) into this folder");

    if (auto status = smql::shell::parseArguments(app, argc, argv)) return *status;
    if (eval->parsed()) return smql::shell::evalCommand(evalOptions);
    if (checkDbCmd->parsed()) return smql::shell::checkCommand(checkDbDir, salvageInto);
    if (import->parsed())
        return smql::shell::importCommand(importFormat, importFile, importDb, importScene, importUpdate, importAll);
    if (exportCmd->parsed() && exportFormat == "evidence") {
        if (exportEvidence.size() != 2)
            throw smql::Error(smql::ErrorKind::Usage, "export evidence takes a node and a folder", std::nullopt,
                              "smql export evidence '#42' evidence/ --db DB");
        return smql::shell::exportEvidenceCommand(exportDb, exportEvidence[0], exportEvidence[1]);
    }
    if (exportCmd->parsed())
        return smql::shell::exportCommand(exportFormat, exportDb, exportScene, exportOut, exportPoints);
    return smql::shell::testCommand(testFiles);
}

}  // namespace

int main(int argc, char** argv) {
    return smql::shell::runReportingErrors([&] {
        std::string first = argc > 1 ? argv[1] : "";
        const auto runs = subcommand(first);
        if (runs == Runs::Ingest) return runTool("smql-ingest", argv);
        if (runs == Runs::Fleet || first.rfind("postgresql://", 0) == 0 || first.rfind("postgres://", 0) == 0)
            return runTool("smql-fleet", argv);
        if (runs == Runs::Here) return runSubcommand(argc, argv);
        return runShell(argc, argv);
    });
}
