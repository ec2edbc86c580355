#include "shell/map_command.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "engine/engine.hpp"
#include "model/error.hpp"
#include "model/geometry.hpp"
#include "model/names.hpp"

namespace smql::shell {

namespace fs = std::filesystem;

namespace {

constexpr double kPixelsPerMetre = 80;
constexpr int kMargin = 40;

// One row of GUIDE's answer, as the files show it.
struct RouteStep {
    std::int64_t step = 0;
    std::string instruction, landmark;
    std::optional<std::int64_t> landmarkId;
    double x = 0, y = 0, distance = 0;
};

// Scene metres to image pixels: x to the right, y up (the image's rows run down).
struct Canvas {
    model::Aabb bounds;
    cv::Mat image;

    explicit Canvas(const model::SceneData& scene) {
        bounds = {{1e300, 1e300, 0}, {-1e300, -1e300, 0}};
        for (const auto& n : scene.nodes) {
            if (n.geometry == model::GeometryKind::None || n.hidden || n.kind == model::NodeKind::Scene) continue;
            auto b = model::worldAabb(n.box);
            bounds.min.x = std::min(bounds.min.x, b.min.x);
            bounds.min.y = std::min(bounds.min.y, b.min.y);
            bounds.max.x = std::max(bounds.max.x, b.max.x);
            bounds.max.y = std::max(bounds.max.y, b.max.y);
        }
        if (bounds.min.x > bounds.max.x) bounds = {{0, 0, 0}, {1, 1, 0}};
        int width = static_cast<int>((bounds.max.x - bounds.min.x) * kPixelsPerMetre) + 2 * kMargin;
        int height = static_cast<int>((bounds.max.y - bounds.min.y) * kPixelsPerMetre) + 2 * kMargin;
        image = cv::Mat(std::min(height, 8000), std::min(width, 8000), CV_8UC3, cv::Scalar(255, 255, 255));
    }
    cv::Point at(double x, double y) const {
        return {static_cast<int>(std::lround(kMargin + (x - bounds.min.x) * kPixelsPerMetre)),
                static_cast<int>(std::lround(image.rows - kMargin - (y - bounds.min.y) * kPixelsPerMetre))};
    }
    std::vector<cv::Point> footprint(const model::Box& box) const {
        double c = std::cos(box.yaw), s = std::sin(box.yaw);
        std::vector<cv::Point> corners;
        for (auto [u, v] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
            double dx = u * box.size.x / 2, dy = v * box.size.y / 2;
            corners.push_back(at(box.center.x + c * dx - s * dy, box.center.y + s * dx + c * dy));
        }
        return corners;
    }
    void label(const std::string& text, cv::Point where, const cv::Scalar& colour) {
        cv::putText(image, text, where + cv::Point(3, -3), cv::FONT_HERSHEY_SIMPLEX, 0.35, colour, 1, cv::LINE_AA);
    }
};

// Anchors and objects from above, then the graph: the picture `smql map` writes.
Canvas drawScene(const Engine::SceneMap& map) {
    Canvas canvas(map.scene);
    const cv::Scalar wall(90, 90, 90), door(60, 160, 60), window(200, 140, 40), object(60, 60, 200),
        graph(225, 205, 170), text(40, 40, 40);
    auto anchors = [&](bool floor) {
        for (const auto& n : map.scene.nodes) {
            if (n.geometry == model::GeometryKind::None || n.hidden || n.kind != model::NodeKind::Anchor ||
                (n.category == "floor") != floor)
                continue;
            auto corners = canvas.footprint(n.box);
            if (n.category == "floor") cv::fillConvexPoly(canvas.image, corners, cv::Scalar(245, 245, 245));
            if (n.category == "wall") cv::fillConvexPoly(canvas.image, corners, wall);
            if (n.category == "door") cv::fillConvexPoly(canvas.image, corners, door);
            if (n.category == "window") cv::fillConvexPoly(canvas.image, corners, window);
        }
    };
    anchors(/*floor=*/true);
    // The floor as guidance sees it: blocked cells (within a body's radius of what stands on the
    // floor) shaded, and free pockets cut off from the room tinted.
    const cv::Scalar blocked(215, 215, 240), pocket(170, 230, 250);
    const auto& space = map.space;
    for (int j = 0; j < space.height(); ++j)
        for (int i = 0; i < space.width(); ++i) {
            if (space.openCell(i, j)) continue;
            const double x = space.minX() + i * space.cell(), y = space.minY() + j * space.cell();
            cv::rectangle(canvas.image, canvas.at(x, y), canvas.at(x + space.cell(), y + space.cell()),
                          space.freeCell(i, j) ? pocket : blocked, cv::FILLED);
        }
    anchors(/*floor=*/false);
    for (const auto& e : map.graph.edges)
        cv::line(canvas.image, canvas.at(map.graph.points[e.a].at.x, map.graph.points[e.a].at.y),
                 canvas.at(map.graph.points[e.b].at.x, map.graph.points[e.b].at.y), graph, 1, cv::LINE_AA);
    for (const auto& p : map.graph.points) cv::circle(canvas.image, canvas.at(p.at.x, p.at.y), 2, graph, -1);
    for (const auto& n : map.scene.nodes) {
        if (n.geometry == model::GeometryKind::None || n.hidden || n.kind != model::NodeKind::Object) continue;
        auto corners = canvas.footprint(n.box);
        cv::polylines(canvas.image, corners, true, object, 1, cv::LINE_AA);
        canvas.label(fmt::format("{}#{}", n.category, n.id), corners[3], text);
    }
    return canvas;
}

void writePng(const cv::Mat& image, const fs::path& path) {
    if (!cv::imwrite(path.string(), image))
        throw Error(ErrorKind::Usage, fmt::format("cannot write {}", path.string()), std::nullopt,
                    "check that the folder exists and is writable");
}

void writeText(const fs::path& path, const std::string& text) {
    std::ofstream out(path);
    out << text;
    if (!out)
        throw Error(ErrorKind::Usage, fmt::format("cannot write {}", path.string()), std::nullopt,
                    "check that the folder exists and is writable");
}

std::vector<RouteStep> stepsOf(const ResultSet& rs) {
    auto text = [&](const std::vector<Value>& row, const char* column) {
        const auto* s = std::get_if<std::string>(&row[rs.columnIndex(column)]);
        return s ? *s : std::string();
    };
    auto real = [&](const std::vector<Value>& row, const char* column) {
        return std::get<double>(row[rs.columnIndex(column)]);
    };
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

int mapCommand(const std::string& dbDir, const std::string& scene, const std::string& outFile) {
    auto engine = Engine::open(dbDir, /*readOnly=*/true);
    auto map = engine->sceneMap(scene);
    writePng(drawScene(map).image, outFile);
    std::cout << fmt::format("wrote the map of scene '{}' ({} nodes, {} decision points) to {}\n", map.scene.info.name,
                             map.scene.nodes.size(), map.graph.points.size(), outFile);
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
    writeText(dir / "guide.json", plan.dump(2) + "\n");

    std::string markdown = fmt::format(
        "# {}\n\nScene `{}`: {}.\n\n![map](guide.png)\n\n| step | instruction | "
        "landmark | x | y | metres |\n|---:|---|---|---:|---:|---:|\n",
        statement, map.scene.info.name, rs.message);
    for (const auto& s : steps)
        markdown += fmt::format("| {} | {} | {} | {:.2f} | {:.2f} | {:.1f} |\n", s.step, s.instruction, s.landmark, s.x,
                                s.y, s.distance);
    writeText(dir / "guide.md", markdown);

    Canvas canvas = drawScene(map);
    const cv::Scalar route(40, 40, 220);
    for (std::size_t i = 1; i < steps.size(); ++i)
        cv::line(canvas.image, canvas.at(steps[i - 1].x, steps[i - 1].y), canvas.at(steps[i].x, steps[i].y), route, 2,
                 cv::LINE_AA);
    for (const auto& s : steps) {
        cv::circle(canvas.image, canvas.at(s.x, s.y), 8, route, -1, cv::LINE_AA);
        std::string number = std::to_string(s.step);
        cv::putText(canvas.image, number, canvas.at(s.x, s.y) + cv::Point(-4 * static_cast<int>(number.size()), 4),
                    cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
    }
    writePng(canvas.image, dir / "guide.png");
    std::cout << fmt::format("{}\nwrote guide.json, guide.md and guide.png to {}\n", rs.message, outDir);
    return 0;
}

}  // namespace smql::shell
