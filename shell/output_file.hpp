// Files the shell writes results and exports to. A write over an LMDB environment's data.mdb or
// lock.mdb while it is open destroys the database (SIGBUS, then an empty file), so no output goes
// into a database's folder; and a write that fails (a full disk, /dev/full, a file of /proc) is
// an error, never a silent empty file with exit status 0.
#pragma once

#include <ostream>
#include <string>

namespace smql::shell {

// Throws a Usage error when `path` lies in a database's folder: `database` (the open one), or any
// folder that holds an LMDB environment's data.mdb.
void refuseDatabaseFile(const std::string& path, const std::string& database);

// Throws when `out` has failed: "cannot write <what>: <the system's reason>".
void checkWritten(std::ostream& out, const std::string& what);

}  // namespace smql::shell
