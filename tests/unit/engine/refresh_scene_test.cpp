// Engine::refreshScene (`smql ingest --update`): concurrent refreshes of one
// scene never lose one another's counts.
#include <catch2/catch.hpp>

#include <chrono>
#include <thread>

#include "engine_support.hpp"

using namespace smql;
using namespace smql::testing;

namespace {

model::SceneData room() {
    model::SceneData data;
    data.info.name = "den";
    data.info.captureTime = "2026-01-01T00:00:00Z";
    model::Node floor;
    floor.id = 1;
    floor.kind = model::NodeKind::Anchor;
    floor.category = "floor";
    floor.geometry = model::GeometryKind::Plane;
    floor.box = {{0, 0, 0}, {6, 6, 0.02}, 0};
    data.nodes.push_back(floor);
    for (model::NodeId id : {2, 3}) {
        model::Node chair;
        chair.id = id;
        chair.kind = model::NodeKind::Object;
        chair.category = id == 2 ? "chair" : "table";
        chair.geometry = model::GeometryKind::Box;
        chair.box = {{double(id), 1, 0.45}, {0.5, 0.5, 0.9}, 0};
        chair.parent = 1;
        data.nodes.push_back(chair);
    }
    return data;
}

// Pairs objects by category. The pause widens the window between reading the
// stored counts and writing the new ones, where a second refresher would read
// the same counts if the two were separate transactions.
std::vector<std::pair<model::NodeId, model::NodeId>> byCategory(const model::SceneData& stored,
                                                                const model::SceneData& observed) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    std::vector<std::pair<model::NodeId, model::NodeId>> pairs;
    for (const auto& s : stored.nodes)
        for (const auto& o : observed.nodes)
            if (s.kind == model::NodeKind::Object && s.category == o.category) pairs.emplace_back(s.id, o.id);
    return pairs;
}

std::string attributeOf(Engine& engine, const std::string& category, const std::string& name) {
    for (const auto& n : engine.readScene("den").nodes)
        if (n.category == category)
            if (const std::string* value = n.attribute(name)) return *value;
    return "(unset)";
}

}  // namespace

TEST_CASE("refreshScene counts every capture and sets the last-seen time") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    engine->importScene(room());
    auto observed = room();
    observed.info.captureTime = "2026-02-02T00:00:00Z";
    observed.nodes.pop_back();  // the table is not seen this time

    auto refresh = engine->refreshScene("den", observed, byCategory);
    REQUIRE(refresh.seenAgain == 1);
    REQUIRE(refresh.storedObjects == 2);
    REQUIRE(attributeOf(*engine, "chair", "captures") == "2");
    REQUIRE(attributeOf(*engine, "chair", "last_seen_at") == "2026-02-02T00:00:00Z");
    REQUIRE(attributeOf(*engine, "table", "captures") == "(unset)");
    engine->refreshScene("den", observed, byCategory);
    REQUIRE(attributeOf(*engine, "chair", "captures") == "3");

    try {
        engine->refreshScene("attic", observed, byCategory);
        FAIL("refreshing a missing scene did not throw");
    } catch (const Error& e) {
        REQUIRE(e.kind() == ErrorKind::Binding);
        REQUIRE_THAT(e.message(), Catch::Contains("no scene named 'attic'"));
    }
}

TEST_CASE("two refreshes of one scene at once lose no update") {
    TempDir dir;
    Engine::open(dir.path.string())->importScene(room());
    auto observed = room();
    observed.info.captureTime = "2026-03-03T00:00:00Z";

    constexpr int kRounds = 15;
    auto refresher = [&] {
        // Each thread its own engine, as two `smql ingest --update` processes would have.
        auto engine = Engine::open(dir.path.string());
        for (int i = 0; i < kRounds; ++i) engine->refreshScene("den", observed, byCategory);
    };
    std::thread first(refresher), second(refresher);
    first.join();
    second.join();

    auto engine = Engine::open(dir.path.string());
    // Unset counts as the first capture; each refresh adds one.
    REQUIRE(attributeOf(*engine, "chair", "captures") == std::to_string(1 + 2 * kRounds));
    REQUIRE(attributeOf(*engine, "table", "captures") == std::to_string(1 + 2 * kRounds));
}
