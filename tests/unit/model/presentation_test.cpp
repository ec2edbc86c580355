// The scene's palette (model/presentation.hpp): categories of one scene never look alike, the
// structure keeps its fixed colours, and a category keeps its colour across scenes of a size.
#include <algorithm>
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "model/presentation.hpp"

using namespace smql;

namespace {

// The categories of the Replica room's objects and of a crowded ScanNet room, as people name them.
const std::vector<std::string> kReplicaCategories = {
    "basket",      "beanbag", "bench", "blanket",   "blinds",       "book",  "bottle",     "box",    "cabinet",
    "candle",      "chair",   "clock", "cushion",   "indoor-plant", "lamp",  "nightstand", "pillar", "pillow",
    "plant-stand", "plate",   "pot",   "rug",       "sculpture",    "shelf", "sofa",       "stool",  "table",
    "tv-screen",   "vase",    "vent",  "wall-plug", "wall",         "floor", "door",       "window"};

double closest(const model::Palette& palette, const std::vector<std::string>& categories) {
    double nearest = 1e9;
    for (std::size_t i = 0; i < categories.size(); ++i)
        for (std::size_t j = i + 1; j < categories.size(); ++j)
            nearest = std::min(nearest, model::perceivedDistance(palette(categories[i]), palette(categories[j])));
    return nearest;
}

}  // namespace

TEST_CASE("palette: no two categories of a scene look alike", "[model][palette]") {
    const model::Palette palette(kReplicaCategories);
    // Delta E 76 of 20 is plainly two colours side by side; the collisions (chair, book,
    // table and vent in one purple) were under 10.
    CHECK(closest(palette, kReplicaCategories) >= 20);
    for (const auto& category : {"chair", "book", "table", "vent"})
        CHECK(model::perceivedDistance(palette(category), {255, 45, 85}) >= 50);  // the view's highlight

    std::vector<std::string> many;
    for (int i = 0; i < 48; ++i) many.push_back("category-" + std::to_string(i));
    CHECK(closest(model::Palette(many), many) >= 20);
}

TEST_CASE("palette: the structure's colours are fixed, the rest follow the name", "[model][palette]") {
    const model::Palette small({"chair", "table", "wall"});
    CHECK(small("wall") == model::Rgb{205, 202, 195});
    CHECK(small("door") == model::Rgb{140, 92, 52});
    // Another scene of a few categories: the same colours for the same names.
    const model::Palette other({"chair", "table", "lamp", "sofa"});
    CHECK(small("chair") == other("chair"));
    CHECK(small("table") == other("table"));
    // Built from nodes, frames and descriptions take no colour of the palette.
    std::vector<model::Node> nodes(3);
    nodes[0].kind = model::NodeKind::Object, nodes[0].category = "chair";
    nodes[1].kind = model::NodeKind::Frame, nodes[1].category = "frame";
    nodes[2].kind = model::NodeKind::Description, nodes[2].category = "description";
    CHECK(model::Palette(nodes)("chair") == model::Palette(std::vector<std::string>{"chair"})("chair"));
    CHECK(model::hexColour({255, 8, 171}) == "#ff08ab");
}
