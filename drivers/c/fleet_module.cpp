// libsmql_fleet.so (fleet_module.hpp): smql_push's and smql_pull's talk with the fleet store.
#include "fleet_module.hpp"

#include "fleet/fleet.hpp"

#include <new>

#include "smql.h"

namespace smql::capi {

namespace {

template <class Call, class Step>
void guarded(Call& call, Step&& step) noexcept {
    try {
        step();
    } catch (const Error& e) {
        call.error = e;
    } catch (const std::bad_alloc&) {
        call.error = Error(ErrorKind::Storage, "out of memory talking to the fleet store");
    } catch (const std::exception& e) {
        call.error = Error(ErrorKind::Storage, std::string("the fleet store's work failed: ") + e.what());
    } catch (...) {
        call.error = Error(ErrorKind::Storage, "the fleet store's work failed with an unknown exception");
    }
}

}  // namespace

}  // namespace smql::capi

extern "C" SMQL_API void smql_fleet_module_push(smql::capi::PushCall& call) noexcept {
    smql::capi::guarded(call, [&] { call.report = smql::fleet::push(*call.local, call.url); });
}

extern "C" SMQL_API void smql_fleet_module_fetch(smql::capi::FetchCall& call) noexcept {
    smql::capi::guarded(call, [&] { call.pulled = smql::fleet::fetch(call.url, call.request); });
}
