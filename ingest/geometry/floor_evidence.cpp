#include "ingest/geometry/floor_evidence.hpp"

#include <cmath>

#include <fmt/format.h>

#include "ingest/geometry/robust.hpp"
#include "ingest/geometry/typical_sizes.hpp"

namespace smql::ingest {

namespace {

// Metres. A thing rests on the surface when its lower end is this close to it; it reaches below
// when its lower end is this far under it (further than depth noise and a box's loose points).
constexpr double kRests = 0.08;
constexpr double kBelow = 0.2;
// A thing that stands on floors counts for the surface only when it rises this far from it: a
// table whose top alone was seen rests on the plane of its own top.
constexpr double kRises = 0.3;
// Fewer points than this say nothing of where a thing ends.
constexpr std::size_t kMinPoints = 20;

double along(const model::Vec3& up, const model::Vec3& p) { return up.x * p.x + up.y * p.y + up.z * p.z; }

std::string listed(const std::vector<std::string>& names) {
    std::string out;
    for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
}

}  // namespace

bool SurfaceEvidence::tableTop() const {
    const std::size_t against = onTop.size() + below.size();
    return against >= 2 && against > standing.size();
}

std::string SurfaceEvidence::describe() const {
    std::vector<std::string> parts;
    if (!onTop.empty())
        parts.push_back(fmt::format("{} that stand on tables rest on it ({})",
                                    onTop.size() == 1 ? "1 thing" : fmt::format("{} things", onTop.size()),
                                    listed(onTop)));
    if (!below.empty())
        parts.push_back(fmt::format("{} below it ({})",
                                    below.size() == 1 ? "1 reaches" : fmt::format("{} reach", below.size()),
                                    listed(below)));
    if (!standing.empty())
        parts.push_back(
            fmt::format("{} on floors rise from it ({})",
                        standing.size() == 1 ? "1 thing that stands" : fmt::format("{} that stand", standing.size()),
                        listed(standing)));
    parts.push_back(fmt::format("{:.0f}% of the points lie below it", 100 * pointsBelow));
    return listed(parts);
}

SurfaceEvidence weighSurface(const Surface& surface, const std::vector<NamedThing>& things,
                             const std::vector<model::Vec3>& cloud, double unit) {
    SurfaceEvidence out;
    for (const auto& thing : things) {
        if (thing.points.size() < kMinPoints) continue;
        std::vector<double> heights;
        heights.reserve(thing.points.size());
        for (const auto& p : thing.points) heights.push_back(along(surface.up, p) - surface.height);
        // Below: a tenth of its points under the surface. Resting: its lowest points on it (a chair's
        // are its legs' ends, a few of its points).
        const double low = detail::quantile(heights, 0.02), high = detail::quantile(heights, 0.9);
        const bool rests = std::abs(low) <= kRests * unit;
        const Support support = usualSupport(thing.category);
        if (detail::quantile(heights, 0.1) < -kBelow * unit)
            out.below.push_back(thing.category);
        else if (rests && support == Support::Surface)
            out.onTop.push_back(thing.category);
        else if (rests && support == Support::Floor && high - low >= kRises * unit)
            out.standing.push_back(thing.category);
    }
    std::size_t under = 0, counted = 0;
    const std::size_t step = std::max<std::size_t>(1, cloud.size() / 20000);
    for (std::size_t i = 0; i < cloud.size(); i += step, ++counted)
        if (along(surface.up, cloud[i]) - surface.height < -kBelow * unit) ++under;
    out.pointsBelow = counted ? static_cast<double>(under) / static_cast<double>(counted) : 0;
    return out;
}

}  // namespace smql::ingest
