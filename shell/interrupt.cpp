#include "shell/interrupt.hpp"

#include <atomic>
#include <csignal>
#include <unistd.h>

namespace smql::shell::interrupt {

namespace {

std::atomic<int> presses{0};
static_assert(std::atomic<int>::is_always_lock_free, "the flag is set from a signal handler");

void onSigint(int) {
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

}  // namespace smql::shell::interrupt
