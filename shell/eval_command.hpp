// `smql eval SUITE --db DIR`: scores a memory with the research system's metrics on a suite of
// episodes whose answers come from a truth scene (docs/eval.md).
#pragma once

#include <string>

namespace smql::shell {

// Prints the metrics as a Markdown table; `jsonOut` (when given) gets them as JSON.
int evalCommand(const std::string& suitePath, const std::string& dbDir, const std::string& scene,
                const std::string& jsonOut);

}  // namespace smql::shell
