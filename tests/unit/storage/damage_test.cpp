// Damaged database files: every kind of damage is a clear smql::Error at
// open or on the read that meets it, never a crash and never an answer.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <optional>

#include "model/error.hpp"
#include "storage/codec.hpp"
#include "storage/database.hpp"
#include "storage_test_support.hpp"

using namespace smql;
using namespace smql::storage;
using namespace smql::storage::testing;

namespace {

namespace fs = std::filesystem;

// Runs `body` in a forked child and returns its wait status, so a crash
// (SIGBUS from a page past the end of the file) fails the test instead of
// killing the test binary.
template <class Body>
int inChild(Body&& body) {
    pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
        try {
            ::_exit(body() ? 0 : 1);
        } catch (...) {
            ::_exit(3);
        }
    }
    int status = 0;
    REQUIRE(::waitpid(child, &status, 0) == child);
    return status;
}

std::string openErrorMessage(const std::string& path, const OpenOptions& options) {
    try {
        auto db = Database::open(path, options);
        db->beginRead().scenes();
    } catch (const Error& e) {
        return e.message() + " | " + e.hint();
    }
    return "no error";
}

void makeDatabase(const std::string& path, std::size_t nodes) {
    auto db = Database::open(path);
    auto txn = db->beginWrite();
    txn.importScene(largeScene("big", nodes));
    txn.commit();
}

}  // namespace

TEST_CASE("a data.mdb cut short is reported as damaged instead of crashing", "[storage][damage]") {
    TempDir tmp;
    const std::string path = tmp.sub("db");
    makeDatabase(path, 5000);
    const auto data = fs::path(path) / "data.mdb";
    const auto size = fs::file_size(data);
    REQUIRE(size > 64 * 4096);
    fs::resize_file(data, size / 2);

    for (bool readOnly : {false, true}) {
        CAPTURE(readOnly);
        int status = inChild([&] {
            std::string message = openErrorMessage(path, {.readOnly = readOnly, .create = false});
            return message.find("database " + path + " is damaged") != std::string::npos &&
                   message.find("cut short") != std::string::npos && message.find("backup") != std::string::npos;
        });
        REQUIRE(WIFEXITED(status));
        REQUIRE(WEXITSTATUS(status) == 0);
    }
    REQUIRE(fs::file_size(data) == size / 2);  // the refused open changed nothing
}

TEST_CASE("a data.mdb truncated to 0 bytes is never re-created in place", "[storage][damage]") {
    TempDir tmp;
    const std::string path = tmp.sub("db");
    makeDatabase(path, 10);
    fs::resize_file(fs::path(path) / "data.mdb", 0);

    for (bool readOnly : {false, true}) {
        CAPTURE(readOnly);
        std::string message = openErrorMessage(path, {.readOnly = readOnly, .create = true});
        REQUIRE_THAT(message, Catch::Contains("database " + path + " is damaged"));
        REQUIRE_THAT(message, Catch::Contains("data.mdb is empty"));
        REQUIRE(fs::file_size(fs::path(path) / "data.mdb") == 0);
    }
}

TEST_CASE("only an absent directory, or an empty one, makes a new database", "[storage][damage]") {
    TempDir tmp;
    SECTION("an absent directory is created when asked to") {
        Database::open(tmp.sub("new"), {.create = true});
        REQUIRE(fs::is_regular_file(tmp.sub("new/data.mdb")));
    }
    SECTION("an absent directory is not created without the create flag") {
        REQUIRE_THAT(openErrorMessage(tmp.sub("new"), {.create = false}), Catch::Contains("no database at"));
        REQUIRE_FALSE(fs::exists(tmp.sub("new")));
    }
    SECTION("an empty directory is initialised") {
        fs::create_directory(tmp.sub("empty"));
        Database::open(tmp.sub("empty"));
        REQUIRE(fs::is_regular_file(tmp.sub("empty/data.mdb")));
    }
}

namespace {

// Flips one bit of `record` where it sits in data.mdb (records are stored
// whole on their leaf page); returns false when the bytes are not found once.
bool flipInFile(const std::string& path, const std::string& record, std::size_t offsetInRecord) {
    std::string file;
    {
        std::ifstream in(fs::path(path) / "data.mdb", std::ios::binary);
        file.assign(std::istreambuf_iterator<char>(in), {});
    }
    auto at = file.find(record);
    if (at == std::string::npos || file.find(record, at + 1) != std::string::npos) return false;
    std::fstream out(fs::path(path) / "data.mdb", std::ios::binary | std::ios::in | std::ios::out);
    out.seekp(static_cast<std::streamoff>(at + offsetInRecord));
    out.put(static_cast<char>(record[offsetInRecord] ^ 0x04));
    return bool(out);
}

std::string errorOf(const std::function<void()>& read) {
    try {
        read();
    } catch (const Error& e) {
        REQUIRE(e.kind() == ErrorKind::Storage);
        REQUIRE_FALSE(e.hint().empty());
        return e.message();
    }
    return "no error";
}

// makeDatabase's scene "big" of 100 nodes in a new folder, with its id and its node 57 (a lamp),
// read before anything is damaged.
struct BigScene {
    TempDir tmp;
    std::string path = tmp.sub("db");
    model::NodeId sceneId = 0;
    model::Node victim;
    BigScene() {
        makeDatabase(path, 100);
        auto db = Database::open(path);
        auto txn = db->beginRead();
        sceneId = txn.sceneByName("big")->id;
        victim = *txn.node(sceneId + 57);
    }
};

}  // namespace

TEST_CASE("a byte flipped in a stored record is reported with its scene, never answered", "[storage][damage]") {
    const BigScene big;
    REQUIRE(big.victim.text == "object number 57");
    std::string record;
    codec::encodeNode(big.victim, record);

    SECTION("in a node's text") {
        // "object number 57" would read as "object number 37" without the checksum.
        REQUIRE(flipInFile(big.path, record, record.find("57")));
    }
    SECTION("in a node's box") {
        REQUIRE(flipInFile(big.path, record, 24 + 8 + 3));  // after the header and source id: the centre's x
    }

    auto db = Database::open(big.path);
    auto txn = db->beginRead();
    const std::string expected = "corrupt record in scene 'big' of database " + big.path + ": node record for id " +
                                 std::to_string(big.victim.id) + ": checksum mismatch";
    REQUIRE_THAT(errorOf([&] { txn.node(big.victim.id); }), Catch::StartsWith(expected));
    REQUIRE_THAT(errorOf([&] { txn.forEachNodeInScene(big.sceneId, [](const model::Node&) {}); }),
                 Catch::StartsWith(expected));
    // The records around it are intact and still read.
    REQUIRE(txn.node(big.victim.id - 1)->text == "object number 56");
    REQUIRE(txn.node(big.victim.id + 1)->text == "object number 58");
}

TEST_CASE("a byte flipped in a label entry is reported when a search across scenes reaches it", "[storage][damage]") {
    const BigScene big;
    // The 20 lamps' entries share one page, their checksums computed four at a time: the victim is
    // the 12th.
    REQUIRE(big.victim.category == "lamp");
    const codec::LabelEntry entry = codec::labelEntry("lamp", big.sceneId, big.victim.id, big.victim);
    REQUIRE(flipInFile(big.path, std::string(reinterpret_cast<const char*>(entry.data()), entry.size()), 27 + 3));

    auto db = Database::open(big.path);
    auto txn = db->beginRead();
    REQUIRE_THAT(errorOf([&] { txn.forEachCategoryRow({"lamp"}, 1000, [](const CategoryRow&) {}); }),
                 Catch::StartsWith("corrupt record in scene 'big' of database " + big.path +
                                   ": label index entry under 'lamp': checksum mismatch"));
    // A search that stops before it answers, and the node's own record is intact.
    std::vector<model::NodeId> ids;
    txn.forEachCategoryRow({"lamp"}, 8, [&](const CategoryRow& row) { ids.push_back(row.id); });
    CHECK(ids.size() == 8);
    CHECK(txn.node(big.victim.id)->text == big.victim.text);
}

TEST_CASE("a damaged scene record is named through its scene node", "[storage][damage]") {
    TempDir tmp;
    const std::string path = tmp.sub("db");
    makeDatabase(path, 10);
    std::string record;
    {
        auto db = Database::open(path);
        codec::encodeScene(*db->beginRead().sceneByName("big"), record);
    }
    REQUIRE(flipInFile(path, record, record.find("test:large")));
    auto db = Database::open(path);
    auto txn = db->beginRead();
    REQUIRE_THAT(errorOf([&] { txn.scenes(); }), Catch::StartsWith("corrupt record in scene 'big'"));
    REQUIRE_THAT(errorOf([&] { txn.sceneByName("big"); }), Catch::Contains("scene record for id 1: checksum mismatch"));
}

TEST_CASE("a write under a lock file removed while the database was open is refused", "[storage][lockfile]") {
    TempDir tmp;
    const std::string path = tmp.sub("db");
    makeDatabase(path, 10);
    auto db = Database::open(path);

    // A transaction begun under the original lock file...
    std::optional<WriteTransaction> write(db->beginWrite());
    write->importScene(largeScene("from-the-first-process", 20));
    fs::remove(fs::path(path) / "lock.mdb");

    // ...then another process opens the database: LMDB makes a new lock file,
    // whose writer mutex knows nothing of the first process's transaction.
    int status = inChild([&] {
        auto other = Database::open(path);
        auto txn = other->beginWrite();
        txn.importScene(largeScene("from-the-second-process", 20));
        txn.commit();
        return true;
    });
    REQUIRE(WIFEXITED(status));
    REQUIRE(WEXITSTATUS(status) == 0);

    auto refused = [&](const std::function<void()>& step, const std::string& operation) {
        try {
            step();
        } catch (const Error& e) {
            REQUIRE(e.kind() == ErrorKind::Storage);
            REQUIRE_THAT(e.message(), Catch::StartsWith(operation + " refused on database " + path));
            REQUIRE_THAT(e.message(), Catch::Contains("lock.mdb was removed"));
            REQUIRE_THAT(e.hint(), Catch::Contains("close every process"));
            return true;
        }
        return false;
    };
    // Committing would write a meta page based on a snapshot that lacks the
    // second process's scene: that scene would be lost.
    REQUIRE(refused([&] { write->commit(); }, "committing"));
    write.reset();  // the refused transaction still holds the (old) writer lock until it is destroyed
    REQUIRE(refused([&] { db->beginWrite(); }, "beginning a write transaction"));

    // Reopened (under the new lock file, whose reader table has the latest commit),
    // the database holds the second process's scene and nothing of the refused one.
    db.reset();
    db = Database::open(path);
    auto txn = db->beginRead();
    REQUIRE(txn.sceneByName("from-the-second-process"));
    REQUIRE_FALSE(txn.sceneByName("from-the-first-process"));
    REQUIRE(txn.sceneByName("big"));
}

TEST_CASE("a lock file replaced while the database was open is noticed too", "[storage][lockfile]") {
    TempDir tmp;
    const std::string path = tmp.sub("db");
    makeDatabase(path, 10);
    auto db = Database::open(path);
    fs::copy_file(fs::path(path) / "lock.mdb", tmp.sub("lock-copy"));
    fs::rename(tmp.sub("lock-copy"), fs::path(path) / "lock.mdb");
    REQUIRE_THAT(errorOf([&] { db->beginWrite(); }), Catch::Contains("lock.mdb was removed or replaced"));
    REQUIRE(db->beginRead().sceneByName("big"));  // reading goes on
}
