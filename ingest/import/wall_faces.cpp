#include "ingest/import/wall_faces.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <vector>

#include <fmt/format.h>
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/linestring.hpp>
#include <boost/geometry/geometries/multi_linestring.hpp>
#include <boost/geometry/geometries/multi_point.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>

#include "model/floor.hpp"
#include "model/geometry.hpp"

namespace smql::import::detail {

namespace {

namespace bg = boost::geometry;
using Point = bg::model::d2::point_xy<double>;
using Polygon = bg::model::polygon<Point>;
using Line = bg::model::linestring<Point>;

bool isWall(const model::Node& n) {
    return n.kind == model::NodeKind::Anchor && n.category == "wall" && !n.hidden &&
           n.geometry != model::GeometryKind::None;
}

bool isDoor(const model::Node& n) {
    return n.kind == model::NodeKind::Anchor && n.category == "door" && !n.hidden &&
           n.geometry != model::GeometryKind::None;
}

Polygon footprintPolygon(const model::Box& box) {
    Polygon out;
    for (model::Vec2 c : model::footprint(box)) bg::append(out.outer(), Point(c.x, c.y));
    bg::correct(out);  // closed, in Boost's clockwise order
    return out;
}

// The room's outline as a closed ring: the labelled floor's footprint, else the convex hull of the walls'.
std::vector<Point> roomOutline(const std::vector<model::Node>& nodes) {
    Polygon outline;
    if (const model::Node* floor = model::labelledFloor(nodes)) {
        outline = footprintPolygon(floor->box);
    } else {
        bg::model::multi_point<Point> corners;
        for (const model::Node& n : nodes)
            if (isWall(n))
                for (model::Vec2 c : model::footprint(n.box)) bg::append(corners, Point(c.x, c.y));
        if (corners.size() < 3) return {};
        bg::convex_hull(corners, outline);
    }
    return outline.outer();
}

struct Piece {
    Point from, to;
};

// The part of one straight edge that a box holds is straight, so its length is its ends' distance.
// (Boost's length() would instantiate Boost 1.74's numeric conversion, whose MPL enums clang 16
// and later reject, so that lint's clang-tidy could not read this file.)
double straightLength(const Line& part) {
    return std::hypot(part.back().x() - part.front().x(), part.back().y() - part.front().y());
}

// The stretches of [0, length] along a piece that no door standing in it covers.
std::vector<std::pair<double, double>> uncut(const Piece& piece, const std::vector<model::Node>& doors) {
    const double dx = piece.to.x() - piece.from.x(), dy = piece.to.y() - piece.from.y();
    const double length = std::hypot(dx, dy);
    const double ux = dx / length, uy = dy / length;
    std::vector<std::pair<double, double>> open{{0.0, length}};
    for (const model::Node& door : doors) {
        const double rx = door.box.center.x - piece.from.x(), ry = door.box.center.y - piece.from.y();
        if (std::abs(rx * uy - ry * ux) > kDoorReach) continue;  // away from the face's line
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (model::Vec2 c : model::footprint(door.box)) {
            const double t = (c.x - piece.from.x()) * ux + (c.y - piece.from.y()) * uy;
            lo = std::min(lo, t), hi = std::max(hi, t);
        }
        std::vector<std::pair<double, double>> left;
        for (auto [a, b] : open) {
            if (hi <= a || lo >= b) {
                left.push_back({a, b});
                continue;
            }
            if (lo > a) left.push_back({a, lo});
            if (hi < b) left.push_back({hi, b});
        }
        open = std::move(left);
    }
    return open;
}

}  // namespace

std::size_t splitWallOutlines(model::SceneData& scene) {
    const std::vector<Point> ring = roomOutline(scene.nodes);
    if (ring.size() < 4) return 0;
    // Doors by value: scene.nodes grows below.
    std::vector<model::Node> doors;
    std::copy_if(scene.nodes.begin(), scene.nodes.end(), std::back_inserter(doors), isDoor);

    model::NodeId nextId = 0;
    for (const model::Node& n : scene.nodes) nextId = std::max(nextId, n.id);
    ++nextId;

    std::size_t split = 0;
    const std::size_t count = scene.nodes.size();
    for (std::size_t i = 0; i < count; ++i) {
        const model::Node wall = scene.nodes[i];
        if (!isWall(wall) || std::min(wall.box.size.x, wall.box.size.y) <= kSlabThickness) continue;
        const Polygon box = footprintPolygon(wall.box);
        std::vector<Piece> pieces;
        for (std::size_t k = 0; k + 1 < ring.size(); ++k) {
            Line edge{ring[k], ring[k + 1]};
            bg::model::multi_linestring<Line> inside;
            bg::intersection(edge, box, inside);
            for (const Line& part : inside) {
                if (part.size() < 2 || straightLength(part) < kMinFaceLength) continue;
                for (auto [a, b] : uncut({part.front(), part.back()}, doors)) {
                    if (b - a < kMinFaceLength) continue;
                    const double length = straightLength(part);
                    const double tx = (part.back().x() - part.front().x()) / length,
                                 ty = (part.back().y() - part.front().y()) / length;
                    pieces.push_back({Point(part.front().x() + tx * a, part.front().y() + ty * a),
                                      Point(part.front().x() + tx * b, part.front().y() + ty * b)});
                }
            }
        }
        if (pieces.empty()) continue;
        ++split;
        for (std::size_t k = 0; k < pieces.size(); ++k) {
            const Piece& p = pieces[k];
            model::Node face = wall;
            const double dx = p.to.x() - p.from.x(), dy = p.to.y() - p.from.y();
            face.box.center.x = (p.from.x() + p.to.x()) / 2;
            face.box.center.y = (p.from.y() + p.to.y()) / 2;
            face.box.size = {std::hypot(dx, dy), kFaceThickness, wall.box.size.z};
            face.box.yaw = std::atan2(dy, dx);
            if (k > 0) {
                face.id = nextId++;
                face.sourceId.reset();
            }
            if (pieces.size() > 1 && face.text.empty()) {
                const std::string instance =
                    wall.sourceId ? fmt::format("#{}", *wall.sourceId) : fmt::format("{}", wall.id);
                face.text = fmt::format("face {} of {} of wall {}", k + 1, pieces.size(), instance);
            }
            if (k == 0)
                scene.nodes[i] = std::move(face);
            else
                scene.nodes.push_back(std::move(face));
        }
    }
    return split;
}

}  // namespace smql::import::detail
