#include "ingest/geometry/floor_evidence.hpp"

#include <cmath>

#include <fmt/format.h>

#include "ingest/geometry/robust.hpp"
#include "ingest/geometry/typical_sizes.hpp"
#include "relations/predicates.hpp"

namespace smql::ingest {

using relations::Support;
using relations::usualSupport;

namespace {

// Metres. A thing rests on the surface when its lower end is this close to it; it reaches below
// when its lower end is this far under it (further than depth noise and a box's loose points).
constexpr double kRests = 0.08;
constexpr double kBelow = 0.2;
// A thing that stands on floors counts for the surface only when it rises this far from it: a
// table whose top alone was seen rests on the plane of its own top.
constexpr double kRises = 0.3;
// The share of the cloud's points under a surface below which something was seen at all; and the
// share that no floor has under it (real floors: under 0.5 %; table tops 3 to 37 %, docs/ingest.md),
// which makes one thing that says "table top" enough (the depth of reflections in a glossy floor
// keeps it from being enough alone).
constexpr double kSeenBelow = 0.01;
constexpr double kUnderFloor = 0.02;
// This many things that stand on floors rising from a surface that nothing lies below make it a floor.
constexpr std::size_t kStandingOnFloor = 3;
// Fewer points than this say nothing of where a thing ends.
constexpr std::size_t kMinPoints = 20;

std::string listed(const std::vector<std::string>& names) {
    std::string out;
    for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
}

}  // namespace

double along(const model::Vec3& up, const model::Vec3& p) { return up.x * p.x + up.y * p.y + up.z * p.z; }

bool SurfaceEvidence::tableTop() const {
    // Things that stand on floors rising from a surface that nothing was seen below, and that nothing
    // reaches below: the floor, whatever small things a detector names on it (a carpet's pattern
    // seen as cakes and phones).
    if (pointsBelow < kSeenBelow && below.empty() && standing.size() >= kStandingOnFloor) return false;
    // A named thing reaching well below a surface with more under it than any floor has: whatever
    // seems to rise from it (a desk's monitor taken for a table) stands on it as on a table top.
    if (muchBelow() && !below.empty()) return true;
    const std::size_t against = onTop.size() + below.size() + topOf.size();
    const bool much = against >= 2 || !topOf.empty() || (against >= 1 && muchBelow());
    return much && against > standing.size();
}

bool SurfaceEvidence::muchBelow() const { return pointsBelow >= kUnderFloor; }

std::string SurfaceEvidence::describe() const {
    std::vector<std::string> parts;
    if (!onTop.empty())
        parts.push_back(fmt::format("{} on it ({})",
                                    onTop.size() == 1
                                        ? "1 thing that stands on tables rests"
                                        : fmt::format("{} things that stand on tables rest", onTop.size()),
                                    listed(onTop)));
    if (!below.empty())
        parts.push_back(fmt::format("{} below it ({})",
                                    below.size() == 1 ? "1 reaches" : fmt::format("{} reach", below.size()),
                                    listed(below)));
    if (!topOf.empty())
        parts.push_back(fmt::format(
            "it is the top of {} ({})",
            topOf.size() == 1 ? "1 thing that holds others" : fmt::format("{} things that hold others", topOf.size()),
            listed(topOf)));
    if (!standing.empty())
        parts.push_back(fmt::format("{} from it ({})",
                                    standing.size() == 1
                                        ? "1 thing that stands on floors rises"
                                        : fmt::format("{} things that stand on floors rise", standing.size()),
                                    listed(standing)));
    parts.push_back(fmt::format("{:.0f}% of the points lie below it", 100 * pointsBelow));
    return listed(parts);
}

SurfaceEvidence weighSurface(const Surface& surface, const std::vector<NamedThing>& things,
                             const std::vector<model::Vec3>& cloud, double unit) {
    SurfaceEvidence out;
    std::size_t under = 0, counted = 0;
    const std::size_t step = std::max<std::size_t>(1, cloud.size() / 20000);
    for (std::size_t i = 0; i < cloud.size(); i += step, ++counted)
        if (along(surface.up, cloud[i]) - surface.height < -kBelow * unit) ++under;
    out.pointsBelow = counted ? static_cast<double>(under) / static_cast<double>(counted) : 0;
    // Nothing reaches below a surface under which next to nothing was seen: a few of a thing's points
    // there are the reconstruction's noise (a table's under a kitchen floor, in 100 photos).
    const bool seenBelow = out.pointsBelow >= kSeenBelow;
    for (const auto& thing : things) {
        if (!thing.measures || thing.points.size() < kMinPoints) continue;
        std::vector<double> heights;
        heights.reserve(thing.points.size());
        for (const auto& p : thing.points) heights.push_back(along(surface.up, p) - surface.height);
        // Below: a tenth of its points under the surface. Resting: its lowest points on it (a chair's
        // are its legs' ends, a few of its points).
        const double low = detail::quantile(heights, 0.02), high = detail::quantile(heights, 0.9);
        const bool rests = std::abs(low) <= kRests * unit;
        // A table whose points lie on the surface, none rising from it: the surface is its top (a
        // kitchen table that ten photos look down at: its median and 90th percentile within 1 cm).
        const bool top = holdsThings(thing.category) && std::abs(detail::quantile(heights, 0.5)) <= kRests * unit &&
                         std::abs(high) <= kRests * unit;
        const Support support = usualSupport(thing.category);
        const bool below = reachesBelow(heights, unit);
        if (below && seenBelow)
            out.below.push_back(thing.category);
        else if (below)
            continue;
        else if (top)
            out.topOf.push_back(thing.category);
        else if (rests && support == Support::Surface)
            out.onTop.push_back(thing.category);
        else if (rests && support == Support::Floor && high - low >= kRises * unit)
            out.standing.push_back(thing.category);
    }
    return out;
}

bool reachesBelow(std::vector<double> heights, double unit) {
    return detail::quantile(std::move(heights), 0.1) < -kBelow * unit;
}

}  // namespace smql::ingest
