// The ingest module, libsmql_ingest.so: what smql_ingest needs of OpenCV, PCL and COLMAP, in a
// library of its own that libsmql.so loads (dlopen) on the first smql_ingest. A program that only
// queries never loads the ~250 libraries the ingest stands on, as the shell hands its capture
// commands to smql-ingest for the same reason.
//
// Internal to the C API: both libraries are built from this tree by one compiler, so the call
// passes our own C++ types. No exception crosses between them; errors travel in the call.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "model/error.hpp"
#include "model/types.hpp"
#include "smql.h"

namespace smql::capi {

struct IngestCall {
    // In.
    std::string capture;
    std::string options;  // a JSON object of ingest options (ingest::ingestOptions), "" for none
    // Each event of the ingest's progress; returns true to stop it.
    std::function<bool(const smql_progress&)> progress;
    const std::atomic<bool>* interrupted = nullptr;  // smql_interrupt on the handle

    // Out of smql_ingest_module_read: the request, checked.
    std::string sceneName;  // the scene the capture becomes
    std::string update;     // or the stored scene whose next version it becomes

    // Out of smql_ingest_module_run: the scene to store.
    model::SceneData scene;
    std::size_t frames = 0;

    std::optional<Error> error;  // set when a step failed; the step's other outputs are then unset
};

// smql_check_ingest: a stored scene against a synthetic capture's truth, or alone.
struct CheckCall {
    model::SceneData stored;  // in
    std::string truth;        // in: the truth.json path; "" for the plausibility checks alone
    std::vector<std::pair<std::string, double>> figures;  // out
    std::vector<std::string> warnings;  // out, without a truth: the things flagged, by `stored`'s ids (objectWarning)
    std::optional<Error> error;
};

// The module's entry points (extern "C" names, so that dlsym finds them).
using IngestStep = void (*)(IngestCall& call) noexcept;
using CheckStep = void (*)(CheckCall& call) noexcept;
inline constexpr const char* kIngestModuleFile = "libsmql_ingest.so";
inline constexpr const char* kReadEntry = "smql_ingest_module_read";  // options -> the request
inline constexpr const char* kRunEntry = "smql_ingest_module_run";    // the request -> the scene
inline constexpr const char* kCheckEntry = "smql_ingest_module_check";

}  // namespace smql::capi
