// Is a horizontal surface the floor, or a table top? What stands on it says so: chairs and beds rise
// from a floor, mugs and keyboards rest on tables, and nothing a capture names reaches below a
// floor. Used by the alignment to choose the floor among the horizontal planes below the cameras
// (docs/ingest.md, "Geometry and metric alignment").
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "ingest/geometry/scale_priors.hpp"
#include "model/types.hpp"

namespace smql::ingest {

// A point's height along `up` (a unit normal), in the cloud's units.
double along(const model::Vec3& up, const model::Vec3& p);

// A horizontal surface: unit normal (up) and height along it, in the cloud's units.
struct Surface {
    model::Vec3 up{0, 0, 1};
    double height = 0;
};

struct SurfaceEvidence {
    std::vector<std::string> standing;  // things that stand on floors, rising from it (a chair's legs and seat)
    std::vector<std::string> onTop;     // things that stand on tables, resting on it (a mug, a keyboard)
    std::vector<std::string> below;     // named things reaching well below it
    std::vector<std::string> topOf;     // things that hold others whose points all lie on it: it is their top
    double pointsBelow = 0;             // share of the cloud's points well below it

    // More says "table top" than says "floor": the surface holds table things, has things under it, or
    // is a table's top; one such thing is enough when much of the cloud lies under the surface, and a
    // thing reaching below it then outweighs whatever rises from it.
    bool tableTop() const;
    // More of the cloud lies under it than under any floor (real floors: under 0.5 %).
    bool muchBelow() const;
    std::string describe() const;  // "2 things that stand on tables rest on it (mug, keyboard), ..."
};

// What the named things and the cloud say of `surface`. `unit`: cloud units per metre (a rough
// estimate for scale-free clouds), which turns the tolerances into the cloud's units.
SurfaceEvidence weighSurface(const Surface& surface, const std::vector<NamedThing>& things,
                             const std::vector<model::Vec3>& cloud, double unit);

// Whether a tenth of a named thing's points lie well under a surface (0.2 m or more): `heights` above it,
// in the cloud's units, `unit` units per metre. Nothing a capture names reaches below a floor: such a
// thing's points hold more than the thing (what a detection's outline takes in behind and under it).
bool reachesBelow(std::vector<double> heights, double unit);

}  // namespace smql::ingest
