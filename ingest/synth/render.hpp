// The rasterizer behind `smql synth`: every node with geometry is an upright
// oriented box (six quads, twelve triangles), drawn with a z-buffer, near-plane
// clipping in camera space and a top-left fill rule, then shaded with a fixed
// light and a texture computed from the world position of each pixel, so a
// surface looks the same from every view. No OpenCV: plain buffers.
#pragma once

#include <cstdint>
#include <vector>

#include "ingest/capture/capture.hpp"
#include "ingest/synth/palette.hpp"
#include "model/types.hpp"

namespace smql::synth {

// Doors and windows are drawn as the panel of their truth box moved this far
// towards the room's interior, so that they win the depth test over the wall
// they sit in (their truth box shares the wall's thickness).
inline constexpr double kPanelOffset = 0.012;
// Camera-space near plane (m); nothing closer is drawn.
inline constexpr double kNearPlane = 0.05;

enum class Look : std::uint8_t { Plain, Door, Window };

// One box as drawn: the node it shows, where it is drawn, and its look.
struct Surface {
    model::NodeId id = model::kNoNode;
    model::Box box;
    Rgb color;
    Look look = Look::Plain;
};

// The boxes of every node with geometry: truth boxes, except doors and windows
// (kPanelOffset towards the room's centre). Colours: the node's `color`
// attribute through the palette, else neutralColor(category).
std::vector<Surface> surfacesOf(const model::SceneData& scene);

struct RenderedFrame {
    int width = 0, height = 0;
    std::vector<float> depth;             // metres along the camera z axis, 0 = nothing drawn
    std::vector<std::uint16_t> instance;  // Surface::id of the visible surface, 0 = nothing
    std::vector<std::uint8_t> rgb;        // 8-bit R, G, B per pixel, row-major
};

class Renderer {
public:
    explicit Renderer(std::vector<Surface> surfaces);
    // Pixel (u, v) samples the ray through its centre, camera direction
    // ((u - cx) / fx, (v - cy) / fy, 1) (the OpenCV convention).
    RenderedFrame render(const ingest::Intrinsics& intrinsics, const ingest::Pose& pose) const;

    const std::vector<Surface>& surfaces() const { return surfaces_; }

private:
    std::vector<Surface> surfaces_;
};

// The texture factor (mean about 1, about +-20 %) of a Plain surface at a world
// point, for a pixel footprint of `footprint` metres (finer octaves fade out as
// they approach the pixel size). Exposed for tests.
double textureFactor(const model::Vec3& world, std::uint32_t seed, double footprint);

}  // namespace smql::synth
