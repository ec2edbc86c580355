// How a node is shown, one rule for every place that shows nodes (the exports, the map, the
// view's page): its label `category#id`, its root-to-leaf path, the colour of its category.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "model/types.hpp"

namespace smql::model {

struct Rgb {
    std::uint8_t r = 0, g = 0, b = 0;
    friend bool operator==(const Rgb&, const Rgb&) = default;
};

// One colour per category, the same in every scene, file and picture: fixed greys and browns for the
// structure (walls, floor, doors, windows), a hue from the name's hash for everything else.
Rgb categoryColour(std::string_view category);

// `category#id`, as the engine names a node.
std::string nodeLabel(const Node& node);

// Every node's path from the scene down, as the engine prints it (`room0 / wall#19 / sofa#50 /
// cushion#42`), in the order of scene.nodes.
std::vector<std::string> nodePaths(const SceneData& scene);

}  // namespace smql::model
