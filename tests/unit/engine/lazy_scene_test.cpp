// Scenes loaded from their stored index (engine/catalog/scene_snapshot.hpp): nodes decoded when a
// statement first asks, spatial queries answered from the stored blocks and the levels made over them.
// Nothing of it may change an answer.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "../storage/storage_test_support.hpp"
#include "engine/catalog/scene_snapshot.hpp"
#include "engine/format.hpp"
#include "engine_support.hpp"
#include "ingest/generate/room_generator.hpp"
#include "query_suites.hpp"
#include "relations/hierarchy.hpp"
#include "relations/predicates.hpp"
#include "storage/database.hpp"

using namespace smql;
using namespace smql::testing;
namespace fs = std::filesystem;

namespace {

// A generated room of `objects` things, stored, with a read transaction that sees it.
struct StoredRoom {
    TempDir dir;
    std::unique_ptr<storage::Database> db = storage::Database::open(dir.path.string());
    std::optional<storage::ReadTransaction> read;
    model::SceneInfo info;

    explicit StoredRoom(int objects) {
        auto scene = generate::generateRoom({.seed = 5, .objectCount = objects, .name = "room"});
        relations::assignParents(scene);
        auto write = db->beginWrite();
        write.importScene(scene);
        write.commit();
        read.emplace(db->beginRead());
        info = *read->sceneByName("room");
    }
};

std::vector<catalog::Slot> sorted(std::vector<catalog::Slot> slots) {
    std::sort(slots.begin(), slots.end());
    return slots;
}

bool sameBounds(const model::Aabb& a, const model::Aabb& b) { return a.min == b.min && a.max == b.max; }

bool hasNaN(const model::Aabb& a) { return std::isnan(a.min.x + a.min.y + a.min.z + a.max.x + a.max.y + a.max.z); }

// A box with a NaN coordinate has no place: last in a walk nearest first.
double squaredGap(const model::Aabb& a, const model::Aabb& b) {
    if (hasNaN(a)) return std::numeric_limits<double>::infinity();
    double dx = std::max({0.0, a.min.x - b.max.x, b.min.x - a.max.x});
    double dy = std::max({0.0, a.min.y - b.max.y, b.min.y - a.max.y});
    double dz = std::max({0.0, a.min.z - b.max.z, b.min.z - a.max.z});
    return dx * dx + dy * dy + dz * dz;
}

}  // namespace

// The query suites on two databases holding the same scenes: one that stores their indexes, and
// one made as an smql of schema version 3 left it (no scene index), whose scenes load whole.
TEST_CASE("every query suite answers the same from scenes loaded whole as from their stored indexes",
          "[lazy][suites]") {
    std::size_t compared = 0;
    for (const fs::path& suite : querySuites()) {
        TempDir indexedDir, wholeDir;
        const std::vector<SuiteBlock> blocks = readSuite(suite);
        {
            auto indexed = Engine::open(indexedDir.path.string());
            auto whole = Engine::open(wholeDir.path.string());
            for (const SuiteBlock& block : blocks)
                for (Engine* engine : {indexed.get(), whole.get()})
                    if (!block.load.empty()) loadSuiteData(*engine, block.load, suite.parent_path());
        }
        storage::testing::asSchemaVersion3(wholeDir.path.string());
        auto indexed = Engine::open(indexedDir.path.string());
        auto whole = Engine::open(wholeDir.path.string());  // upgraded, its scenes still without an index
        bool statementsBegan = false;
        for (const SuiteBlock& block : blocks) {
            if (!block.load.empty()) {
                REQUIRE_FALSE(statementsBegan);  // the scenes were all loaded above
                continue;
            }
            statementsBegan = true;
            INFO(suite.filename().string() << ": " << block.text);
            CHECK(outcome(*indexed, block.text) == outcome(*whole, block.text));
            ++compared;
        }
    }
    CHECK(compared > 150);
}

TEST_CASE("a scene's nodes and relations decoded one by one are its records", "[lazy]") {
    StoredRoom room(300);
    auto snapshot = catalog::SceneSnapshot::load(*room.read, room.info);
    std::vector<model::Node> records;
    room.read->forEachNodeInScene(room.info.id, [&](const model::Node& n) { records.push_back(n); });
    REQUIRE(snapshot->size() == records.size());
    // A few first, out of order, then all of them.
    for (catalog::Slot s : {7u, 3u, 250u, 0u}) REQUIRE(snapshot->node(s) == records[s]);
    for (catalog::Slot s = 0; s < records.size(); ++s) {
        REQUIRE(snapshot->kind(s) == records[s].kind);
        REQUIRE(snapshot->category(s) == records[s].category);
        REQUIRE(snapshot->hidden(s) == records[s].hidden);
    }
    REQUIRE(snapshot->nodes() == records);
    REQUIRE(snapshot->storedRelations() == room.read->relationsInScene(room.info.id));
}

// The predicates ask the obstacles for a node's world bounds per pair: a scene answers from its index
// for its own nodes, and computes them for anything else, a copy of one of its nodes moved included.
TEST_CASE("a scene's obstacles give each node's world bounds, its own from the index", "[lazy]") {
    StoredRoom room(100);
    auto snapshot = catalog::SceneSnapshot::load(*room.read, room.info);
    snapshot->readThrough(&*room.read);
    const catalog::SceneObstacles obstacles(*snapshot);
    for (catalog::Slot s = 0; s < snapshot->size(); ++s) {
        const model::Node& n = snapshot->node(s);
        if (n.geometry == model::GeometryKind::None) continue;
        REQUIRE(sameBounds(obstacles.bounds(n), model::worldAabb(n.box)));
        model::Node moved = n;
        moved.box.center.x += 1.5;
        moved.box.yaw += 0.3;
        REQUIRE(sameBounds(obstacles.bounds(moved), model::worldAabb(moved.box)));
    }
    snapshot->readThrough(nullptr);
}

// A snapshot's first 32 spatial queries scan the stored blocks, the later ones walk down the levels
// it then packs over them (one level over 600 boxes' 38 blocks, two over 5,000 boxes' 313), and the
// nearest-first walk takes the blocks: each must answer what a look at every box answers. Also with
// boxes holding a NaN, which storage now refuses but a database written before may hold (here a
// version from the history, whose index is made from its nodes): they meet no region and come last.
TEST_CASE("spatial queries from the stored blocks answer as a look at every box does", "[lazy][spatial]") {
    const int objects = GENERATE(600, 5000);
    const std::size_t nanEvery = GENERATE(0, 7);
    StoredRoom room(objects);
    std::shared_ptr<const catalog::SceneSnapshot> snapshot;
    if (nanEvery == 0) {
        snapshot = catalog::SceneSnapshot::load(*room.read, room.info);
    } else {
        model::SceneVersion version;
        version.number = 1;
        version.info = room.info;
        room.read->forEachNodeInScene(room.info.id, [&](const model::Node& n) { version.nodes.push_back(n); });
        for (std::size_t i = 1; i < version.nodes.size(); i += nanEvery)
            (i % 2 ? version.nodes[i].box.center.z : version.nodes[i].box.size.x) = std::nan("");
        snapshot = catalog::SceneSnapshot::fromVersion(version);
    }
    std::vector<catalog::Slot> spatial;
    for (catalog::Slot s = 0; s < snapshot->size(); ++s)
        if (snapshot->kind(s) != model::NodeKind::Scene && snapshot->geometry(s) != model::GeometryKind::None)
            spatial.push_back(s);
    REQUIRE(snapshot->spatialSize() == spatial.size());
    std::vector<model::Aabb> regions;
    for (std::size_t i = 0; i < spatial.size(); i += spatial.size() / 64) {
        model::Aabb r = snapshot->bounds(spatial[i]);
        const double pad = 0.1 * static_cast<double>(i % 20);
        r.min = {r.min.x - pad, r.min.y - pad, r.min.z - pad};
        r.max = {r.max.x + pad, r.max.y + pad, r.max.z + pad};
        regions.push_back(r);
    }
    REQUIRE(regions.size() > 60);  // past the 32 scans
    for (const model::Aabb& region : regions) {
        std::vector<catalog::Slot> expected;
        for (catalog::Slot s : spatial)
            if (relations::intersects(snapshot->bounds(s), region)) expected.push_back(s);
        std::vector<catalog::Slot> found;
        snapshot->intersecting(region, found);
        REQUIRE(sorted(found) == expected);

        // Nearest first: every box once, by the gaps of every box sorted (which of equal gaps is free).
        std::vector<double> gaps;
        for (catalog::Slot s : spatial) gaps.push_back(squaredGap(snapshot->bounds(s), region));
        std::sort(gaps.begin(), gaps.end());
        std::vector<catalog::Slot> walked;
        auto walk = snapshot->walkNearest(region);
        while (const auto s = walk.next()) {
            REQUIRE(walked.size() < gaps.size());
            REQUIRE(squaredGap(snapshot->bounds(*s), region) == Approx(gaps[walked.size()]).margin(1e-12));
            walked.push_back(*s);
        }
        REQUIRE(sorted(walked) == spatial);
    }
}

// An index that says otherwise than a record it leads to is an error when that node is read, not
// an answer (smql check finds it without a query: tests/unit/storage/scene_index_test.cpp).
TEST_CASE("a node whose record contradicts the scene index is refused when a statement reads it", "[lazy]") {
    StoredRoom room(100);
    const model::NodeId scene = room.info.id;
    storage::SceneIndex index = *room.read->sceneIndex(room.info);
    room.read.reset();
    room.db.reset();  // closed, so the index can be changed behind it
    const std::string path = room.dir.path.string();
    model::NodeId moved = 0;
    const auto position = [&](const std::string& name) {
        return static_cast<std::uint32_t>(std::find(index.categories.begin(), index.categories.end(), name) -
                                          index.categories.begin());
    };
    for (std::size_t s = 0; s < index.entries.size() && !moved; ++s)
        if (index.categories[index.entries[s].category] == "chair") {
            index.entries[s].category = position("table");  // a chair listed as a table
            moved = scene + s;
        }
    REQUIRE(moved != 0);
    storage::testing::editTable(path, "scene_index", [&](MDB_txn* txn, MDB_dbi table) {
        std::string record;
        storage::codec::encodeSceneIndex(scene, index, record);
        auto key = storage::codec::idKey(scene);
        MDB_val k = storage::toVal(key), v = storage::toVal(record);
        REQUIRE(mdb_put(txn, table, &k, &v, 0) == 0);
    });
    auto engine = Engine::open(path);
    try {
        run(*engine, "FIND table");
        FAIL("the query answered from an index its records contradict");
    } catch (const Error& e) {
        REQUIRE(e.kind() == ErrorKind::Storage);
        REQUIRE_THAT(e.message(), Catch::Contains("does not match the record of node #" + std::to_string(moved)));
    }
}
