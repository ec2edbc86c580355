// A push killed at random moments (SIGKILL: no clean-up of any kind) leaves the store consistent:
// every scene version whole or absent, none twice; the next push completes the device's scenes.
// SMQL_FLEET_KILLS sets how many kills (20 here, 10 into a sharded store; `make stress` runs 100).
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <random>
#include <thread>

#include "fleet/fleet.hpp"
#include "fleet/local/local_scenes.hpp"
#include "fleet_support.hpp"
#include "storage/database.hpp"

using namespace smql;
using namespace smql::testing;

namespace {

using Clock = std::chrono::steady_clock;

// `smql-fleet push DB URL` as its own process; returns its pid.
pid_t startPush(const std::string& database, const std::string& url) {
    const char* program = std::getenv("SMQL_FLEET_PROGRAM");
    REQUIRE(program != nullptr);
    pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        int quiet = open("/dev/null", O_WRONLY);
        dup2(quiet, STDOUT_FILENO);
        execl(program, program, "push", database.c_str(), url.c_str(), static_cast<char*>(nullptr));
        _exit(127);
    }
    return pid;
}

int waitFor(pid_t pid) {
    int status = 0;
    waitpid(pid, &status, 0);
    return status;
}

// A new device id for the database, so that the next push has every scene to send.
void becomeAnotherDevice(storage::Database& database) {
    auto txn = database.beginWrite();
    txn.eraseSetting(fleet::kDeviceSetting);
    txn.commit();
    fleet::deviceId(database);
}

}  // namespace

namespace smql::testing {

KilledPushes killPushes(storage::Database& database, const std::string& url, int kills) {
    const std::string path = database.directory();
    const auto versions = static_cast<long long>(fleet::localSource(database).scenes.size());
    // A whole push first, as a device of its own: how long one takes sets the range the kills fall in.
    becomeAnotherDevice(database);
    auto started = Clock::now();
    REQUIRE(waitFor(startPush(path, url)) == 0);
    KilledPushes out;
    out.wholeMilliseconds = std::chrono::duration<double, std::milli>(Clock::now() - started).count();
    REQUIRE(storedVersions(url, *database.beginRead().setting(fleet::kDeviceSetting)) == versions);

    std::mt19937 random(20261125);
    std::uniform_real_distribution<double> moment(0, out.wholeMilliseconds * 1000);
    std::string device;
    for (int i = 0; i < kills; ++i) {
        becomeAnotherDevice(database);
        device = *database.beginRead().setting(fleet::kDeviceSetting);
        pid_t pid = startPush(path, url);
        std::this_thread::sleep_for(std::chrono::microseconds(static_cast<long long>(moment(random))));
        kill(pid, SIGKILL);
        waitFor(pid);
        const long long stored = storedVersions(url, device);
        out.cutShort += stored > 0 && stored < versions;
        INFO("kill " << i);
        REQUIRE(inconsistencies(url) == 0);
    }
    // The last device's push, run again, completes it.
    REQUIRE(waitFor(startPush(path, url)) == 0);
    CHECK(storedVersions(url, device) == versions);
    CHECK(inconsistencies(url) == 0);
    std::cout << kills << " pushes of " << versions << " scenes (" << static_cast<int>(out.wholeMilliseconds)
              << " ms for a whole one) killed, " << out.cutShort << " of them between two scenes' transactions\n";
    return out;
}

}  // namespace smql::testing

TEST_CASE("pushes killed at random moments leave no partial or duplicated scene") {
    const std::string url = freshStore("fleet_kills");
    fleet::init(url);
    TempDir dir;
    {
        auto engine = Engine::open(dir.sub("device"));
        buildRealLayouts(*engine);
    }
    auto database = storage::Database::open(dir.sub("device"));
    const KilledPushes killed = killPushes(*database, url, killCount(20));
    CHECK(killed.cutShort > 0);  // the kills did land in the middle of pushes
}
