#include "query_suites.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "ingest/generate/room_generator.hpp"
#include "ingest/import/registry.hpp"

namespace fs = std::filesystem;

namespace smql::testing {

std::vector<fs::path> querySuites() {
    std::vector<fs::path> out;
    for (const auto& entry : fs::directory_iterator(fs::path(SMQL_SOURCE_DIR) / "tests" / "suites"))
        if (entry.path().extension() == ".smqlt") out.push_back(entry.path());
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<SuiteBlock> readSuite(const fs::path& file) {
    std::ifstream in(file);
    std::vector<SuiteBlock> blocks;
    bool inBlock = false, inExpected = false;
    for (std::string line; std::getline(in, line);) {
        const bool blank = line.find_first_not_of(" \t\r") == std::string::npos;
        if (inBlock && blank) inBlock = inExpected = false;
        if (blank) continue;
        if (!inBlock) {
            if (line[0] == '#') continue;
            std::istringstream words(line);
            std::vector<std::string> all;
            for (std::string w; words >> w;) all.push_back(w);
            if (all[0] == "load") blocks.push_back({{all.begin() + 1, all.end()}, {}});
            if (all[0] == "load") continue;
            blocks.push_back({});
            inBlock = true;
        } else if (line == "----") {
            inExpected = true;
        } else if (!inExpected) {
            blocks.back().text += (blocks.back().text.empty() ? "" : "\n") + line;
        }
    }
    return blocks;
}

std::string loadSuiteData(Engine& engine, const std::vector<std::string>& words, const fs::path& suiteDir) {
    auto option = [&](const std::string& key, const std::string& fallback) {
        auto it = std::find(words.begin(), words.end(), key);
        return it != words.end() && it + 1 != words.end() ? *(it + 1) : fallback;
    };
    model::SceneData scene = words.at(0) == "demo"
                                 ? generate::generateRoom({.seed = std::stoull(option("seed", "7")),
                                                           .objectCount = std::stoi(option("objects", "36")),
                                                           .name = option("scene", "demo-room")})
                                 : import::read(words.at(0), (suiteDir / words.at(1)).string(), option("scene", ""));
    scene.info.captureTime = "2026-01-01T00:00:00Z";
    std::string name = scene.info.name;
    engine.importScene(std::move(scene));
    return name;
}

}  // namespace smql::testing
