#include "ingest/geometry/scale_priors.hpp"

#include <algorithm>
#include <cassert>
#include <map>

#include <fmt/format.h>

#include "ingest/geometry/floor_evidence.hpp"
#include "ingest/geometry/robust.hpp"

namespace smql::ingest {

std::optional<ScaleEstimate> scaleFromHeights(const std::vector<NamedThing>& things, const model::Vec3& up,
                                              double floorHeight, double unit, bool seenWhole, std::size_t minThings) {
    // Kinds that stand in one kind of room (a fridge in a kitchen, a toilet in a bathroom) named in a
    // capture that names as many or more of another room's: one of the two names is wrong, so neither
    // measures the room. ScanNet's bathroom, its 296 frames without depth: two "fridges" (1.75 m) beside
    // two toilets put the scale 1.19x too large, and with the cameras' height, as wrong, the memory was
    // stored 1.21x too large. Fusion's doubt of a name among another room's things (outOfPlace,
    // object_fusion.cpp) needs the boxes in metres and the walls, which come after the scale; and it keeps a
    // name on a tie, where a prior, to be trusted, leaves both out.
    std::map<RoomKind, std::size_t> rooms;
    for (const auto& thing : things) ++rooms[roomKind(thing.category)];
    auto doubted = [&](const std::string& category) {
        const RoomKind own = roomKind(category);
        return own != RoomKind::Any && std::any_of(rooms.begin(), rooms.end(), [&](const auto& other) {
                   return other.first != RoomKind::Any && other.first != own && other.second >= rooms.at(own);
               });
    };
    struct Top {
        std::string_view category;
        double height = 0;  // the kind's typical height, metres
        double top = 0;     // the thing's, capture units above the floor
    };
    std::vector<Top> tops;
    std::map<std::string, int> counted, left, partial;
    for (const auto& thing : things) {
        auto height = typicalHeight(thing.category);
        if (!height || thing.points.empty()) continue;
        if (doubted(thing.category)) {
            ++left[thing.category];
            continue;
        }
        std::vector<double> above;
        for (const auto& p : thing.points) above.push_back(up.x * p.x + up.y * p.y + up.z * p.z - floorHeight);
        if (reachesBelow(above, unit)) continue;
        double top = detail::robustRange(std::move(above)).second;
        if (top > 0) tops.push_back({thing.category, *height, top});
    }
    std::map<std::string_view, double> tallest;  // by kindName
    for (const auto& t : tops) tallest[kindName(t.category)] = std::max(tallest[kindName(t.category)], t.top);
    std::vector<double> estimates;
    for (const auto& t : tops) {
        if (seenWhole && t.top < kShortOfItsKind * tallest[kindName(t.category)]) {
            ++partial[std::string(t.category)];
            continue;
        }
        estimates.push_back(t.height / t.top);
        ++counted[std::string(t.category)];
    }
    if (estimates.size() < std::max<std::size_t>(minThings, 1)) return std::nullopt;
    std::string kinds;
    for (const auto& [category, n] : counted)
        kinds += fmt::format("{}{} {}{} ({:.2f} m)", kinds.empty() ? "" : ", ", n, category, n == 1 ? "" : "s",
                             *typicalHeight(category));
    // "2 fridges, 1 toilet", wrapped in why they were left out; nothing when none was.
    auto leftOut = [](const std::map<std::string, int>& counts, std::string_view why) {
        std::string listed;
        for (const auto& [category, n] : counts)
            listed += fmt::format("{}{} {}{}", listed.empty() ? "" : ", ", n, category, n == 1 ? "" : "s");
        return listed.empty() ? listed : fmt::format(" (left out, {})", fmt::format(fmt::runtime(why), listed));
    };
    const std::string doubts = leftOut(left, "named beside another room's things: {}") +
                               leftOut(partial, "seen in part: {} short of the tallest of their kind");
    std::sort(estimates.begin(), estimates.end());
    bool twoAgree = false;
    for (std::size_t i = 1; i < estimates.size() && !twoAgree; ++i)
        twoAgree = estimates[i] <= (1 + kThingsAgree) * estimates[i - 1];
    const bool heldTogether = !seenWhole || twoAgree;
    const double median = detail::median(std::move(estimates));
    if (!heldTogether)
        return ScaleEstimate{
            .prior = fmt::format("the typical heights of {}{}: {:.4g} at their median, held by no two of them "
                                 "within {:.0f}%, so they do not measure the room",
                                 kinds, doubts, median, 100 * kThingsAgree),
            .scale = median,
            .heldTogether = false,
            .things = kinds};
    return ScaleEstimate{.prior = fmt::format("the typical heights of {}{}", kinds, doubts),
                         .scale = median,
                         .leads = twoAgree,
                         .things = kinds};
}

ScaleChoice combineScales(const std::vector<ScaleEstimate>& estimates) {
    assert(!estimates.empty());
    std::vector<double> values;
    for (const auto& e : estimates) values.push_back(e.scale);
    ScaleChoice out;
    auto [low, high] = std::minmax_element(values.begin(), values.end());
    // Two priors a factor apart leave no majority: one of them measured something wrong (a table top
    // taken for the floor), and the more trusted one, listed first, is kept.
    const bool split = values.size() == 2 && *high > kDisagreement * *low;
    const bool leads = estimates.front().leads;
    out.scale = split || leads ? values.front() : detail::median(values);
    out.spread = (*high - *low) / out.scale;
    if (split) out.split = *high / *low;
    std::string each;
    for (const auto& e : estimates) each += fmt::format("; {}: {:.4g}", e.prior, e.scale);
    if (estimates.size() == 1)
        out.note = fmt::format("scale: {:.4g} m per unit from one prior{}", out.scale, each);
    else if (leads && !split)
        out.note = fmt::format(
            "scale: {:.4g} m per unit from the first of {} priors, which the others check: they "
            "agree within {:.0f}%{}",
            out.scale, estimates.size(), 100 * out.spread, each);
    else if (split)
        out.note = fmt::format(
            "scale: {:.4g} m per unit from the first of 2 priors that disagree by a factor of {:.1f}: check the "
            "floor and the objects, or give --scale{}",
            out.scale, *high / *low, each);
    else
        out.note = fmt::format("scale: {:.4g} m per unit, the median of {} priors that agree within {:.0f}%{}",
                               out.scale, estimates.size(), 100 * out.spread, each);
    return out;
}

}  // namespace smql::ingest
