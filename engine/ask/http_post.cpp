#include "engine/ask/http_post.hpp"

#include <cstdlib>

#include "model/module.hpp"

namespace smql::ask {

namespace {

// The module, once per process: its entry, or why it could not be loaded.
struct HttpModule {
    HttpPostEntry post = nullptr;
    std::string failure;
};

const HttpModule& module() {
    static const HttpModule loaded = [] {
        const Module opened =
            openModule(kHttpModuleFile, reinterpret_cast<void*>(&httpPost), SMQL_HTTP_MODULE_BUILT, kHttpPostEntry);
        return HttpModule{reinterpret_cast<HttpPostEntry>(opened.entry), opened.failure};
    }();
    return loaded;
}

}  // namespace

HttpReply httpPost(const std::string& origin, const std::string& path, const std::string& body, double timeoutSeconds) {
    const HttpModule& m = module();
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
