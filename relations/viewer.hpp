// VIEW FROM x [FACING y] and the sides of the room (`wall.left`): where a viewer stands and looks,
// and which thing lies farthest out on a side of it. The engine's executor and the fleet store ask
// here, so one statement has one viewer and one `wall.left` wherever it runs.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string_view>

#include "model/geometry.hpp"
#include "relations/predicates.hpp"

namespace smql::relations {

// The viewer at `origin` (a box's centre, at its height) looking towards `towards` on the floor
// plan; nothing when the two are at the same place. viewFrame() makes its frame.
std::optional<model::Viewpoint> lookingAt(const model::Vec3& origin, const model::Vec2& towards);

// Where a viewer without FACING looks: into the room, the middle of `centres` (the scene's visible
// boxes, in id order), or straight ahead along +y from `origin` when there are none.
model::Vec2 middleOf(std::span<const model::Vec2> centres, const model::Vec3& origin);

// Which of `centres` lies farthest out on `side` (left, right, front, back) of the viewer: those
// inside the 90-degree sector around that side first; nothing when none lies on that side.
std::optional<std::size_t> farthestOnSide(const Frame& viewer, std::string_view side,
                                          std::span<const model::Vec2> centres);

}  // namespace smql::relations
