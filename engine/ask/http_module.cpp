// libsmql_http.so: the POST of http_post.hpp, through cpp-httplib. Loaded by smql_ask on the first
// question a model translator is asked, so the query shell starts without OpenSSL and its kin.
#include <cstdlib>
#include <cstring>
#include <string>

#include <httplib.h>

namespace {

char* copied(const std::string& text) {
    char* out = static_cast<char*>(std::malloc(text.size() + 1));
    if (out) std::memcpy(out, text.c_str(), text.size() + 1);
    return out;
}

}  // namespace

extern "C" __attribute__((visibility("default"))) int smql_http_post(const char* origin, const char* path,
                                                                     const char* body, double timeoutSeconds,
                                                                     char** response, char** error) {
    *response = nullptr;
    *error = nullptr;
    try {
        httplib::Client client(origin);
        const auto seconds = static_cast<time_t>(timeoutSeconds);
        const auto micros = static_cast<time_t>((timeoutSeconds - static_cast<double>(seconds)) * 1e6);
        client.set_connection_timeout(seconds, micros);
        client.set_read_timeout(seconds, micros);
        client.set_write_timeout(seconds, micros);
        auto result = client.Post(path, body, "application/json");
        if (!result) {
            *error = copied(httplib::to_string(result.error()));
            return 1;
        }
        if (result->status != 200) {
            *error = copied("HTTP status " + std::to_string(result->status) + ": " + result->body.substr(0, 200));
            return 2;
        }
        *response = copied(result->body);
        return 0;
    } catch (const std::exception& e) {
        *error = copied(e.what());
        return 3;
    }
}
