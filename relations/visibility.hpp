// Lines of sight between boxes: what visible_from and near's "nothing in between" measure.
// Every node is an upright oriented box; a sight line is blocked by a box it passes through
// (the slab test in the box's own frame). docs/relations.md states the rules.
#pragma once

#include <span>

#include "model/types.hpp"

namespace smql::relations {

// The height of an eye standing at a node that reaches the floor (1.6 m, as the importers' default
// viewpoints); a lower node puts the eye on its top.
inline constexpr double kEyeHeight = 1.6;
// visible_from samples a box at 3 x 3 x 3 points, at these fractions of its size from its centre
// along each of its axes: inside the box, so that a point on a face shared with a neighbour is not
// hidden by that neighbour.
inline constexpr double kSampleFraction = 0.4;
inline constexpr int kSamplesPerBox = 27;

// Where one looks from when standing at `node`: the centre of its footprint, kEyeHeight above its
// bottom or at its top when it is lower than that.
model::Vec3 eyeAt(const model::Box& node);

// A field of view: the directions within the half-angles (their tangents) of `forward`, measured
// along `right` and `up`. An unbounded tangent leaves that direction open.
struct ViewCone {
    model::Vec3 forward{1, 0, 0};
    model::Vec3 right{0, -1, 0};
    model::Vec3 up{0, 0, 1};
    double tanHalfWidth = 1.0;
    double tanHalfHeight = 1.0;
    bool contains(const model::Vec3& eye, const model::Vec3& point) const;
};

// Whether the segment from p to q passes through the box, entering it strictly between its ends.
bool segmentCrosses(const model::Vec3& p, const model::Vec3& q, const model::Box& box);
bool pointInBox(const model::Vec3& point, const model::Box& box);

// The share of `target`'s kSamplesPerBox sample points that the eye sees: inside the cone (when
// one is given), and no obstacle on the way. An obstacle that holds the eye or the sample point
// does not block that sight line (boxes are loose hulls: a cushion sunk into a sofa's box, the
// eye standing in a door set in its wall); `target` and `viewer` never block.
double visibleShare(const model::Vec3& eye, const model::Node& target, std::span<const model::Node* const> obstacles,
                    const ViewCone* cone, const model::Node* viewer);

}  // namespace smql::relations
