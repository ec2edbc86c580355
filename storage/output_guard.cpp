#include "storage/output_guard.hpp"

#include <sys/stat.h>

#include <fmt/format.h>

#include "model/error.hpp"
#include "storage/lmdb_env.hpp"

namespace smql::storage {

namespace fs = std::filesystem;

namespace {

// Whether two existing paths are the same file (device and inode, links followed).
bool sameFile(const fs::path& a, const fs::path& b) {
    struct stat sa {
    }, sb{};
    return ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev &&
           sa.st_ino == sb.st_ino;
}

[[noreturn]] void refuse(const fs::path& target, const std::string& why) {
    throw Error(ErrorKind::Usage, fmt::format("{} {}: writing it would destroy the database", target.string(), why),
                std::nullopt, "write the output to a file outside the database's folder");
}

}  // namespace

void refuseDatabaseFile(const fs::path& target, const fs::path& database) {
    std::error_code ec;
    // The folder the file is (or would be) in, with links and `..` resolved where they exist.
    const fs::path folder = fs::weakly_canonical(fs::absolute(target, ec), ec).parent_path();
    if (!database.empty()) {
        for (auto file : {kDataFile, kLockFile})
            if (sameFile(target, database / file)) refuse(target, fmt::format("is the database's {}", file));
        if (sameFile(folder, database)) refuse(target, fmt::format("is in the database folder {}", folder.string()));
    }
    if (fs::exists(folder / kDataFile, ec))
        refuse(target, fmt::format("is in the database folder {}", folder.string()));
}

std::string safeFileName(const std::string& name, const std::string& fallback) {
    std::string out = name;
    for (char& c : out)
        if (c == '/' || c == '\\' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '_';
    return out.empty() || out == "." || out == ".." ? fallback : out;
}

}  // namespace smql::storage
