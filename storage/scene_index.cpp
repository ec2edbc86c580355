#include "storage/scene_index.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <unordered_map>

namespace smql::storage {

namespace {

// A box's centre along one axis (times two), with NaN last, so the sorts below stay well defined.
double centreKey(const model::Aabb& b, bool alongY) {
    double twice = alongY ? b.min.y + b.max.y : b.min.x + b.max.x;
    return std::isnan(twice) ? std::numeric_limits<double>::infinity() : twice;
}

// The float nearest below or at `v`, and the one nearest above or at it; beyond float's range, the
// largest finite float or an infinity on the side that still holds `v`.
float below(double v) {
    constexpr double kLargest = std::numeric_limits<float>::max();
    if (std::isnan(v)) return std::numeric_limits<float>::quiet_NaN();
    if (v >= kLargest) return std::isinf(v) ? std::numeric_limits<float>::infinity() : static_cast<float>(kLargest);
    if (v < -kLargest) return -std::numeric_limits<float>::infinity();
    const auto f = static_cast<float>(v);
    return static_cast<double>(f) > v ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}

float above(double v) { return -below(-v); }

}  // namespace

IndexBounds IndexBounds::around(const model::Aabb& exact) {
    return {below(exact.min.x), below(exact.min.y), below(exact.min.z),
            above(exact.max.x), above(exact.max.y), above(exact.max.z)};
}

std::vector<model::Aabb> packTiles(const std::vector<model::Aabb>& bounds, std::vector<std::uint32_t>& order) {
    auto byAxis = [&](bool alongY) {
        return [&bounds, alongY](std::uint32_t a, std::uint32_t b) {
            double ka = centreKey(bounds[a], alongY), kb = centreKey(bounds[b], alongY);
            return ka != kb ? ka < kb : a < b;
        };
    };
    std::sort(order.begin(), order.end(), byAxis(false));
    const std::size_t runs = (order.size() + SceneIndex::kBlock - 1) / SceneIndex::kBlock;
    const auto slices = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(runs))));
    const std::size_t perSlice = slices == 0 ? 0 : SceneIndex::kBlock * ((runs + slices - 1) / slices);
    for (std::size_t from = 0; from < order.size(); from += perSlice) {
        auto end = order.begin() + static_cast<std::ptrdiff_t>(std::min(order.size(), from + perSlice));
        std::sort(order.begin() + static_cast<std::ptrdiff_t>(from), end, byAxis(true));
    }
    std::vector<model::Aabb> runBounds;
    runBounds.reserve(runs);
    for (std::size_t from = 0; from < order.size(); from += SceneIndex::kBlock) {
        model::Aabb run = bounds[order[from]];
        for (std::size_t i = from + 1; i < std::min(order.size(), from + SceneIndex::kBlock); ++i) {
            const model::Aabb& b = bounds[order[i]];
            run.min = {std::min(run.min.x, b.min.x), std::min(run.min.y, b.min.y), std::min(run.min.z, b.min.z)};
            run.max = {std::max(run.max.x, b.max.x), std::max(run.max.y, b.max.y), std::max(run.max.z, b.max.z)};
        }
        runBounds.push_back(run);
    }
    return runBounds;
}

SceneIndex SceneIndex::of(const std::vector<model::Node>& nodes, std::uint64_t version) {
    SceneIndex index;
    index.version = version;
    index.entries.reserve(nodes.size());
    std::unordered_map<std::string_view, std::uint32_t> positions;
    for (const model::Node& n : nodes) {
        auto [at, added] = positions.try_emplace(n.category, static_cast<std::uint32_t>(index.categories.size()));
        if (added) index.categories.push_back(n.category);
        SceneIndexEntry entry{};  // zeroed (there is no padding, but reserved): entries are stored as bytes
        entry.bounds = IndexBounds::around(model::worldAabb(n.box));
        entry.category = at->second;
        entry.kind = n.kind;
        entry.geometry = n.geometry;
        entry.hidden = n.hidden ? 1 : 0;
        index.entries.push_back(entry);
    }
    index.pack();
    return index;
}

void SceneIndex::pack() {
    std::vector<model::Aabb> bounds;
    bounds.reserve(entries.size());
    spatialOrder.clear();
    for (std::uint32_t s = 0; s < entries.size(); ++s) {
        const auto& e = entries[s];
        bounds.push_back(e.bounds.aabb());
        if (e.kind != model::NodeKind::Scene && e.geometry != model::GeometryKind::None) spatialOrder.push_back(s);
    }
    // The runs' bounds are unions of floats: floats again, exactly.
    blockBounds.clear();
    for (const model::Aabb& run : packTiles(bounds, spatialOrder)) blockBounds.push_back(IndexBounds::around(run));
}

bool operator==(const SceneIndex& a, const SceneIndex& b) {
    auto sameBytes = [](const auto& x, const auto& y) {
        return x.size() == y.size() &&
               (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(*x.data())) == 0);
    };
    return a.version == b.version && a.categories == b.categories && sameBytes(a.entries, b.entries) &&
           a.spatialOrder == b.spatialOrder && sameBytes(a.blockBounds, b.blockBounds);
}

}  // namespace smql::storage
