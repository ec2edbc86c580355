// The named colours of smql: the `color` attribute values the room generator
// assigns, the RGB each is rendered with by `smql synth`, and the colour the
// ingest names an object from its pixels. One table, so that the renderer and
// the namer cannot drift apart (docs/ingest.md, "Synthetic captures").
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace smql::synth {

struct Rgb {
    std::uint8_t r = 0, g = 0, b = 0;
    friend bool operator==(const Rgb&, const Rgb&) = default;
};

struct NamedColor {
    std::string_view name;
    Rgb rgb;
};

// Chosen so that each stays the nearest to itself when scaled by a shading
// factor: in RGB (Euclidean) for any factor in [0.78, 1.05], in CIE Lab with
// lightness weighted by 0.5 (what ingest's colour naming uses) for any factor
// in [0.72, 1.3]. Synthetic frames shade surfaces by 0.87..0.99 times a
// texture of mean 1 (+-22 %), so an object's pixels name the colour it was
// rendered with.
inline constexpr std::array<NamedColor, 11> kNamedColors = {{
    {"red", {200, 30, 35}},
    {"orange", {240, 120, 20}},
    {"yellow", {235, 220, 50}},
    {"green", {45, 150, 60}},
    {"blue", {40, 80, 200}},
    {"purple", {125, 55, 165}},
    {"pink", {240, 110, 180}},
    {"brown", {120, 75, 40}},
    {"black", {25, 25, 25}},
    {"white", {250, 250, 250}},
    {"gray", {110, 110, 110}},
}};

inline std::span<const NamedColor> namedColors() { return kNamedColors; }

// The palette entry of that name ("grey" is accepted for "gray").
std::optional<Rgb> colorByName(std::string_view name);

// The palette name nearest to an RGB colour (Euclidean distance in RGB).
std::string_view nearestColorName(double r, double g, double b);

// What anchors (walls, floor, ceiling, door, window ...) and objects without a
// `color` attribute are rendered with: light neutral tones, never a palette colour.
Rgb neutralColor(std::string_view category);

}  // namespace smql::synth
