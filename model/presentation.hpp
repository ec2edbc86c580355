// How a node is shown, one rule for every place that shows nodes (the exports, the map, the
// view's page, SHOW CATEGORIES and Python): its label `category#id`, its root-to-leaf path, the
// colour of its category in its scene.
#pragma once

#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "model/types.hpp"

namespace smql::model {

struct Rgb {
    std::uint8_t r = 0, g = 0, b = 0;
    friend bool operator==(const Rgb&, const Rgb&) = default;
};

// The colours of one scene's categories: fixed quiet ones for the structure (walls, floor, doors,
// windows), and for every other category its own colour of a qualitative palette, chosen so that no
// two categories of the scene look alike (docs/formats.md, "Colours"). A category keeps its colour
// in every scene with about as many categories, since its place in the palette follows its name.
class Palette {
public:
    // The categories of the scene's shown rooms, anchors and objects: those SHOW CATEGORIES lists
    // (frames and descriptions are not drawn, hidden nodes not shown).
    explicit Palette(std::span<const Node> nodes);
    explicit Palette(std::vector<std::string> categories);
    // A category the palette was not made with gets the colour it would have in a scene of its own.
    Rgb operator()(std::string_view category) const;

private:
    std::map<std::string, Rgb, std::less<>> colours_;
};

// Whether a node of this kind is drawn, and so has a colour of its scene's palette.
bool drawnKind(NodeKind kind);

// The distance between two colours as a person sees it: CIE 1976 delta E, in CIELAB of sRGB.
double perceivedDistance(const Rgb& a, const Rgb& b);

// The first `shown` of the items, joined by ", ", then " and N more" for the rest: how an error or a note names
// many things ("258.jpg, 259.jpg and 30 more").
std::string listFirst(const std::vector<std::string>& items, std::size_t shown);

// `#rrggbb`, as CSS, SVG and SHOW CATEGORIES write a colour.
std::string hexColour(const Rgb& colour);

// `category#id`, as the engine names a node.
std::string nodeLabel(const Node& node);

// Every node's path from the scene down, as the engine prints it (`room0 / wall#19 / sofa#50 /
// cushion#42`), in the order of scene.nodes.
std::vector<std::string> nodePaths(const SceneData& scene);

}  // namespace smql::model
