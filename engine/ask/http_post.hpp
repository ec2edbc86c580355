// The one HTTP call ASK's model translator makes (a POST of JSON to an OpenAI-compatible endpoint),
// in a module of its own, libsmql_http.so, loaded (dlopen) on the first question a model
// translates: cpp-httplib, as Debian builds it, brings OpenSSL, zlib and Brotli, which a program
// that only queries never loads. The module's entry is C, so nothing of C++ crosses.
#pragma once

#include <optional>
#include <string>

namespace smql::ask {

// The entry the module exports: POST `body` (JSON) to `origin` (`http://host:port`) at `path`,
// waiting at most `timeoutSeconds`. Returns 0 with *response (malloc'd) holding the reply's body,
// else non-zero with *error (malloc'd) saying why (no connection, a status other than 200).
extern "C" typedef int (*HttpPostEntry)(const char* origin, const char* path, const char* body, double timeoutSeconds,
                                        char** response, char** error);
inline constexpr const char* kHttpPostEntry = "smql_http_post";
inline constexpr const char* kHttpModuleFile = "libsmql_http.so";

struct HttpReply {
    std::optional<std::string> body;  // the reply's body, or nothing
    std::string error;                // why there is none
};

// The module's POST; an error reply when the module cannot be loaded (it names where it looked).
HttpReply httpPost(const std::string& origin, const std::string& path, const std::string& body, double timeoutSeconds);

}  // namespace smql::ask
