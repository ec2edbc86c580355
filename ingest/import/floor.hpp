// Imported scenes stand on their floor: every importer stores its scene in the upright floor frame,
// the floor at z = 0, so heights, `above`, `on` and guidance mean the same on every source
// (docs/formats.md, "The floor frame"). Internal to ingest/import.
#pragma once

#include <optional>
#include <vector>

#include "model/types.hpp"

namespace smql::import::detail {

// A floor this close to z = 0 (metres) is taken as already there: the scene is not moved.
inline constexpr double kFloorTolerance = 0.02;

struct FloorFound {
    double height = 0;  // of the floor in the file's frame
    const char* how;    // "the labelled floor's top", "the lowest boxes' bottoms"
};

// The labelled floor's top (the largest `floor` box), else the bottoms that the lowest things
// share (the median of the lowest cluster of box bottoms that holds enough of the boxes); nullopt
// for a scene without boxes.
std::optional<FloorFound> findFloor(const std::vector<model::Node>& nodes);

// Moves the scene down by its floor's height (boxes, viewpoint) and records the move in its
// alignment, so that an export can go back to the file's frame. Returns what was found; nothing
// moves when the floor is within kFloorTolerance of z = 0.
std::optional<FloorFound> standOnFloor(model::SceneData& scene);

}  // namespace smql::import::detail
