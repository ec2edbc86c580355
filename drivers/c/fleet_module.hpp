// The fleet module, libsmql_fleet.so: what smql_push, smql_pull and a handle smql_open made of a
// postgresql:// URL need of libpq (and the TLS and
// Kerberos libraries it loads), in a library of its own that libsmql.so loads (dlopen) on the
// first of those calls, as it loads the ingest module: a program that never talks to a fleet store
// never loads them. libsmql.so reads and writes its database itself (fleet/local); the module
// talks to the server.
//
// Internal to the C API: both libraries are built from this tree by one compiler, so the call
// passes our own C++ types. No exception crosses between them; errors travel in the call.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "fleet/local/local_scenes.hpp"
#include "model/error.hpp"
#include "model/result.hpp"

namespace smql::fleet {
class StoreSession;
}

namespace smql::capi {

struct PushCall {
    std::string url;                            // in
    const fleet::LocalSource* local = nullptr;  // in: its `read` throws std::exception only (smql_c.cpp)
    fleet::PushReport report;                   // out
    std::optional<Error> error;
};

struct FetchCall {
    std::string url;             // in
    fleet::PullRequest request;  // in
    fleet::Pulled pulled;        // out
    std::optional<Error> error;
};

// A handle on a fleet store (smql_open of a postgresql:// URL): the first call connects (a null
// `session` and the URL), each later call runs `statements` in it, the last (`close`) ends it.
struct SessionCall {
    std::string url;                         // in, to connect
    fleet::StoreSession* session = nullptr;  // in/out: the module's, owned through these calls
    std::string statements;                  // in: empty to connect or to close
    bool close = false;                      // in
    std::vector<ResultSet> results;          // out
    std::optional<Error> error;
};

using PushStep = void (*)(PushCall& call) noexcept;
using SessionStep = void (*)(SessionCall& call) noexcept;
using FetchStep = void (*)(FetchCall& call) noexcept;
inline constexpr const char* kFleetModuleFile = "libsmql_fleet.so";
inline constexpr const char* kPushEntry = "smql_fleet_module_push";
inline constexpr const char* kFetchEntry = "smql_fleet_module_fetch";
inline constexpr const char* kSessionEntry = "smql_fleet_module_session";

}  // namespace smql::capi
