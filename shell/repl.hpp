// The interactive shell: readline with history in ~/.smql_history (one entry per statement, multi-line
// statements kept whole), completion from the engine's vocabularies, Ctrl-C that cancels the line
// being typed or the running statement, never the shell.
#pragma once

#include <string>

#include "shell/session.hpp"

namespace smql::shell {

// Returns the exit status: 0, or 1 when .bail is on and a statement failed.
int runRepl(Session& session, const std::string& databaseDir);

}  // namespace smql::shell
