#include "ingest/import/registry.hpp"

#include <fmt/format.h>

#include "ingest/import/importers.hpp"
#include "model/category.hpp"
#include "model/error.hpp"
#include "model/names.hpp"

namespace smql::import {

namespace {

// One row per format; its reader and writer are in <format>.cpp.
constexpr SceneFormat kFormats[] = {
    {"replica", "Replica's info_semantic.json", readReplica, nullptr},
    {"spatiallm", "a SpatialLM layout text", readSpatialLm, nullptr},
    {"json", "the smql JSON scene format", readSceneJson,
     [](const model::SceneData& scene) { return writeSceneJson(scene) + "\n"; }, nullptr, true},
    {"vsibench", "VSI-Bench's meta-info JSON of ScanNet or ARKitScenes rooms", readVsiBench, nullptr, readVsiBenchAll},
    {"spark-dsg", "Hydra's Spark-DSG scene graph JSON", readSparkDsg, writeSparkDsg},
    {"glb", "glTF 2.0 binary: the boxes as meshes coloured by category", nullptr, writeGlb, nullptr, false, true},
    {"gltf", "glTF 2.0 JSON with the buffer embedded", nullptr, writeGltf},
    {"ply", "PLY (binary): the boxes as a triangle mesh with colours", nullptr, writePly, nullptr, false, true},
    {"geojson", "GeoJSON floor plan: the boxes' footprints in metres", nullptr, writeGeoJson},
};

std::vector<std::string> namesWhere(bool (*has)(const SceneFormat&)) {
    std::vector<std::string> out;
    for (const auto& f : kFormats)
        if (has(f)) out.emplace_back(f.name);
    return out;
}

// A format of `names` by its name, else Error(Usage) with the nearest of them.
const SceneFormat& known(std::string_view name, const std::vector<std::string>& names, std::string_view what) {
    const SceneFormat* f = findFormat(name);
    for (const auto& n : names)
        if (f && n == f->name) return *f;
    auto close = model::nearestNames(std::string(name), names);
    throw Error(ErrorKind::Usage, fmt::format("unknown {} format '{}'", what, name), std::nullopt,
                close.empty() ? "formats: " + model::joinAlternatives(names)
                              : "did you mean " + model::joinAlternatives(close) + "?");
}

}  // namespace

std::span<const SceneFormat> formats() { return kFormats; }

std::vector<std::string> readableFormats() {
    return namesWhere([](const SceneFormat& f) { return f.read != nullptr; });
}

std::vector<std::string> writableFormats() {
    return namesWhere([](const SceneFormat& f) { return f.write != nullptr; });
}

const SceneFormat* findFormat(std::string_view name) {
    for (const auto& f : kFormats)
        if (f.name == name) return &f;
    return nullptr;
}

model::SceneData read(std::string_view format, const std::string& path, const std::string& sceneName) {
    model::SceneData scene = known(format, readableFormats(), "import").read(path, sceneName);
    // Whatever a format writes ("Trash_Can", "trash cans"), its categories are stored by their one
    // canonical name (model/category.hpp), so a room answers the same however it was imported.
    model::canonicaliseCategories(scene);
    return scene;
}

bool writesFileIds(std::string_view format) {
    const SceneFormat* f = findFormat(format);
    return f && f->fileIds;
}

std::string write(std::string_view format, const model::SceneData& scene) {
    return known(format, writableFormats(), "export").write(scene);
}

}  // namespace smql::import
