// The map as SVG: the plan's shapes, lines and labels, text in a monospace font whose advance is
// the layout's kMapCharWidth.
#include <fmt/format.h>

#include "view/map.hpp"

namespace smql::view {

namespace {

std::string colour(const Rgb& c) { return fmt::format("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]); }

std::string escaped(const std::string& text) {
    std::string out;
    for (char c : text) {
        if (c == '&')
            out += "&amp;";
        else if (c == '<')
            out += "&lt;";
        else if (c == '>')
            out += "&gt;";
        else if (c == '"')
            out += "&quot;";
        else
            out += c;
    }
    return out;
}

std::string text(double x, double y, const std::string& content, const char* anchor = "start",
                 const char* weight = "normal") {
    return fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="{}" font-weight="{}">{}</text>)", x, y, anchor,
                       weight, escaped(content)) +
           "\n";
}

}  // namespace

std::string renderSvg(const MapPlan& plan) {
    std::string svg =
        fmt::format(R"(<svg xmlns="http://www.w3.org/2000/svg" width="{0}" height="{1}" viewBox="0 0 {0} {1}" )"
                    R"(font-family="DejaVu Sans Mono, monospace" font-size="{2}px">)"
                    "\n<title>{3}</title>\n<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n",
                    plan.width, plan.height, kMapTextHeight, escaped("smql map: " + plan.scene));
    for (const auto& s : plan.shapes) {
        std::string points;
        for (const auto& p : s.corners) points += fmt::format("{:.1f},{:.1f} ", p.x, p.y);
        svg += fmt::format(R"(<polygon points="{}" fill="{}" stroke="{}" stroke-width="1"/>)", points,
                           s.filled ? colour(s.fill) : "none", colour(s.stroke)) +
               "\n";
    }
    for (const auto& l : plan.segments)
        svg += fmt::format(R"(<line x1="{:.1f}" y1="{:.1f}" x2="{:.1f}" y2="{:.1f}" stroke="{}" stroke-width="{}"/>)",
                           l.a.x, l.a.y, l.b.x, l.b.y, colour(l.colour), l.width) +
               "\n";
    for (const auto& l : plan.labels) {
        const double cx = l.box.left + l.box.width / 2, cy = l.box.top + l.box.height / 2;
        if (l.marker) {
            svg += fmt::format(R"(<circle cx="{:.1f}" cy="{:.1f}" r="{:.1f}" fill="{}"/>)", cx, cy, l.box.width / 2,
                               colour(l.colour)) +
                   "\n";
            svg += fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="middle" fill="#ffffff">{}</text>)", cx,
                               cy + kMapTextHeight / 2 - 1.5, escaped(l.text)) +
                   "\n";
        } else {
            svg += fmt::format(R"(<rect x="{:.1f}" y="{:.1f}" width="{:.1f}" height="{:.1f}" fill="#ffffff" )"
                               R"(fill-opacity="0.75"/>)",
                               l.box.left, l.box.top, l.box.width, l.box.height) +
                   "\n";
            svg += text(cx, cy + kMapTextHeight / 2 - 1.5, l.text, "middle");
        }
    }
    const double line = kMapTextHeight + 6;
    svg += text(plan.legendBox.left, plan.legendBox.top, "Legend", "start", "bold");
    for (std::size_t i = 0; i < plan.legend.size(); ++i) {
        const double y = plan.legendBox.top + (i + 1) * line;
        svg += fmt::format(R"(<rect x="{:.1f}" y="{:.1f}" width="10" height="10" fill="{}"/>)", plan.legendBox.left,
                           y - kMapTextHeight + 1, colour(plan.legend[i].colour)) +
               "\n";
        svg += text(plan.legendBox.left + 16, y, plan.legend[i].text);
    }
    if (!plan.key.empty()) {
        svg += text(plan.keyBox.left, plan.keyBox.top, "Numbered on the map", "start", "bold");
        for (std::size_t i = 0; i < plan.key.size(); ++i)
            svg += text(plan.keyBox.left, plan.keyBox.top + (i + 1) * line, plan.key[i]);
    }
    const auto& bar = plan.scale;
    svg += fmt::format(R"(<rect x="{:.1f}" y="{:.1f}" width="{:.1f}" height="5" fill="#282828"/>)", bar.start.x,
                       bar.start.y, bar.pixels) +
           "\n";
    svg += text(bar.start.x + bar.pixels + 6, bar.start.y + 6, bar.text);
    return svg + "</svg>\n";
}

}  // namespace smql::view
