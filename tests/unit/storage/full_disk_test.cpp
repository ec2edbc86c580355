// A full file system: creating a database or writing to one says "no space
// left on device" and leaves nothing behind. Runs on a small tmpfs mounted
// for the test; skipped (with a warning) where mounting is not permitted.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sys/mount.h>
#include <sys/statvfs.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>

#include "model/error.hpp"
#include "storage/check.hpp"
#include "storage/database.hpp"
#include "storage_test_support.hpp"

using namespace smql;
using namespace smql::storage;
using namespace smql::storage::testing;

namespace {

namespace fs = std::filesystem;

// A tmpfs of `bytes` on a fresh temp directory, unmounted at the end.
class SmallFileSystem {
public:
    explicit SmallFileSystem(std::size_t bytes) {
        const std::string options = "size=" + std::to_string(bytes);
        mounted_ = ::mount("tmpfs", tmp_.path().c_str(), "tmpfs", 0, options.c_str()) == 0;
    }
    ~SmallFileSystem() {
        if (mounted_) ::umount2(tmp_.path().c_str(), MNT_DETACH);
    }
    bool mounted() const { return mounted_; }
    std::string sub(const std::string& name) const { return tmp_.sub(name); }

    // Takes all free space but `keep` bytes with a file of really allocated blocks.
    void fillLeaving(std::uint64_t keep) {
        struct statvfs info {};
        REQUIRE(::statvfs(tmp_.path().c_str(), &info) == 0);
        const std::uint64_t free = std::uint64_t(info.f_bavail) * info.f_frsize;
        REQUIRE(free > keep);
        int fd = ::open(sub("filler").c_str(), O_CREAT | O_WRONLY, 0644);
        REQUIRE(fd >= 0);
        REQUIRE(::posix_fallocate(fd, 0, static_cast<off_t>(free - keep)) == 0);
        ::close(fd);
    }
    void makeRoom() { fs::remove(sub("filler")); }

private:
    TempDir tmp_;
    bool mounted_ = false;
};

std::string messageAndHintOf(const std::function<void()>& step) {
    try {
        step();
    } catch (const Error& e) {
        REQUIRE(e.kind() == ErrorKind::Storage);
        return e.message() + " | " + e.hint();
    }
    return "no error";
}

}  // namespace

TEST_CASE("creating a database on a full file system is refused and leaves nothing", "[storage][full]") {
    SmallFileSystem disk(4 << 20);
    if (!disk.mounted()) {
        WARN("skipped: mounting a tmpfs is not permitted here (needs root or CAP_SYS_ADMIN)");
        return;
    }
    const std::uint64_t keep = GENERATE(0u, 64u << 10, 512u << 10);
    CAPTURE(keep);
    disk.fillLeaving(keep);
    const std::string path = disk.sub("new/db");

    // In a child: without the check, LMDB's first write to the mapped lock file is SIGBUS.
    pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
        try {
            std::string message = messageAndHintOf([&] { Database::open(path); });
            ::_exit(message.find("no space left on device") != std::string::npos &&
                            message.find("free some space") != std::string::npos
                        ? 0
                        : 1);
        } catch (...) {
            ::_exit(3);
        }
    }
    int status = 0;
    REQUIRE(::waitpid(child, &status, 0) == child);
    REQUIRE(WIFEXITED(status));
    REQUIRE(WEXITSTATUS(status) == 0);
    REQUIRE_FALSE(fs::exists(disk.sub("new")));  // no directory, no lock file left behind

    disk.makeRoom();
    auto db = Database::open(path);
    REQUIRE(db->beginRead().scenes().empty());
}

TEST_CASE("an import that fills the file system says so and changes nothing", "[storage][full]") {
    SmallFileSystem disk(4 << 20);
    if (!disk.mounted()) {
        WARN("skipped: mounting a tmpfs is not permitted here (needs root or CAP_SYS_ADMIN)");
        return;
    }
    const std::string path = disk.sub("db");
    {
        auto db = Database::open(path);
        auto txn = db->beginWrite();
        txn.importScene(largeScene("kept", 50));
        txn.commit();
    }
    // Some room left, but less than the scene needs: LMDB's pages are written
    // in part, which it reports as an I/O error.
    const std::uint64_t keep = GENERATE(0u, 8u << 10, 40u << 10);
    CAPTURE(keep);
    disk.fillLeaving(keep);
    {
        auto db = Database::open(path);
        std::string message = messageAndHintOf([&] {
            auto txn = db->beginWrite();
            txn.importScene(largeScene("too-big", 5000));
            txn.commit();
        });
        REQUIRE_THAT(message, Catch::Contains("failed on database " + path + ": no space left on device"));
        REQUIRE_THAT(message, Catch::Contains("as it was before"));
        auto txn = db->beginRead();
        REQUIRE_FALSE(txn.sceneByName("too-big"));
        REQUIRE(txn.sceneByName("kept"));
    }
    REQUIRE(checkDatabase(path).ok());

    disk.makeRoom();
    auto db = Database::open(path);
    auto txn = db->beginWrite();
    txn.importScene(largeScene("too-big", 5000));
    txn.commit();
    REQUIRE(db->beginRead().scenes().size() == 2);
}
