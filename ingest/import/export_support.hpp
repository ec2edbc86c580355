// What the mesh and map writers (glTF, PLY, GeoJSON, Spark-DSG) share: which nodes are drawn, a
// box's corners and faces (labels, paths and colours are model/presentation.hpp's). Internal to
// ingest/import.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "model/presentation.hpp"
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

}  // namespace smql::import::detail
