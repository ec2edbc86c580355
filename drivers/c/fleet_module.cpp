// libsmql_fleet.so (fleet_module.hpp): smql_push's and smql_pull's talk with the fleet store.
#include "fleet_module.hpp"

#include "fleet/fleet.hpp"

#include "module_call.hpp"
#include "smql.h"

extern "C" SMQL_API void smql_fleet_module_push(smql::capi::PushCall& call) noexcept {
    smql::capi::guarded(call, "the fleet store's work", smql::ErrorKind::Storage,
                        [&] { call.report = smql::fleet::push(*call.local, call.url); });
}

extern "C" SMQL_API void smql_fleet_module_fetch(smql::capi::FetchCall& call) noexcept {
    smql::capi::guarded(call, "the fleet store's work", smql::ErrorKind::Storage,
                        [&] { call.pulled = smql::fleet::fetch(call.url, call.request); });
}
