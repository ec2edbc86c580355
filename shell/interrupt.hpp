// Ctrl-C in the shell cancels what is running (a statement, or the line being typed), never the
// shell: SIGINT only raises a flag that the session and the line editor poll.
#pragma once

namespace smql {
class Engine;
}

namespace smql::shell::interrupt {

// Installs the SIGINT handler, without SA_RESTART so that a blocking read returns EINTR at once.
// Three presses with nobody taking notice (a statement that does not stop) end the process, as in
// sqlite3, so a stuck statement never traps the user.
void install();
// Whether Ctrl-C was pressed since the last clear().
bool requested();
void clear();
// The engine whose running statement Ctrl-C stops (Engine::interrupt); null for none.
void watch(Engine* engine);
// A file descriptor that becomes readable at each Ctrl-C, for a loop waiting on input with select():
// a signal that comes while the loop is busy elsewhere still wakes its next wait. -1 before install().
int wakeFd();
// Empties wakeFd() after a wake-up.
void drainWakeFd();

}  // namespace smql::shell::interrupt
