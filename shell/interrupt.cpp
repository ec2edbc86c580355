#include "shell/interrupt.hpp"

#include <fcntl.h>
#include <unistd.h>
#include <atomic>
#include <csignal>

#include "engine/engine.hpp"

namespace smql::shell::interrupt {

namespace {

std::atomic<int> presses{0};
std::atomic<Engine*> watched{nullptr};
int wakePipe[2] = {-1, -1};
static_assert(std::atomic<int>::is_always_lock_free && std::atomic<Engine*>::is_always_lock_free,
              "both are read in a signal handler");

void onSigint(int) {
    // Counted first, so that whoever the wake-up below reaches sees the press.
    int count = presses.fetch_add(1) + 1;
    // Engine::interrupt only sets an atomic flag that the running statement polls: safe here.
    if (Engine* engine = watched.load()) engine->interrupt();
    if (wakePipe[1] >= 0) {
        [[maybe_unused]] auto written = write(wakePipe[1], "!", 1);
    }
    if (count >= 3) {
        constexpr char kMessage[] = "\nsmql: interrupted three times; leaving\n";
        [[maybe_unused]] auto written = write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
        _exit(1);
    }
}

}  // namespace

void install() {
    // Non-blocking both ways: the handler never waits on a full pipe, draining never waits on an empty one.
    if (wakePipe[0] < 0 && pipe2(wakePipe, O_NONBLOCK | O_CLOEXEC) != 0) wakePipe[0] = wakePipe[1] = -1;
    struct sigaction action {};
    action.sa_handler = onSigint;
    sigemptyset(&action.sa_mask);
    action.sa_flags = 0;
    sigaction(SIGINT, &action, nullptr);
}

bool requested() { return presses.load() > 0; }

void clear() { presses.store(0); }

void watch(Engine* engine) { watched.store(engine); }

int wakeFd() { return wakePipe[0]; }

void drainWakeFd() {
    char buffer[64];
    while (wakePipe[0] >= 0 && read(wakePipe[0], buffer, sizeof buffer) > 0) {
    }
}

}  // namespace smql::shell::interrupt
