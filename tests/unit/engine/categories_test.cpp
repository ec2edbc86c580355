// One canonical name per category (model/category.hpp), whoever wrote it: the same real room
// imported through `import vsibench` and through the smql JSON format with spaced names answers
// the same; a database written before names were canonical still answers by any spelling.
#include <fstream>
#include <regex>
#include <sstream>

#include <fmt/format.h>
#include <catch2/catch.hpp>

#include "engine_support.hpp"
#include "ingest/import/importers.hpp"
#include "ingest/import/registry.hpp"
#include "model/category.hpp"
#include "relations/hierarchy.hpp"
#include "relations/thresholds.hpp"
#include "storage/database.hpp"

using namespace smql;
using smql::testing::run;
using smql::testing::TempDir;

namespace {

const std::string kLayouts = std::string(SMQL_SHARED_DATA) + "/real-layouts/scannet_meta_info_val.json";
// An office of VSI-Bench's validation rooms: monitors, keyboards, a computer mouse, two trash bins.
const std::string kRoom = "scene0591_01";

// The room as the smql JSON format writes it, its two-word categories spelt with spaces and
// capitals ("Trash Bin", "computer mouse"), as a person or another tool writes them.
std::string spacedJson() {
    std::string json = import::write("json", import::readVsiBench(kLayouts, kRoom));
    json = std::regex_replace(json, std::regex(R"("category": "trash-bin")"), R"("category": "Trash Bin")");
    json = std::regex_replace(json, std::regex(R"("category": "computer-mouse")"), R"("category": "computer mouse")");
    json = std::regex_replace(json, std::regex(R"("category": "monitor")"), R"("category": "Monitors")");
    REQUIRE(json.find("Trash Bin") != std::string::npos);
    REQUIRE(json.find("computer mouse") != std::string::npos);
    return json;
}

std::string valueText(const Value& v) {
    if (const auto* i = std::get_if<std::int64_t>(&v)) return std::to_string(*i);
    if (const auto* d = std::get_if<double>(&v)) return fmt::format("{:.4f}", *d);
    if (const auto* t = std::get_if<std::string>(&v)) return *t;
    if (const auto* b = std::get_if<model::Box>(&v))
        return fmt::format("({:.3f} {:.3f} {:.3f})", b->center.x, b->center.y, b->center.z);
    return "null";
}

// Every answer an ASK gives, messages and rows, as text.
std::string answers(Engine& engine, const std::vector<std::string>& questions) {
    std::string out;
    for (const auto& q : questions) {
        out += q + "\n";
        try {
            ResultSet rs = run(engine, "ASK '" + q + "'");
            out += rs.message + "\n";
            for (const auto& row : rs.rows)
                for (const auto& v : row) out += fmt::format("{} ", valueText(v));
        } catch (const Error& e) {
            out += "error: " + e.message();
        }
        out += "\n";
    }
    return out;
}

const std::vector<std::string> kQuestions = {
    "How many trash bin(s) are in this room?",
    "how many trash bins are there?",
    "is there a trash can?",
    "where is the computer mouse?",
    "what is the distance between the computer mouse and the trash bin (in meters)?",
    "What is the length of the longest dimension (length, width, or height) of the trash bin, measured in "
    "centimeters?",
    "what is the length of the longest dimension of the computer mouse (cm)?",
    "which of these objects (trash bin, computer mouse, sofa, door) is the closest to the monitor?",
    "If I am standing by the sofa and facing the door, is the trash bin to my left or right?",
    "how many monitors are in here?",
    "what is the biggest thing in here?",
    "what is near the computer mouse?",
};

}  // namespace

TEST_CASE("a room imported from vsibench and from JSON with spaced names answers the same", "[categories]") {
    TempDir fromVsiBench, fromJson, files;
    auto a = Engine::open(fromVsiBench.path.string());
    a->importScene(import::read("vsibench", kLayouts, kRoom));
    const std::string json = (files.path / "room.json").string();
    std::ofstream(json) << spacedJson();
    auto b = Engine::open(fromJson.path.string());
    b->importScene(import::read("json", json, kRoom));

    CHECK(a->knownCategories() == b->knownCategories());
    CHECK(run(*a, "SHOW CATEGORIES").rows == run(*b, "SHOW CATEGORIES").rows);
    const std::string viaVsiBench = answers(*a, kQuestions), viaJson = answers(*b, kQuestions);
    CHECK(viaVsiBench == viaJson);
    // And the answers are answers: the reader found the things by their two-word names.
    CHECK(viaJson.find("trash-bin") != std::string::npos);
    CHECK(viaJson.find("computer-mouse") != std::string::npos);
    CHECK(viaJson.find("door-cm") == std::string::npos);
    CHECK(viaJson.find("error") == std::string::npos);
}

TEST_CASE("a category is found however it is written", "[categories]") {
    TempDir dir, files;
    const std::string json = (files.path / "room.json").string();
    std::ofstream(json) << spacedJson();
    auto engine = Engine::open(dir.path.string());
    engine->importScene(import::read("json", json, kRoom));
    for (const char* name : {"trash-bin", "trash_bin", "'trash bin'", "'Trash Bins'", "trash-bins", "TRASH_BIN"})
        CHECK(std::get<std::int64_t>(run(*engine, fmt::format("COUNT {}", name)).rows.at(0).at(0)) == 2);
    CHECK(run(*engine, "FIND thing WHERE category = 'Trash Bin'").rows.size() == 2);
    CHECK(!run(*engine, "FIND object WHERE near('computer mouse', 2 m) AND NOT category = 'trash bins'").rows.empty());
    CHECK(testing::categories(run(*engine, "FIND 'Computer Mice'")) == std::vector<std::string>{"computer-mouse"});
    run(*engine, "USE SCENE '*'");
    CHECK(std::get<std::int64_t>(run(*engine, "COUNT 'trash bin'").rows.at(0).at(0)) == 2);
}

TEST_CASE("a database stored before names were canonical still answers by any spelling", "[categories]") {
    TempDir dir;
    {
        // What an earlier smql stored from a JSON file with spaced names: the names as written.
        model::SceneData scene = import::readVsiBench(kLayouts, kRoom);
        for (auto& node : scene.nodes) {
            if (node.category == "trash-bin") node.category = "trash bin";
            if (node.category == "computer-mouse") node.category = "Computer Mouse";
        }
        relations::assignParents(scene, relations::Thresholds{});
        auto db = storage::Database::open(dir.path.string());
        auto txn = db->beginWrite();
        txn.importScene(scene);
        txn.commit();
    }
    auto engine = Engine::open(dir.path.string());
    run(*engine, fmt::format("USE SCENE '{}'", kRoom));
    CHECK(std::get<std::int64_t>(run(*engine, "COUNT trash-bin").rows.at(0).at(0)) == 2);
    CHECK(std::get<std::int64_t>(run(*engine, "COUNT 'Trash Bins'").rows.at(0).at(0)) == 2);
    CHECK(testing::categories(run(*engine, "FIND computer-mouse")) == std::vector<std::string>{"computer-mouse"});
    CHECK(run(*engine, "FIND thing WHERE category = 'trash-bin'").rows.size() == 2);
    CHECK(run(*engine, "ASK 'how many trash bins are there?'").message.find("2 trash") != std::string::npos);
    const auto known = engine->knownCategories();
    CHECK(std::count(known.begin(), known.end(), "trash-bin") == 1);
    CHECK(std::count(known.begin(), known.end(), "trash bin") == 0);
    run(*engine, "USE SCENE '*'");
    CHECK(std::get<std::int64_t>(run(*engine, "COUNT trash_bin").rows.at(0).at(0)) == 2);
    CHECK(run(*engine, "FIND 'computer mouse'").rows.size() == 1);
    auto all = run(*engine, "SHOW CATEGORIES");
    std::size_t bins = 0;
    for (const auto& row : all.rows) bins += std::get<std::string>(row.at(1)) == "trash-bin";
    CHECK(bins == 1);
}
