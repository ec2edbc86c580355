#include "ingest/import/common.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include <fmt/format.h>

#include "model/error.hpp"

namespace smql::import::detail {

std::string readTextFile(const std::string& path, const std::string& hint) {
    auto fail = [&](std::string_view why) {
        throw Error(ErrorKind::Input, path + ": cannot read file: " + std::string(why), std::nullopt, hint);
    };
    std::error_code ec;
    auto status = std::filesystem::status(path, ec);
    if (!std::filesystem::exists(status)) fail("no such file");
    // ifstream happily "opens" a directory and then reads nothing.
    if (std::filesystem::is_directory(status)) fail("it is a directory");
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(std::strerror(errno));
    // Read in pieces up to the bound: a device (/dev/zero) or a huge file ends here, not in memory.
    std::string text;
    char piece[1 << 16];
    while (in.read(piece, sizeof piece) || in.gcount() > 0) {
        text.append(piece, static_cast<std::size_t>(in.gcount()));
        if (text.size() > kMaxFileBytes)
            throw Error(ErrorKind::Input,
                        fmt::format("{}: more than {} MiB: a layout file is at most that", path, kMaxFileBytes >> 20),
                        std::nullopt, hint);
    }
    if (in.bad()) fail("read error");
    return text;
}

std::string lowerCase(std::string_view text) {
    std::string out(text);
    for (char& c : out)
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return out;
}

std::string angleProblem(double radians) {
    if (std::abs(radians) <= kMaxAngle) return {};
    return fmt::format("{} is not an angle in radians: angles must lie within +-4 pi (two turns){}", radians,
                       std::abs(radians) <= 720 ? "; degrees must be converted to radians" : "");
}

double normaliseYaw(double yaw) {
    double turned = std::remainder(yaw, 2 * std::numbers::pi);  // [-pi, pi]
    return turned <= -std::numbers::pi ? turned + 2 * std::numbers::pi : turned;
}

}  // namespace smql::import::detail
