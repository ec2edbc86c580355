// Files the shell writes results and exports to. A write over an LMDB environment's data.mdb or
// lock.mdb while it is open destroys the database (SIGBUS, then an empty file), so no output goes
// to a database's files (storage::refuseDatabaseFile, the library's one guard); and a write that
// fails (a full disk, /dev/full, a file of /proc) is an error, never a silent empty file with exit
// status 0.
#pragma once

#include <ostream>
#include <string>

namespace smql::shell {

// Throws when `out` has failed: "cannot write <what>: <the system's reason>".
void checkWritten(std::ostream& out, const std::string& what);

}  // namespace smql::shell
