#include "shell/commands.hpp"

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <fmt/format.h>
#include <unistd.h>

#include "engine/engine.hpp"
#include "engine/format.hpp"
#include "ingest/import/importers.hpp"
#include "ingest/import/registry.hpp"
#include "model/error.hpp"
#include "model/utf8.hpp"
#include "shell/output_file.hpp"
#include "storage/output_guard.hpp"
#include "view/view.hpp"

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
                  const std::string& sceneName, const std::string& update, bool all) {
    auto start = std::chrono::steady_clock::now();
    // Read and validate every scene before the database is touched.
    std::vector<model::SceneData> scenes;
    if (all) {
        const import::SceneFormat* f = import::findFormat(format);
        if (!f->readAll)
            throw Error(ErrorKind::Usage, fmt::format("--all: a {} file holds one scene", format), std::nullopt,
                        "import it without --all");
        scenes = f->readAll(file);
    } else {
        scenes.push_back(import::read(format, file, sceneName));
    }
    auto engine = Engine::open(dbDir);
    std::string report;
    if (!update.empty()) {
        const auto updated = engine->updateScene(update, scenes.front());
        report = updated.summary() + "\n";
        if (const auto warning = updated.warning()) std::cerr << "warning: " << *warning << "\n";
    } else {
        for (const model::SceneData& scene : scenes) {
            engine->importScene(scene);
            report += fmt::format("imported scene '{}' ({}) into {} in {:.1f} ms\n", scene.info.name, summary(scene),
                                  dbDir, millisecondsSince(start));
        }
    }
    // The work is done and stored: a report that cannot be written (a full disk, /dev/full) is said,
    // not an exit status that would tell a script the import failed.
    std::cout << report << std::flush;
    if (!std::cout) {
        std::cerr << fmt::format("note: stored; the report could not be written to standard output: {}",
                                 std::strerror(errno))
                  << std::endl;
        std::cout.clear();
    }
    return 0;
}

int exportCommand(const std::string& format, const std::string& dbDir, const std::string& sceneName,
                  const std::string& outFile, bool points) {
    if (points && format != "ply")
        throw Error(ErrorKind::Usage, fmt::format("--points is an export of the ply format, not of {}", format),
                    std::nullopt, "smql export ply --points --db DB -o points.ply");
    // Bytes on a terminal are noise and can leave it in a strange state (sqlite3 refuses likewise).
    const import::SceneFormat* written = import::findFormat(format);
    if (outFile.empty() && written && written->binary && isatty(STDOUT_FILENO))
        throw Error(ErrorKind::Usage, fmt::format("a {} file is binary: it is not written to a terminal", format),
                    std::nullopt,
                    fmt::format("give -o FILE, or redirect: smql export {} --db DB > scene.{}", format, format));
    auto engine = Engine::open(dbDir, /*readOnly=*/true);
    std::string bytes = points ? engine->scenePoints(sceneName)
                        : format == "html"
                            ? view::standalonePage(*engine, sceneName)
                            : import::write(format, import::writesFileIds(format) ? engine->exportScene(sceneName)
                                                                                  : engine->readScene(sceneName));
    if (outFile.empty()) {
        std::cout << bytes;
        checkWritten(std::cout, "standard output");
        return 0;
    }
    storage::refuseDatabaseFile(outFile, dbDir);
    std::ofstream out(outFile, std::ios::binary);
    out << bytes;
    checkWritten(out, outFile);
    std::cerr << fmt::format("exported scene to {}\n", outFile);
    return 0;
}

int exportEvidenceCommand(const std::string& dbDir, const std::string& node, const std::string& outDir) {
    std::string digits = node.rfind('#', 0) == 0 ? node.substr(1) : node;
    model::NodeId id = 0;
    try {
        id = std::stoull(digits);
    } catch (const std::exception&) {
        throw Error(ErrorKind::Usage, fmt::format("'{}' is not a node id", node), std::nullopt,
                    "smql export evidence '#42' DIR --db DB");
    }
    auto engine = Engine::open(dbDir, /*readOnly=*/true);
    auto blobs = engine->evidence(id);
    if (blobs.empty())
        throw Error(ErrorKind::Binding, fmt::format("node #{} has no evidence", id), std::nullopt,
                    "evidence comes from ingested captures; DESCRIBE #id lists it");
    fs::create_directories(outDir);
    // A blob's name comes from data (an imported scene, a pulled one): it names a file in outDir and
    // nothing else, whatever separators or `..` it holds.
    for (std::size_t k = 0; k < blobs.size(); ++k) {
        const auto& blob = blobs[k];
        const std::string name = storage::safeFileName(blob.name, fmt::format("evidence-{}", k + 1));
        if (name != blob.name)
            std::cerr << fmt::format("note: the blob name '{}' is no file name in {}: written as '{}'\n",
                                     model::escapeInvalidUtf8(blob.name), outDir, name);
        const fs::path path = fs::path(outDir) / name;
        storage::refuseDatabaseFile(path, dbDir);
        std::ofstream out(path, std::ios::binary);
        out << blob.bytes;
        checkWritten(out, path.string());
        std::cout << path.string() << "\n";
    }
    return 0;
}

}  // namespace smql::shell
