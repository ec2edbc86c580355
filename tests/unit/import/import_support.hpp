// Helpers for the importer tests: temporary files and error assertions.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <string>

#include <catch2/catch.hpp>

#include "model/error.hpp"

namespace smql::import::test {

inline std::string replicaPath() { return std::string(SMQL_SHARED_DATA) + "/replica-room0/info_semantic.json"; }

// A fresh directory under the system temp dir, removed with everything in it.
class TempDir {
public:
    TempDir() {
        std::string pattern = (std::filesystem::temp_directory_path() / "smql-import-XXXXXX").string();
        if (!mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
        path_ = pattern;
    }
    ~TempDir() {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    std::string path(const std::string& name) const { return (path_ / name).string(); }
    std::string write(const std::string& name, const std::string& content) const {
        std::ofstream(path(name), std::ios::binary) << content;
        return path(name);
    }

private:
    std::filesystem::path path_;
};

// `read` must throw an Input error whose message contains every fragment
// (the file and the field or line), and, for text formats, the line number.
template <typename Read>
void requireInputError(Read&& read, std::initializer_list<std::string> fragments,
                       std::optional<int> line = std::nullopt) {
    try {
        read();
        FAIL("no error was thrown");
    } catch (const smql::Error& e) {
        INFO("message: " << e.message());
        CHECK(e.kind() == ErrorKind::Input);
        for (const std::string& fragment : fragments) CHECK_THAT(e.message(), Catch::Contains(fragment));
        if (line) {
            REQUIRE(e.where().has_value());
            CHECK(e.where()->line == *line);
        }
    }
}

}  // namespace smql::import::test
