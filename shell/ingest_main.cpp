// `smql-ingest`: the capture commands of `smql` (ingest, check-ingest, synth, demo). They need OpenCV
// and PCL, whose ~250 shared libraries would otherwise load on every query; `smql` executes this
// program, installed next to it, when one of these commands is asked for, passing its argv as is.
#include <iostream>

#include "ingest/pipeline/request.hpp"
#include "model/error.hpp"
#include "shell/cli.hpp"
#include "shell/ingest_command.hpp"
#include "shell/map_command.hpp"
#include "view/view.hpp"

namespace {

int run(int argc, char** argv) {
    CLI::App app{"smql capture commands: ingest, check-ingest, synth, demo"};
    app.name("smql");
    app.require_subcommand(1);

    auto* ingestCmd =
        app.add_subcommand("ingest", "turn a capture (RGB-D folder, TUM, nerfstudio, COLMAP ...) into a new scene");
    smql::shell::IngestArguments ingestArgs;
    bool ingestQuiet = false;
    ingestCmd->add_option("capture", ingestArgs.request.capture, "capture folder or file")
        ->required()
        ->check(CLI::ExistingPath);
    ingestCmd->add_option("--db", ingestArgs.db, "database directory (created if missing)")->required();
    // The options smql_ingest and Python's smql.ingest take too, from their one table.
    for (const auto& option : smql::ingest::ingestOptions()) {
        const std::string flag = smql::ingest::optionFlag(option.name);
        if (option.valueName.empty())
            ingestCmd->add_flag_function(
                flag, [&ingestArgs, &option](std::int64_t) { option.set(ingestArgs.request, "true"); }, option.help());
        else
            ingestCmd
                ->add_option_function<std::string>(
                    flag, [&ingestArgs, &option](const std::string& value) { option.set(ingestArgs.request, value); },
                    option.help())
                ->type_name(std::string(option.valueName));
    }
    ingestCmd->add_flag("--quiet", ingestQuiet, "print nothing but errors");
    ingestCmd->add_option("--log", ingestArgs.log, "progress as a bar (default), json lines, or quiet")
        ->check(CLI::IsMember({"bar", "json", "quiet"}));

    auto* check = app.add_subcommand("check-ingest",
                                     "check an ingested scene: does it look like a room (cameras, ceiling, sizes), and "
                                     "with --truth, how close it is to a synthetic capture's truth");
    std::string checkDb, checkTruth, checkScene, checkFormat = "table";
    bool checkMisses = false;
    check->add_option("database", checkDb, "database directory")->required()->check(CLI::ExistingDirectory);
    check->add_option("--truth", checkTruth, "truth.json of the capture (smql synth writes it)")
        ->check(CLI::ExistingFile);
    check->add_option("--scene", checkScene, "scene name (default: the most recent)");
    check->add_option("--format", checkFormat, "table or json")->check(CLI::IsMember({"table", "json"}));
    check->add_flag("--misses", checkMisses,
                    "also list the objects without a match: truth objects missed and ingested objects the truth lacks");

    auto* demo = app.add_subcommand("demo", "build a sample memory of a generated room and query it");
    std::string demoDb;
    demo->add_option("--db", demoDb, "the database to build: a new or empty folder (default: a new folder under /tmp)");

    auto* synth = app.add_subcommand("synth", "write a synthetic RGB-D capture of a generated room, with ground truth");
    std::string synthOut;
    std::uint64_t synthSeed = 1;
    int synthFrames = 60, synthObjects = 24;
    bool synthForce = false, synthChanges = false, synthRgbOnly = false;
    synth->add_option("--out", synthOut, "output folder (refused when not empty, unless --force)")->required();
    synth->add_option("--seed", synthSeed, "room and walk seed (default 1)");
    synth->add_option("--frames", synthFrames, "frames along the walk (default 60)")->check(CLI::Range(1, 100000));
    synth->add_option("--objects", synthObjects, "objects in the room (default 24)")->check(CLI::Range(1, 5000));
    synth->add_flag("--force", synthForce, "write into a non-empty folder, replacing an earlier capture's files");
    synth->add_flag("--changes", synthChanges,
                    "the same room and walk after a few small things moved, went and appeared (changes.json lists "
                    "them): a second capture for `smql ingest --update`");
    synth->add_flag("--rgb-only", synthRgbOnly,
                    "only what a plain camera gives: the colour frames as photos in OUT/images (with camera.json and "
                    "a perfect detector's detections.json), no depth, masks or poses");

    auto* map = app.add_subcommand("map", "draw a scene from above: anchors, objects and the guidance graph (PNG)");
    std::string mapDb, mapScene, mapOut;
    map->add_option("database", mapDb, "the database directory")->required();
    map->add_option("--scene", mapScene, "the scene (default: the most recently stored)");
    map->add_option("--out", mapOut, "the file to write: map.png or map.svg")->required();
    smql::view::MapOptions mapOptions;
    map->add_flag("--fixtures", mapOptions.fixtures,
                  "draw ceiling and wall fixtures too (lights, switches, plugs, pictures; left out by default)");
    map->add_flag("--graph", mapOptions.graph, "draw guidance's decision-point graph too");

    auto* guide = app.add_subcommand("guide", "a route in steps, written as JSON, Markdown and a PNG map");
    std::string guideDb, guideScene, guideFrom, guideTo, guideOut;
    guide->add_option("database", guideDb, "the database directory")->required();
    guide->add_option("--scene", guideScene, "the scene (default: the most recently stored)");
    guide->add_option("--from", guideFrom, "where to start: a reference (door, '#12'), here, or (x, y)")->required();
    guide->add_option("--to", guideTo, "where to go: a reference or a sub-query, (FIND mug LIMIT 1)")->required();
    guide->add_option("--out", guideOut, "the folder for guide.json, guide.md and guide.png")->required();

    auto* view =
        app.add_subcommand("view", "look at the memory in a browser: a local, read-only web page (docs/view.md)");
    smql::view::ViewOptions viewOptions;
    view->add_option("database", viewOptions.database, "the database directory")
        ->required()
        ->check(CLI::ExistingDirectory);
    view->add_option("--host", viewOptions.host, "the address to listen on (default 127.0.0.1: this machine only)");
    view->add_option("--port", viewOptions.port, "the port (default 8080; 0: any free one)")
        ->check(CLI::Range(0, 65535));
    view->add_option("--scene", viewOptions.scene, "the scene the page opens on (default: the most recently stored)");
    view->add_option("--timeout", viewOptions.statementMilliseconds,
                     "a statement running longer than this many milliseconds is interrupted (default 5000)")
        ->check(CLI::PositiveNumber);

    if (auto status = smql::shell::parseArguments(app, argc, argv)) return *status;
    if (view->parsed()) {
        smql::view::serve(viewOptions, [&](const std::string& url) {
            std::cout << "smql view: serving " << viewOptions.database << " read-only at " << url << " (Ctrl-C stops)"
                      << std::endl;
            if (viewOptions.host != "127.0.0.1" && viewOptions.host != "localhost")
                std::cerr << "warning: --host " << viewOptions.host
                          << " lets other machines run statements on this database\n";
        });
        return 0;
    }
    if (map->parsed()) return smql::shell::mapCommand(mapDb, mapScene, mapOut, mapOptions);
    if (guide->parsed()) return smql::shell::guideCommand(guideDb, guideScene, guideFrom, guideTo, guideOut);
    if (ingestCmd->parsed()) {
        if (ingestQuiet) ingestArgs.log = "quiet";
        return smql::shell::ingestCommand(ingestArgs);
    }
    if (check->parsed())
        return smql::shell::checkIngestCommand(checkDb, checkTruth, checkScene, checkFormat, checkMisses);
    if (demo->parsed()) return smql::shell::demoCommand(demoDb);
    return smql::shell::synthCommand({.seed = synthSeed,
                                      .frames = synthFrames,
                                      .objects = synthObjects,
                                      .force = synthForce,
                                      .changes = synthChanges,
                                      .rgbOnly = synthRgbOnly},
                                     synthOut);
}

}  // namespace

int main(int argc, char** argv) {
    return smql::shell::runReportingErrors([&] { return run(argc, argv); });
}
