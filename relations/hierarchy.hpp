// Gives every node of an imported scene its place in the tree (DESIGN.md 3):
// an object resting on another object (not much smaller than it) hangs below it; any other object hangs
// below the nearest upright anchor (wall, door, window, pillar); anchors hang
// below the scene root.
#pragma once

#include "model/types.hpp"
#include "relations/thresholds.hpp"

namespace smql::relations {

// Fills `parent` of every Object node whose parent is kNoNode (local ids).
// Parents already set by the importer are kept.
void assignParents(model::SceneData& scene, const Thresholds& thresholds = {});

}  // namespace smql::relations
