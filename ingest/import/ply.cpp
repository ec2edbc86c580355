// PLY, binary little endian (docs/formats.md, "PLY"): the drawn boxes as one triangle mesh, eight
// corners and twelve triangles a box, each corner coloured by its box's category.
#include <bit>
#include <cstdint>

#include <fmt/format.h>

#include "ingest/import/export_support.hpp"
#include "ingest/import/importers.hpp"

namespace smql::import {

namespace {

void appendLittleEndian(std::string& out, std::uint32_t value) {
    for (int shift = 0; shift < 32; shift += 8) out += static_cast<char>(value >> shift & 0xFF);
}

// A header line holds no line break: a name with one would end the comment early.
std::string oneLine(std::string text) {
    for (char& c : text)
        if (c == '\n' || c == '\r') c = ' ';
    return text;
}

std::string header(const model::SceneData& scene, const std::vector<const model::Node*>& boxes) {
    std::string out = "ply\nformat binary_little_endian 1.0\n";
    out += fmt::format("comment smql scene {}: {} boxes, metres, z up\n", oneLine(scene.info.name), boxes.size());
    // Which box is which: box k owns vertices 8k..8k+7 and faces 12k..12k+11.
    for (std::size_t k = 0; k < boxes.size(); ++k)
        out += fmt::format("comment box {} {}\n", k, oneLine(model::nodeLabel(*boxes[k])));
    out += fmt::format(
        "element vertex {}\nproperty float x\nproperty float y\nproperty float z\n"
        "property uchar red\nproperty uchar green\nproperty uchar blue\n",
        boxes.size() * 8);
    out += fmt::format("element face {}\nproperty list uchar int vertex_indices\nend_header\n",
                       boxes.size() * detail::kBoxTriangles.size());
    return out;
}

}  // namespace

std::string writePly(const model::SceneData& scene) {
    std::vector<const model::Node*> boxes;
    for (const model::Node& node : scene.nodes)
        if (detail::isDrawn(node)) boxes.push_back(&node);

    std::string out = header(scene, boxes);
    const model::Palette palette(scene.nodes);
    for (const model::Node* node : boxes) {
        model::Rgb colour = palette(node->category);
        for (const model::Vec3& corner : detail::boxCorners(node->box)) {
            for (double coordinate : {corner.x, corner.y, corner.z})
                appendLittleEndian(out, std::bit_cast<std::uint32_t>(static_cast<float>(coordinate)));
            out += static_cast<char>(colour.r);
            out += static_cast<char>(colour.g);
            out += static_cast<char>(colour.b);
        }
    }
    for (std::uint32_t first = 0; first < boxes.size() * 8; first += 8)
        for (const auto& triangle : detail::kBoxTriangles) {
            out += static_cast<char>(3);
            for (std::uint8_t corner : triangle) appendLittleEndian(out, first + corner);
        }
    return out;
}

}  // namespace smql::import
