// Up from the photos' own lines (docs/ingest.md, "Up from the photos' lines"). A room is full of vertical
// edges: the corners of walls, door frames, cupboards, the legs of tables and chairs. A straight edge lies in
// the plane through the camera's centre and its segment in the photo, so the room's up is perpendicular to
// the normals of the planes of all its vertical edges, whichever photo saw them. With TUM's own poses, the
// office photos' edges stand 0.14 degrees from TUM's up. Photos without depth measure their floor against
// them, and level the room by them where the floor is seen little.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "ingest/capture/capture.hpp"
#include "model/types.hpp"

namespace smql::ingest {

struct FrameImages;  // frame_loader.hpp

struct LineOptions {
    double minLength = 0.06;        // a segment's length, as a share of the photo's diagonal
    std::size_t maxPerPhoto = 200;  // the longest segments of a photo kept
    double search = 10;             // degrees around the surface's normal that up is looked for in
    double tolerance = 1.5;         // degrees: a segment within this of vertical supports a direction
    std::size_t minSegments = 40;   // a vertical needs this many supporting segments ...
    std::size_t minPhotos = 3;      // ... from this many photos
};

// The segments' planes, in the capture's world frame: unit normals and the photo each came from.
struct LinePlanes {
    std::vector<model::Vec3> normals;
    std::vector<std::uint32_t> photo;
    std::size_t photos = 0;  // photos whose segments were added
};

// Adds the photo's longest straight segments (OpenCV's line segment detector on its grey image) as the
// normals of their planes in the world frame; `pose` is the camera-to-world pose of `images`' camera.
void addLinePlanes(LinePlanes& planes, const FrameImages& images, const Pose& pose, const LineOptions& options = {});

struct Vertical {
    model::Vec3 up;            // unit, on the side of `near`
    std::size_t segments = 0;  // segments within `tolerance` of it
    std::size_t photos = 0;    // photos they come from
    double degreesFromNear = 0;
};

// The direction within `search` degrees of `near` that the most segments' planes contain (a grid over the
// cone scored with a robust kernel, then refined by reweighted least squares). Nothing when too few
// segments or photos support it, or when the best direction lies on the cone's rim (up is then outside it,
// or what was found is not up).
std::optional<Vertical> verticalFromLines(const LinePlanes& planes, const model::Vec3& near,
                                          const LineOptions& options = {});

}  // namespace smql::ingest
