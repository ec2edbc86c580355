// `smql map` and `smql guide`'s picture (docs/guidance.md, "Maps"): a scene from above, laid out
// once in pixels and drawn by either renderer (SVG here, PNG with OpenCV in smql-ingest). The
// layout places every label where it overlaps no other (beside its thing with a leader line when
// its own place is taken, else a number in a key), and adds a legend and a scale bar.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "engine/engine.hpp"

namespace smql::view {

using Rgb = std::array<unsigned char, 3>;

struct MapOptions {
    bool fixtures = false;  // ceiling and wall fixtures (lights, switches, pictures) drawn too
    bool graph = false;     // guidance's decision points and their edges (to see how GUIDE routes)
};

// One step of a route to draw (GUIDE's step, x, y).
struct RouteMark {
    long long step = 0;
    double x = 0, y = 0;
};

struct Rect {
    double left = 0, top = 0, width = 0, height = 0;
    bool overlaps(const Rect& o) const {
        return left < o.left + o.width && o.left < left + width && top < o.top + o.height && o.top < top + height;
    }
};

struct MapPlan {
    struct Point {
        double x = 0, y = 0;
    };
    struct Shape {
        std::vector<Point> corners;  // a closed polygon
        Rgb fill{}, stroke{};
        bool filled = true;
    };
    struct Segment {
        Point a, b;
        Rgb colour{};
        double width = 1;
    };
    struct Label {
        std::string text;
        Rect box;             // where the text goes
        Point anchor;         // the thing it names
        bool leader = false;  // a line from the anchor to the box
        bool marker = false;  // a number in a circle (its text is in the key), or a route step
        Rgb colour{};
    };
    struct LegendEntry {
        std::string text;
        Rgb colour{};
    };

    std::string scene;
    int width = 0, height = 0;
    std::vector<Shape> shapes;      // in drawing order: floor, blocked cells, anchors, objects
    std::vector<Segment> segments;  // the guidance graph, leader lines, the route
    std::vector<Label> labels;      // objects' names or numbers, the route's steps
    std::vector<LegendEntry> legend;
    std::vector<std::string> key;  // "3  vase#12" for a thing numbered on the map
    Rect keyBox;                   // where the key's lines go
    Rect legendBox;
    struct ScaleBar {
        Point start;
        double pixels = 0;
        std::string text;  // "1 m"
    } scale;
    std::size_t fixturesLeftOut = 0;
};

inline constexpr double kMapTextHeight = 10;  // px: the label font's line, both renderers
inline constexpr double kMapCharWidth = 6;    // px: its advance (a monospace font)

MapPlan planMap(const Engine::SceneMap& map, const std::vector<RouteMark>& route, const MapOptions& options);
std::string renderSvg(const MapPlan& plan);

}  // namespace smql::view
