// A wall instance that is no slab: one `wall` box of a semantic layout (Replica, any semantic mesh) often
// covers two or three faces of a room, an L or a U of wall, and then holds floor, doors and furniture. Such
// a box becomes the faces of the room it bounds (docs/formats.md, "Walls of several faces"). Internal to
// ingest/import.
#pragma once

#include <cstddef>

#include "model/types.hpp"

namespace smql::import::detail {

// A wall box whose thinner horizontal side is more than this (metres) is no slab: a real wall is 0.1 to
// 0.3 m thick, a scan's box of one face at most 0.35 m (Replica room1's wall 5).
inline constexpr double kSlabThickness = 0.5;
// A face of the room is a wall this thick (metres), standing on the room's outline.
inline constexpr double kFaceThickness = 0.1;
// Pieces of outline shorter than this (metres) inside a wall box are a corner grazed, not a face.
inline constexpr double kMinFaceLength = 0.3;
// A door whose centre is this close (metres) to a face stands in it: the face is cut at the door's width.
inline constexpr double kDoorReach = 0.5;

// Replaces every wall box more than kSlabThickness thick that the room's outline (the labelled floor's
// footprint, else the convex hull of the walls' footprints) passes through by the pieces of that outline
// inside it: each a wall anchor of its own, kFaceThickness thick, as tall as the box, cut where a door
// stands in it. The first piece keeps the instance's id and source id; the others get new ids and say in
// their text which instance they are a face of. A box the outline does not pass through is left as it is.
// Returns the number of wall boxes split.
std::size_t splitWallOutlines(model::SceneData& scene);

}  // namespace smql::import::detail
