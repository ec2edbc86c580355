#include "model/module.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <vector>

#include <fmt/format.h>

namespace smql {

Module openModule(const char* file, const void* anchor, const char* built, const char* entry) {
    std::vector<std::filesystem::path> candidates;
    if (const char* dir = std::getenv("SMQL_MODULE_DIR")) candidates.push_back(std::filesystem::path(dir) / file);
    Dl_info self{};
    if (dladdr(anchor, &self) && self.dli_fname)
        candidates.push_back(std::filesystem::path(self.dli_fname).parent_path() / file);
    if (built) candidates.emplace_back(built);
#ifdef SMQL_INSTALL_LIBDIR
    candidates.push_back(std::filesystem::path(SMQL_INSTALL_LIBDIR) / file);
#endif
    candidates.emplace_back(file);
    Module out;
    std::string tried;
    for (const auto& place : candidates) {
        if (place.has_parent_path() && !std::filesystem::exists(place)) continue;
        void* handle = dlopen(place.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            const char* why = dlerror();
            tried += fmt::format("{}{}: {}", tried.empty() ? "" : "; ", place.string(), why ? why : "not loaded");
            continue;
        }
        out.entry = dlsym(handle, entry);
        if (out.entry) return out;
        tried += fmt::format("{}{}: not smql's {}", tried.empty() ? "" : "; ", place.string(), file);
    }
    out.failure = fmt::format("cannot load {} ({})", file, tried.empty() ? "not found" : tried);
    return out;
}

}  // namespace smql
