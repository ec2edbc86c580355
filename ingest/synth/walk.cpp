#include "ingest/synth/walk.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <sstream>

#include <Eigen/Geometry>

#include "model/error.hpp"
#include "model/geometry.hpp"

namespace smql::synth {

namespace {

constexpr double kPi = std::numbers::pi;
using model::kDegree;

// Deterministic numbers in [0, 1) from the seed (no std distributions: their output is not portable).
double unitFromSeed(std::uint64_t seed, std::uint64_t salt) {
    std::uint64_t x = seed * 0x9E3779B97F4A7C15ULL + salt * 0xD1B54A32D192ED03ULL + 0x8CB92BA72F3D8DD7ULL;
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    x ^= x >> 31;
    return static_cast<double>(x >> 11) / 9007199254740992.0;
}

// Distance from a point to an upright box (0 inside).
double pointBoxDistance(const Eigen::Vector3d& p, const model::Box& box) {
    const model::Vec2 at = model::BoxFrame(box).local({p.x(), p.y()});
    const double ex = std::max(0.0, std::abs(at.x) - box.size.x / 2),
                 ey = std::max(0.0, std::abs(at.y) - box.size.y / 2),
                 ez = std::max(0.0, std::abs(p.z() - box.center.z) - box.size.z / 2);
    return std::sqrt(ex * ex + ey * ey + ez * ez);
}

struct Room {
    double x0 = 0, y0 = 0, x1 = 4, y1 = 4;
    double floorTop = 0;
};

Room roomOf(const model::SceneData& scene) {
    Room room;
    bool any = false;
    for (const model::Node& n : scene.nodes) {
        if (n.geometry == model::GeometryKind::None) continue;
        model::Aabb a = model::worldAabb(n.box);
        if (!any) room = {a.min.x, a.min.y, a.max.x, a.max.y, a.min.z};
        room.x0 = std::min(room.x0, a.min.x), room.y0 = std::min(room.y0, a.min.y);
        room.x1 = std::max(room.x1, a.max.x), room.y1 = std::max(room.y1, a.max.y);
        room.floorTop = std::min(room.floorTop, a.min.z);
        any = true;
    }
    for (const model::Node& n : scene.nodes) {
        if (n.kind != model::NodeKind::Anchor || n.category != "floor" || n.geometry == model::GeometryKind::None)
            continue;
        model::Aabb a = model::worldAabb(n.box);
        room = {a.min.x, a.min.y, a.max.x, a.max.y, a.max.z};
        break;
    }
    return room;
}

// A rounded rectangle walked counter-clockwise (the room's interior on the left),
// parametrised by arc length from the start of the south side.
class Loop {
public:
    Loop(double x0, double y0, double x1, double y1, double radius) : x0_(x0), y0_(y0), x1_(x1), y1_(y1), r_(radius) {
        sx_ = (x1 - x0) - 2 * r_;
        sy_ = (y1 - y0) - 2 * r_;
        arc_ = kPi / 2 * r_;
        length_ = 2 * sx_ + 2 * sy_ + 4 * arc_;
    }
    double length() const { return length_; }

    // Position in the floor plane and heading (radians about +z).
    void at(double s, double& x, double& y, double& heading) const {
        s = std::fmod(s, length_);
        if (s < 0) s += length_;
        // Sides in order: south (east-bound), east (north-bound), north (west-bound), west (south-bound).
        const double sides[4] = {sx_, sy_, sx_, sy_};
        const double startX[4] = {x0_ + r_, x1_, x1_ - r_, x0_};
        const double startY[4] = {y0_, y0_ + r_, y1_, y1_ - r_};
        const double cornerX[4] = {x1_ - r_, x1_ - r_, x0_ + r_, x0_ + r_};
        const double cornerY[4] = {y0_ + r_, y1_ - r_, y1_ - r_, y0_ + r_};
        for (int i = 0; i < 4; ++i) {
            double direction = i * kPi / 2;
            if (s <= sides[i]) {
                x = startX[i] + std::cos(direction) * s;
                y = startY[i] + std::sin(direction) * s;
                heading = direction;
                return;
            }
            s -= sides[i];
            if (s <= arc_ || i == 3) {
                double turned = r_ > 0 ? std::min(s / r_, kPi / 2) : kPi / 2;
                double angle = direction - kPi / 2 + turned;  // from the corner's centre
                x = cornerX[i] + r_ * std::cos(angle);
                y = cornerY[i] + r_ * std::sin(angle);
                heading = direction + turned;
                return;
            }
            s -= arc_;
        }
    }

private:
    double x0_, y0_, x1_, y1_, r_;
    double sx_ = 0, sy_ = 0, arc_ = 0, length_ = 0;
};

}  // namespace

std::vector<ingest::Pose> planWalk(const model::SceneData& scene, const WalkOptions& options) {
    Room room = roomOf(scene);
    double width = room.x1 - room.x0, depth = room.y1 - room.y0;
    double inset = std::min(options.wallInset, 0.3 * std::min(width, depth));
    double loopW = width - 2 * inset, loopD = depth - 2 * inset;
    double radius = std::min(0.8, 0.45 * std::min(loopW, loopD));
    Loop loop(room.x0 + inset, room.y0 + inset, room.x1 - inset, room.y1 - inset, radius);

    // Start on the loop point nearest the door.
    double start = 0;
    for (const model::Node& n : scene.nodes) {
        if (n.category != "door" || n.geometry == model::GeometryKind::None) continue;
        double best = std::numeric_limits<double>::max();
        constexpr int kSamples = 4000;
        for (int i = 0; i < kSamples; ++i) {
            double s = loop.length() * i / kSamples, x, y, h;
            loop.at(s, x, y, h);
            double d = std::hypot(x - n.box.center.x, y - n.box.center.y);
            if (d < best) best = d, start = s;
        }
        break;
    }

    // Only what reaches up near eye height can come closer than the clearance.
    const double eye = room.floorTop + options.eyeHeight;
    std::vector<const model::Box*> obstacles;
    for (const model::Node& n : scene.nodes)
        if (n.kind == model::NodeKind::Object && n.geometry != model::GeometryKind::None &&
            model::top(n.box) > eye - options.clearance - 0.05)
            obstacles.push_back(&n.box);
    auto clearance = [&](double x, double y, double z) {
        double d = std::min({x - room.x0, room.x1 - x, y - room.y0, room.y1 - y});
        d = d >= 0.35 ? std::numeric_limits<double>::max() : -1;  // stay off the walls
        for (const model::Box* box : obstacles) d = std::min(d, pointBoxDistance(Eigen::Vector3d(x, y, z), *box));
        return d;
    };

    // Walk around whatever the loop runs into (a tall shelf): a sideways offset from the loop,
    // chosen for the whole walk at once (dynamic programming over samples 5 cm apart) so that
    // the detour is short, gradual (at most 45 degrees off the loop) and keeps the clearance.
    constexpr double kSample = 0.05, kOffsetStep = 0.05;
    constexpr int kOffsets = 24;  // offsets -1.2 .. +1.2 m
    constexpr int kStates = 2 * kOffsets + 1;
    const int samples = std::max(2, static_cast<int>(std::ceil(loop.length() / kSample)));
    const double ds = loop.length() / samples;
    std::vector<std::array<double, kStates>> cost(samples);
    std::vector<std::array<int, kStates>> from(samples);
    for (int i = 0; i < samples; ++i) {
        double x, y, heading;
        loop.at(start + i * ds, x, y, heading);
        for (int o = 0; o < kStates; ++o) {
            double offset = (o - kOffsets) * kOffsetStep;
            double c = clearance(x - std::sin(heading) * offset, y + std::cos(heading) * offset, eye);
            double local = std::abs(offset) + (c < options.clearance ? 1000 + 1000 * (options.clearance - c) : 0);
            if (i == 0) {
                cost[i][o] = local;
                continue;
            }
            cost[i][o] = std::numeric_limits<double>::max();
            for (int p = std::max(0, o - 1); p <= std::min(kStates - 1, o + 1); ++p)
                if (cost[i - 1][p] < cost[i][o]) cost[i][o] = cost[i - 1][p], from[i][o] = p;
            cost[i][o] += local;
        }
    }
    std::vector<double> offsets(samples);
    int state = static_cast<int>(std::min_element(cost.back().begin(), cost.back().end()) - cost.back().begin());
    for (int i = samples - 1; i >= 0; --i) {
        offsets[i] = (state - kOffsets) * kOffsetStep;
        if (i > 0) state = from[i][state];
    }

    const std::uint64_t seed = options.seed;
    const double phaseYaw = 2 * kPi * unitFromSeed(seed, 1), phasePitch = 2 * kPi * unitFromSeed(seed, 2),
                 phaseRoll = 2 * kPi * unitFromSeed(seed, 3), phaseBob = 2 * kPi * unitFromSeed(seed, 4);
    const double lookAhead = (50 + 10 * unitFromSeed(seed, 5)) * kDegree;  // from the walking direction

    std::vector<ingest::Pose> poses;
    const int frames = std::max(1, options.frames);
    for (int k = 0; k < frames; ++k) {
        double s = start + loop.length() * k / frames;
        double x, y, heading;
        loop.at(s, x, y, heading);
        double z = eye + 0.015 * std::sin(2 * kPi * s / 0.65 + phaseBob);
        Eigen::Vector3d inward(-std::sin(heading), std::cos(heading), 0);
        // The detour at this point of the walk, between the two nearest samples.
        double along = (s - start) / ds;
        int i0 = std::min(samples - 1, static_cast<int>(along));
        int i1 = std::min(samples - 1, i0 + 1);
        double w = std::clamp(along - i0, 0.0, 1.0);
        double offset = offsets[i0] * (1 - w) + offsets[i1] * w;
        Eigen::Vector3d position = Eigen::Vector3d(x, y, z) + offset * inward;

        double yaw = heading + lookAhead + 4 * kDegree * std::sin(2 * kPi * s / 2.3 + phaseYaw);
        double pitch = 15 * kDegree + 2.5 * kDegree * std::sin(2 * kPi * s / 3.1 + phasePitch);
        double roll = 1.5 * kDegree * std::sin(2 * kPi * s / 1.9 + phaseRoll);
        Eigen::Vector3d forward(std::cos(yaw) * std::cos(pitch), std::sin(yaw) * std::cos(pitch), -std::sin(pitch));
        Eigen::Vector3d right0(std::sin(yaw), -std::cos(yaw), 0);
        Eigen::Vector3d down0 = forward.cross(right0);
        Eigen::Vector3d right = std::cos(roll) * right0 + std::sin(roll) * down0;
        Eigen::Vector3d down = forward.cross(right);
        Eigen::Matrix3d R;
        R.col(0) = right;
        R.col(1) = down;
        R.col(2) = forward;

        ingest::Pose pose;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) pose.rotation[i * 3 + j] = R(i, j);
        pose.translation = {position.x(), position.y(), position.z()};
        // What pose.txt says is what gets rendered: round-trip through the text.
        poses.push_back(parsePoseLine(poseLine(pose)));
    }
    return poses;
}

std::string poseLine(const ingest::Pose& pose) {
    Eigen::Matrix3d R;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) R(i, j) = pose.rotation[i * 3 + j];
    Eigen::Quaterniond q(R);
    q.normalize();
    if (q.w() < 0) q.coeffs() *= -1;
    char line[256];
    std::snprintf(line, sizeof line, "%.9f %.9f %.9f %.9f %.9f %.9f %.9f", pose.translation.x, pose.translation.y,
                  pose.translation.z, q.x(), q.y(), q.z(), q.w());
    return line;
}

ingest::Pose parsePoseLine(const std::string& line) {
    std::istringstream in(line);
    double v[7];
    for (double& x : v)
        if (!(in >> x)) throw Error(ErrorKind::Input, "pose line needs 7 numbers (tx ty tz qx qy qz qw): " + line);
    Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
    if (!(q.norm() > 0)) throw Error(ErrorKind::Input, "pose line has a zero quaternion: " + line);
    q.normalize();
    Eigen::Matrix3d R = q.toRotationMatrix();
    ingest::Pose pose;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) pose.rotation[i * 3 + j] = R(i, j);
    pose.translation = {v[0], v[1], v[2]};
    return pose;
}

}  // namespace smql::synth
