// Finding smql's modules (model/module.hpp): where it looked and why each place failed, named in the
// failure, so that a missing or damaged module is an error a user can act on.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "model/module.hpp"
#include "scoped_env.hpp"

TEST_CASE("module: a module found nowhere says so") {
    const int anchor = 0;
    const smql::Module opened = smql::openModule("libsmql_no_such_module.so", &anchor, nullptr, "smql_entry");
    CHECK(opened.entry == nullptr);
    CHECK_THAT(opened.failure, Catch::StartsWith("cannot load libsmql_no_such_module.so ("));
}

TEST_CASE("module: a damaged module is named with the loader's reason, and no entry is taken from it") {
    const auto dir = std::filesystem::temp_directory_path() / ("smql-module-test-" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    const auto file = dir / "libsmql_damaged.so";
    std::ofstream(file) << "not a shared library";
    const smql::testing::ScopedEnv moduleDir("SMQL_MODULE_DIR", dir.string());
    const int anchor = 0;
    const smql::Module opened = smql::openModule("libsmql_damaged.so", &anchor, nullptr, "smql_entry");
    CHECK(opened.entry == nullptr);
    CHECK_THAT(opened.failure, Catch::Contains(file.string() + ": "));
    std::filesystem::remove_all(dir);
}

TEST_CASE("module: a library without the entry is not taken for the module") {
    // libc is a shared library every program has loaded, and it exports no smql entry.
    const int anchor = 0;
    const smql::Module opened = smql::openModule("libc.so.6", &anchor, nullptr, "smql_no_such_entry");
    CHECK(opened.entry == nullptr);
    CHECK_THAT(opened.failure, Catch::Contains("libc.so.6: not smql's libc.so.6"));
}
