// One guard for every file smql writes on a user's word (exports, maps, evaluations, the shell's
// .output and .once, the C API's and Python's exports, evidence crops): never a file of a database.
// Paths compare by what they are, not how they are written: the device and inode of the target
// against those of data.mdb and lock.mdb (a hard link, a symbolic link or a path through `..` to them
// is caught), and the target's folder against the database's folder (docs/shell.md, "Output").
#pragma once

#include <filesystem>
#include <string>

namespace smql::storage {

// Throws smql::Error(Usage) when writing `target` would touch the database in `database`: it is
// data.mdb or lock.mdb (by device and inode), or it lies in the database's folder, or in any folder
// that holds a data.mdb (another database). `database` may be empty (no database at hand).
void refuseDatabaseFile(const std::filesystem::path& target, const std::filesystem::path& database);

// A blob's name as the name of a file in a folder: separators, NUL and control characters become
// '_', and a name that is empty, "." or ".." becomes `fallback`. Nothing else changes.
std::string safeFileName(const std::string& name, const std::string& fallback);

}  // namespace smql::storage
