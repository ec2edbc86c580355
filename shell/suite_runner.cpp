// `smql test`: declarative query suites in the spirit of sqllogictest.
// The format is documented in docs/testing.md.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <fmt/format.h>

#include "engine/engine.hpp"
#include "engine/format.hpp"
#include "ingest/generate/room_generator.hpp"
#include "ingest/import/registry.hpp"
#include "model/error.hpp"
#include "model/names.hpp"
#include "shell/commands.hpp"

namespace smql::shell {

namespace fs = std::filesystem;

namespace {

std::vector<std::string> splitWords(const std::string& line) {
    std::istringstream in(line);
    std::vector<std::string> words;
    for (std::string w; in >> w;) words.push_back(w);
    return words;
}

std::string cellText(const Value& v) { return typeOf(v) == ValueType::Null ? "NULL" : valueText(v); }

struct Block {
    int line = 0;
    std::string kind;               // statement | query | load
    std::vector<std::string> args;  // words after the kind
    std::string text;               // the SMQL
    std::vector<std::string> expected;
};

std::vector<Block> parseSuite(const std::string& path) {
    std::ifstream in(path);
    std::vector<Block> blocks;
    std::string line;
    int number = 0;
    Block* open = nullptr;
    bool inExpected = false;
    while (std::getline(in, line)) {
        ++number;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        bool blank = line.find_first_not_of(" \t") == std::string::npos;
        if (open && blank) {
            open = nullptr, inExpected = false;
            continue;
        }
        if (!open) {
            if (blank || line[0] == '#') continue;
            auto words = splitWords(line);
            if (words[0] != "statement" && words[0] != "query" && words[0] != "load")
                throw Error(
                    ErrorKind::Input,
                    fmt::format("{}:{}: expected 'statement', 'query' or 'load', got '{}'", path, number, words[0]),
                    SourceLocation{number, 1, static_cast<int>(words[0].size())});
            blocks.push_back({number, words[0], {words.begin() + 1, words.end()}, {}, {}});
            open = &blocks.back();
            if (open->kind == "load") open = nullptr;
            continue;
        }
        if (open->kind == "query" && line == "----") {
            inExpected = true;
        } else if (inExpected) {
            open->expected.push_back(line);
        } else {
            open->text += (open->text.empty() ? "" : "\n") + line;
        }
    }
    return blocks;
}

// A suite's scenes are captured at one fixed instant, so that what they record (first_seen_at,
// last_seen_at) and their answers do not change with the clock.
constexpr const char* kSuiteCaptureTime = "2026-01-01T00:00:00Z";

model::SceneData capturedAtSuiteTime(model::SceneData scene) {
    if (scene.info.captureTime.empty()) scene.info.captureTime = kSuiteCaptureTime;
    return scene;
}

void load(Engine& engine, const Block& block, const fs::path& suiteDir) {
    const auto& a = block.args;
    if (a.empty())
        throw Error(ErrorKind::Input,
                    fmt::format("load needs a source: {} or demo", model::joinAlternatives(import::readableFormats())));
    auto option = [&](const std::string& key, const std::string& fallback) {
        auto it = std::find(a.begin(), a.end(), key);
        return it != a.end() && it + 1 != a.end() ? *(it + 1) : fallback;
    };
    if (a[0] == "demo") {
        engine.importScene(
            capturedAtSuiteTime(generate::generateRoom({.seed = std::stoull(option("seed", "7")),
                                                        .objectCount = std::stoi(option("objects", "36")),
                                                        .name = option("scene", "demo-room")})));
        return;
    }
    if (a.size() < 2) throw Error(ErrorKind::Input, "load " + a[0] + " needs a file");
    std::string file = (suiteDir / a[1]).string();
    engine.importScene(capturedAtSuiteTime(import::read(a[0], file, option("scene", ""))));
}

// Runs one block; returns an empty string when it passed, else what went wrong.
std::string runBlock(Engine& engine, const Block& block) {
    if (block.kind == "statement") {
        bool wantError = !block.args.empty() && block.args[0] == "error";
        std::string wantText;
        for (std::size_t i = 1; i < block.args.size(); ++i) wantText += (i > 1 ? " " : "") + block.args[i];
        try {
            engine.execute(block.text);
            return wantError ? "expected an error, the statement succeeded" : "";
        } catch (const Error& e) {
            if (!wantError) return "unexpected error: " + e.render(block.text);
            std::string all = e.message() + " " + e.hint();
            if (!wantText.empty() && all.find(wantText) == std::string::npos)
                return fmt::format("error did not mention '{}': {}", wantText, e.render(block.text));
            return "";
        }
    }
    // query COLUMNS [rowsort]
    if (block.args.empty()) return "query needs the columns to compare, e.g. 'query category,source_id'";
    std::vector<std::string> columns;
    std::stringstream list(block.args[0]);
    for (std::string c; std::getline(list, c, ',');) columns.push_back(c);
    bool rowsort = std::find(block.args.begin(), block.args.end(), "rowsort") != block.args.end();
    std::vector<std::string> actual;
    try {
        auto results = engine.execute(block.text);
        if (results.empty()) return "the query returned no result set";
        const auto& rs = results.back();
        std::vector<int> index;
        for (const auto& c : columns) {
            int i = rs.columnIndex(c);
            if (i < 0) return fmt::format("no column '{}' in the result", c);
            index.push_back(i);
        }
        for (const auto& row : rs.rows) {
            std::string line;
            for (std::size_t k = 0; k < index.size(); ++k) line += (k ? "|" : "") + cellText(row[index[k]]);
            actual.push_back(line);
        }
    } catch (const Error& e) {
        return "unexpected error: " + e.render(block.text);
    }
    auto expected = block.expected;
    if (rowsort) std::sort(actual.begin(), actual.end()), std::sort(expected.begin(), expected.end());
    if (actual == expected) return "";
    std::string out = "result differs\n    expected:";
    for (const auto& l : expected) out += "\n      " + l;
    out += "\n    actual:";
    for (const auto& l : actual) out += "\n      " + l;
    return out;
}

}  // namespace

int testCommand(const std::vector<std::string>& files) {
    int passed = 0, failed = 0;
    for (const auto& file : files) {
        std::string pattern = (fs::temp_directory_path() / "smql-test-XXXXXX").string();
        if (!mkdtemp(pattern.data())) throw Error(ErrorKind::Usage, "cannot create a folder under /tmp");
        int filePassed = 0, fileFailed = 0;
        try {
            auto engine = Engine::open(pattern);
            auto blocks = parseSuite(file);
            // A suite that checks nothing would pass whatever the engine does.
            if (std::none_of(blocks.begin(), blocks.end(), [](const Block& b) { return b.kind != "load"; }))
                throw Error(ErrorKind::Input, "no statement or query block");
            for (const auto& block : blocks) {
                std::string problem;
                try {
                    if (block.kind == "load")
                        load(*engine, block, fs::path(file).parent_path());
                    else
                        problem = runBlock(*engine, block);
                } catch (const Error& e) {
                    problem = e.render();
                }
                if (block.kind == "load" && problem.empty()) continue;
                if (problem.empty()) {
                    ++filePassed;
                } else {
                    ++fileFailed;
                    std::cout << fmt::format("FAIL {}:{}: {}\n  {}\n", file, block.line, block.text, problem);
                }
            }
        } catch (const Error& e) {
            ++fileFailed;
            std::cout << fmt::format("FAIL {}: {}\n", file, e.render());
        }
        fs::remove_all(pattern);
        std::cout << fmt::format("{}: {} passed, {} failed\n", file, filePassed, fileFailed);
        passed += filePassed, failed += fileFailed;
    }
    std::cout << fmt::format("{} passed, {} failed\n", passed, failed);
    return failed == 0 ? 0 : 1;
}

}  // namespace smql::shell
