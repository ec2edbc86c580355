// The import formats, one table: what `smql import FORMAT`, the query-suite
// runner's `load FORMAT` and the C API's smql_import_file accept. A format is
// a reader (its own file, declared in importers.hpp) and one row in
// registry.cpp; everything that lists or dispatches formats reads the table.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "model/types.hpp"

namespace smql::import {

struct ImportFormat {
    std::string_view name;         // as typed: `smql import replica ...`
    std::string_view description;  // for --help and error hints
    // Reads the whole file into a scene named `sceneName`, or by the format's rule when it is empty.
    model::SceneData (*read)(const std::string& path, const std::string& sceneName);
    // The scenes a file holds, for formats whose files hold several (`read` then takes one by its
    // name); null for formats of one scene a file.
    std::vector<std::string> (*scenes)(const std::string& path) = nullptr;
};

std::span<const ImportFormat> formats();
std::vector<std::string> formatNames();
// Null when no format has that name.
const ImportFormat* findFormat(std::string_view name);

// Reads `path` as `format` into a scene named `sceneName`, or the format's default name when it is
// empty. Throws smql::Error: Usage for an unknown format (naming the known ones), Input for a bad file.
model::SceneData read(std::string_view format, const std::string& path, const std::string& sceneName = {});

}  // namespace smql::import
