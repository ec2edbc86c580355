// Versions of a scene: replaceScene keeps the superseded one in the history table; renameScene
// and dropScene carry the history with the name.
#include <catch2/catch.hpp>

#include "model/error.hpp"
#include "storage/check.hpp"
#include "storage/codec.hpp"
#include "storage/database.hpp"
#include "storage_test_support.hpp"

using namespace smql;
using namespace smql::storage;
using namespace smql::storage::testing;
using model::NodeId;
using model::NodeKind;

namespace {

model::Node objectAt(NodeId id, NodeId parent, std::string category, double x) {
    auto node = localNode(id, NodeKind::Object, parent, std::move(category));
    node.geometry = model::GeometryKind::Box;
    node.box = {{x, 1, 0.5}, {0.4, 0.4, 0.4}, 0};
    return node;
}

model::SceneData den(double mugX, bool withLamp) {
    model::SceneData data;
    data.info.name = "den";
    data.info.captureTime = withLamp ? "2026-11-20T09:00:00Z" : "2026-11-21T09:00:00Z";
    data.nodes = {localNode(1, NodeKind::Room, model::kNoNode, "room"), objectAt(2, 1, "table", 1),
                  objectAt(3, 2, "mug", mugX)};
    if (withLamp) data.nodes.push_back(objectAt(4, 1, "lamp", 3));
    data.relations = {{3, 2, model::RelationType::On, 1.0f, 1, model::kNoNode}};
    return data;
}

model::SceneData officeScene() {
    model::SceneData data;
    data.info.name = "office";
    data.nodes = {localNode(1, NodeKind::Room, model::kNoNode, "room"), objectAt(2, 1, "chair", 0)};
    return data;
}

}  // namespace

TEST_CASE("a history record decodes to what was encoded, and a flipped byte is refused", "[storage][history]") {
    model::SceneVersion version;
    version.number = 7;
    version.info.id = 40;
    version.info.name = "den";
    version.info.nodeCount = 1;
    version.nodes = {localNode(40, NodeKind::Scene, model::kNoNode, "den")};
    version.nodes[0].scene = 40;
    version.relations = {{41, 42, model::RelationType::Near, 0.5f, 2, model::kNoNode}};
    version.supersededAt = "2026-11-21T09:00:00Z";
    version.changes = {{model::ChangeKind::Moved, "mug", 43, 97, {{1, 1, 1}, {1, 1, 1}, 0}, {{2, 1, 1}, {1, 1, 1}, 0}}};
    const std::string key = codec::historyKey("den", 7);
    std::string bytes;
    codec::encodeVersion(key, version, bytes);
    REQUIRE(codec::decodeVersion(key, bytes) == version);
    REQUIRE_THROWS_AS(codec::decodeVersion(codec::historyKey("den", 8), bytes), codec::CorruptRecord);
    bytes[bytes.size() / 2] ^= 0x10;
    REQUIRE_THROWS_AS(codec::decodeVersion(key, bytes), codec::CorruptRecord);
}

TEST_CASE("replaceScene keeps the superseded version with its changes", "[storage][history]") {
    TempDir tmp;
    auto db = Database::open(tmp.path());
    const NodeId first = importCommitted(*db, den(1, true));
    importCommitted(*db, officeScene());

    model::SceneData next = den(2.5, false);
    const std::vector<model::ObjectChange> changes = {
        {model::ChangeKind::Moved,
         "mug",
         first + 3,
         3,
         {{1, 1, 0.5}, {0.4, 0.4, 0.4}, 0},
         {{2.5, 1, 0.5}, {0.4, 0.4, 0.4}, 0}},
        {model::ChangeKind::Missing, "lamp", first + 4, model::kNoNode, {{3, 1, 0.5}, {0.4, 0.4, 0.4}, 0}, {}}};
    NodeId second = 0;
    {
        auto txn = db->beginWrite();
        auto replaced = txn.replaceScene(first, next, "2026-11-21T09:00:00Z", changes);
        REQUIRE(replaced.superseded == 1);
        second = replaced.scene;
        txn.commit();
    }
    auto read = db->beginRead();
    auto info = read.sceneByName("den");
    REQUIRE(info);
    REQUIRE(info->id == second);
    REQUIRE(second > first);
    REQUIRE(info->nodeCount == 3);
    REQUIRE_FALSE(read.node(first + 4));  // the old block is gone from the live tables

    auto history = read.history("den");
    REQUIRE(history.size() == 1);
    const auto& old = history.front();
    REQUIRE(old.number == 1);
    REQUIRE(old.info.id == first);
    REQUIRE(old.info.captureTime == "2026-11-20T09:00:00Z");
    REQUIRE(old.nodes.size() == 5);  // the scene node, room, table, mug, lamp
    REQUIRE(old.nodes.front().kind == NodeKind::Scene);
    REQUIRE(old.relations.size() == 1);
    REQUIRE(old.supersededAt == "2026-11-21T09:00:00Z");
    REQUIRE(old.changes.size() == 2);
    REQUIRE(old.changes[0].after == second + 3);  // local id 3 is the third node of the new version
    REQUIRE(read.node(old.changes[0].after)->category == "mug");
    REQUIRE(old.changes[1].after == model::kNoNode);
    REQUIRE(read.history("office").empty());
    REQUIRE(checkDatabase(tmp.path()).problems.empty());

    SECTION("a second update adds version 2") {
        {
            auto txn = db->beginWrite();
            REQUIRE(txn.replaceScene(second, den(2.5, false), "2026-11-22T09:00:00Z", {}).superseded == 2);
            txn.commit();
        }
        auto again = db->beginRead().history("den");
        REQUIRE(again.size() == 2);
        REQUIRE(again[1].number == 2);
        REQUIRE(again[1].info.id == second);
    }
    SECTION("rename carries the history, and the scene node takes the new name") {
        {
            auto txn = db->beginWrite();
            txn.renameScene(second, "study");
            txn.commit();
        }
        auto after = db->beginRead();
        REQUIRE_FALSE(after.sceneByName("den"));
        REQUIRE(after.sceneByName("study")->id == second);
        REQUIRE(after.sceneByName("study")->version == info->version + 1);
        REQUIRE(after.node(second)->category == "study");
        REQUIRE(after.history("den").empty());
        REQUIRE(after.history("study").size() == 1);
        REQUIRE(checkDatabase(tmp.path()).problems.empty());
    }
    SECTION("drop removes the history too") {
        {
            auto txn = db->beginWrite();
            txn.dropScene(second);
            txn.commit();
        }
        REQUIRE(db->beginRead().history("den").empty());
        REQUIRE(checkDatabase(tmp.path()).problems.empty());
    }
}

TEST_CASE("renameScene refuses a taken or empty name and changes nothing", "[storage][history][errors]") {
    TempDir tmp;
    auto db = Database::open(tmp.path());
    const NodeId den1 = importCommitted(*db, den(1, true));
    importCommitted(*db, officeScene());
    auto txn = db->beginWrite();
    try {
        txn.renameScene(den1, "office");
        FAIL("renamed onto a taken name");
    } catch (const Error& e) {
        REQUIRE(e.kind() == ErrorKind::Input);
        REQUIRE(e.message() == "a scene named 'office' already exists");
    }
    REQUIRE_THROWS_AS(txn.renameScene(den1, ""), Error);
    REQUIRE_THROWS_AS(txn.renameScene(den1 + 1000, "elsewhere"), Error);
    txn.commit();
    auto read = db->beginRead();
    REQUIRE(read.sceneByName("den")->id == den1);
    REQUIRE(read.sceneByName("office"));
}

TEST_CASE("a new version must keep the scene's name", "[storage][history][errors]") {
    TempDir tmp;
    auto db = Database::open(tmp.path());
    const NodeId id = importCommitted(*db, den(1, true));
    auto renamed = den(1, true);
    renamed.info.name = "elsewhere";
    auto txn = db->beginWrite();
    REQUIRE_THROWS_AS(txn.replaceScene(id, renamed, "2026-11-21", {}), Error);
}
