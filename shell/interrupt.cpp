#include "shell/interrupt.hpp"

#include <atomic>
#include <csignal>
#include <unistd.h>

#include "engine/engine.hpp"

namespace smql::shell::interrupt {

namespace {

std::atomic<int> presses{0};
std::atomic<Engine*> watched{nullptr};
static_assert(std::atomic<int>::is_always_lock_free && std::atomic<Engine*>::is_always_lock_free,
              "both are read in a signal handler");

void onSigint(int) {
    // Engine::interrupt only sets an atomic flag that the running statement polls: safe here.
    if (Engine* engine = watched.load()) engine->interrupt();
    if (presses.fetch_add(1) + 1 >= 3) {
        constexpr char kMessage[] = "\nsmql: interrupted three times; leaving\n";
        [[maybe_unused]] auto written = write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
        _exit(1);
    }
}

}  // namespace

void install() {
    struct sigaction action {};
    action.sa_handler = onSigint;
    sigemptyset(&action.sa_mask);
    action.sa_flags = 0;
    sigaction(SIGINT, &action, nullptr);
}

bool requested() { return presses.load() > 0; }

void clear() { presses.store(0); }

void watch(Engine* engine) { watched.store(engine); }

}  // namespace smql::shell::interrupt
