// libsmql_fleet.so (fleet_module.hpp): smql_push's and smql_pull's talk with the fleet store, and
// the statements of a handle on a store.
#include "fleet_module.hpp"

#include "fleet/fleet.hpp"
#include "fleet/query.hpp"

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

extern "C" SMQL_API void smql_fleet_module_session(smql::capi::SessionCall& call) noexcept {
    smql::capi::guarded(call, "the fleet store's work", smql::ErrorKind::Storage, [&] {
        if (call.close) {
            delete call.session;
            call.session = nullptr;
            return;
        }
        if (!call.session) call.session = new smql::fleet::StoreSession(call.url, "");
        call.results.clear();
        if (!call.statements.empty())
            call.session->execute(call.statements,
                                  [&](smql::ResultSet&& rs) { call.results.push_back(std::move(rs)); });
    });
}
