#include "model/points.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>

#include <fmt/format.h>

#include "model/error.hpp"

namespace smql::model {

namespace {

// x, y, z as float, then red, green, blue.
constexpr std::size_t kVertexBytes = 3 * sizeof(float) + 3;
constexpr std::string_view kProperties =
    "property float x\nproperty float y\nproperty float z\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";

static_assert(std::endian::native == std::endian::little, "the points are written as the machine holds floats");

}  // namespace

std::string pointsPly(const ScenePoints& points, std::string_view comment) {
    std::string line(comment);
    std::replace_if(
        line.begin(), line.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
    std::string out = fmt::format("ply\nformat binary_little_endian 1.0\ncomment {}\nelement vertex {}\n{}", line,
                                  points.positions.size(), kProperties);
    const std::size_t start = out.size();
    out.resize(start + points.positions.size() * kVertexBytes);
    char* at = out.data() + start;
    for (std::size_t i = 0; i < points.positions.size(); ++i, at += kVertexBytes) {
        const Vec3& p = points.positions[i];
        const float xyz[3] = {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)};
        std::memcpy(at, xyz, sizeof xyz);
        const Rgb& c = points.colours[i];
        at[12] = static_cast<char>(c.r), at[13] = static_cast<char>(c.g), at[14] = static_cast<char>(c.b);
    }
    return out;
}

ScenePoints readPointsPly(std::string_view bytes) {
    auto fail = [](std::string_view why) {
        return Error(ErrorKind::Input, fmt::format("the scene's points are damaged: {}", why));
    };
    const std::size_t end = bytes.find("end_header\n");
    if (!bytes.starts_with("ply\nformat binary_little_endian 1.0\n") || end == std::string_view::npos)
        throw fail("no binary PLY header");
    const std::size_t body = end + std::string_view("end_header\n").size();
    const std::string_view header = bytes.substr(0, body);
    const std::size_t element = header.find("\nelement vertex ");
    if (element == std::string_view::npos || header.substr(element).find(kProperties) == std::string_view::npos)
        throw fail("not the layout smql writes (x, y, z as float, red, green, blue)");
    const std::size_t count = std::strtoull(header.data() + element + 16, nullptr, 10);
    if ((bytes.size() - body) / kVertexBytes < count || bytes.size() - body != count * kVertexBytes)
        throw fail(fmt::format("{} points announced, {} bytes of them", count, bytes.size() - body));
    ScenePoints out;
    out.positions.reserve(count);
    out.colours.reserve(count);
    for (const char* at = bytes.data() + body; out.positions.size() < count; at += kVertexBytes) {
        float xyz[3];
        std::memcpy(xyz, at, sizeof xyz);
        out.positions.push_back({xyz[0], xyz[1], xyz[2]});
        out.colours.push_back(
            {static_cast<std::uint8_t>(at[12]), static_cast<std::uint8_t>(at[13]), static_cast<std::uint8_t>(at[14])});
    }
    return out;
}

const Blob* pointsBlob(const SceneData& scene) {
    auto it = std::find_if(scene.blobs.begin(), scene.blobs.end(),
                           [](const Blob& b) { return b.node == kNoNode && b.name == kPointsBlobName; });
    return it == scene.blobs.end() ? nullptr : &*it;
}

}  // namespace smql::model
