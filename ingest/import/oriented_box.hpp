// Files that give a box a full 3D rotation (Replica, Spark-DSG) -> smql's upright boxes. Internal
// to ingest/import.
#pragma once

#include <Eigen/Core>

#include "model/types.hpp"

namespace smql::import::detail {

// Quaternions this close to unit norm are float round-off and get normalised; anything further off
// is a corrupt rotation.
inline constexpr double kQuaternionNormTolerance = 1e-3;
// A box whose own z axis leans further than this from world z is not upright and is folded to its
// world AABB.
inline constexpr double kMaxTiltDegrees = 10;

// The box centred at `center` with full extents `sizes` along the axes of `rotation` (box frame to
// world): the same box with its yaw when it stands within kMaxTiltDegrees of upright, else the
// world-aligned box around it (yaw 0).
model::Box uprightBox(const model::Vec3& center, const model::Vec3& sizes, const Eigen::Matrix3d& rotation);

}  // namespace smql::import::detail
