#include "model/presentation.hpp"

#include <array>
#include <cmath>
#include <unordered_map>

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

// Hues spread by the name's FNV-1a hash: stable across runs and machines, unlike std::hash.
std::uint32_t fnv1a(std::string_view text) {
    std::uint32_t hash = 2166136261U;
    for (char c : text) {
        hash ^= static_cast<std::uint8_t>(c);
        hash *= 16777619U;
    }
    return hash;
}

Rgb fromHsv(double hueDegrees, double saturation, double value) {
    double chroma = value * saturation;
    double sector = hueDegrees / 60.0;
    double second = chroma * (1 - std::abs(std::fmod(sector, 2.0) - 1));
    // Which channel holds the chroma and which the second largest part, by sixth of the hue circle.
    const std::array<std::array<double, 3>, 6> bySector = {{{chroma, second, 0},
                                                            {second, chroma, 0},
                                                            {0, chroma, second},
                                                            {0, second, chroma},
                                                            {second, 0, chroma},
                                                            {chroma, 0, second}}};
    const std::array<double, 3>& rgb = bySector[static_cast<std::size_t>(sector) % 6];
    double lift = value - chroma;
    auto byte = [&](double channel) { return static_cast<std::uint8_t>(std::lround((channel + lift) * 255)); };
    return {byte(rgb[0]), byte(rgb[1]), byte(rgb[2])};
}

}  // namespace

Rgb categoryColour(std::string_view category) {
    for (const auto& [name, colour] : kStructureColours)
        if (name == category) return colour;
    return fromHsv(fnv1a(category) % 360, 0.55, 0.85);
}

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
