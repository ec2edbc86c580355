#include "model/presentation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace smql::model {

namespace {

struct FixedColour {
    std::string_view category;
    Rgb colour;
};

// The structure in quiet colours, so that the things in the room stand out against it.
constexpr FixedColour kStructureColours[] = {
    {"wall", {205, 202, 195}},
    {"floor", {150, 140, 128}},
    {"door", {140, 92, 52}},
    {"window", {150, 200, 232}},
};

// Colours the palette keeps away from besides the structure's: the view's highlight of a hit
// (view/page/view.js), which no category may come near, and its background.
constexpr Rgb kHighlight{255, 45, 85}, kBackground{244, 245, 247};
constexpr double kHighlightClearance = 50;  // delta E

// Palettes for scenes of up to 12, 24, 48 and 96 categories: each a prefix of one sequence, so
// the colours of a small scene are the sequence's most distinct ones.
constexpr std::size_t kSmallestPalette = 12, kLargestPalette = 96;

// Stable across runs and machines, unlike std::hash.
std::uint32_t fnv1a(std::string_view text) {
    std::uint32_t hash = 2166136261U;
    for (char c : text) {
        hash ^= static_cast<std::uint8_t>(c);
        hash *= 16777619U;
    }
    return hash;
}

struct Lab {
    double l, a, b;
};

Lab toLab(const Rgb& c) {
    auto linear = [](std::uint8_t channel) {
        double v = channel / 255.0;
        return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
    };
    const double r = linear(c.r), g = linear(c.g), b = linear(c.b);
    // sRGB to XYZ (D65), relative to the white point.
    const double x = (0.4124 * r + 0.3576 * g + 0.1805 * b) / 0.95047;
    const double y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
    const double z = (0.0193 * r + 0.1192 * g + 0.9505 * b) / 1.08883;
    auto f = [](double t) { return t > 216.0 / 24389 ? std::cbrt(t) : (24389.0 / 27 * t + 16) / 116; };
    return {116 * f(y) - 16, 500 * (f(x) - f(y)), 200 * (f(y) - f(z))};
}

double distance(const Lab& p, const Lab& q) { return std::hypot(p.l - q.l, p.a - q.a, p.b - q.b); }

// The qualitative sequence: from the sRGB colours of 16 levels a channel that are neither dark,
// pale nor greyish (lightness 45-85, chroma 30 and more) nor near the highlight, each next one the
// farthest from those chosen and from the reserved colours (greedy farthest-point sampling in
// CIELAB). Any two of the first 12 are 40 delta E apart or more, of the first 24 30, of the first
// 48 20.
const std::vector<Rgb>& qualitativeSequence() {
    static const std::vector<Rgb> sequence = [] {
        std::vector<Rgb> candidates;
        std::vector<Lab> labs;
        for (int r = 0; r < 256; r += 17)
            for (int g = 0; g < 256; g += 17)
                for (int b = 0; b < 256; b += 17) {
                    const Rgb c{static_cast<std::uint8_t>(r), static_cast<std::uint8_t>(g),
                                static_cast<std::uint8_t>(b)};
                    const Lab lab = toLab(c);
                    if (lab.l < 45 || lab.l > 85 || std::hypot(lab.a, lab.b) < 30 ||
                        distance(lab, toLab(kHighlight)) < kHighlightClearance)
                        continue;
                    candidates.push_back(c);
                    labs.push_back(lab);
                }
        std::vector<double> nearest(candidates.size(), std::numeric_limits<double>::infinity());
        auto keepAway = [&](const Lab& from) {
            for (std::size_t i = 0; i < labs.size(); ++i) nearest[i] = std::min(nearest[i], distance(labs[i], from));
        };
        for (const auto& [name, colour] : kStructureColours) keepAway(toLab(colour));
        for (const Rgb& colour : {kHighlight, kBackground}) keepAway(toLab(colour));
        std::vector<Rgb> out;
        while (out.size() < kLargestPalette) {
            const std::size_t next =
                static_cast<std::size_t>(std::max_element(nearest.begin(), nearest.end()) - nearest.begin());
            out.push_back(candidates[next]);
            keepAway(labs[next]);
        }
        return out;
    }();
    return sequence;
}

const Rgb* structureColour(std::string_view category) {
    for (const auto& [name, colour] : kStructureColours)
        if (name == category) return &colour;
    return nullptr;
}

}  // namespace

bool drawnKind(NodeKind kind) { return kind == NodeKind::Room || kind == NodeKind::Anchor || kind == NodeKind::Object; }

Palette::Palette(std::span<const Node> nodes)
    : Palette([&] {
          std::vector<std::string> categories;
          for (const Node& node : nodes)
              if (drawnKind(node.kind) && !node.hidden) categories.push_back(node.category);
          return categories;
      }()) {}

Palette::Palette(std::vector<std::string> categories) {
    std::sort(categories.begin(), categories.end());
    categories.erase(std::unique(categories.begin(), categories.end()), categories.end());
    std::erase_if(categories, [](const std::string& c) { return structureColour(c) != nullptr; });
    std::size_t size = kSmallestPalette;
    while (size < categories.size() && size < kLargestPalette) size *= 2;
    const std::vector<Rgb>& sequence = qualitativeSequence();
    std::vector<bool> taken(size, false);
    std::size_t used = 0;
    // Each category at the place its name hashes to, or the next free one (by name order, so the
    // choice is the same on every run); past the largest palette colours repeat.
    for (const std::string& category : categories) {
        std::size_t slot = fnv1a(category) % size;
        if (used < size) {
            while (taken[slot]) slot = (slot + 1) % size;
            taken[slot] = true;
            ++used;
        }
        colours_.emplace(category, sequence[slot]);
    }
}

Rgb Palette::operator()(std::string_view category) const {
    if (const Rgb* fixed = structureColour(category)) return *fixed;
    if (auto it = colours_.find(category); it != colours_.end()) return it->second;
    return qualitativeSequence()[fnv1a(category) % kSmallestPalette];
}

double perceivedDistance(const Rgb& a, const Rgb& b) { return distance(toLab(a), toLab(b)); }

std::string listFirst(const std::vector<std::string>& items, std::size_t shown) {
    const auto end = items.begin() + static_cast<std::ptrdiff_t>(std::min(shown, items.size()));
    std::string out = fmt::format("{}", fmt::join(items.begin(), end, ", "));
    if (items.size() > shown) out += fmt::format(" and {} more", items.size() - shown);
    return out;
}

std::string hexColour(const Rgb& colour) { return fmt::format("#{:02x}{:02x}{:02x}", colour.r, colour.g, colour.b); }

std::string nodeLabel(const model::Node& node) { return node.category + "#" + std::to_string(node.id); }

std::vector<std::string> nodePaths(const model::SceneData& scene) {
    std::unordered_map<model::NodeId, std::size_t> indexOf;
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) indexOf.emplace(scene.nodes[i].id, i);
    std::vector<std::string> paths;
    paths.reserve(scene.nodes.size());
    for (const model::Node& node : scene.nodes) {
        std::vector<const model::Node*> chain{&node};
        // Bounded by the node count, so that a parent cycle in a damaged scene cannot hang an export.
        for (auto it = indexOf.find(node.parent); it != indexOf.end() && chain.size() <= scene.nodes.size();
             it = indexOf.find(chain.back()->parent))
            chain.push_back(&scene.nodes[it->second]);
        std::string path = scene.info.name;
        for (auto up = chain.rbegin(); up != chain.rend(); ++up) path += " / " + nodeLabel(**up);
        paths.push_back(std::move(path));
    }
    return paths;
}

}  // namespace smql::model
