#include "shell/output_file.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "model/error.hpp"

namespace smql::shell {

namespace fs = std::filesystem;

namespace {

// The folder a path's file is (or would be) in, with links and `..` resolved where they exist.
fs::path folderOf(const std::string& path) {
    std::error_code ec;
    fs::path full = fs::weakly_canonical(fs::absolute(path, ec), ec);
    return full.parent_path();
}

bool sameFolder(const fs::path& a, const std::string& b) {
    std::error_code ec;
    return !b.empty() && fs::equivalent(a, b, ec);
}

}  // namespace

void refuseDatabaseFile(const std::string& path, const std::string& database) {
    const fs::path folder = folderOf(path);
    std::error_code ec;
    if (sameFolder(folder, database) || fs::exists(folder / "data.mdb", ec))
        throw Error(ErrorKind::Usage,
                    fmt::format("{} is in the database folder {}: writing there would destroy the database", path,
                                folder.string()),
                    std::nullopt, "write the output to a file outside the database's folder");
}

void checkWritten(std::ostream& out, const std::string& what) {
    // A stream that failed already failed in the write just before: errno still says why.
    if (out) {
        errno = 0;
        out.flush();
        if (out) return;
    }
    const int error = errno;
    throw Error(ErrorKind::Usage,
                fmt::format("cannot write {}{}", what, error ? std::string(": ") + std::strerror(error) : ""),
                std::nullopt, "check that the disk has room and that the file can be written");
}

}  // namespace smql::shell
