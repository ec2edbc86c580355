// The scene file formats, one table: what `smql import FORMAT`, the query-suite runner's `load
// FORMAT`, the C API's smql_import_file and `smql export FORMAT` accept. A format is a reader
// and/or a writer (their own files, declared in importers.hpp) and one row in registry.cpp;
// everything that lists or dispatches formats reads the table.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "model/types.hpp"

namespace smql::import {

struct SceneFormat {
    std::string_view name;         // as typed: `smql import replica ...`, `smql export json`
    std::string_view description;  // for --help and error hints
    // Reads the whole file into a scene named `sceneName`, or by the format's rule when it is
    // empty; null for formats smql only writes.
    model::SceneData (*read)(const std::string& path, const std::string& sceneName);
    // The scene as the file's bytes; null for formats smql only reads.
    std::string (*write)(const model::SceneData& scene);
    // Every scene a file holds, each under its name, in one read of the file, for formats whose
    // files hold several (`read` then takes one by its name); null for formats of one scene a file.
    std::vector<model::SceneData> (*readAll)(const std::string& path) = nullptr;
    // The writer is given the scene in its file form, ids renumbered 1..n (Engine::exportScene), as
    // the smql JSON format keeps them for reading back; others get the database's ids
    // (Engine::readScene), so that names and paths in the file are the ones queries print.
    bool fileIds = false;
    // The file is bytes, not text: written to a terminal only when asked for.
    bool binary = false;
};

std::span<const SceneFormat> formats();
// The names of the formats smql reads (imports), and of those it writes (exports).
std::vector<std::string> readableFormats();
std::vector<std::string> writableFormats();
// Null when no format has that name.
const SceneFormat* findFormat(std::string_view name);

// Reads `path` as `format` into a scene named `sceneName`, or the format's default name when it is
// empty. Throws smql::Error: Usage for an unknown format (naming the known ones), Input for a bad file.
model::SceneData read(std::string_view format, const std::string& path, const std::string& sceneName = {});
// The scene in `format`. Throws smql::Error(Usage) for a format smql does not write.
std::string write(std::string_view format, const model::SceneData& scene);
// Whether `format`'s writer takes the scene in its file form (SceneFormat::fileIds).
bool writesFileIds(std::string_view format);

}  // namespace smql::import
