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
    // A device never ends (/dev/zero) or is no file at all; a pipe is read, up to the bound.
    if (std::filesystem::is_character_file(status) || std::filesystem::is_block_file(status) ||
        std::filesystem::is_socket(status))
        fail("it is a device, not a file");
    auto tooLarge = [&] {
        return Error(ErrorKind::Input,
                     fmt::format("{}: more than {} MiB: a layout file is at most that", path, kMaxFileBytes >> 20),
                     std::nullopt, hint);
    };
    // A regular file's size is known: one too large is refused before a byte of it is read.
    std::uintmax_t size = std::filesystem::is_regular_file(status) ? std::filesystem::file_size(path, ec) : 0;
    if (!ec && size > kMaxFileBytes) throw tooLarge();
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(std::strerror(errno));
    // Read in pieces up to the bound: a pipe, or a file that grows while it is read, ends here.
    std::string text;
    if (!ec) text.reserve(static_cast<std::size_t>(size));
    char piece[1 << 16];
    while (in.read(piece, sizeof piece) || in.gcount() > 0) {
        text.append(piece, static_cast<std::size_t>(in.gcount()));
        if (text.size() > kMaxFileBytes) throw tooLarge();
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
