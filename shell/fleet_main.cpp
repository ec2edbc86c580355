// `smql-fleet`: the commands of `smql` that talk to a fleet store in PostgreSQL (fleet init, push,
// pull, and statements on the store, `smql URL -c '...'`; docs/fleet.md). libpq and the TLS and
// Kerberos libraries it loads would add milliseconds to every query's start-up, so `smql` executes
// this program, installed next to it, for them.
#include <iostream>

#include <fmt/format.h>

#include "fleet/fleet.hpp"
#include "fleet/query.hpp"
#include "fleet/shards.hpp"
#include "model/error.hpp"
#include "shell/cli.hpp"
#include "shell/output.hpp"
#include "storage/database.hpp"

namespace {

int run(int argc, char** argv) {
    CLI::App app{"smql fleet commands: fleet init, push, pull (docs/fleet.md)"};
    app.name("smql");
    app.require_subcommand(1);

    auto* fleetCmd = app.add_subcommand("fleet", "manage a fleet store in PostgreSQL + PostGIS");
    fleetCmd->require_subcommand(1);
    auto* init = fleetCmd->add_subcommand("init", "create the store's schema in a database, or bring it up to date");
    std::string initUrl;
    init->add_option("url", initUrl, "the database: postgresql://USER@HOST:PORT/DATABASE")->required();
    std::vector<std::string> initShards;
    init->add_option("--shard", initShards,
                     "a shard's database (repeatable): URL becomes the coordinator of a store sharded by scene "
                     "over them (docs/fleet.md, \"Shards\")");

    auto* push = app.add_subcommand("push", "send every scene version the fleet store lacks, each in one transaction");
    std::string pushDb, pushUrl;
    push->add_option("database", pushDb, "the local database directory")->required()->check(CLI::ExistingDirectory);
    push->add_option("url", pushUrl, "the fleet store: postgresql://USER@HOST:PORT/DATABASE")->required();

    auto* pull = app.add_subcommand("pull", "bring a scene from the fleet store into a local database");
    std::string pullUrl, pullDb;
    smql::fleet::PullRequest request;
    pull->add_option("url", pullUrl, "the fleet store: postgresql://USER@HOST:PORT/DATABASE")->required();
    pull->add_option("database", pullDb, "the local database directory (created if missing)")->required();
    pull->add_option("--scene", request.scene, "the scene's name")->required();
    pull->add_option("--device", request.device, "whose scene it is: the device's id, or its start");
    pull->add_option("--version", request.version, "which version (default: the newest)")->check(CLI::PositiveNumber);

    if (auto status = smql::shell::parseArguments(app, argc, argv)) return *status;
    if (init->parsed()) {
        auto report = initShards.empty() ? smql::fleet::init(initUrl) : smql::fleet::initSharded(initUrl, initShards);
        std::cout << (report.before == report.after
                          ? fmt::format("the fleet store is at schema version {}; nothing to do\n", report.after)
                          : fmt::format("created the fleet store's schema: version {} (was {})\n", report.after,
                                        report.before));
        if (!report.predicates)
            std::cout << "note: SMQL statements will not run on this store: " << report.predicatesMissing
                      << " (push and pull work; docs/fleet.md, \"SMQL on the store\")\n";
        return 0;
    }
    if (push->parsed()) {
        auto database = smql::storage::Database::open(pushDb, {.create = false});
        std::cout << smql::fleet::push(*database, pushUrl).summary() << "\n";
        return 0;
    }
    auto database = smql::storage::Database::open(pullDb);
    auto pulled = smql::fleet::pull(pullUrl, request, *database);
    std::cout << fmt::format("pulled version {} of scene '{}' (device {}, {} nodes) into {}\n", pulled.version.version,
                             request.scene, pulled.device, pulled.version.data.nodes.size(), pullDb);
    return 0;
}

// `smql URL [-c] 'STATEMENTS'`: statements run by the store's server (docs/fleet.md, "SMQL on the store").
int runStatements(int argc, char** argv) {
    CLI::App app{"smql URL: statements on a fleet store (COUNT and FIND in one scene so far; docs/fleet.md)"};
    app.name("smql");
    std::string url, command, device, mode = "table";
    std::vector<std::string> statements;
    app.add_option("url", url, "the fleet store: postgresql://USER@HOST:PORT/DATABASE")->required();
    app.add_option("statements", statements, "statements to run (as -c)");
    app.add_option("-c,--command", command, "run these statements: USE SCENE 'name' first");
    app.add_option("--device", device, "whose scenes USE SCENE picks: the device's id, or its start");
    const std::vector<std::string> modes = {"table", "box", "markdown", "csv", "tsv", "list", "line"};
    app.add_option("--format,--mode", mode, "output mode (default table)")->check(CLI::IsMember(modes));
    for (const std::string& name : modes)
        app.add_flag_callback(
            "--" + name, [&mode, name] { mode = name; }, "same as --format " + name);
    if (auto status = smql::shell::parseArguments(app, argc, argv)) return *status;
    if (!command.empty()) statements.insert(statements.begin(), command);
    if (statements.empty())
        throw smql::Error(smql::ErrorKind::Usage, "no statement for the fleet store", std::nullopt,
                          "smql URL -c \"USE SCENE 'kitchen'; COUNT chair\"");
    smql::shell::OutputOptions output;
    output.mode = smql::shell::parseOutputMode(mode);
    smql::fleet::StoreSession session(url, device);
    for (const std::string& text : statements)
        session.execute(text,
                        [&](smql::ResultSet&& result) { std::cout << smql::shell::renderResult(result, output); });
    return 0;
}

bool isUrl(const char* argument) {
    std::string_view a = argument;
    return a.rfind("postgresql://", 0) == 0 || a.rfind("postgres://", 0) == 0;
}

}  // namespace

int main(int argc, char** argv) {
    return smql::shell::runReportingErrors(
        [&] { return argc > 1 && isUrl(argv[1]) ? runStatements(argc, argv) : run(argc, argv); });
}
