#include "bench/data_set.hpp"

#include <optional>

#include <fmt/format.h>
#include <fmt/ostream.h>

#include "bench/postgis_baseline.hpp"
#include "bench/sqlite_baseline.hpp"
#include "bench/stats.hpp"
#include "engine/engine.hpp"
#include "ingest/generate/room_generator.hpp"
#include "relations/hierarchy.hpp"
#include "storage/database.hpp"

namespace smql::bench {

namespace {

// Timing the tree derivation twice per scene would double the import phase;
// a few scenes show its share.
constexpr int kTreeSampleScenes = 3;

}  // namespace

std::string sceneName(int index) { return fmt::format("room_{}", index); }

DataSet buildDataSet(const DataSetSpec& spec, const std::filesystem::path& directory, PostgresServer* postgres,
                     std::ostream& progress) {
    DataSet out;
    out.spec = spec;
    out.smqlDirectory = directory / "smql";
    out.sqliteFile = directory / "baseline.sqlite";
    std::filesystem::create_directories(directory);

    auto engine = Engine::open(out.smqlDirectory.string());
    SqliteBaseline sqlite(out.sqliteFile.string(), true);
    std::unique_ptr<PostgisBaseline> postgis;
    if (postgres) {
        postgres->createDatabase(spec.label);
        out.postgisConnection = postgres->connectionString(spec.label);
        postgis = std::make_unique<PostgisBaseline>(out.postgisConnection, true);
        postgis->beginLoad();
    }
    const int step = std::max(1, spec.scenes / 10);
    auto started = Clock::now();
    for (int i = 0; i < spec.scenes; ++i) {
        auto scene = generate::generateRoom({static_cast<std::uint64_t>(i), spec.objectsPerScene, sceneName(i)});
        std::optional<model::SceneData> copy;
        if (i < kTreeSampleScenes) copy = scene;

        auto t = Clock::now();
        model::NodeId sceneId = engine->importScene(std::move(scene));
        double seconds = microsecondsSince(t) / 1e6;
        out.import.smqlSeconds += seconds;
        if (copy) {
            out.import.treeScenesImportSeconds += seconds;
            t = Clock::now();
            relations::assignParents(*copy, relations::Thresholds{});
            out.import.treeSeconds += microsecondsSince(t) / 1e6;
        }

        // SQLite stores what smql stored (ids, parents, boxes), so answers compare by id.
        std::vector<model::Node> nodes;
        model::SceneInfo info;
        {
            auto txn = engine->database().beginRead();
            info = txn.scene(sceneId).value();
            nodes.reserve(info.nodeCount + 1);
            txn.forEachNodeInScene(sceneId, [&](const model::Node& n) {
                if (n.kind != model::NodeKind::Scene) nodes.push_back(n);
                if (n.kind == model::NodeKind::Object) ++out.objects;
            });
        }
        out.nodes += nodes.size();
        t = Clock::now();
        sqlite.importScene(info, nodes);
        out.import.sqliteSeconds += microsecondsSince(t) / 1e6;
        if (postgis) {
            t = Clock::now();
            postgis->addScene(info, nodes);
            out.import.postgisSeconds += microsecondsSince(t) / 1e6;
        }

        if ((i + 1) % step == 0 || i + 1 == spec.scenes) {
            fmt::print(progress, "  {}: {}/{} scenes imported ({:.0f} s)\n", spec.label, i + 1, spec.scenes,
                       microsecondsSince(started) / 1e6);
            progress.flush();
        }
    }
    sqlite.checkpoint();
    if (postgis) {
        auto t = Clock::now();
        postgis->endLoad();
        out.import.postgisSeconds += microsecondsSince(t) / 1e6;
        out.postgisBytes = postgis->databaseBytes();
        fmt::print(progress, "  {}: PostGIS loaded and indexed ({:.0f} s)\n", spec.label, out.import.postgisSeconds);
    }
    out.smqlBytes = engine->database().fileSizeBytes();
    out.sqliteBytes = std::filesystem::file_size(out.sqliteFile);
    return out;
}

}  // namespace smql::bench
