#pragma once

#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include "engine/engine.hpp"
#include "engine/format.hpp"
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

// Everything a statement answers, or the error as the shell shows it, as one text.
inline std::string outcome(Engine& engine, const std::string& text) {
    try {
        std::string out;
        for (const ResultSet& rs : engine.execute(text)) out += formatCsv(rs) + "|" + rs.message + "\n";
        return out;
    } catch (const Error& e) {
        return "error: " + e.render(text);
    }
}

// The category column (the second) of a FIND's rows.
inline std::vector<std::string> categories(const ResultSet& rs) {
    std::vector<std::string> out;
    for (const auto& row : rs.rows) out.push_back(std::get<std::string>(row[1]));
    return out;
}

// The last column of SIMILAR TO's rows: the similarity.
inline std::vector<double> similarities(const ResultSet& rs) {
    std::vector<double> out;
    for (const auto& row : rs.rows) out.push_back(std::get<double>(row.back()));
    return out;
}

}  // namespace smql::testing
