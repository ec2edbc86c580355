// One call into a module libsmql.so loads (the ingest, the fleet store): no exception crosses
// between the libraries, so whatever the module's work throws becomes the call's error.
#pragma once

#include <exception>
#include <new>
#include <string>

#include "model/error.hpp"

namespace smql::capi {

// Runs `step`; an exception becomes `call.error`: ours as it is, out-of-memory as a storage error,
// any other as `failure` naming `work` ("the ingest failed: ...").
template <class Call, class Step>
void guarded(Call& call, const char* work, ErrorKind failure, Step&& step) noexcept {
    try {
        step();
    } catch (const Error& e) {
        call.error = e;
    } catch (const std::bad_alloc&) {
        call.error = Error(ErrorKind::Storage, std::string("out of memory during ") + work);
    } catch (const std::exception& e) {
        call.error = Error(failure, std::string(work) + " failed: " + e.what());
    } catch (...) {
        call.error = Error(failure, std::string(work) + " failed with an unknown exception");
    }
}

}  // namespace smql::capi
