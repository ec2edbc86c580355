// The research system's metrics on a memory (docs/eval.md): relative position, guidance and
// object retrieval, scored against a truth scene by running the engine's own statements. `smql
// eval` prints them, smql_evaluate returns them as rows.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "model/types.hpp"

namespace smql {
class Engine;
}

namespace smql::eval {

struct EvalRequest {
    std::string suite;  // the suite file; empty: generated from the scene, which is its own truth
    std::string scene;  // the memory's scene; empty: the suite's, else the only or current one
};

struct Metric {
    std::string task;    // relative position | guidance | object retrieval
    std::string metric;  // Acc_rel, SR_nav, StepComp, SPL, SR_obj, ...
    double value = 0;
    std::size_t episodes = 0;
    double medianMicroseconds = 0;  // of the statements the task ran
};

struct EvalReport {
    std::string scene;  // the memory's scene that was scored
    std::vector<Metric> metrics;
    std::string suiteJson;   // the suite that was run (the generated one when none was given)
    model::SceneData truth;  // its truth, in the scene-file form (local ids)
};

// Reads the suite and its truth (or generates both from the scene), makes the scene current and
// scores it. Throws smql::Error(Input) for a file that is not a suite or names nodes its truth
// lacks, Error(Binding) for a scene the database does not hold.
EvalReport evaluate(Engine& engine, const EvalRequest& request);

}  // namespace smql::eval
