// The page's files, built into the program (embed_assets.cmake writes assets.cpp at build time
// from view/page and three.js's npm package): the server reads no file but the database.
#pragma once

#include <span>
#include <string_view>

namespace smql::view {

struct Asset {
    std::string_view path;       // as requested: "/", "/assets/view.js", "/assets/three.module.min.js"
    std::string_view mediaType;  // text/html, text/javascript ...: every file is UTF-8 text
    std::string_view bytes;
};

std::span<const Asset> assets();
// Null when there is none.
const Asset* findAsset(std::string_view path);

}  // namespace smql::view
