#include "ingest/geometry/view_consistency.hpp"

#include <algorithm>
#include <cmath>

namespace smql::ingest {

namespace {

// Two depths agree within this (metres, plus a share of the depth: sensors' noise grows with it).
constexpr double kAgreeMetres = 0.03;
constexpr double kAgreeShare = 0.05;
// A pair counts when this many of one frame's points land in the other's view.
constexpr std::size_t kMinOverlap = 100;
// The share means something from this many pairs and points.
constexpr std::size_t kMinPairs = 2;
constexpr std::size_t kMinPoints = 1000;

struct Counts {
    std::size_t overlap = 0, agree = 0, conflict = 0;
};

// `from`'s points seen from `to`.
Counts project(const DepthSketch& from, const DepthSketch& to) {
    Counts out;
    const Intrinsics& a = from.intrinsics;
    const Intrinsics& b = to.intrinsics;
    const auto& ra = from.pose.rotation;
    const auto& rb = to.pose.rotation;
    const model::Vec3 ta = from.pose.translation, tb = to.pose.translation;
    for (int v = 0; v < a.height; ++v)
        for (int u = 0; u < a.width; ++u) {
            const double z = from.metres[static_cast<std::size_t>(v) * a.width + u];
            if (!(z > 0)) continue;
            const double x = (u - a.cx) * z / a.fx, y = (v - a.cy) * z / a.fy;
            // World, then `to`'s camera frame (the transpose of its rotation).
            const double wx = ra[0] * x + ra[1] * y + ra[2] * z + ta.x - tb.x;
            const double wy = ra[3] * x + ra[4] * y + ra[5] * z + ta.y - tb.y;
            const double wz = ra[6] * x + ra[7] * y + ra[8] * z + ta.z - tb.z;
            const double cx = rb[0] * wx + rb[3] * wy + rb[6] * wz;
            const double cy = rb[1] * wx + rb[4] * wy + rb[7] * wz;
            const double cz = rb[2] * wx + rb[5] * wy + rb[8] * wz;
            if (cz < 0.1) continue;
            const long pu = std::lround(b.fx * cx / cz + b.cx), pv = std::lround(b.fy * cy / cz + b.cy);
            if (pu < 0 || pv < 0 || pu >= b.width || pv >= b.height) continue;
            const double seen = to.metres[static_cast<std::size_t>(pv) * b.width + static_cast<std::size_t>(pu)];
            if (!(seen > 0)) continue;
            ++out.overlap;
            const double tolerance = kAgreeMetres + kAgreeShare * cz;
            if (std::abs(seen - cz) <= tolerance)
                ++out.agree;
            else if (seen > cz + tolerance)
                ++out.conflict;  // `to` reads past the point: it would have hidden what `to` sees
        }
    return out;
}

}  // namespace

DepthSketch sketchDepth(const DepthView& depth, const Pose& pose, int width) {
    DepthSketch out;
    out.pose = pose;
    if (!depth.metres || depth.width <= 0 || depth.height <= 0) return out;
    const double s = static_cast<double>(width) / depth.width;
    const int height = std::max(1, static_cast<int>(std::lround(depth.height * s)));
    const Intrinsics& k = depth.intrinsics;
    // Pixel centres: sketch pixel u covers source pixels around (u + 0.5) / s - 0.5.
    out.intrinsics = {width, height, k.fx * s, k.fy * s, (k.cx + 0.5) * s - 0.5, (k.cy + 0.5) * s - 0.5};
    out.metres.resize(static_cast<std::size_t>(width) * height);
    for (int v = 0; v < height; ++v)
        for (int u = 0; u < width; ++u) {
            const int su = std::min(depth.width - 1, static_cast<int>((u + 0.5) / s));
            const int sv = std::min(depth.height - 1, static_cast<int>((v + 0.5) / s));
            const float z = depth.metres[static_cast<std::size_t>(sv) * depth.width + su];
            out.metres[static_cast<std::size_t>(v) * width + u] = z > 0 && z <= kMaxDepthReading ? z : 0.0F;
        }
    return out;
}

double ViewAgreement::share() const {
    const std::size_t tested = agree + conflict;
    return tested ? static_cast<double>(agree) / static_cast<double>(tested) : 1.0;
}

bool ViewAgreement::tested() const { return pairs >= kMinPairs && agree + conflict >= kMinPoints; }

ViewAgreement compareViews(const std::vector<DepthSketch>& sketches) {
    ViewAgreement out;
    for (std::size_t i = 0; i < sketches.size(); ++i)
        for (std::size_t j = i + 1; j < sketches.size(); ++j) {
            if (sketches[i].metres.empty() || sketches[j].metres.empty()) continue;
            const Counts forth = project(sketches[i], sketches[j]), back = project(sketches[j], sketches[i]);
            if (forth.overlap < kMinOverlap || back.overlap < kMinOverlap) continue;
            ++out.pairs;
            out.agree += forth.agree + back.agree;
            out.conflict += forth.conflict + back.conflict;
        }
    return out;
}

}  // namespace smql::ingest
