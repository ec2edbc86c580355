// `smql eval [SUITE] --db DIR`: scores a memory with the research system's metrics on a suite of
// episodes whose answers come from a truth scene (docs/eval.md). Without a suite, the memory's
// scene is its own truth and the suite is generated from it (an imported real layout, say).
#pragma once

#include <string>

namespace smql::shell {

struct EvalOptions {
    std::string suite;       // the suite file; empty: generated from the scene
    std::string db;          // the database holding the memory
    std::string scene;       // the memory's scene; empty: the suite's, else the only or current one
    std::string jsonOut;     // also write the metrics here
    std::string writeSuite;  // write the generated suite and its truth into this folder
};

// Prints the metrics as a Markdown table; `jsonOut` (when given) gets them as JSON.
int evalCommand(const EvalOptions& options);

}  // namespace smql::shell
