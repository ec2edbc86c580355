// storage::checkDatabase (`smql check DB`): a sound database passes, and each
// kind of damage is reported as a problem naming where it is.
#include <catch2/catch.hpp>

#include <lmdb.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "storage/check.hpp"
#include "storage/codec.hpp"
#include "storage/database.hpp"
#include "storage/lmdb_env.hpp"
#include "storage_test_support.hpp"

using namespace smql;
using namespace smql::storage;
using namespace smql::storage::testing;

namespace {

namespace fs = std::filesystem;

void makeDatabase(const std::string& path) {
    auto db = Database::open(path);
    auto txn = db->beginWrite();
    auto data = largeScene("big", 300);
    data.blobs.push_back({5, "crop.jpg", "image/jpeg", std::string(100, 'j')});
    txn.importScene(data);
    txn.importScene(largeScene("small", 20));
    txn.commit();
}

// Deletes one entry straight through LMDB, as damage or a bug elsewhere would.
void deleteEntry(const std::string& path, const char* table, std::string_view key,
                 std::optional<std::string_view> value) {
    editTable(path, table, [&](MDB_txn* txn, MDB_dbi dbi) {
        MDB_val k = toVal(key), v;
        if (value) v = toVal(*value);
        REQUIRE(mdb_del(txn, dbi, &k, value ? &v : nullptr) == 0);
    });
}

// Moves one entry to another key straight through LMDB, as a bit flipped in its key would.
void moveEntry(const std::string& path, const char* table, const std::string& from, const std::string& to) {
    editTable(path, table, [&](MDB_txn* txn, MDB_dbi dbi) {
        MDB_val k = toVal(from), v;
        REQUIRE(mdb_get(txn, dbi, &k, &v) == 0);
        std::string value(static_cast<const char*>(v.mv_data), v.mv_size);
        MDB_val target = toVal(to), moved = toVal(value);
        REQUIRE(mdb_put(txn, dbi, &target, &moved, 0) == 0);
        REQUIRE(mdb_del(txn, dbi, &k, nullptr) == 0);
    });
}

std::string keyOf(model::NodeId id) {
    auto key = codec::idKey(id);
    return {reinterpret_cast<const char*>(key.data()), key.size()};
}

bool reported(const CheckReport& report, const std::string& part) {
    for (const auto& problem : report.problems)
        if (problem.find(part) != std::string::npos) return true;
    return false;
}

}  // namespace

TEST_CASE("a sound database passes the check", "[storage][check]") {
    TempDir tmp;
    makeDatabase(tmp.sub("db"));
    auto report = checkDatabase(tmp.sub("db"));
    INFO((report.problems.empty() ? std::string() : report.problems.front()));
    REQUIRE(report.ok());
    REQUIRE(report.scenes == 2);
    REQUIRE(report.nodes == 300 + 20);  // each scene's own node not counted, as SHOW SCENES counts
    REQUIRE(report.relations == 298 + 18);
    REQUIRE(report.blobs == 1);
}

TEST_CASE("the check reports each kind of damage", "[storage][check]") {
    TempDir tmp;
    const std::string path = tmp.sub("db");
    makeDatabase(path);
    model::NodeId big = 0;
    {
        auto db = Database::open(path);
        big = db->beginRead().sceneByName("big")->id;
    }

    SECTION("a record with a flipped byte") {
        model::Node node;
        {
            auto db = Database::open(path);
            node = *db->beginRead().node(big + 40);
        }
        std::string record;
        codec::encodeNode(node, record);
        std::string file;
        {
            std::ifstream in(fs::path(path) / "data.mdb", std::ios::binary);
            file.assign(std::istreambuf_iterator<char>(in), {});
        }
        auto at = file.find(record);
        REQUIRE(at != std::string::npos);
        std::fstream out(fs::path(path) / "data.mdb", std::ios::binary | std::ios::in | std::ios::out);
        out.seekp(static_cast<std::streamoff>(at + record.size() - 8));
        out.put(static_cast<char>(record[record.size() - 8] ^ 1));
        out.close();
        auto report = checkDatabase(path);
        REQUIRE_FALSE(report.ok());
        REQUIRE(reported(report, "corrupt record in scene 'big'"));
        REQUIRE(reported(report, "node record for id " + std::to_string(node.id)));
    }
    SECTION("a missing label entry") {
        std::string category;
        codec::LabelEntry entry;
        {
            auto db = Database::open(path);
            auto node = *db->beginRead().node(big + 7);
            category = node.category;
            entry = codec::labelEntry(category, big, big + 7, node);
        }
        deleteEntry(path, "labels", category,
                    std::string_view(reinterpret_cast<const char*>(entry.data()), entry.size()));
        auto report = checkDatabase(path);
        REQUIRE(reported(report, "scene 'big' (#" + std::to_string(big) + "): the label index for '" + category + "'"));
        REQUIRE(reported(report, "table labels holds"));
    }
    SECTION("a missing node record") {
        // The room (the scene's first node after the scene node): every object hangs below it.
        deleteEntry(path, "nodes", keyOf(big + 1), std::nullopt);
        auto report = checkDatabase(path);
        REQUIRE(reported(report, "the scene record counts 300 nodes, the node table holds 299"));
        REQUIRE(reported(report, "node #" + std::to_string(big + 2) + " has parent #" + std::to_string(big + 1) +
                                     ", which is not a node of the scene"));
    }
    SECTION("a relation stored under one end only") {
        std::vector<model::Relation> relations;
        {
            auto db = Database::open(path);
            relations = db->beginRead().relationsOf(big + 3);
        }
        REQUIRE_FALSE(relations.empty());
        const auto& r = relations.front();
        auto entry = codec::encodeRelationEntry(r, codec::RelationSide::Object);
        deleteEntry(path, "relations", keyOf(r.object),
                    std::string_view(reinterpret_cast<const char*>(entry.data()), entry.size()));
        auto report = checkDatabase(path);
        REQUIRE(reported(report, "is stored under its subject only"));
        // A read of the scene's relations fails rather than answer with some of them.
        auto db = Database::open(path, {.readOnly = true, .create = false});
        REQUIRE_THROWS_WITH(db->beginRead().forEachRelationInScene(big, [](const model::Relation&) {}),
                            Catch::Contains("relations of scene 'big'") && Catch::Contains("are damaged"));
    }
    SECTION("a blob whose key names a node that is not there") {
        // The crop of the big scene's node 5 (local), moved to an id no node has.
        auto report = checkDatabase(path);
        REQUIRE(report.blobs == 1);
        moveEntry(path, "blobs", codec::blobKey(big + 5, "crop.jpg"), codec::blobKey(big + 100000, "crop.jpg"));
        report = checkDatabase(path);
        REQUIRE(report.blobs == 0);
        REQUIRE(reported(report, "table blobs holds 1 entries, the scenes account for 0"));
    }
    SECTION("leaf pages' node pointers flipped: reported from the pages, never given to LMDB") {
        const fs::path file = fs::path(path) / "data.mdb";
        std::string bytes;
        {
            std::ifstream in(file, std::ios::binary);
            bytes.assign(std::istreambuf_iterator<char>(in), {});
        }
        // The first node pointer of every leaf page (free ones too) now points past the page's end.
        const std::size_t page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
        std::size_t leaves = 0;
        for (std::size_t p = 2; (p + 1) * page <= bytes.size(); ++p)
            if ((static_cast<unsigned char>(bytes[p * page + 10]) & 0x22) == 0x02 &&
                static_cast<unsigned char>(bytes[p * page + 12]) > 18) {
                bytes[p * page + 17] = static_cast<char>(0x7F);
                ++leaves;
            }
        REQUIRE(leaves > 0);
        std::ofstream(file, std::ios::binary) << bytes;
        auto report = checkDatabase(path);
        REQUIRE(reported(report, "(LMDB's own structure) is damaged: node 0 lies outside it"));
    }
    SECTION("a data file cut short") {
        fs::resize_file(fs::path(path) / "data.mdb", fs::file_size(fs::path(path) / "data.mdb") / 2);
        auto report = checkDatabase(path);
        REQUIRE(report.problems.size() == 1);
        REQUIRE_THAT(report.problems.front(), Catch::Contains("cut short"));
    }
}

TEST_CASE("the check names a process that has the database open under a removed lock file", "[storage][check]") {
    TempDir tmp;
    const std::string path = tmp.sub("db");
    makeDatabase(path);
    int ready[2];
    REQUIRE(::pipe(ready) == 0);
    pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
        ::close(ready[0]);
        try {
            auto db = Database::open(path);
            db->beginRead().scenes();
            char c = 'r';
            if (::write(ready[1], &c, 1) != 1) ::_exit(2);
            ::pause();
        } catch (...) {
            ::_exit(3);
        }
        ::_exit(0);
    }
    // A failed REQUIRE below must not leave the child waiting (and ctest waiting on its output).
    struct KillOnExit {
        pid_t pid;
        ~KillOnExit() {
            if (pid > 0) ::kill(pid, SIGKILL), ::waitpid(pid, nullptr, 0);
        }
    } guard{child};
    ::close(ready[1]);
    char c = 0;
    REQUIRE(::read(ready[0], &c, 1) == 1);
    ::close(ready[0]);

    REQUIRE(checkDatabase(path).ok());  // the child uses the current lock file
    fs::remove(fs::path(path) / "lock.mdb");
    auto report = checkDatabase(path);
    ::kill(child, SIGKILL);
    ::waitpid(child, nullptr, 0);
    guard.pid = 0;

    REQUIRE(reported(report, "lock.mdb: process " + std::to_string(child) + " has the database open under"));
    REQUIRE(reported(report, "(deleted)"));
    // With that process gone, the new lock file is the only one: nothing to report.
    REQUIRE(checkDatabase(path).ok());
}

TEST_CASE("a branch key flipped is reported from the pages, not met as a blob that is silently not found",
          "[storage][check]") {
    TempDir tmp;
    const std::string path = tmp.sub("db");
    // Blobs enough for the blobs table to need branch pages: 320 of 300 bytes, two dozen leaves.
    const std::string name = "evidence-00.jpg";
    {
        auto data = largeScene("crops", 41);
        for (model::NodeId node = 2; node <= 41; ++node)
            for (char i = '0'; i < '8'; ++i) {
                std::string blobName = name;
                blobName[10] = i;
                data.blobs.push_back({node, blobName, "image/jpeg", std::string(300, 'j')});
            }
        auto db = Database::open(path);
        importCommitted(*db, data);
    }
    REQUIRE(checkDatabase(path).ok());

    // The second key of each branch page of the blobs table (keys of a node id and a blob name),
    // raised past the first key of the child it starts: searches for the keys between the two now
    // end in the child before, where they are not.
    const fs::path file = fs::path(path) / "data.mdb";
    std::string bytes;
    {
        std::ifstream in(file, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    const std::size_t page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
    auto u16 = [&](std::size_t at) {
        return static_cast<std::size_t>(static_cast<unsigned char>(bytes[at]) |
                                        static_cast<unsigned char>(bytes[at + 1]) << 8);
    };
    std::size_t branches = 0;
    for (std::size_t p = 2; (p + 1) * page <= bytes.size(); ++p) {
        const std::size_t base = p * page;
        if ((u16(base + 10) & 0x01) == 0 || u16(base + 12) < 16 + 2 * 2) continue;
        const std::size_t node = base + u16(base + 16 + 2);
        if (u16(node + 6) != 8 + name.size()) continue;
        bytes[node + 8 + 8 + name.size() - 1] |= static_cast<char>(0x80);
        ++branches;
    }
    REQUIRE(branches > 0);
    std::ofstream(file, std::ios::binary) << bytes;
    auto report = checkDatabase(path);
    REQUIRE_FALSE(report.ok());
    REQUIRE(report.pagesDamaged);  // a salvage says its copy is as LMDB's searches read it
    REQUIRE(
        reported(report, "(LMDB's own structure) is damaged: key 0 lies outside the range its parent page gives it"));
}
