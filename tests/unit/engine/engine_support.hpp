#pragma once

#include <filesystem>
#include <string>

#include "engine/engine.hpp"
#include "model/error.hpp"

namespace smql::testing {

// A fresh database directory, removed when the test ends.
struct TempDir {
    std::filesystem::path path;
    TempDir() {
        std::string pattern = (std::filesystem::temp_directory_path() / "smql-engine-test-XXXXXX").string();
        path = mkdtemp(pattern.data());
    }
    ~TempDir() { std::filesystem::remove_all(path); }
};

inline std::string replicaRoom0() { return std::string(SMQL_SHARED_DATA) + "/replica-room0/info_semantic.json"; }
inline std::string replicaRelations() { return std::string(SMQL_SHARED_DATA) + "/replica-room0/relationships.json"; }

inline ResultSet run(Engine& engine, const std::string& statement) {
    auto results = engine.execute(statement);
    return results.back();
}

}  // namespace smql::testing
