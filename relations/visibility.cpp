#include "relations/visibility.hpp"

#include <algorithm>
#include <cmath>

#include "model/geometry.hpp"

namespace smql::relations {

using model::Vec3;

namespace {

double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 minus(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }

// A world point in the box's own frame (origin at its centre, axes along its sides).
Vec3 toBoxFrame(const Vec3& p, const model::BoxFrame& frame, const model::Box& box) {
    const model::Vec2 at = frame.local({p.x, p.y});
    return {at.x, at.y, p.z - box.center.z};
}

}  // namespace

Vec3 eyeAt(const model::Box& node) {
    double bottom = node.center.z - node.size.z / 2, top = node.center.z + node.size.z / 2;
    return {node.center.x, node.center.y, std::min(top, bottom + kEyeHeight)};
}

bool ViewCone::contains(const Vec3& eye, const Vec3& point) const {
    Vec3 d = minus(point, eye);
    double depth = dot(d, forward);
    if (depth <= 0) return false;
    return std::abs(dot(d, right)) <= tanHalfWidth * depth && std::abs(dot(d, up)) <= tanHalfHeight * depth;
}

bool pointInBox(const Vec3& point, const model::Box& box) {
    Vec3 p = toBoxFrame(point, model::BoxFrame(box), box);
    return std::abs(p.x) <= box.size.x / 2 && std::abs(p.y) <= box.size.y / 2 && std::abs(p.z) <= box.size.z / 2;
}

bool segmentCrosses(const Vec3& p, const Vec3& q, const model::Box& box) {
    const model::BoxFrame frame(box);
    Vec3 from = toBoxFrame(p, frame, box), to = toBoxFrame(q, frame, box);
    const double start[3] = {from.x, from.y, from.z};
    const double delta[3] = {to.x - from.x, to.y - from.y, to.z - from.z};
    const double half[3] = {box.size.x / 2, box.size.y / 2, box.size.z / 2};
    double enter = 0, leave = 1;
    for (int axis = 0; axis < 3; ++axis) {
        if (std::abs(delta[axis]) < 1e-12) {
            if (std::abs(start[axis]) > half[axis]) return false;  // parallel to this slab and outside it
            continue;
        }
        double t0 = (-half[axis] - start[axis]) / delta[axis], t1 = (half[axis] - start[axis]) / delta[axis];
        if (t0 > t1) std::swap(t0, t1);
        enter = std::max(enter, t0);
        leave = std::min(leave, t1);
        if (enter > leave) return false;
    }
    return enter < 1 && leave > 0;
}

double visibleShare(const Vec3& eye, const model::Node& target, std::span<const model::Node* const> obstacles,
                    const ViewCone* cone, const model::Node* viewer) {
    const model::Box& box = target.box;
    const model::BoxFrame frame(box);
    int seen = 0;
    for (int i = -1; i <= 1; ++i)
        for (int j = -1; j <= 1; ++j)
            for (int k = -1; k <= 1; ++k) {
                const model::Vec2 at =
                    frame.world({i * kSampleFraction * box.size.x, j * kSampleFraction * box.size.y});
                Vec3 point{at.x, at.y, box.center.z + k * kSampleFraction * box.size.z};
                if (cone && !cone->contains(eye, point)) continue;
                bool blocked = std::any_of(obstacles.begin(), obstacles.end(), [&](const model::Node* o) {
                    if (o == &target || o == viewer || o->id == target.id || (viewer && o->id == viewer->id))
                        return false;
                    if (pointInBox(eye, o->box) || pointInBox(point, o->box)) return false;
                    return segmentCrosses(eye, point, o->box);
                });
                seen += !blocked;
            }
    return static_cast<double>(seen) / kSamplesPerBox;
}

}  // namespace smql::relations
