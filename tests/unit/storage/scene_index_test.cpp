// The scene index (storage/scene_index.hpp): stored with every write of a scene, always what the
// scene's records give, refused when damaged, absent from databases written before schema 4, and
// read in its first format (bounds in doubles) from those written before schema 6.
#include <catch2/catch.hpp>

#include <lmdb.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <fmt/format.h>

#include "model/error.hpp"
#include "model/geometry.hpp"
#include "storage/check.hpp"
#include "storage/codec.hpp"
#include "storage/database.hpp"
#include "storage/lmdb_env.hpp"
#include "storage_test_support.hpp"

using namespace smql;
using namespace smql::storage;
using namespace smql::storage::testing;
using model::NodeId;
using model::NodeKind;

namespace {

// A hall of `count` boxes on a grid, turned by various angles, with walls, a hidden part, a node
// without geometry and one without a category: every field the index keeps, in several values.
model::SceneData hall(std::string name, std::size_t count) {
    model::SceneData data;
    data.info.name = std::move(name);
    data.info.source = "test:hall";
    data.nodes.push_back(localNode(1, NodeKind::Room, model::kNoNode, "hall"));
    for (NodeId id = 2; id <= 5; ++id) {
        model::Node wall = localNode(id, NodeKind::Anchor, 1, "wall");
        wall.geometry = model::GeometryKind::Plane;
        wall.box = {{id % 2 ? 0.0 : 20.0, 10.0, 1.5}, {0.1, 20.0, 3.0}, id >= 4 ? M_PI / 2 : 0.0};
        data.nodes.push_back(wall);
    }
    for (std::size_t i = 0; i < count; ++i) {
        const auto id = static_cast<NodeId>(6 + i);
        const std::size_t row = i / 50;  // the grid's rows of 50
        model::Node thing = localNode(id, NodeKind::Object, 1, i % 3 == 0 ? "chair" : i % 3 == 1 ? "table" : "mug");
        thing.geometry = model::GeometryKind::Box;
        thing.box = {{0.37 * static_cast<double>(i % 50), 0.41 * static_cast<double>(row), 0.5},
                     {0.4, 0.3 + 0.01 * static_cast<double>(i % 7), 0.9},
                     0.1 * static_cast<double>(i % 13)};
        thing.hidden = i % 17 == 0;
        if (i % 29 == 0) thing.category.clear();
        data.nodes.push_back(thing);
    }
    data.nodes.push_back(localNode(static_cast<NodeId>(6 + count), NodeKind::Description, 1, "note"));
    return data;
}

// The index stored for a scene equals the one its records give, and its spatial order holds every
// node with geometry once, in blocks whose bounds hold their boxes.
void requireIndexOfRecords(const ReadTransaction& txn, NodeId scene) {
    const model::SceneInfo info = *txn.scene(scene);
    std::optional<SceneIndex> stored = txn.sceneIndex(info);
    REQUIRE(stored);
    const std::vector<model::Node> nodes = nodesOf(txn, scene);
    REQUIRE(*stored == SceneIndex::of(nodes, info.version));
    std::vector<std::uint32_t> spatial;
    for (std::uint32_t s = 0; s < nodes.size(); ++s)
        if (nodes[s].kind != NodeKind::Scene && nodes[s].geometry != model::GeometryKind::None) spatial.push_back(s);
    std::vector<std::uint32_t> order = stored->spatialOrder;
    std::sort(order.begin(), order.end());
    REQUIRE(order == spatial);
    auto requireHolds = [](const model::Aabb& outer, const model::Aabb& inner) {
        REQUIRE(outer.min.x <= inner.min.x);
        REQUIRE(outer.min.y <= inner.min.y);
        REQUIRE(outer.min.z <= inner.min.z);
        REQUIRE(inner.max.x <= outer.max.x);
        REQUIRE(inner.max.y <= outer.max.y);
        REQUIRE(inner.max.z <= outer.max.z);
    };
    // Each box's bounds rounded outward, to floats that hold them, and each block's holding its boxes.
    for (std::uint32_t s = 0; s < nodes.size(); ++s)
        requireHolds(stored->entries[s].bounds.aabb(), model::worldAabb(nodes[s].box));
    for (std::size_t i = 0; i < stored->spatialOrder.size(); ++i)
        requireHolds(stored->blockBounds.at(i / SceneIndex::kBlock).aabb(),
                     model::worldAabb(nodes[stored->spatialOrder[i]].box));
}

std::uint64_t sceneIndexEntries(const ReadTransaction& txn) {
    for (const auto& table : txn.tableStats())
        if (table.name == "scene_index") return table.entries;
    FAIL("no scene_index table");
    return 0;
}

}  // namespace

TEST_CASE("a scene's stored index is what its records give, through every write", "[storage][scene_index]") {
    TempDir tmp;
    auto db = Database::open(tmp.path());
    const NodeId first = importCommitted(*db, hall("first", 300));
    const NodeId second = importCommitted(*db, hall("second", 5));
    requireIndexOfRecords(db->beginRead(), first);
    requireIndexOfRecords(db->beginRead(), second);

    SECTION("nodes updated in place: boxes moved, a node hidden") {
        std::vector<model::Node> changed;
        {
            auto read = db->beginRead();
            for (NodeId id : {first + 7, first + 40}) {
                model::Node n = *read.node(id);
                n.box.center.x += 30;
                n.box.yaw += 0.5;
                n.hidden = !n.hidden;
                changed.push_back(n);
            }
        }
        auto write = db->beginWrite();
        write.updateNodes(changed);
        write.commit();
        auto read = db->beginRead();
        REQUIRE(read.scene(first)->version == 2);
        requireIndexOfRecords(read, first);
    }
    SECTION("renamed") {
        auto write = db->beginWrite();
        write.renameScene(first, "renamed");
        write.commit();
        auto read = db->beginRead();
        requireIndexOfRecords(read, first);
        REQUIRE(read.sceneIndex(*read.scene(first))->categories.front() == "renamed");
    }
    SECTION("replaced by its next version, then dropped") {
        NodeId next = 0;
        {
            auto write = db->beginWrite();
            next = write.replaceScene(first, hall("first", 120), "2026-11-25T09:00:00Z", {}).scene;
            write.commit();
        }
        requireIndexOfRecords(db->beginRead(), next);
        REQUIRE(sceneIndexEntries(db->beginRead()) == 2);
        {
            auto write = db->beginWrite();
            write.dropScene(next);
            write.commit();
        }
        REQUIRE(sceneIndexEntries(db->beginRead()) == 1);
    }
    SECTION("an index of another version than the scene's is not believed") {
        auto read = db->beginRead();
        model::SceneInfo info = *read.scene(first);
        ++info.version;
        REQUIRE_FALSE(read.sceneIndex(info));
    }
    REQUIRE(checkDatabase(tmp.path()).problems.empty());
}

TEST_CASE("a scene index record round-trips, and damage to it is refused", "[storage][scene_index][codec]") {
    // A few categories (the header is read from a copy of the record's first bytes) and hundreds
    // (the header is longer than that copy, and is read in place).
    const std::size_t categories = GENERATE(2, 300);
    std::vector<model::Node> nodes;
    nodes.push_back(localNode(7, NodeKind::Scene, model::kNoNode, "s"));
    for (NodeId id = 8; id < static_cast<NodeId>(8 + std::max<std::size_t>(categories, 22)); ++id) {
        model::Node n = localNode(id, NodeKind::Object, 7, fmt::format("category-{}", id % categories));
        n.geometry = model::GeometryKind::Box;
        n.box = {{static_cast<double>(id), 1, 0.5}, {0.2, 0.2, 0.2}, 0.3};
        nodes.push_back(n);
    }
    const SceneIndex index = SceneIndex::of(nodes, 3);
    std::string record;
    codec::encodeSceneIndex(7, index, record);
    REQUIRE(codec::decodeSceneIndex(7, record) == index);
    // The arrays and the checksum are read through the copy the caller gives, the header from the
    // record's first bytes (or in place): here the bytes after the header are garbage, and the copy
    // reads the record's own.
    const std::size_t header = record.size() - 4 - index.entries.size() * sizeof(storage::SceneIndexEntry) -
                               index.spatialOrder.size() * 4 - index.blockBounds.size() * sizeof(storage::IndexBounds);
    std::string garbled = record;
    std::fill(garbled.begin() + static_cast<std::ptrdiff_t>(header), garbled.end(), '\x5a');
    std::size_t copied = 0;
    const SceneIndex read = codec::decodeSceneIndex(7, garbled, [&](void* into, std::string_view from) {
        const auto offset = static_cast<std::size_t>(from.data() - garbled.data());
        std::memcpy(into, record.data() + offset, from.size());
        copied += from.size();
    });
    REQUIRE(read == index);
    CHECK(copied >= record.size() - header);
    // Stored under another scene's key: the checksum covers the key.
    REQUIRE_THROWS_AS(codec::decodeSceneIndex(8, record), codec::CorruptRecord);
    for (std::size_t byte = 0; byte < record.size(); byte += 7) {
        std::string flipped = record;
        flipped[byte] = static_cast<char>(flipped[byte] ^ 0x10);
        REQUIRE_THROWS_AS(codec::decodeSceneIndex(7, flipped), codec::CorruptRecord);
    }
    for (std::size_t length = 0; length < record.size(); length += 5)
        REQUIRE_THROWS_AS(codec::decodeSceneIndex(7, record.substr(0, length)), codec::CorruptRecord);
}

TEST_CASE("a database of schema version 3 is read without scene indexes, and a writable open upgrades it",
          "[storage][scene_index][database]") {
    TempDir tmp;
    NodeId old = 0;
    {
        auto db = Database::open(tmp.path());
        old = importCommitted(*db, hall("old", 40));
    }
    asSchemaVersion3(tmp.path());
    const std::vector<model::Node> before = [&] {
        auto db = Database::open(tmp.path(), {.readOnly = true});
        auto read = db->beginRead();
        REQUIRE_FALSE(read.sceneIndex(*read.scene(old)));
        for (const auto& table : read.tableStats()) REQUIRE(table.name != "scene_index");
        return nodesOf(read, old);
    }();
    REQUIRE(before.size() == 47);  // the scene node, the hall, 4 walls, 40 things, a note
    REQUIRE(checkDatabase(tmp.path()).problems.empty());

    auto db = Database::open(tmp.path());
    const NodeId added = importCommitted(*db, hall("new", 40));
    auto read = db->beginRead();
    REQUIRE(nodesOf(read, old) == before);
    REQUIRE_FALSE(read.sceneIndex(*read.scene(old)));  // until a write of that scene
    requireIndexOfRecords(read, added);
    REQUIRE(checkDatabase(tmp.path()).problems.empty());
    REQUIRE_NOTHROW(Database::open(tmp.path(), {.readOnly = true}));  // now the current version
}

TEST_CASE("an index's bounds are the nearest floats that hold the box", "[storage][scene_index]") {
    const double third = 1.0 / 3, big = 1e300, tiny = 1e-50;
    const model::Aabb exact{{third, -third, -big}, {2 * third, tiny, big}};
    const storage::IndexBounds held = storage::IndexBounds::around(exact);
    const model::Aabb widened = held.aabb();
    REQUIRE(widened.min.x <= exact.min.x);
    REQUIRE(widened.min.y <= exact.min.y);
    REQUIRE(exact.max.x <= widened.max.x);
    REQUIRE(exact.max.y <= widened.max.y);
    // The nearest: one float further in would no longer hold the box.
    REQUIRE(std::nextafter(held.minX, 1.0f) > exact.min.x);
    REQUIRE(std::nextafter(held.maxX, 0.0f) < exact.max.x);
    REQUIRE(std::nextafter(held.minY, 0.0f) > exact.min.y);
    REQUIRE(held.maxY > 0);  // 1e-50 is below every float but zero: the smallest float above it
    // Beyond float's range: the largest float or an infinity on the side that still holds it.
    REQUIRE(std::isinf(held.minZ));
    REQUIRE(held.minZ < 0);
    REQUIRE(std::isinf(held.maxZ));
    // Exact floats stay as they are; NaN stays NaN.
    const storage::IndexBounds whole = storage::IndexBounds::around({{0.5, -2, 0}, {1.25, 3, 0.75}});
    REQUIRE((whole.minX == 0.5f && whole.minY == -2.0f && whole.maxX == 1.25f && whole.maxZ == 0.75f));
    const double nan = std::numeric_limits<double>::quiet_NaN();
    REQUIRE(std::isnan(storage::IndexBounds::around({{nan, 0, 0}, {1, 1, 1}}).minX));
}

TEST_CASE("an index record of format 1 (bounds in doubles) is read rounded outward and packed again",
          "[storage][scene_index][codec]") {
    model::SceneData data = hall("hall", 120);
    model::Node scene = localNode(1000, NodeKind::Scene, model::kNoNode, "hall");
    std::vector<model::Node> nodes{scene};
    for (model::Node n : data.nodes) {
        n.id += 1000;
        nodes.push_back(n);
    }
    const std::string record = formatOneSceneIndex(1000, nodes, 4);
    REQUIRE(codec::decodeSceneIndex(1000, record) == SceneIndex::of(nodes, 4));
    std::string flipped = record;
    flipped[record.size() / 2] = static_cast<char>(flipped[record.size() / 2] ^ 0x01);
    REQUIRE_THROWS_AS(codec::decodeSceneIndex(1000, flipped), codec::CorruptRecord);
}

TEST_CASE("a database of schema version 5 is read with its scene indexes of format 1, and a writable open upgrades it",
          "[storage][scene_index][database]") {
    TempDir tmp;
    NodeId first = 0, second = 0;
    {
        auto db = Database::open(tmp.path());
        first = importCommitted(*db, hall("first", 300));
        second = importCommitted(*db, hall("second", 40));
    }
    asSchemaVersion5(tmp.path());
    {
        auto db = Database::open(tmp.path(), {.readOnly = true});
        auto read = db->beginRead();
        requireIndexOfRecords(read, first);  // as this smql would store it
        requireIndexOfRecords(read, second);
    }
    REQUIRE(checkDatabase(tmp.path()).problems.empty());

    auto db = Database::open(tmp.path());
    {
        auto write = db->beginWrite();
        write.renameScene(second, "renamed");
        write.commit();
    }
    auto read = db->beginRead();
    requireIndexOfRecords(read, first);
    requireIndexOfRecords(read, second);
    REQUIRE(checkDatabase(tmp.path()).problems.empty());
    REQUIRE_NOTHROW(Database::open(tmp.path(), {.readOnly = true}));  // now the current version
}

TEST_CASE("smql check reports a scene index that does not match the records", "[storage][scene_index][check]") {
    TempDir tmp;
    NodeId scene = 0;
    SceneIndex wrong;
    {
        auto db = Database::open(tmp.path());
        scene = importCommitted(*db, hall("hall", 30));
        auto read = db->beginRead();
        wrong = *read.sceneIndex(*read.scene(scene));
    }
    wrong.entries[3].hidden = 1 - wrong.entries[3].hidden;  // sealed again: only the check can tell
    editTable(tmp.path(), "scene_index", [&](MDB_txn* txn, MDB_dbi table) {
        std::string record;
        codec::encodeSceneIndex(scene, wrong, record);
        auto key = codec::idKey(scene);
        MDB_val k = toVal(key), v = toVal(record);
        REQUIRE(mdb_put(txn, table, &k, &v, 0) == 0);
    });
    auto problems = checkDatabase(tmp.path()).problems;
    REQUIRE(problems.size() == 1);
    REQUIRE_THAT(problems.front(), Catch::Contains("its scene index does not match its node records"));
}

namespace {

// A category's rows as its nodes' records give them, in id order, over every scene.
std::vector<CategoryRow> rowsOfRecords(const ReadTransaction& txn, const std::string& category) {
    std::vector<CategoryRow> rows;
    for (const auto& scene : txn.scenes())
        txn.forEachNodeInScene(scene.id, [&](const model::Node& n) {
            if (n.kind != NodeKind::Scene && n.category == category)
                rows.push_back({n.id, scene.id, n.sourceId, n.geometry, n.box});
        });
    std::sort(rows.begin(), rows.end(), [](const CategoryRow& a, const CategoryRow& b) { return a.id < b.id; });
    return rows;
}

void requireRowsOfRecords(const ReadTransaction& txn) {
    for (const std::string category : {"chair", "table", "mug", "wall", "note", "hall"}) {
        const auto expected = rowsOfRecords(txn, category);
        REQUIRE(txn.categoryRows(category) == expected);
        const auto first = txn.categoryRows(category, 7);
        REQUIRE(first == std::vector<CategoryRow>(expected.begin(),
                                                  expected.begin() + static_cast<std::ptrdiff_t>(
                                                                         std::min<std::size_t>(7, expected.size()))));
        // Row by row as read, by the keys worked out once: the same rows, in the same order.
        for (const std::size_t limit : {std::size_t{0}, std::size_t{1}, std::size_t{7}, SIZE_MAX}) {
            std::vector<CategoryRow> visited;
            txn.forEachCategoryRow(txn.labelKeys(category), limit,
                                   [&](const CategoryRow& row) { visited.push_back(row); });
            REQUIRE(visited == txn.categoryRows(category, limit));
        }
        REQUIRE(txn.countWithKeys(txn.labelKeys(category)) == expected.size());
    }
}

}  // namespace

TEST_CASE("a category's rows come from its label entries as the records give them, through every write",
          "[storage][labels]") {
    TempDir tmp;
    auto db = Database::open(tmp.path());
    const NodeId first = importCommitted(*db, hall("first", 120));
    importCommitted(*db, hall("second", 30));
    requireRowsOfRecords(db->beginRead());
    REQUIRE(db->beginRead().categoryRowsInScene("mug", first).size() == 40 - 2);  // two mugs lack a category

    SECTION("an update of a box") {
        std::vector<model::Node> moved;
        {
            auto read = db->beginRead();
            for (NodeId id : read.nodesWithCategory("mug", first, 3)) {
                model::Node n = *read.node(id);
                n.box.center.x += 1.5;
                n.box.yaw = 0.25;
                moved.push_back(n);
            }
        }
        auto write = db->beginWrite();
        write.updateNodes(moved);
        write.commit();
        auto read = db->beginRead();
        requireRowsOfRecords(read);
        REQUIRE(read.categoryRows("mug").front().box == moved.front().box);
    }
    SECTION("a replacement and a drop") {
        {
            auto write = db->beginWrite();
            write.replaceScene(first, hall("first", 60), "2026-11-25T09:00:00Z", {});
            write.commit();
        }
        requireRowsOfRecords(db->beginRead());
        {
            auto write = db->beginWrite();
            write.dropScene(db->beginRead().sceneByName("second")->id);
            write.commit();
        }
        requireRowsOfRecords(db->beginRead());
    }
    REQUIRE(checkDatabase(tmp.path()).problems.empty());
}

TEST_CASE("label entries of the ids alone (schema version 4) are read read-only and widened by a writable open",
          "[storage][labels][database]") {
    TempDir tmp;
    std::vector<CategoryRow> chairs;
    {
        auto db = Database::open(tmp.path());
        importCommitted(*db, hall("old", 80));
        importCommitted(*db, hall("older", 20));
        chairs = db->beginRead().categoryRows("chair");
    }
    REQUIRE(chairs.size() == 26 + 6);  // a third of each hall, less those without a category
    asSchemaVersion4(tmp.path());
    {
        auto db = Database::open(tmp.path(), {.readOnly = true});
        auto read = db->beginRead();
        REQUIRE(read.categoryRows("chair") == chairs);  // from the records
        REQUIRE(read.categoryRowsInScene("chair", chairs.front().scene).empty());
        requireRowsOfRecords(read);
    }
    REQUIRE(checkDatabase(tmp.path()).problems.empty());

    auto db = Database::open(tmp.path());  // upgrades to version 5
    auto read = db->beginRead();
    REQUIRE(read.categoryRowsInScene("chair", chairs.front().scene).size() == 26);
    REQUIRE(read.categoryRows("chair") == chairs);
    requireRowsOfRecords(read);
    REQUIRE(checkDatabase(tmp.path()).problems.empty());
    REQUIRE_NOTHROW(Database::open(tmp.path(), {.readOnly = true}));
}

TEST_CASE("smql check reports a label entry whose box is not its record's", "[storage][labels][check]") {
    TempDir tmp;
    model::Node mug;
    NodeId scene = 0;
    {
        auto db = Database::open(tmp.path());
        scene = importCommitted(*db, hall("hall", 30));
        auto read = db->beginRead();
        mug = *read.node(read.nodesWithCategory("mug", scene).front());
    }
    editTable(tmp.path(), "labels", [&](MDB_txn* txn, MDB_dbi labels) {
        auto entry = codec::labelEntry("mug", scene, mug.id, mug);
        MDB_val k = toVal(std::string_view("mug")), v = toVal(entry);
        REQUIRE(mdb_del(txn, labels, &k, &v) == 0);
        mug.box.center.z += 0.5;  // sealed again: only the check can tell
        entry = codec::labelEntry("mug", scene, mug.id, mug);
        v = toVal(entry);
        REQUIRE(mdb_put(txn, labels, &k, &v, 0) == 0);
    });
    auto problems = checkDatabase(tmp.path()).problems;
    REQUIRE(problems.size() == 1);
    REQUIRE_THAT(problems.front(), Catch::Contains("the label index entries for 'mug' do not match the records"));
}
