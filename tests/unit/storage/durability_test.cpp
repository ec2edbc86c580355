// Concurrency and crash behaviour: a reader never sees part of a scene, and a
// writer killed mid-transaction leaves no trace of what it was writing.
#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>

#include "model/error.hpp"
#include "storage/database.hpp"
#include "storage_test_support.hpp"

using namespace smql;
using namespace smql::storage;
using namespace smql::storage::testing;
using model::NodeId;

namespace {

// Waits until `counter` passes `from`; false after a generous timeout.
bool waitPast(const std::atomic<std::uint64_t>& counter, std::uint64_t from) {
    auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (counter.load() <= from)
        if (std::chrono::steady_clock::now() > deadline)
            return false;
        else
            std::this_thread::yield();
    return true;
}

}  // namespace

TEST_CASE("readers see a scene whole or not at all while a writer imports", "[storage][concurrency]") {
    TempDir tmp;
    auto db = Database::open(tmp.path());
    constexpr std::size_t kNodes = 20000;
    const auto data = largeScene("big", kNodes);
    const std::size_t chairs = countCategory(data, "chair");

    std::atomic<bool> stop{false};
    std::atomic<std::uint64_t> sawWhole{0}, sawNone{0}, sawPartial{0};
    std::mutex failureMutex;
    std::string failure;

    std::thread reader([&] {
        try {
            while (!stop.load()) {
                auto txn = db->beginRead();
                auto scene = txn.sceneByName("big");
                std::uint64_t inScene = 0;
                if (scene) txn.forEachNodeInScene(scene->id, [&](const model::Node&) { ++inScene; });
                const std::uint64_t total = txn.nodeCount();
                const std::size_t labelled = txn.nodesWithCategory("chair").size();
                const std::size_t relations = scene ? txn.relationsOf(scene->id + 2).size() : 0;
                if (!scene && total == 0 && labelled == 0)
                    ++sawNone;
                else if (scene && inScene == kNodes + 1 && total == kNodes + 1 && labelled == chairs &&
                         relations == 2000)
                    ++sawWhole;
                else
                    ++sawPartial;
            }
        } catch (const std::exception& e) {
            std::lock_guard lock(failureMutex);
            failure = e.what();
        }
    });

    constexpr int kRounds = 4;
    bool readerKeptUp = true;
    for (int round = 0; round < kRounds && readerKeptUp; ++round) {
        std::uint64_t whole = sawWhole.load();
        NodeId sceneId;
        {
            auto txn = db->beginWrite();
            sceneId = txn.importScene(data);
            txn.commit();
        }
        // Let the reader observe the committed scene before it is dropped again.
        readerKeptUp = waitPast(sawWhole, whole);
        std::uint64_t none = sawNone.load();
        {
            auto txn = db->beginWrite();
            txn.dropScene(sceneId);
            txn.commit();
        }
        readerKeptUp = readerKeptUp && waitPast(sawNone, none);
    }
    stop = true;
    reader.join();

    REQUIRE(failure.empty());
    REQUIRE(readerKeptUp);
    REQUIRE(sawPartial.load() == 0);
    REQUIRE(sawWhole.load() >= kRounds);
    REQUIRE(sawNone.load() >= kRounds);
}

TEST_CASE("a writer killed before commit leaves no trace of its scene", "[storage][crash]") {
    TempDir tmp;
    const std::string path = tmp.path();
    const auto kept = largeScene("kept", 500);
    {
        auto db = Database::open(path);
        auto txn = db->beginWrite();
        txn.importScene(kept);
        txn.putSetting("units", "m");
        txn.commit();
    }

    // How far the child gets before it is killed: right after beginWrite,
    // between two imports of one transaction, or with everything written but
    // commit() not yet called.
    enum class KillPoint { InsideTransaction, BetweenImports, BeforeCommit };
    auto killPoint = GENERATE(KillPoint::InsideTransaction, KillPoint::BetweenImports, KillPoint::BeforeCommit);

    // The parent keeps the database open throughout, like a shell querying
    // while another process ingests.
    auto db = Database::open(path);
    const auto keptBefore = *db->beginRead().sceneByName("kept");

    int pipeFds[2];
    REQUIRE(::pipe(pipeFds) == 0);
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
        // Child: no Catch2 and no destructors; report progress through the pipe.
        ::close(pipeFds[0]);
        auto signal = [&](char c) {
            if (::write(pipeFds[1], &c, 1) != 1) ::_exit(4);
        };
        try {
            auto childDb = Database::open(path);
            auto txn = childDb->beginWrite();
            signal('w');
            txn.importScene(largeScene("crash-a", 30000, "crashthing"));
            signal('a');
            txn.importScene(largeScene("crash-b", 30000, "crashthing"));
            txn.putSetting("units", "furlongs");
            signal('b');
            ::pause();
        } catch (...) {
            ::_exit(3);
        }
        ::_exit(0);
    }

    ::close(pipeFds[1]);
    const char awaited = killPoint == KillPoint::InsideTransaction ? 'w'
                         : killPoint == KillPoint::BetweenImports  ? 'a'
                                                                   : 'b';
    char got = 0;
    while (got != awaited) REQUIRE(::read(pipeFds[0], &got, 1) == 1);
    if (killPoint == KillPoint::InsideTransaction)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));  // well into the first import
    REQUIRE(::kill(child, SIGKILL) == 0);
    int status = 0;
    REQUIRE(::waitpid(child, &status, 0) == child);
    ::close(pipeFds[0]);
    REQUIRE(WIFSIGNALED(status));
    REQUIRE(WTERMSIG(status) == SIGKILL);

    auto requireNoTrace = [&](Database& database) {
        auto txn = database.beginRead();
        REQUIRE_FALSE(txn.sceneByName("crash-a"));
        REQUIRE_FALSE(txn.sceneByName("crash-b"));
        REQUIRE(txn.scenes().size() == 1);
        REQUIRE(txn.nodesWithCategory("crashthing").empty());
        REQUIRE(txn.nodeCount() == kept.nodes.size() + 1);
        REQUIRE(txn.setting("units") == "m");
        auto keptNow = txn.sceneByName("kept");
        REQUIRE(keptNow);
        REQUIRE(*keptNow == keptBefore);
        std::size_t nodes = 0;
        txn.forEachNodeInScene(keptNow->id, [&](const model::Node& n) {
            if (n.kind == model::NodeKind::Object)
                REQUIRE(n.text == "object number " + std::to_string(n.id - keptNow->id));
            ++nodes;
        });
        REQUIRE(nodes == kept.nodes.size() + 1);
        REQUIRE(txn.children(keptNow->id + 1).size() == kept.nodes.size() - 1);
    };

    // The open handle sees no trace, and can write again: the dead writer's lock was recovered.
    requireNoTrace(*db);
    {
        auto txn = db->beginWrite();
        NodeId next = txn.importScene(largeScene("after", 10));
        REQUIRE(next == keptBefore.id + kept.nodes.size() + 1);  // the dead writer's ids were never committed
        txn.dropScene(next);
        txn.commit();
    }
    db.reset();

    // A fresh open of the directory finds a consistent database too.
    auto reopened = Database::open(path);
    requireNoTrace(*reopened);
}
