#include <catch2/catch.hpp>

#include <lmdb.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <thread>

#include "model/error.hpp"
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

// Local ids deliberately sparse and out of order, to show they are mapped.
model::SceneData kitchen() {
    model::SceneData data;
    data.info.name = "kitchen";
    data.info.source = "replica:/data/kitchen/info_semantic.json";
    data.info.captureTime = "2024-05-01T10:00:00Z";
    data.info.alignment = {0, -1, 0, 2, 1, 0, 0, 3, 0, 0, 1, 0, 0, 0, 0, 1};
    data.info.scale = 1.02;
    data.info.viewpoint = {{1, 2, 1.6}, 1.5};
    data.info.viewpointNote = "door, facing in";
    data.info.nodeCount = 999;  // ignored: the import counts
    data.info.version = 41;     // ignored: the import sets it

    auto room = localNode(10, NodeKind::Room, model::kNoNode, "room");
    room.sourceId = 100;
    auto wall = localNode(20, NodeKind::Anchor, 10, "wall");
    wall.geometry = model::GeometryKind::Plane;
    wall.box = {{0, 2, 1.3}, {4, 0.05, 2.6}, 0};
    wall.sourceId = 101;
    auto table = localNode(30, NodeKind::Object, 20, "table");
    table.geometry = model::GeometryKind::Box;
    table.box = {{1, 1.5, 0.4}, {1.2, 0.8, 0.8}, 0.3};
    table.attributes = {{"color", "brown"}};
    table.sourceId = 102;
    table.text = "a wooden table";
    auto mug = localNode(40, NodeKind::Object, 30, "mug");
    mug.attributes = {{"color", "red"}, {"material", "ceramic"}};
    mug.text = "rote Tasse ☕";
    mug.sourceId = -5;
    mug.confidence = 0.75f;
    auto hiddenMug = localNode(50, NodeKind::Object, 30, "mug");
    hiddenMug.hidden = true;
    auto description = localNode(60, NodeKind::Description, 40, "");
    description.text = "a red mug on the table";
    auto frame = localNode(70, NodeKind::Frame, 10, "frame");
    // Listed child before parent: the order of the list is the id order, not the tree order.
    data.nodes = {room, wall, table, mug, hiddenMug, description, frame};
    std::swap(data.nodes[5], data.nodes[6]);  // frame (70) before description (60)

    data.relations = {{40, 30, model::RelationType::On, 0.9f, 3, model::kNoNode},
                      {50, 30, model::RelationType::On, 0.8f, 1, model::kNoNode},
                      {40, 50, model::RelationType::Near, 0.6f, 2, 70}};
    return data;
}

model::SceneData office() {
    model::SceneData data;
    data.info.name = "office";
    auto room = localNode(1, NodeKind::Room, model::kNoNode, "room");
    room.sourceId = 100;  // same source id as the kitchen's room: source ids are per scene
    auto chair = localNode(2, NodeKind::Object, 1, "chair");
    auto mug = localNode(3, NodeKind::Object, 2, "mug");
    data.nodes = {room, chair, mug};
    data.relations = {{3, 2, model::RelationType::On, 1.0f, 1, model::kNoNode}};
    return data;
}

// A scene of one node, local id 1, of the category.
model::SceneData oneNodeScene(const std::string& name, const std::string& category) {
    model::SceneData scene;
    scene.info.name = name;
    model::Node node;
    node.id = 1;
    node.category = category;
    scene.nodes.push_back(node);
    return scene;
}

std::vector<model::Relation> relationsIn(const ReadTransaction& txn, NodeId sceneId) {
    std::vector<model::Relation> relations;
    txn.forEachRelationInScene(sceneId, [&](const model::Relation& r) { relations.push_back(r); });
    return relations;
}

std::uint64_t entries(const ReadTransaction& txn, std::string_view table) {
    for (const auto& stats : txn.tableStats())
        if (stats.name == table) return stats.entries;
    FAIL("no table " << table);
    return 0;
}

Error openError(const std::string& path, const OpenOptions& options = {}) {
    try {
        Database::open(path, options);
    } catch (const Error& e) {
        return e;
    }
    FAIL("opening " << path << " did not throw");
    return Error(ErrorKind::Storage, "unreachable");
}

template <class F>
Error errorOf(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e;
    }
    FAIL("no smql::Error thrown");
    return Error(ErrorKind::Storage, "unreachable");
}

// Checks everything the kitchen and office imports stored; ids as a fresh database assigns them.
void requireKitchenAndOffice(const ReadTransaction& txn) {
    const NodeId k = 1, room = 2, wall = 3, table = 4, mug = 5, hiddenMug = 6, frame = 7, description = 8;
    const NodeId o = 9, officeRoom = 10, chair = 11, officeMug = 12;

    auto scenes = txn.scenes();
    REQUIRE(scenes.size() == 2);
    model::SceneInfo expected = kitchen().info;
    expected.id = k;
    expected.nodeCount = 7;
    expected.version = 1;
    REQUIRE(scenes[0] == expected);
    REQUIRE(scenes[1].name == "office");
    REQUIRE(scenes[1].id == o);
    REQUIRE(txn.sceneByName("office") == scenes[1]);
    REQUIRE(txn.scene(k) == scenes[0]);
    REQUIRE_FALSE(txn.sceneByName("garage"));
    REQUIRE_FALSE(txn.scene(room));

    auto sceneNode = txn.node(k);
    REQUIRE(sceneNode);
    REQUIRE(sceneNode->kind == NodeKind::Scene);
    REQUIRE(sceneNode->category == "kitchen");
    REQUIRE(sceneNode->scene == k);
    REQUIRE(sceneNode->parent == model::kNoNode);

    model::Node expectedMug = kitchen().nodes[3];
    expectedMug.id = mug;
    expectedMug.scene = k;
    expectedMug.parent = table;
    REQUIRE(txn.node(mug) == expectedMug);
    REQUIRE(txn.node(description)->kind == NodeKind::Description);
    REQUIRE(txn.node(description)->parent == mug);
    REQUIRE(txn.node(hiddenMug)->hidden);
    REQUIRE_FALSE(txn.node(999));
    REQUIRE_FALSE(txn.node(model::kNoNode));

    model::Node reused = *txn.node(wall);
    REQUIRE(txn.readNode(officeMug, reused));
    REQUIRE(reused == *txn.node(officeMug));
    REQUIRE_FALSE(txn.readNode(999, reused));

    REQUIRE(txn.children(k) == std::vector<NodeId>{room});
    REQUIRE(txn.children(room) == std::vector<NodeId>{wall, frame});
    REQUIRE(txn.children(table) == std::vector<NodeId>{mug, hiddenMug});
    REQUIRE(txn.children(o) == std::vector<NodeId>{officeRoom});
    REQUIRE(txn.children(description).empty());
    REQUIRE(txn.children(999).empty());

    auto kitchenNodes = nodesOf(txn, k);
    REQUIRE(kitchenNodes.size() == 8);
    for (std::size_t i = 0; i < kitchenNodes.size(); ++i) {
        REQUIRE(kitchenNodes[i].id == k + i);
        REQUIRE(kitchenNodes[i] == *txn.node(k + i));
    }
    REQUIRE(nodesOf(txn, o).size() == 4);
    REQUIRE(nodesOf(txn, room).empty());  // not a scene
    REQUIRE(nodesOf(txn, 999).empty());
    REQUIRE(txn.nodeCount() == 12);

    using Categories = std::vector<std::pair<std::string, std::uint64_t>>;
    REQUIRE(txn.categories() ==
            Categories{{"chair", 1}, {"frame", 1}, {"mug", 3}, {"room", 2}, {"table", 1}, {"wall", 1}});
    REQUIRE(txn.nodesWithCategory("mug") == std::vector<NodeId>{mug, hiddenMug, officeMug});
    REQUIRE(txn.nodesWithCategory("mug", k) == std::vector<NodeId>{mug, hiddenMug});
    REQUIRE(txn.nodesWithCategory("mug", o) == std::vector<NodeId>{officeMug});
    REQUIRE(txn.nodesWithCategory("room") == std::vector<NodeId>{room, officeRoom});
    REQUIRE(txn.nodesWithCategory("chair", k).empty());
    REQUIRE(txn.nodesWithCategory("sofa").empty());
    REQUIRE(txn.nodesWithCategory("mu").empty());
    REQUIRE(txn.nodesWithCategory("").empty());
    REQUIRE(txn.nodesWithCategory("kitchen").empty());  // scene nodes are not labels

    REQUIRE(txn.nodeBySourceId(k, 100) == room);
    REQUIRE(txn.nodeBySourceId(o, 100) == officeRoom);
    REQUIRE(txn.nodeBySourceId(k, -5) == mug);
    REQUIRE(txn.nodeBySourceId(k, 102) == table);
    REQUIRE_FALSE(txn.nodeBySourceId(k, 7));
    REQUIRE_FALSE(txn.nodeBySourceId(o, 101));

    using model::Relation;
    using model::RelationType;
    const Relation mugOnTable{mug, table, RelationType::On, 0.9f, 3, model::kNoNode};
    const Relation hiddenOnTable{hiddenMug, table, RelationType::On, 0.8f, 1, model::kNoNode};
    const Relation mugNearHidden{mug, hiddenMug, RelationType::Near, 0.6f, 2, frame};
    REQUIRE(txn.relationsOf(mug) == std::vector<Relation>{mugOnTable, mugNearHidden});
    REQUIRE(txn.relationsOf(table) == std::vector<Relation>{mugOnTable, hiddenOnTable});
    REQUIRE(txn.relationsOf(hiddenMug) == std::vector<Relation>{hiddenOnTable, mugNearHidden});
    REQUIRE(txn.relationsOf(wall).empty());
    auto inKitchen = relationsIn(txn, k);
    REQUIRE(inKitchen.size() == 3);
    for (const auto& r : {mugOnTable, hiddenOnTable, mugNearHidden})
        REQUIRE(std::count(inKitchen.begin(), inKitchen.end(), r) == 1);
    REQUIRE(relationsIn(txn, o) == std::vector<Relation>{{officeMug, chair, RelationType::On, 1.0f, 1, 0}});
    REQUIRE(relationsIn(txn, 999).empty());
}

}  // namespace

TEST_CASE("open creates a database, and reopening finds it", "[storage][database]") {
    TempDir tmp;
    const std::string path = tmp.sub("nested/db");
    {
        auto db = Database::open(path);
        REQUIRE(db->directory() == path);
        REQUIRE_FALSE(db->readOnly());
        REQUIRE(std::filesystem::is_regular_file(path + "/data.mdb"));
        REQUIRE(db->fileSizeBytes() > 0);
        REQUIRE(db->fileSizeBytes() < (1u << 20));  // the map size is reserved address space, not disk
        auto txn = db->beginRead();
        REQUIRE(txn.scenes().empty());
        REQUIRE(txn.nodeCount() == 0);
        REQUIRE(txn.categories().empty());
    }
    {
        auto db = Database::open(path);
        importCommitted(*db, kitchen());
    }
    auto db = Database::open(path, {.readOnly = true});
    REQUIRE(db->readOnly());
    REQUIRE(db->beginRead().sceneByName("kitchen"));
    auto error = errorOf([&] { db->beginWrite(); });
    REQUIRE(error.kind() == ErrorKind::Storage);
    REQUIRE_THAT(error.message(), Catch::Contains("read-only"));
}

TEST_CASE("opening the same directory twice in a process shares one environment", "[storage][database]") {
    TempDir tmp;
    auto first = Database::open(tmp.path());
    auto second = Database::open(tmp.path());
    importCommitted(*first, office());
    REQUIRE(second->beginRead().sceneByName("office"));
    first.reset();  // closing one handle must leave the other working
    REQUIRE(second->beginRead().nodeCount() == 4);
    importCommitted(*second, kitchen());
    REQUIRE(second->beginRead().scenes().size() == 2);
}

TEST_CASE("open refuses what is not an smql database", "[storage][database][errors]") {
    TempDir tmp;

    SECTION("a directory with other files") {
        std::filesystem::create_directory(tmp.sub("photos"));
        std::ofstream(tmp.sub("photos/notes.txt")) << "hello";
        auto error = openError(tmp.sub("photos"));
        REQUIRE(error.kind() == ErrorKind::Storage);
        REQUIRE_THAT(error.message(), Catch::Contains(tmp.sub("photos")));
        REQUIRE_THAT(error.message(), Catch::Contains("not an smql database"));
        REQUIRE_FALSE(error.hint().empty());
        REQUIRE_FALSE(std::filesystem::exists(tmp.sub("photos/data.mdb")));  // nothing created in it
    }
    SECTION("a file") {
        std::ofstream(tmp.sub("file")) << "x";
        auto error = openError(tmp.sub("file"));
        REQUIRE_THAT(error.message(), Catch::Contains("is not a directory"));
        REQUIRE_THAT(error.message(), Catch::Contains(tmp.sub("file")));
    }
    SECTION("a data.mdb that is not LMDB") {
        std::filesystem::create_directory(tmp.sub("fake"));
        std::ofstream(tmp.sub("fake/data.mdb")) << std::string(8192, 'z');
        auto error = openError(tmp.sub("fake"));
        REQUIRE_THAT(error.message(), Catch::Contains("not an smql database"));
    }
    SECTION("another program's LMDB database") {
        std::filesystem::create_directory(tmp.sub("other"));
        MDB_env* env = nullptr;
        REQUIRE(mdb_env_create(&env) == 0);
        REQUIRE(mdb_env_open(env, tmp.sub("other").c_str(), 0, 0644) == 0);
        MDB_txn* txn = nullptr;
        REQUIRE(mdb_txn_begin(env, nullptr, 0, &txn) == 0);
        MDB_dbi dbi;
        REQUIRE(mdb_dbi_open(txn, nullptr, 0, &dbi) == 0);
        MDB_val key = toVal("user:1"), value = toVal("alice");
        REQUIRE(mdb_put(txn, dbi, &key, &value, 0) == 0);
        REQUIRE(mdb_txn_commit(txn) == 0);
        mdb_env_close(env);
        auto error = openError(tmp.sub("other"));
        REQUIRE_THAT(error.message(), Catch::Contains("not an smql database"));
        REQUIRE_THAT(error.message(), Catch::Contains("meta"));
    }
    SECTION("a directory it may not read") {
        const std::string locked = tmp.sub("locked");
        Database::open(locked);
        std::filesystem::permissions(tmp.path(),
                                     std::filesystem::perms::owner_all | std::filesystem::perms::others_exec);
        std::filesystem::permissions(locked, std::filesystem::perms::owner_all);
        auto check = [&] {
            auto error = openError(locked);
            return error.kind() == ErrorKind::Storage && error.message().find(locked) != std::string::npos &&
                   error.message().find("Permission denied") != std::string::npos && !error.hint().empty();
        };
        if (::getuid() != 0) {
            std::filesystem::permissions(locked, std::filesystem::perms::none);
            bool refused = check();
            std::filesystem::permissions(locked, std::filesystem::perms::owner_all);
            REQUIRE(refused);
        } else {
            // Root reads everything: check as `nobody` in a child process.
            pid_t child = ::fork();
            REQUIRE(child >= 0);
            if (child == 0) {
                if (::setgid(65534) != 0 || ::setuid(65534) != 0) ::_exit(2);
                try {
                    ::_exit(check() ? 0 : 1);
                } catch (...) {
                    ::_exit(3);
                }
            }
            int status = 0;
            REQUIRE(::waitpid(child, &status, 0) == child);
            REQUIRE(WIFEXITED(status));
            REQUIRE(WEXITSTATUS(status) == 0);
        }
    }
    SECTION("a missing directory when read-only or not creating") {
        REQUIRE_THAT(openError(tmp.sub("missing"), {.readOnly = true}).message(), Catch::Contains("no database at"));
        REQUIRE_THAT(openError(tmp.sub("missing"), {.create = false}).message(), Catch::Contains("no database at"));
        REQUIRE_FALSE(std::filesystem::exists(tmp.sub("missing")));
    }
}

namespace {

// Rewrites the schema version of the database at `path`, as another smql would have written it;
// `dropHistory` also deletes the history table, which databases before version 3 lack.
void setSchemaVersion(const std::string& path, std::uint64_t version, bool dropHistory = false) {
    editTable(path, "meta", [&](MDB_txn* txn, MDB_dbi meta) {
        std::string bytes = codec::encodeU64(version);
        MDB_val key = toVal(kSchemaVersionKey), value = toVal(bytes);
        REQUIRE(mdb_put(txn, meta, &key, &value, 0) == 0);
        if (dropHistory) {
            MDB_dbi history;
            REQUIRE(mdb_dbi_open(txn, "history", 0, &history) == 0);
            REQUIRE(mdb_drop(txn, history, 1) == 0);
        }
    });
}

}  // namespace

TEST_CASE("a database of schema version 2 is upgraded in place by a writable open, not a read-only one",
          "[storage][database]") {
    TempDir tmp;
    {
        auto db = Database::open(tmp.path());
        importCommitted(*db, kitchen());
    }
    setSchemaVersion(tmp.path(), 2, /*dropHistory=*/true);
    auto error = openError(tmp.path(), {.readOnly = true});
    REQUIRE(error.message() == "database " + tmp.path() + " has schema version 2; this smql reads version " +
                                   std::to_string(kSchemaVersion));
    REQUIRE_THAT(error.hint(), Catch::Contains("open it once for writing"));

    auto db = Database::open(tmp.path());
    auto read = db->beginRead();
    REQUIRE(read.sceneByName("kitchen"));
    REQUIRE(read.history("kitchen").empty());
    REQUIRE(Database::open(tmp.path(), {.readOnly = true})->beginRead().sceneByName("kitchen"));
}

TEST_CASE("a database of schema version 1 (records without checksums) is refused with the way forward",
          "[storage][database][errors]") {
    TempDir tmp;
    Database::open(tmp.path());
    setSchemaVersion(tmp.path(), 1);
    auto error = openError(tmp.path());
    REQUIRE(error.message() == "database " + tmp.path() + " has schema version 1; this smql reads version " +
                                   std::to_string(kSchemaVersion));
    REQUIRE_THAT(error.hint(), Catch::Contains("older smql"));
    REQUIRE_THAT(error.hint(), Catch::Contains("smql export json"));
}

TEST_CASE("open refuses another schema version", "[storage][database][errors]") {
    TempDir tmp;
    Database::open(tmp.path());  // a valid database, closed again

    // Rewrite its schema version the way a future smql would.
    MDB_env* env = nullptr;
    REQUIRE(mdb_env_create(&env) == 0);
    REQUIRE(mdb_env_set_maxdbs(env, kMaxTables) == 0);
    REQUIRE(mdb_env_open(env, tmp.path().c_str(), 0, 0644) == 0);
    MDB_txn* txn = nullptr;
    REQUIRE(mdb_txn_begin(env, nullptr, 0, &txn) == 0);
    MDB_dbi meta;
    REQUIRE(mdb_dbi_open(txn, "meta", 0, &meta) == 0);
    std::string seven = codec::encodeU64(7);
    MDB_val key = toVal(kSchemaVersionKey), value = toVal(seven);
    REQUIRE(mdb_put(txn, meta, &key, &value, 0) == 0);
    REQUIRE(mdb_txn_commit(txn) == 0);
    mdb_env_close(env);

    auto error = openError(tmp.path());
    REQUIRE(error.kind() == ErrorKind::Storage);
    REQUIRE(error.message() == "database " + tmp.path() + " has schema version 7; this smql reads version " +
                                   std::to_string(kSchemaVersion));
    REQUIRE_THAT(error.hint(), Catch::Contains("newer smql"));
    REQUIRE_THAT(openError(tmp.path(), {.readOnly = true}).message(), Catch::Contains("schema version 7"));
}

TEST_CASE("two imported scenes read back completely", "[storage][database]") {
    TempDir tmp;
    {
        auto db = Database::open(tmp.path());
        auto txn = db->beginWrite();
        REQUIRE(txn.importScene(kitchen()) == 1);
        REQUIRE(txn.importScene(office()) == 9);
        txn.putSetting("viewpoint", "kitchen");
        txn.putSetting("units", "m");
        txn.putSetting("near.threshold", "0.5");
        txn.commit();
        requireKitchenAndOffice(db->beginRead());
    }
    auto db = Database::open(tmp.path(), {.readOnly = true});
    auto txn = db->beginRead();
    requireKitchenAndOffice(txn);
    REQUIRE(txn.setting("units") == "m");
    REQUIRE_FALSE(txn.setting("colour"));
    REQUIRE_FALSE(txn.setting(""));
    using Settings = std::vector<std::pair<std::string, std::string>>;
    REQUIRE(txn.settings() == Settings{{"near.threshold", "0.5"}, {"units", "m"}, {"viewpoint", "kitchen"}});
}

TEST_CASE("settings are put, replaced and erased", "[storage][database]") {
    TempDir tmp;
    auto db = Database::open(tmp.path());
    {
        auto txn = db->beginWrite();
        txn.putSetting("units", "m");
        txn.putSetting("units", "cm");
        txn.putSetting("a", "");
        txn.eraseSetting("never-set");
        txn.commit();
    }
    REQUIRE(db->beginRead().setting("units") == "cm");
    REQUIRE(db->beginRead().setting("a") == "");
    {
        auto txn = db->beginWrite();
        txn.eraseSetting("units");
        REQUIRE(errorOf([&] { txn.putSetting("", "x"); }).kind() == ErrorKind::Usage);
        txn.commit();
    }
    REQUIRE_FALSE(db->beginRead().setting("units"));
    REQUIRE(db->beginRead().settings().size() == 1);
}

TEST_CASE("a duplicate scene name is rejected and changes nothing", "[storage][database][errors]") {
    TempDir tmp;
    auto db = Database::open(tmp.path());
    importCommitted(*db, kitchen());
    const auto before = db->beginRead().tableStats();

    auto txn = db->beginWrite();
    auto error = errorOf([&] { txn.importScene(kitchen()); });
    REQUIRE(error.kind() == ErrorKind::Input);
    REQUIRE(error.message() == "a scene named 'kitchen' already exists");
    REQUIRE(error.hint() == "choose another name, or remove the stored one first (DROP SCENE)");
    txn.commit();  // the rejected import wrote nothing, so committing the rest changes nothing

    auto read = db->beginRead();
    auto after = read.tableStats();
    for (std::size_t i = 0; i < before.size(); ++i) REQUIRE(after[i].entries == before[i].entries);
    REQUIRE(read.scenes().size() == 1);

    // A duplicate within one transaction is caught too.
    auto second = db->beginWrite();
    second.importScene(office());
    REQUIRE(errorOf([&] { second.importScene(office()); }).kind() == ErrorKind::Input);
}

TEST_CASE("inconsistent local ids are rejected before anything is written", "[storage][database][errors]") {
    TempDir tmp;
    auto db = Database::open(tmp.path());
    importCommitted(*db, office());
    model::SceneData data = kitchen();
    std::string expected;

    SECTION("local id 0") {
        data.nodes[2].id = 0;
        expected = "local id 0";
    }
    SECTION("duplicate local ids") {
        data.nodes[3].id = 20;
        expected = "local id 20 is used by node #2 and node #4";
    }
    SECTION("a parent that is not in the scene") {
        data.nodes[4].parent = 9;  // the office chair's database id, not a local id of the kitchen
        expected = "has parent 9, which is not a node of the scene";
    }
    SECTION("a relation end that is not in the scene") {
        data.relations[1].object = 31;
        expected = "refers to node 31";
    }
    SECTION("a relation frame that is not in the scene") {
        data.relations[2].frame = 71;
        expected = "seen from frame 71";
    }
    SECTION("a parent cycle") {
        data.nodes[0].parent = 40;  // room under mug, which is under table < wall < room
        expected = "form a cycle";
    }
    SECTION("a node that is its own parent") {
        data.nodes[1].parent = 20;
        expected = "form a cycle";
    }
    SECTION("a node of kind scene") {
        data.nodes[1].kind = NodeKind::Scene;
        expected = "has kind scene";
    }
    SECTION("duplicate source ids") {
        data.nodes[1].sourceId = 100;
        expected = "source id 100 is used by node 10 and node 20";
    }
    SECTION("no scene name") {
        data.info.name.clear();
        expected = "a scene needs a name";
    }
    SECTION("a category with a NUL") {
        data.nodes[2].category = std::string("ta\0ble", 6);
        expected = "NUL";
    }

    auto txn = db->beginWrite();
    auto error = errorOf([&] { txn.importScene(data); });
    REQUIRE(error.kind() == ErrorKind::Input);
    REQUIRE_THAT(error.message(), Catch::Contains(expected));
    txn.commit();

    auto read = db->beginRead();
    REQUIRE(read.nodeCount() == 4);
    REQUIRE(read.scenes().size() == 1);
    REQUIRE(entries(read, "labels") == 3);
    REQUIRE(entries(read, "children") == 3);
    REQUIRE(entries(read, "relations") == 2);
    REQUIRE(entries(read, "source_ids") == 1);
    // Next ids are untouched too: the next import starts right after the office.
    REQUIRE(importCommitted(*db, kitchen()) == 5);
}

TEST_CASE("a write transaction destroyed without commit leaves nothing", "[storage][database]") {
    TempDir tmp;
    auto db = Database::open(tmp.path());
    importCommitted(*db, office());
    const auto txnId = db->beginRead().transactionId();
    {
        auto txn = db->beginWrite();
        txn.importScene(kitchen());
        txn.putSetting("units", "m");
        txn.dropScene(1);
    }
    auto read = db->beginRead();
    REQUIRE(read.transactionId() == txnId);
    REQUIRE(read.scenes().size() == 1);
    REQUIRE(read.sceneByName("office"));
    REQUIRE_FALSE(read.sceneByName("kitchen"));
    REQUIRE(read.nodeCount() == 4);
    REQUIRE(read.settings().empty());
    // Its ids were not consumed either.
    REQUIRE(importCommitted(*db, kitchen()) == 5);
}

TEST_CASE("dropScene removes a scene and every index entry of it", "[storage][database]") {
    TempDir tmp;
    auto db = Database::open(tmp.path());
    NodeId kitchenId = importCommitted(*db, kitchen());
    NodeId officeId = importCommitted(*db, office());
    {
        auto txn = db->beginWrite();
        txn.dropScene(kitchenId);
        auto error = errorOf([&] { txn.dropScene(424242); });
        REQUIRE(error.kind() == ErrorKind::Binding);
        REQUIRE_THAT(error.message(), Catch::Contains("424242"));
        txn.commit();
    }
    {
        auto read = db->beginRead();
        REQUIRE(read.scenes().size() == 1);
        REQUIRE_FALSE(read.sceneByName("kitchen"));
        REQUIRE_FALSE(read.scene(kitchenId));
        for (NodeId id = kitchenId; id < officeId; ++id) {
            REQUIRE_FALSE(read.node(id));
            REQUIRE(read.children(id).empty());
            REQUIRE(read.relationsOf(id).empty());
        }
        REQUIRE(read.nodeCount() == 4);
        using Categories = std::vector<std::pair<std::string, std::uint64_t>>;
        REQUIRE(read.categories() == Categories{{"chair", 1}, {"mug", 1}, {"room", 1}});
        REQUIRE(read.nodesWithCategory("mug") == std::vector<NodeId>{officeId + 3});
        REQUIRE_FALSE(read.nodeBySourceId(kitchenId, 100));
        REQUIRE(read.nodeBySourceId(officeId, 100) == officeId + 1);
        REQUIRE(entries(read, "labels") == 3);
        REQUIRE(entries(read, "children") == 3);
        REQUIRE(entries(read, "relations") == 2);
        REQUIRE(entries(read, "source_ids") == 1);
        REQUIRE(entries(read, "scene_names") == 1);
        REQUIRE(relationsIn(read, officeId).size() == 1);
        REQUIRE(nodesOf(read, officeId).size() == 4);
    }
    // The name is free again; ids are never reused.
    NodeId again = importCommitted(*db, kitchen());
    REQUIRE(again > officeId);
    REQUIRE(db->beginRead().nodesWithCategory("mug", again) == std::vector<NodeId>{again + 4, again + 5});
}

TEST_CASE("a large scene keeps many children and relations under one key", "[storage][database]") {
    TempDir tmp;
    auto db = Database::open(tmp.path());
    auto data = largeScene("big", 12000);
    NodeId sceneId = importCommitted(*db, data);
    auto read = db->beginRead();
    const NodeId room = sceneId + 1;

    auto children = read.children(room);
    REQUIRE(children.size() == 3000);
    for (std::size_t i = 0; i < children.size(); ++i) REQUIRE(children[i] == room + 1 + i);
    REQUIRE(read.children(room + 1) == std::vector<NodeId>{room + 3001});

    auto relations = read.relationsOf(room + 1);
    REQUIRE(relations.size() == 2000);
    for (std::size_t i = 0; i < relations.size(); ++i) {
        REQUIRE(relations[i].subject == room + 1);
        REQUIRE(relations[i].object == room + 2 + i);
    }
    std::size_t inScene = 0;
    read.forEachRelationInScene(sceneId, [&](const model::Relation& r) {
        REQUIRE(r.subject == room + 1);
        ++inScene;
    });
    REQUIRE(inScene == 2000);

    auto chairs = read.nodesWithCategory("chair");
    REQUIRE(chairs.size() == countCategory(data, "chair"));
    REQUIRE(std::is_sorted(chairs.begin(), chairs.end()));
    REQUIRE(read.nodesWithCategory("chair", sceneId) == chairs);
    REQUIRE(read.nodeBySourceId(sceneId, 11990) == sceneId + 1199);
    REQUIRE(read.node(sceneId + 12000)->text == "object number 12000");
}

TEST_CASE("read transactions are snapshots", "[storage][database][mvcc]") {
    TempDir tmp;
    auto db = Database::open(tmp.path());
    auto before = db->beginRead();
    const auto beforeId = before.transactionId();
    NodeId kitchenId = importCommitted(*db, kitchen());

    REQUIRE_FALSE(before.sceneByName("kitchen"));
    REQUIRE(before.nodeCount() == 0);
    REQUIRE(before.nodesWithCategory("mug").empty());
    REQUIRE(before.transactionId() == beforeId);

    auto after = db->beginRead();
    REQUIRE(after.transactionId() > beforeId);
    REQUIRE(after.sceneByName("kitchen"));

    {
        auto txn = db->beginWrite();
        txn.dropScene(kitchenId);
        txn.commit();
    }
    // `after` still sees the dropped scene, from another thread too (MDB_NOTLS).
    std::size_t seen = 0;
    std::thread([&] { seen = after.nodesWithCategory("mug").size(); }).join();
    REQUIRE(seen == 2);
    REQUIRE(after.node(kitchenId + 3));
    REQUIRE(db->beginRead().nodeCount() == 0);

    // A moved transaction keeps its snapshot.
    ReadTransaction moved = std::move(after);
    REQUIRE(moved.sceneByName("kitchen"));
}

TEST_CASE("a read transaction's cursors, handed on to the next one, read that one's snapshot",
          "[storage][database][mvcc]") {
    TempDir tmp;
    auto db = Database::open(tmp.path());
    const NodeId kitchenId = importCommitted(*db, kitchen());
    auto categoryRows = [](const ReadTransaction& read, const std::string& category) {
        std::vector<NodeId> ids;
        read.forEachCategoryRow({category}, 100, [&](const CategoryRow& row) { ids.push_back(row.id); });
        return ids;
    };
    {
        // Opens the label index's and the nodes' cursors; they go back to the pool with the transaction.
        auto read = db->beginRead();
        REQUIRE(read.nodesWithCategory("mug") == std::vector<NodeId>{kitchenId + 4, kitchenId + 5});
        REQUIRE(read.node(kitchenId + 3)->category == "table");
    }
    {
        auto txn = db->beginWrite();
        txn.dropScene(kitchenId);
        txn.commit();
    }
    const NodeId officeId = importCommitted(*db, office());
    {
        // The pooled transaction and its cursors, renewed: the kitchen is gone, the office is there.
        auto renewed = db->beginRead();
        REQUIRE(renewed.nodesWithCategory("mug") == std::vector<NodeId>{officeId + 3});
        REQUIRE_FALSE(renewed.node(kitchenId + 3));
        REQUIRE(categoryRows(renewed, "chair") == std::vector<NodeId>{officeId + 2});
        // A second reader while the first is open: a transaction of its own, not the pooled one.
        auto second = db->beginRead();
        REQUIRE(second.nodesWithCategory("mug") == renewed.nodesWithCategory("mug"));
        REQUIRE(categoryRows(second, "table").empty());
    }
    // Both pooled now, each with its cursors: two readers at once, after another write.
    importCommitted(*db, kitchen());
    auto first = db->beginRead();
    auto second = db->beginRead();
    REQUIRE(first.nodesWithCategory("mug").size() == 3);
    REQUIRE(second.nodesWithCategory("mug") == first.nodesWithCategory("mug"));
    REQUIRE(categoryRows(first, "table") == categoryRows(second, "table"));
    REQUIRE(categoryRows(first, "table").size() == 1);
}

TEST_CASE("blobs are stored with their scene, listed per node and dropped with it") {
    TempDir dir;
    auto db = Database::open(dir.path());
    model::SceneData scene = oneNodeScene("with-evidence", "mug");
    std::string jpeg("\xff\xd8\xff\xe0 not really a jpeg \0 with a zero", 32);
    scene.blobs.push_back({1, "evidence-1.jpg", "image/jpeg", jpeg});
    scene.blobs.push_back({1, "evidence-2.jpg", "image/jpeg", "xyz"});
    const model::NodeId sceneId = importCommitted(*db, scene);
    model::NodeId mugId = sceneId + 1;
    {
        auto read = db->beginRead();
        auto list = read.blobsOf(mugId);
        REQUIRE(list.size() == 2);
        CHECK(list[0].name == "evidence-1.jpg");
        CHECK(list[0].mediaType == "image/jpeg");
        CHECK(list[0].size == jpeg.size());
        auto blob = read.blob(mugId, "evidence-1.jpg");
        REQUIRE(blob);
        CHECK(blob->bytes == jpeg);
        CHECK(blob->node == mugId);
        CHECK_FALSE(read.blob(mugId, "missing.jpg"));
        CHECK(read.blobsOf(sceneId).empty());
    }
    // A blob of a node that is not in the scene, or a duplicate name, is rejected before any write.
    auto bad = scene;
    bad.info.name = "bad";
    bad.blobs.push_back({7, "x.jpg", "image/jpeg", "x"});
    {
        auto write = db->beginWrite();
        CHECK_THROWS_AS(write.importScene(bad), Error);
    }
    bad.blobs.back() = {1, "evidence-1.jpg", "image/jpeg", "again"};
    {
        auto write = db->beginWrite();
        CHECK_THROWS_AS(write.importScene(bad), Error);
    }
    {
        auto write = db->beginWrite();
        write.dropScene(sceneId);
        write.commit();
    }
    CHECK(db->beginRead().blobsOf(mugId).empty());
}

TEST_CASE("updateNodes rewrites attributes in place and bumps the scene version") {
    TempDir dir;
    auto db = Database::open(dir.path());
    model::SceneData scene = oneNodeScene("updated", "mug");
    scene.nodes[0].attributes = {{"last_seen_at", "2026-01-01"}};
    const model::NodeId sceneId = importCommitted(*db, scene);
    auto before = db->beginRead().scene(sceneId)->version;
    auto stored = *db->beginRead().node(sceneId + 1);
    stored.attributes = {{"last_seen_at", "2026-02-01"}};
    {
        auto write = db->beginWrite();
        write.updateNodes({stored});
        write.commit();
    }
    auto read = db->beginRead();
    CHECK(*read.node(sceneId + 1)->attribute("last_seen_at") == "2026-02-01");
    CHECK(read.scene(sceneId)->version == before + 1);
    CHECK(read.nodesWithCategory("mug").size() == 1);
    // A changed category (an indexed field) or a missing node is refused, and nothing is written.
    auto renamed = stored;
    renamed.category = "cup";
    renamed.attributes = {{"last_seen_at", "2026-03-01"}};
    auto missing = stored;
    missing.id = 999;
    {
        auto write = db->beginWrite();
        CHECK_THROWS_AS(write.updateNodes({renamed}), Error);
        CHECK_THROWS_AS(write.updateNodes({stored, missing}), Error);
    }
    CHECK(*db->beginRead().node(sceneId + 1)->attribute("last_seen_at") == "2026-02-01");
    // So is a box that no spatial query could place.
    auto unplaced = stored;
    unplaced.box.center.y = std::numeric_limits<double>::infinity();
    {
        auto write = db->beginWrite();
        CHECK_THROWS_WITH(write.updateNodes({unplaced}), Catch::Contains("node #") && Catch::Contains("finite"));
    }
    CHECK(db->beginRead().node(sceneId + 1)->box == stored.box);
}

TEST_CASE("a scene whose box holds a NaN or an infinity is refused, and nothing is written", "[storage]") {
    TempDir dir;
    auto db = Database::open(dir.path());
    model::SceneData scene = oneNodeScene("unplaced", "table");
    model::Node table = scene.nodes[0];
    table.geometry = model::GeometryKind::Box;
    table.box = {{1, 2, 0.4}, {1.2, 0.8, 0.75}, 0};
    model::Node lamp = table;
    lamp.id = 2;
    lamp.category = "lamp";
    for (double* field : {&lamp.box.center.x, &lamp.box.size.z, &lamp.box.yaw})
        for (double bad : {std::nan(""), -std::numeric_limits<double>::infinity()}) {
            const double kept = *field;
            *field = bad;
            scene.nodes = {table, lamp};
            {
                auto write = db->beginWrite();
                CHECK_THROWS_WITH(write.importScene(scene),
                                  Catch::Contains("scene 'unplaced': node 2") && Catch::Contains("finite"));
            }
            *field = kept;
        }
    CHECK(db->beginRead().scenes().empty());
}
