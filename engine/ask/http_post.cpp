#include "engine/ask/http_post.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <vector>

#include <fmt/format.h>

namespace smql::ask {

namespace {

struct Module {
    HttpPostEntry post = nullptr;
    std::string failure;  // why it could not be loaded
};

// The module, once per process: beside the program or library that holds this code (its installed
// place), in the build tree it was built in, in the installed library folder, then by name.
const Module& module() {
    static const Module loaded = [] {
        std::vector<std::filesystem::path> places;
        if (const char* dir = std::getenv("SMQL_MODULE_DIR"))
            places.push_back(std::filesystem::path(dir) / kHttpModuleFile);
        Dl_info self{};
        if (dladdr(reinterpret_cast<void*>(&httpPost), &self) && self.dli_fname)
            places.push_back(std::filesystem::path(self.dli_fname).parent_path() / kHttpModuleFile);
#ifdef SMQL_HTTP_MODULE_BUILT
        places.emplace_back(SMQL_HTTP_MODULE_BUILT);
#endif
#ifdef SMQL_INSTALL_LIBDIR
        places.push_back(std::filesystem::path(SMQL_INSTALL_LIBDIR) / kHttpModuleFile);
#endif
        places.emplace_back(kHttpModuleFile);
        Module out;
        std::string tried;
        for (const auto& place : places) {
            if (place.has_parent_path() && !std::filesystem::exists(place)) continue;
            void* handle = dlopen(place.c_str(), RTLD_NOW | RTLD_LOCAL);
            if (!handle) {
                const char* why = dlerror();
                tried += fmt::format("{}{}: {}", tried.empty() ? "" : "; ", place.string(), why ? why : "not loaded");
                continue;
            }
            out.post = reinterpret_cast<HttpPostEntry>(dlsym(handle, kHttpPostEntry));
            if (out.post) return out;
            tried += fmt::format("{}{}: not smql's HTTP module", tried.empty() ? "" : "; ", place.string());
        }
        out.failure = fmt::format("cannot load {} ({})", kHttpModuleFile, tried.empty() ? "not found" : tried);
        return out;
    }();
    return loaded;
}

}  // namespace

HttpReply httpPost(const std::string& origin, const std::string& path, const std::string& body, double timeoutSeconds) {
    const Module& m = module();
    if (!m.post) return {std::nullopt, m.failure};
    char* response = nullptr;
    char* error = nullptr;
    int status = m.post(origin.c_str(), path.c_str(), body.c_str(), timeoutSeconds, &response, &error);
    HttpReply out;
    if (status == 0 && response)
        out.body = std::string(response);
    else
        out.error = error ? error : "no reply";
    std::free(response);
    std::free(error);
    return out;
}

}  // namespace smql::ask
