#include "model/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace smql::model {

namespace {

double cross(Vec2 o, Vec2 a, Vec2 b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

// A convex polygon with room for what clipping a rectangle by a rectangle can make (at most 8
// corners): footprint overlaps run in the inner loops of queries and imports, so no heap.
struct SmallPolygon {
    std::array<Vec2, 12> corners;
    std::size_t size = 0;
    void push(Vec2 p) { corners[size++] = p; }
};

double polygonArea(const SmallPolygon& poly) {
    double twice = 0;
    for (std::size_t i = 0; i < poly.size; ++i) {
        const Vec2& p = poly.corners[i];
        const Vec2& q = poly.corners[(i + 1) % poly.size];
        twice += p.x * q.y - q.x * p.y;
    }
    return std::abs(twice) / 2;
}

// Squared: a caller after the least of several distances takes one root of the least square
// (the root is monotonic and correctly rounded, so that is the least of the roots).
double pointSegmentSquaredDistance(Vec2 p, Vec2 a, Vec2 b) {
    double dx = b.x - a.x, dy = b.y - a.y;
    double len2 = dx * dx + dy * dy;
    double t = len2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
    double ex = a.x + t * dx - p.x, ey = a.y + t * dy - p.y;
    return ex * ex + ey * ey;
}

// Separating-axis test for two rectangles: the edge normals of both are the only candidate axes.
bool footprintsSeparated(const std::array<Vec2, 4>& a, const std::array<Vec2, 4>& b) {
    for (const auto* poly : {&a, &b}) {
        for (int i = 0; i < 2; ++i) {
            Vec2 edge{(*poly)[i + 1].x - (*poly)[i].x, (*poly)[i + 1].y - (*poly)[i].y};
            Vec2 axis{-edge.y, edge.x};
            double minA = std::numeric_limits<double>::max(), maxA = -minA, minB = minA, maxB = -minA;
            for (const auto& p : a) {
                double d = p.x * axis.x + p.y * axis.y;
                minA = std::min(minA, d), maxA = std::max(maxA, d);
            }
            for (const auto& p : b) {
                double d = p.x * axis.x + p.y * axis.y;
                minB = std::min(minB, d), maxB = std::max(maxB, d);
            }
            if (maxA < minB || maxB < minA) return true;
        }
    }
    return false;
}

}  // namespace

std::array<Vec2, 4> footprint(const Box& box) {
    const BoxFrame frame(box);
    const double hx = box.size.x / 2, hy = box.size.y / 2;
    return {frame.world({-hx, -hy}), frame.world({hx, -hy}), frame.world({hx, hy}), frame.world({-hx, hy})};
}

Aabb worldAabb(const Box& box) {
    double c = std::abs(std::cos(box.yaw)), s = std::abs(std::sin(box.yaw));
    double hx = (c * box.size.x + s * box.size.y) / 2;
    double hy = (s * box.size.x + c * box.size.y) / 2;
    double hz = box.size.z / 2;
    return {{box.center.x - hx, box.center.y - hy, box.center.z - hz},
            {box.center.x + hx, box.center.y + hy, box.center.z + hz}};
}

double footprintArea(const Box& box) { return box.size.x * box.size.y; }
double volume(const Box& box) { return box.size.x * box.size.y * box.size.z; }

double footprintOverlap(const Box& a, const Box& b) {
    // Sutherland-Hodgman: clip a's rectangle by each edge of b's (both convex, counter-clockwise).
    auto fa = footprint(a);
    auto fb = footprint(b);
    SmallPolygon poly;
    for (const auto& p : fa) poly.push(p);
    for (int i = 0; i < 4 && poly.size > 0; ++i) {
        Vec2 e0 = fb[i], e1 = fb[(i + 1) % 4];
        SmallPolygon clipped;
        for (std::size_t k = 0; k < poly.size; ++k) {
            Vec2 p = poly.corners[k], q = poly.corners[(k + 1) % poly.size];
            double sp = cross(e0, e1, p), sq = cross(e0, e1, q);
            if (sp >= 0) clipped.push(p);
            if ((sp >= 0) != (sq >= 0)) {
                double t = sp / (sp - sq);
                clipped.push({p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)});
            }
        }
        poly = clipped;
    }
    return poly.size < 3 ? 0.0 : polygonArea(poly);
}

double horizontalGap(const Box& a, const Box& b) {
    auto fa = footprint(a);
    auto fb = footprint(b);
    if (!footprintsSeparated(fa, fb)) return 0.0;
    double best = std::numeric_limits<double>::max();
    for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) {
            best = std::min(best, pointSegmentSquaredDistance(fa[i], fb[j], fb[(j + 1) % 4]));
            best = std::min(best, pointSegmentSquaredDistance(fb[i], fa[j], fa[(j + 1) % 4]));
        }
    }
    return std::sqrt(best);
}

double verticalGap(const Box& a, const Box& b) {
    return std::max(0.0, std::max(bottom(a), bottom(b)) - std::min(top(a), top(b)));
}

double verticalOverlap(const Box& a, const Box& b) {
    return std::max(0.0, std::min(top(a), top(b)) - std::max(bottom(a), bottom(b)));
}

double distance(const Box& a, const Box& b) {
    // Prisms: the closest points split into a floor-plane part and a height part.
    double h = horizontalGap(a, b), v = verticalGap(a, b);
    return std::sqrt(h * h + v * v);
}

double centerDistance(const Box& a, const Box& b) {
    double dx = a.center.x - b.center.x, dy = a.center.y - b.center.y, dz = a.center.z - b.center.z;
    return std::sqrt(dx * dx + dy * dy + dz * dz);
}

double fractionInside(const Box& a, const Box& b) {
    double va = volume(a);
    if (va <= 0) return 0.0;
    return std::clamp(footprintOverlap(a, b) * verticalOverlap(a, b) / va, 0.0, 1.0);
}

bool footprintContains(const Box& box, Vec2 point, double margin) { return BoxFrame(box).contains(point, margin); }

double footprintGap(const Box& box, Vec2 point) { return BoxFrame(box).gap(point); }

void takeInFootprint(Box& box, const Box& other) {
    const BoxFrame frame(box);
    double lo[2] = {-box.size.x / 2, -box.size.y / 2}, hi[2] = {-lo[0], -lo[1]};
    for (const Vec2& corner : footprint(other)) {
        const Vec2 at = frame.local(corner);
        lo[0] = std::min(lo[0], at.x), lo[1] = std::min(lo[1], at.y);
        hi[0] = std::max(hi[0], at.x), hi[1] = std::max(hi[1], at.y);
    }
    const Vec2 centre = frame.world({(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2});
    box.center.x = centre.x, box.center.y = centre.y;
    box.size.x = hi[0] - lo[0], box.size.y = hi[1] - lo[1];
}

}  // namespace smql::model
