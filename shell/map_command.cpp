#include "shell/map_command.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "engine/engine.hpp"
#include "ingest/capture/media.hpp"
#include "model/error.hpp"
#include "model/geometry.hpp"
#include "model/names.hpp"
#include "storage/output_guard.hpp"
#include "view/map.hpp"

namespace smql::shell {

namespace fs = std::filesystem;

namespace {

// One row of GUIDE's answer, as the files show it.
struct RouteStep {
    std::int64_t step = 0;
    std::string instruction, landmark;
    std::optional<std::int64_t> landmarkId;
    double x = 0, y = 0, distance = 0;
};

cv::Scalar bgr(const view::Rgb& c) { return {double(c[2]), double(c[1]), double(c[0])}; }
cv::Point pixel(const view::MapPlan::Point& p) {
    return {static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y))};
}

// OpenCV's Hershey font scaled to the layout's character advance.
double fontScale() {
    static const double scale = [] {
        int baseline = 0;
        const double advance =
            cv::getTextSize("abcdefghijklmnopqrstuvwxyz#0123456789", cv::FONT_HERSHEY_SIMPLEX, 1.0, 1, &baseline)
                .width /
            37.0;
        return view::kMapCharWidth / advance;
    }();
    return scale;
}

void drawText(cv::Mat& image, const std::string& text, double centreX, double baselineY, const cv::Scalar& colour,
              bool centred = true) {
    int baseline = 0;
    const auto size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, fontScale(), 1, &baseline);
    const int x = static_cast<int>(std::lround(centred ? centreX - size.width / 2.0 : centreX));
    cv::putText(image, text, {x, static_cast<int>(std::lround(baselineY))}, cv::FONT_HERSHEY_SIMPLEX, fontScale(),
                colour, 1, cv::LINE_AA);
}

// The map as a PNG: the same plan the SVG draws.
cv::Mat renderPng(const view::MapPlan& plan) {
    cv::Mat image(plan.height, plan.width, CV_8UC3, cv::Scalar(255, 255, 255));
    for (const auto& s : plan.shapes) {
        std::vector<cv::Point> corners;
        for (const auto& p : s.corners) corners.push_back(pixel(p));
        if (s.filled) cv::fillConvexPoly(image, corners, bgr(s.fill), cv::LINE_AA);
        cv::polylines(image, corners, true, bgr(s.stroke), 1, cv::LINE_AA);
    }
    for (const auto& l : plan.segments)
        cv::line(image, pixel(l.a), pixel(l.b), bgr(l.colour), std::max(1, static_cast<int>(std::lround(l.width))),
                 cv::LINE_AA);
    const cv::Scalar dark(40, 40, 40), white(255, 255, 255);
    for (const auto& l : plan.labels) {
        const double cx = l.box.left + l.box.width / 2, cy = l.box.top + l.box.height / 2;
        if (l.marker) {
            cv::circle(image, pixel({cx, cy}), static_cast<int>(l.box.width / 2), bgr(l.colour), cv::FILLED,
                       cv::LINE_AA);
            drawText(image, l.text, cx, cy + view::kMapTextHeight / 2 - 1.5, white);
            continue;
        }
        cv::Rect box(static_cast<int>(l.box.left), static_cast<int>(l.box.top), static_cast<int>(l.box.width),
                     static_cast<int>(l.box.height));
        box &= cv::Rect(0, 0, image.cols, image.rows);
        cv::Mat region = image(box);
        cv::addWeighted(region, 0.25, cv::Mat(region.size(), region.type(), white), 0.75, 0, region);
        drawText(image, l.text, cx, cy + view::kMapTextHeight / 2 - 1.5, dark);
    }
    const double line = view::kMapTextHeight + 6;
    drawText(image, "Legend", plan.legendBox.left, plan.legendBox.top, dark, false);
    for (std::size_t i = 0; i < plan.legend.size(); ++i) {
        const double y = plan.legendBox.top + (i + 1) * line;
        cv::rectangle(image, pixel({plan.legendBox.left, y - view::kMapTextHeight + 1}),
                      pixel({plan.legendBox.left + 10, y + 1}), bgr(plan.legend[i].colour), cv::FILLED);
        drawText(image, plan.legend[i].text, plan.legendBox.left + 16, y, dark, false);
    }
    if (!plan.key.empty()) {
        drawText(image, "Numbered on the map", plan.keyBox.left, plan.keyBox.top, dark, false);
        for (std::size_t i = 0; i < plan.key.size(); ++i)
            drawText(image, plan.key[i], plan.keyBox.left, plan.keyBox.top + (i + 1) * line, dark, false);
    }
    const auto& bar = plan.scale;
    cv::rectangle(image, pixel(bar.start), pixel({bar.start.x + bar.pixels, bar.start.y + 5}), dark, cv::FILLED);
    drawText(image, bar.text, bar.start.x + bar.pixels + 6, bar.start.y + 6, dark, false);
    return image;
}

// PNG or SVG, as the file's name says.
void writeMap(const view::MapPlan& plan, const fs::path& path, const std::string& database) {
    storage::refuseDatabaseFile(path, database);
    if (path.extension() == ".svg") {
        std::ofstream out(path);
        out << view::renderSvg(plan);
        if (out) return;
    } else if (ingest::media::write(path.string(), renderPng(plan))) {
        return;
    }
    throw Error(ErrorKind::Usage, fmt::format("cannot write {}", path.string()), std::nullopt,
                "check that the folder exists and is writable; the map is a .png or an .svg");
}

void writeText(const fs::path& path, const std::string& text, const std::string& database) {
    storage::refuseDatabaseFile(path, database);
    std::ofstream out(path);
    out << text;
    if (!out)
        throw Error(ErrorKind::Usage, fmt::format("cannot write {}", path.string()), std::nullopt,
                    "check that the folder exists and is writable");
}

std::vector<RouteStep> stepsOf(const ResultSet& rs) {
    auto text = [&](const Row& row, const char* column) {
        const auto* s = std::get_if<std::string>(&row[rs.columnIndex(column)]);
        return s ? *s : std::string();
    };
    auto real = [&](const Row& row, const char* column) { return std::get<double>(row[rs.columnIndex(column)]); };
    std::vector<RouteStep> steps;
    for (const auto& row : rs.rows) {
        RouteStep s;
        s.step = std::get<std::int64_t>(row[rs.columnIndex("step")]);
        s.instruction = text(row, "instruction");
        s.landmark = text(row, "landmark");
        if (const auto* id = std::get_if<std::int64_t>(&row[rs.columnIndex("landmark_id")])) s.landmarkId = *id;
        s.x = real(row, "x");
        s.y = real(row, "y");
        s.distance = real(row, "distance");
        steps.push_back(std::move(s));
    }
    return steps;
}

}  // namespace

int mapCommand(const std::string& dbDir, const std::string& scene, const std::string& outFile,
               const view::MapOptions& options) {
    auto engine = Engine::open(dbDir, /*readOnly=*/true);
    auto map = engine->sceneMap(scene);
    const view::MapPlan plan = view::planMap(map, {}, options);
    writeMap(plan, outFile, dbDir);
    // The scene's own node is not counted, as SHOW SCENES and imports count.
    const auto nodes = std::count_if(map.scene.nodes.begin(), map.scene.nodes.end(),
                                     [](const model::Node& n) { return n.kind != model::NodeKind::Scene; });
    std::cout << fmt::format("wrote the map of scene '{}' ({} nodes, {} decision points{}) to {}\n",
                             map.scene.info.name, nodes, map.graph.points.size(),
                             plan.fixturesLeftOut ? fmt::format("; {} ceiling and wall fixtures left out (--fixtures "
                                                                "draws them)",
                                                                plan.fixturesLeftOut)
                                                  : std::string(),
                             outFile);
    return 0;
}

int guideCommand(const std::string& dbDir, const std::string& scene, const std::string& from, const std::string& to,
                 const std::string& outDir) {
    auto engine = Engine::open(dbDir, /*readOnly=*/true);
    if (!scene.empty()) engine->execute("USE SCENE " + model::quoted(scene));
    const std::string statement = fmt::format("GUIDE FROM {} TO {}", from, to);
    ResultSet rs = engine->execute(statement).back();
    auto steps = stepsOf(rs);
    auto map = engine->sceneMap("");
    fs::create_directories(outDir);

    nlohmann::ordered_json plan = {{"scene", map.scene.info.name}, {"statement", statement}, {"summary", rs.message}};
    plan["steps"] = nlohmann::ordered_json::array();
    for (const auto& s : steps) {
        nlohmann::ordered_json step = {
            {"step", s.step}, {"instruction", s.instruction}, {"x", s.x}, {"y", s.y}, {"distance", s.distance}};
        if (s.landmarkId) step["landmark"] = {{"id", *s.landmarkId}, {"label", s.landmark}};
        plan["steps"].push_back(step);
    }
    const fs::path dir(outDir);
    writeText(dir / "guide.json", plan.dump(2) + "\n", dbDir);

    std::string markdown = fmt::format(
        "# {}\n\nScene `{}`: {}.\n\n![map](guide.png)\n\n| step | instruction | "
        "landmark | x | y | metres |\n|---:|---|---|---:|---:|---:|\n",
        statement, map.scene.info.name, rs.message);
    for (const auto& s : steps)
        markdown += fmt::format("| {} | {} | {} | {:.2f} | {:.2f} | {:.1f} |\n", s.step, s.instruction, s.landmark, s.x,
                                s.y, s.distance);
    writeText(dir / "guide.md", markdown, dbDir);

    std::vector<view::RouteMark> route;
    for (const auto& s : steps) route.push_back({s.step, s.x, s.y});
    writeMap(view::planMap(map, route, {}), dir / "guide.png", dbDir);
    std::cout << fmt::format("{}\nwrote guide.json, guide.md and guide.png to {}\n", rs.message, outDir);
    return 0;
}

}  // namespace smql::shell
