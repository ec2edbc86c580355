// The map's layout (view/map.hpp) on the Replica room and on real rooms of ScanNet and ARKitScenes
// (../shared/data/real-layouts, every tenth): a legend, a scale bar, every drawn thing named (by
// its label or by a number in the key), no two labels overlapping, fixtures left out unless asked.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <regex>

#include "engine/engine.hpp"
#include "ingest/import/importers.hpp"
#include "view/map.hpp"

using namespace smql;

namespace {

struct TempDir {
    std::filesystem::path path;
    TempDir() {
        path = std::filesystem::temp_directory_path() / ("smql-map-" + std::to_string(::getpid()));
        std::filesystem::remove_all(path);
    }
    ~TempDir() { std::filesystem::remove_all(path); }
};

const std::string kData = SMQL_SHARED_DATA;

// Every pair of labels apart; every label inside the picture; returns how many things are named.
std::size_t checkLabels(const view::MapPlan& plan) {
    std::size_t named = 0;
    for (std::size_t i = 0; i < plan.labels.size(); ++i) {
        const auto& a = plan.labels[i].box;
        INFO(plan.scene << ": label '" << plan.labels[i].text << "'");
        CHECK(a.left >= 0);
        CHECK(a.top >= 0);
        CHECK(a.left + a.width <= plan.width);
        CHECK(a.top + a.height <= plan.height);
        for (std::size_t j = i + 1; j < plan.labels.size(); ++j) {
            INFO("overlaps '" << plan.labels[j].text << "'");
            CHECK_FALSE(a.overlaps(plan.labels[j].box));
        }
        named += plan.labels[i].text.find('#') != std::string::npos || plan.labels[i].marker;
    }
    return named;
}

}  // namespace

TEST_CASE("the Replica room's map has a legend, a scale bar and labels that do not overlap", "[map]") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    engine->importScene(import::readReplica(kData + "/replica-room0/info_semantic.json", "replica-room0"));
    auto map = engine->sceneMap("replica-room0");

    const auto plan = view::planMap(map, {}, {});
    CHECK(plan.legend.size() > 10);
    for (const char* entry : {"wall", "door", "window", "sofa", "cushion"}) {
        INFO(entry);
        CHECK(std::any_of(plan.legend.begin(), plan.legend.end(), [&](const auto& e) { return e.text == entry; }));
    }
    CHECK(plan.scale.pixels > 0);
    CHECK(std::regex_match(plan.scale.text, std::regex(R"(\d+ (m|cm))")));
    // The legend is beside the drawing, not over it.
    for (const auto& label : plan.labels) CHECK_FALSE(label.box.overlaps(plan.legendBox));

    // Every drawn object is named once: by a label, or by a number whose key line names it.
    std::size_t objects = 0;
    for (const auto& n : map.scene.nodes)
        objects += n.kind == model::NodeKind::Object && !n.hidden && n.geometry != model::GeometryKind::None;
    CHECK(checkLabels(plan) == objects - plan.fixturesLeftOut);
    for (const auto& line : plan.key) CHECK(std::regex_match(line, std::regex(R"(\d+  [a-z-]+#\d+)")));

    // Ceiling lights and what hangs on the walls are left out unless asked for.
    CHECK(plan.fixturesLeftOut > 0);
    const auto all = view::planMap(map, {}, {.fixtures = true});
    CHECK(all.fixturesLeftOut == 0);
    CHECK(checkLabels(all) == objects);
    CHECK(std::none_of(plan.labels.begin(), plan.labels.end(), [](const auto& l) {
        return l.text.rfind("wall-plug#", 0) == 0 || l.text.rfind("picture#", 0) == 0;
    }));

    // A route's steps are numbered, and the labels keep clear of them.
    const auto steps = engine->execute("GUIDE FROM door TO sofa#50").back();
    std::vector<view::RouteMark> route;
    for (const auto& row : steps.rows)
        route.push_back({std::get<std::int64_t>(row[steps.columnIndex("step")]),
                         std::get<double>(row[steps.columnIndex("x")]), std::get<double>(row[steps.columnIndex("y")])});
    const auto guided = view::planMap(map, route, {});
    CHECK(std::count_if(guided.labels.begin(), guided.labels.end(), [](const auto& l) {
              return l.marker && l.text.size() <= 2;
          }) >= static_cast<long>(route.size()));
    checkLabels(guided);

    const std::string svg = view::renderSvg(plan);
    CHECK(svg.rfind("<svg", 0) == 0);
    CHECK(svg.find(">Legend</text>") != std::string::npos);
    CHECK(svg.find(">" + plan.scale.text + "</text>") != std::string::npos);
}

TEST_CASE("maps of real rooms keep their labels apart", "[map]") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    std::size_t rooms = 0;
    for (const char* file : {"scannet_meta_info_val.json", "arkitscenes_meta_info_val.json"}) {
        const std::string path = kData + "/real-layouts/" + file;
        auto all = import::readVsiBenchAll(path);
        for (std::size_t i = 0; i < all.size(); i += 10) {
            engine->importScene(all[i]);
            const auto plan = view::planMap(engine->sceneMap(all[i].info.name), {}, {});
            checkLabels(plan);
            CHECK(plan.scale.pixels > 0);
            ++rooms;
        }
    }
    CHECK(rooms >= 20);
}
