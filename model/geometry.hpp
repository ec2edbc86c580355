// Exact measures on upright oriented boxes. An upright box is a prism (a
// rectangle in the floor plane times a height interval), so gaps, overlaps
// and containment split into a 2D footprint part and a 1D vertical part.
#pragma once

#include <array>
#include <numbers>

#include "model/types.hpp"

namespace smql::model {

// Radians in a degree: angles are written in degrees (yaw, thresholds), computed in radians.
inline constexpr double kDegree = std::numbers::pi / 180;

struct Vec2 {
    double x = 0, y = 0;
};

struct Aabb {
    Vec3 min, max;
};

Aabb worldAabb(const Box& box);
std::array<Vec2, 4> footprint(const Box& box);  // counter-clockwise corners
double footprintArea(const Box& box);
double volume(const Box& box);
inline double bottom(const Box& b) { return b.center.z - b.size.z / 2; }
inline double top(const Box& b) { return b.center.z + b.size.z / 2; }

// Area of the intersection of the two footprints (m^2).
double footprintOverlap(const Box& a, const Box& b);
// Shortest distance between the footprints in the floor plane; 0 when they meet.
double horizontalGap(const Box& a, const Box& b);
// Gap between the height intervals; 0 when they overlap.
double verticalGap(const Box& a, const Box& b);
// Length of the overlap of the height intervals; 0 when disjoint.
double verticalOverlap(const Box& a, const Box& b);
// Shortest distance between the two solids (0 when they touch or intersect).
double distance(const Box& a, const Box& b);
double centerDistance(const Box& a, const Box& b);
// Share of a's volume that lies inside b, in [0, 1].
double fractionInside(const Box& a, const Box& b);
// Is the point inside the box's footprint (grown by `margin` metres on each side)?
bool footprintContains(const Box& box, Vec2 point, double margin = 0);
// Shortest distance in the floor plane from the point to the box's footprint; 0 inside it.
double footprintGap(const Box& box, Vec2 point);

}  // namespace smql::model
