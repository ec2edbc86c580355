// What the mesh and map writers (glTF, PLY, GeoJSON, Spark-DSG) share: which nodes are drawn, a
// box's corners and faces, a colour per category and a node's path. Internal to ingest/import.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "model/types.hpp"

namespace smql::import::detail {

// Walls, the floor, doors, windows, other anchors and objects with a box that queries see. Left
// out: hidden nodes (Replica's `undefined` parts), nodes without a box, rooms, frames and
// descriptions, and the ceiling, which would hide the room from a viewer looking in from above.
bool isDrawn(const model::Node& node);

// The eight corners of a box: the footprint's four corners counter-clockwise (seen from above) at
// the bottom, then the same four at the top.
std::array<model::Vec3, 8> boxCorners(const model::Box& box);

// The box's twelve triangles as indices into boxCorners, counter-clockwise seen from outside (the
// normals point out of the box, as glTF and PLY readers expect).
inline constexpr std::array<std::array<std::uint8_t, 3>, 12> kBoxTriangles = {{
    // the bottom, then the top
    {0, 2, 1},
    {0, 3, 2},
    {4, 5, 6},
    {4, 6, 7},
    // the sides, two triangles per footprint edge
    {0, 1, 5},
    {0, 5, 4},
    {1, 2, 6},
    {1, 6, 5},
    {2, 3, 7},
    {2, 7, 6},
    {3, 0, 4},
    {3, 4, 7},
}};

struct Rgb {
    std::uint8_t r = 0, g = 0, b = 0;
    friend bool operator==(const Rgb&, const Rgb&) = default;
};

// One colour per category, the same in every scene and every format: fixed greys and browns for the
// structure (walls, floor, doors, windows), a hue from the name's hash for everything else.
Rgb categoryColour(std::string_view category);

// `category#id`, as the engine names a node.
std::string nodeLabel(const model::Node& node);

// Every node's path from the scene down, as the engine prints it (`room0 / wall#19 / sofa#50 /
// cushion#42`), in the order of scene.nodes.
std::vector<std::string> nodePaths(const model::SceneData& scene);

}  // namespace smql::import::detail
