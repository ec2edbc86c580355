#include "fleet_support.hpp"

#include <cstdlib>

#include <fmt/format.h>

#include "fleet/pg/connection.hpp"
#include "ingest/generate/room_generator.hpp"
#include "ingest/import/importers.hpp"
#include "ingest/import/registry.hpp"
#include "model/embedding.hpp"

namespace smql::testing {

namespace fs = std::filesystem;

TempDir::TempDir() {
    std::string pattern = (fs::temp_directory_path() / "smql-fleet-test-XXXXXX").string();
    path = mkdtemp(pattern.data());
}

TempDir::~TempDir() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
}

std::string freshStore(const std::string& name) {
    cluster().createDatabase(name);
    return cluster().url(name);
}

namespace {

const std::string kLayouts = std::string(SMQL_SHARED_DATA) + "/real-layouts/";

// A generated room whose objects carry stored embeddings (8 numbers, awkward ones included) and
// one an evidence crop whose bytes include every value COPY escapes.
model::SceneData generatedDen(const std::string& time, bool changed) {
    model::SceneData den = generate::generateRoom({.seed = 3, .objectCount = 20, .name = "den"});
    den.info.captureTime = time;
    if (changed) {
        for (auto& n : den.nodes)
            if (n.kind == model::NodeKind::Object) {
                n.box.center.x += 1.5;  // the first object moved
                break;
            }
        den.nodes.pop_back();  // the last one is gone
        return den;
    }
    for (const auto& n : den.nodes) {
        if (n.kind != model::NodeKind::Object) continue;
        const float f = static_cast<float>(n.id);
        den.blobs.push_back(model::embeddingBlob(
            n.id, std::vector<float>{f, 1.0f / 3.0f, -f / 7.0f, 1e-30f, 3.4e38f, 0.1f, -0.0f, 2.5f}));
    }
    // On an object the update sees again where it was (the first moved, the last went), so the
    // crop stays with the current version.
    const model::Node& kept = den.nodes[den.nodes.size() - 2];
    den.blobs.push_back({kept.id, "evidence-1.jpg", "image/jpeg", std::string("\xff\xd8\0\\\t\n\r\x7f end", 12)});
    return den;
}

}  // namespace

void buildRooms(Engine& engine) {
    engine.importScene(
        import::readReplica(std::string(SMQL_SHARED_DATA) + "/replica-room0/info_semantic.json", "replica-room0"));
    engine.importScene(import::readVsiBench(kLayouts + "scannet_meta_info_val.json", "scene0251_00"));
    engine.importScene(import::readVsiBench(kLayouts + "scannet_meta_info_val.json", "scene0277_02"));
    engine.importScene(import::readVsiBench(kLayouts + "arkitscenes_meta_info_val.json", "41069025"));
    engine.importScene(generatedDen("2026-11-20T10:00:00Z", false));
    engine.updateScene("den", generatedDen("2026-11-21T10:00:00Z", true));
}

void buildRealLayouts(Engine& engine) {
    for (const char* file : {"scannet_meta_info_val.json", "arkitscenes_meta_info_val.json"})
        for (const model::SceneData& room : import::readVsiBenchAll(kLayouts + file)) engine.importScene(room);
}

std::string exportedJson(Engine& engine, const std::string& scene) {
    return import::write("json", engine.exportScene(scene));
}

namespace {

long long single(const std::string& url, const std::string& sql) {
    fleet::pg::Connection c(url, "the test's store");
    return c.exec(sql, "checking the store").integer(0, 0);
}

}  // namespace

long long inconsistencies(const std::string& url) {
    return single(url, R"sql(
        SELECT (SELECT count(*) FROM smql.scenes s WHERE
                   node_count <> (SELECT count(*) FROM smql.nodes n WHERE n.scene = s.id)
                OR relation_count <> (SELECT count(*) FROM smql.relations r WHERE r.scene = s.id)
                OR blob_count <> (SELECT count(*) FROM smql.blobs b WHERE b.scene = s.id)
                                + (SELECT count(*) FROM smql.embeddings e WHERE e.scene = s.id)
                OR change_count <> (SELECT count(*) FROM smql.changes c WHERE c.scene = s.id))
             + (SELECT count(*) - count(DISTINCT (device, name, version)) FROM smql.scenes)
             + (SELECT count(*) FROM smql.nodes n WHERE NOT EXISTS (SELECT 1 FROM smql.scenes s WHERE s.id = n.scene))
    )sql");
}

long long storedVersions(const std::string& url, const std::string& device) {
    return single(url, device.empty() ? "SELECT count(*) FROM smql.scenes"
                                      : fmt::format("SELECT count(*) FROM smql.scenes WHERE device = {}",
                                                    fleet::pg::quoted(device)));
}

}  // namespace smql::testing
