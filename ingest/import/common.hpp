// Helpers shared by the importers: file reading, plausibility limits, and
// small conversions. Internal to ingest/import.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "model/types.hpp"

namespace smql::import::detail {

// Plausibility limits for imported geometry (metres): anything beyond them is
// a unit mix-up or a corrupt file, not a room.
inline constexpr double kMaxCoordinate = 1e4;
inline constexpr double kMaxSize = 1000;
// Angles (radians): a box's yaw turns at most two whole turns either way.
// Files write angles in (-pi, pi]; a larger one is degrees written as radians
// or garbage (a yaw of 1e300 has no digits left below a whole turn).
inline constexpr double kMaxAngle = 4 * 3.141592653589793;

// The most bytes an imported file may have (docs/formats.md, "Bounds"): Replica's and SpatialLM's
// files are megabytes; more is not a room's layout, and a device such as /dev/zero never ends.
inline constexpr std::size_t kMaxFileBytes = std::size_t{256} << 20;

// The whole file as bytes (at most kMaxFileBytes); throws an Input error naming the file when it
// does not exist, is not a regular file, or cannot be read.
std::string readTextFile(const std::string& path, const std::string& hint);

std::string lowerCase(std::string_view text);

// "<what> <value> is beyond +-4 pi radians ..." when |value| > kMaxAngle, else empty.
std::string angleProblem(double radians);

// The same angle in (-pi, pi].
double normaliseYaw(double yaw);

}  // namespace smql::import::detail
