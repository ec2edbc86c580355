// The capture's points: the coloured cloud ingest fused from every frame, kept once per scene as a
// blob of the scene's own node, in the file form `smql export ply --points` writes (binary PLY), so
// that Open3D, CloudCompare or MeshLab open it as it is stored.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "model/presentation.hpp"
#include "model/types.hpp"

namespace smql::model {

struct ScenePoints {
    std::vector<Vec3> positions;  // metres, the scene's floor frame
    std::vector<Rgb> colours;     // sRGB, one per position
};

// The blob's name and media type, on the scene's node (Blob::node kNoNode in SceneData).
inline constexpr std::string_view kPointsBlobName = "points.ply";
inline constexpr std::string_view kPointsMediaType = "application/x-ply";

// A binary little-endian PLY of vertices with float x, y, z and uchar red, green, blue;
// `comment` (one line) goes in its header.
std::string pointsPly(const ScenePoints& points, std::string_view comment);

// The points of a PLY as pointsPly writes it. Throws smql::Error(Input) for any other layout or a
// file shorter than its header says.
ScenePoints readPointsPly(std::string_view bytes);

// The scene's points, or null when it has none (scenes imported from layouts).
const Blob* pointsBlob(const SceneData& scene);

}  // namespace smql::model
