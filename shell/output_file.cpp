#include "shell/output_file.hpp"

#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include "model/error.hpp"

namespace smql::shell {

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
