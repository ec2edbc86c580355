#include "ingest/import/registry.hpp"

#include <fmt/format.h>

#include "ingest/import/importers.hpp"
#include "model/error.hpp"
#include "model/names.hpp"

namespace smql::import {

namespace {

// One row per format; its reader is in <format>.cpp.
constexpr ImportFormat kFormats[] = {
    {"replica", "Replica's info_semantic.json", readReplica},
    {"spatiallm", "a SpatialLM layout text", readSpatialLm},
    {"json", "the smql JSON scene format (smql export json)", readSceneJson},
    {"vsibench", "VSI-Bench's meta-info JSON of ScanNet or ARKitScenes rooms", readVsiBench, vsiBenchRooms},
};

}  // namespace

std::span<const ImportFormat> formats() { return kFormats; }

std::vector<std::string> formatNames() {
    std::vector<std::string> out;
    for (const auto& f : kFormats) out.emplace_back(f.name);
    return out;
}

const ImportFormat* findFormat(std::string_view name) {
    for (const auto& f : kFormats)
        if (f.name == name) return &f;
    return nullptr;
}

model::SceneData read(std::string_view format, const std::string& path, const std::string& sceneName) {
    const ImportFormat* f = findFormat(format);
    if (!f) {
        auto names = formatNames();
        auto close = model::nearestNames(std::string(format), names);
        throw Error(ErrorKind::Usage, fmt::format("unknown import format '{}'", format), std::nullopt,
                    close.empty() ? "formats: " + model::joinAlternatives(names)
                                  : "did you mean " + model::joinAlternatives(close) + "?");
    }
    return f->read(path, sceneName);
}

}  // namespace smql::import
