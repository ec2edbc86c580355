#include "ingest/synth/palette.hpp"

#include <limits>

namespace smql::synth {

std::optional<Rgb> colorByName(std::string_view name) {
    if (name == "grey") name = "gray";
    for (const NamedColor& c : kNamedColors)
        if (c.name == name) return c.rgb;
    return std::nullopt;
}

std::string_view nearestColorName(double r, double g, double b) {
    std::string_view best;
    double bestDistance = std::numeric_limits<double>::max();
    for (const NamedColor& c : kNamedColors) {
        double dr = r - c.rgb.r, dg = g - c.rgb.g, db = b - c.rgb.b;
        double d = dr * dr + dg * dg + db * db;
        if (d < bestDistance) bestDistance = d, best = c.name;
    }
    return best;
}

Rgb neutralColor(std::string_view category) {
    if (category == "wall") return {214, 208, 196};   // warm off-white
    if (category == "floor") return {178, 160, 138};  // light oak
    if (category == "ceiling") return {236, 236, 232};
    if (category == "door") return {168, 138, 104};    // pale wood
    if (category == "window") return {196, 214, 226};  // pale sky behind glass
    return {190, 186, 180};
}

}  // namespace smql::synth
