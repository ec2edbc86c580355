// The query suites (tests/suites/*.smqlt, docs/testing.md) as tests other than `smql test` read
// them: their `load` lines and the SMQL of each block, for tests that run every statement of the
// suites another way (the cache of statement shapes, the fleet store) and compare with the engine.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "engine/engine.hpp"

namespace smql::testing {

struct SuiteBlock {
    std::vector<std::string> load;  // the words after `load`, or empty for SMQL
    std::string text;
};

// Every suite of tests/suites, in name order.
std::vector<std::filesystem::path> querySuites();

std::vector<SuiteBlock> readSuite(const std::filesystem::path& file);

// Imports what a `load` line names (paths relative to the suite's folder) and returns the scene's
// name; the scene's capture time is fixed, so two engines' scenes record the same times.
std::string loadSuiteData(Engine& engine, const std::vector<std::string>& words, const std::filesystem::path& suiteDir);

}  // namespace smql::testing
