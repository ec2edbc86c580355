#include "ingest/geometry/scale_priors.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <map>
#include <set>

#include <fmt/format.h>

#include "ingest/geometry/floor_evidence.hpp"
#include "ingest/geometry/robust.hpp"

namespace smql::ingest {

namespace {

// Whether each thing's name is in doubt as a measure of the room (nothing in the capture's units is known in
// metres yet).
std::vector<bool> namesInDoubt(const std::vector<NamedThing>& things, const model::Vec3& up, double floorHeight) {
    // Kinds that stand in one kind of room (a fridge in a kitchen, a toilet in a bathroom) named within
    // kOneRoom times the taller's height of things of another room's kinds stand in one room with them: one of
    // the two names is wrong. The room is the one of which more kinds are named there (a fridge, an oven and a
    // microwave beside one "toilet": ScanNet's apartment's kitchen), counted by kind, since one thing is often
    // named twice; where neither has more, the bathroom's (roomOutweighs, typical_sizes.hpp). A name fusion did not
    // keep (a toilet stored as "object") counts among them. ScanNet's bathroom, its 296 frames without depth: three
    // "fridges" beside two toilets outnumbered them, here and in fusion, which stored the toilets as "object",
    // and the fridges' heights, with a chair's and a table's, led the scale 1.36x and 1.30x too large, the
    // cameras' assumed height, as wrong, checking it. Farther apart they are rooms of one home (the
    // apartment's toilet stands 4.3 m from its fridge, 2.7 times the fridge's 1.57 m). Distances and heights
    // are both in capture units, so the test needs no scale; fusion's doubt (outOfPlace, object_fusion.cpp)
    // needs metres and the walls, which come after the scale.
    constexpr double kOneRoom = 2;  // a bathroom's or a kitchen's side, 1.5-4 m, is about twice a fridge's height
    struct Place {
        model::Vec3 centre;  // the medians of its points
        double top = 0;      // above the floor
    };
    std::vector<std::optional<Place>> places(things.size());  // of things that stand in one kind of room
    for (std::size_t i = 0; i < things.size(); ++i) {
        if (!oneRoom(roomKind(things[i].category)) || things[i].points.empty()) continue;
        std::vector<double> xs, ys, zs, above;
        for (const auto& p : things[i].points) {
            xs.push_back(p.x);
            ys.push_back(p.y);
            zs.push_back(p.z);
            above.push_back(along(up, p) - floorHeight);
        }
        places[i] = Place{{detail::median(std::move(xs)), detail::median(std::move(ys)), detail::median(std::move(zs))},
                          std::max(0.0, detail::robustRange(std::move(above)).second)};
    }
    auto oneRoom = [&](const Place& a, const Place& b) {
        const model::Vec3 d{a.centre.x - b.centre.x, a.centre.y - b.centre.y, a.centre.z - b.centre.z};
        const double rise = along(up, d);
        const double apart = std::sqrt(std::max(0.0, d.x * d.x + d.y * d.y + d.z * d.z - rise * rise));
        return apart <= kOneRoom * std::max(a.top, b.top);
    };
    std::vector<bool> doubted(things.size());
    for (std::size_t i = 0; i < things.size(); ++i) {
        if (!places[i]) continue;
        std::map<RoomKind, std::set<std::string_view>> kinds;  // named in one room with thing i
        for (std::size_t j = 0; j < things.size(); ++j)
            if (places[j] && (j == i || oneRoom(*places[i], *places[j])))
                kinds[roomKind(things[j].category)].insert(kindName(things[j].category));
        const std::size_t own = kinds.at(roomKind(things[i].category)).size();
        const RoomKind ownRoom = roomKind(things[i].category);
        doubted[i] = std::any_of(kinds.begin(), kinds.end(), [&](const auto& other) {
            return other.first != ownRoom && roomOutweighs(other.first, other.second.size(), ownRoom, own);
        });
    }
    return doubted;
}

// What the heights are measured above: the floor (typicalHeight) or a table top (typicalHeightOnTop).
enum class Above { Floor, TableTop };

std::optional<double> usualHeight(std::string_view category, Above above) {
    return above == Above::Floor ? typicalHeight(category) : typicalHeightOnTop(category);
}

// "2 fridges, 1 toilet"; with `heights`, each kind's typical height above that after it: "2 fridges (1.75 m)".
std::string listCounts(const std::map<std::string, int>& counts, std::optional<Above> heights = std::nullopt) {
    std::string listed;
    for (const auto& [category, n] : counts) {
        listed += fmt::format("{}{} {}{}", listed.empty() ? "" : ", ", n, category, n == 1 ? "" : "s");
        if (heights) listed += fmt::format(" ({:.2f} m)", usualHeight(category, *heights).value_or(0));
    }
    return listed;
}

// Whether a thing's height would measure the room: a measure (NamedThing::measures) of a kind of a typical height.
bool measuresHeight(const NamedThing& thing, Above above) {
    return thing.measures && !thing.points.empty() && usualHeight(thing.category, above);
}

// How the heights prior takes each thing: no measure of height (measuresHeight), left out (its name in doubt, its
// points reaching well below the floor or top `base`, or, with `seenWhole`, its top short of the tallest of its kind:
// seen in part), or counted, with its top in capture units above `base`.
struct Taken {
    enum class As { NoMeasure, Doubted, BelowFloor, Partial, Counted } as = As::NoMeasure;
    double top = 0;
};

std::vector<Taken> takeHeights(const std::vector<NamedThing>& things, const model::Vec3& up, double base, double unit,
                               bool seenWhole, Above over = Above::Floor) {
    const std::vector<bool> doubted = namesInDoubt(things, up, base);
    std::vector<Taken> out(things.size());
    std::map<std::string_view, double> tallest;  // by kindName
    for (std::size_t i = 0; i < things.size(); ++i) {
        if (!measuresHeight(things[i], over)) continue;
        if (doubted[i]) {
            out[i].as = Taken::As::Doubted;
            continue;
        }
        std::vector<double> above;
        for (const auto& p : things[i].points) above.push_back(along(up, p) - base);
        if (reachesBelow(above, unit)) {
            out[i].as = Taken::As::BelowFloor;
            continue;
        }
        const double top = detail::robustRange(std::move(above)).second;
        if (top <= 0) continue;
        out[i] = {Taken::As::Counted, top};
        double& kindTallest = tallest[kindName(things[i].category)];
        kindTallest = std::max(kindTallest, top);
    }
    if (seenWhole)
        for (std::size_t i = 0; i < things.size(); ++i)
            if (out[i].as == Taken::As::Counted && out[i].top < kShortOfItsKind * tallest[kindName(things[i].category)])
                out[i].as = Taken::As::Partial;
    return out;
}

// The things taken as `as`, by category.
std::map<std::string, int> countTaken(const std::vector<NamedThing>& things, const std::vector<Taken>& taken,
                                      Taken::As as) {
    std::map<std::string, int> out;
    for (std::size_t i = 0; i < things.size(); ++i)
        if (taken[i].as == as) ++out[things[i].category];
    return out;
}

}  // namespace

HeightsLeftOut heightsLeftOut(const std::vector<NamedThing>& things, const model::Vec3& up, double floorHeight,
                              double unit, bool seenWhole) {
    const std::vector<Taken> taken = takeHeights(things, up, floorHeight, unit, seenWhole);
    return {listCounts(countTaken(things, taken, Taken::As::Doubted)),
            listCounts(countTaken(things, taken, Taken::As::BelowFloor)),
            listCounts(countTaken(things, taken, Taken::As::Partial)),
            listCounts(countTaken(things, taken, Taken::As::Counted))};
}

namespace {

// scaleFromHeights above the floor or a table top; `where` follows the things in the prior's name.
std::optional<ScaleEstimate> heightsPrior(const std::vector<NamedThing>& things, const model::Vec3& up, double base,
                                          double unit, bool seenWhole, std::size_t minThings, Above over,
                                          std::string_view where) {
    const std::vector<Taken> taken = takeHeights(things, up, base, unit, seenWhole, over);
    std::vector<double> estimates;
    for (std::size_t i = 0; i < things.size(); ++i)
        if (taken[i].as == Taken::As::Counted)
            estimates.push_back(*usualHeight(things[i].category, over) / taken[i].top);
    if (estimates.size() < std::max<std::size_t>(minThings, 1)) return std::nullopt;
    const std::map<std::string, int> counted = countTaken(things, taken, Taken::As::Counted);
    const std::string kinds = listCounts(counted, over) + std::string(where);
    // "2 fridges, 1 toilet", wrapped in why they were left out; nothing when none was.
    auto leftOut = [](const std::map<std::string, int>& counts, std::string_view why) {
        const std::string listed = listCounts(counts);
        return listed.empty() ? listed : fmt::format(" (left out, {})", fmt::format(fmt::runtime(why), listed));
    };
    const std::string doubts =
        leftOut(countTaken(things, taken, Taken::As::Doubted), "named beside another room's things: {}") +
        leftOut(countTaken(things, taken, Taken::As::BelowFloor), over == Above::Floor
                                                                      ? "their points reaching below the floor: {}"
                                                                      : "their points reaching below the top: {}") +
        leftOut(countTaken(things, taken, Taken::As::Partial), "seen in part: {} short of the tallest of their kind");
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

}  // namespace

std::optional<ScaleEstimate> scaleFromHeights(const std::vector<NamedThing>& things, const model::Vec3& up,
                                              double floorHeight, double unit, bool seenWhole, std::size_t minThings) {
    return heightsPrior(things, up, floorHeight, unit, seenWhole, minThings, Above::Floor, "");
}

std::optional<ScaleEstimate> scaleFromHeightsOnTop(const std::vector<NamedThing>& things, const model::Vec3& up,
                                                   double topHeight, double unit) {
    return heightsPrior(things, up, topHeight, unit, /*seenWhole=*/false, /*minThings=*/1, Above::TableTop,
                        " above the table top");
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
