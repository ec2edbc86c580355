// The floor a scene stands on, as its nodes label it: one rule for the importers (which stand the
// scene on it), the default viewpoint (which stands on it) and guidance (whose walkable floor it is).
#pragma once

#include <span>

#include "model/types.hpp"

namespace smql::model {

// The largest visible box named `floor` (by footprint), or null when the scene labels none.
const Node* labelledFloor(std::span<const Node> nodes);

}  // namespace smql::model
