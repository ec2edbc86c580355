// Detections without sparse points, placed by their boxes' rays: cameras on a circle around
// three boxes, each view's detection the box its corners project to.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <opencv2/core.hpp>

#include "ingest/pipeline/ray_tracks.hpp"

using namespace smql;
using namespace smql::ingest;

namespace {

const Intrinsics kCamera{640, 480, 500, 500, 319.5, 239.5};

// A camera at `eye` looking at `target`, z up (camera x right, y down, z forward).
Pose lookAt(const cv::Vec3d& eye, const cv::Vec3d& target) {
    cv::Vec3d f = cv::normalize(target - eye);
    cv::Vec3d r = cv::normalize(f.cross(cv::Vec3d(0, 0, 1)));
    cv::Vec3d d = f.cross(r);
    Pose pose;
    pose.rotation = {r[0], d[0], f[0], r[1], d[1], f[1], r[2], d[2], f[2]};
    pose.translation = {eye[0], eye[1], eye[2]};
    return pose;
}

struct Thing {
    std::string category;
    cv::Vec3d centre;
    double side;
};

// The box a cube's corners project to in a camera, when all of them are in front of it and the
// box lies inside the image.
std::optional<cv::Rect> boxOf(const Thing& thing, const MaskView& camera) {
    double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
    for (int corner = 0; corner < 8; ++corner) {
        cv::Vec3d offset((corner & 1 ? 0.5 : -0.5) * thing.side, (corner & 2 ? 0.5 : -0.5) * thing.side,
                         (corner & 4 ? 0.5 : -0.5) * thing.side);
        cv::Vec3d p = thing.centre + offset;
        auto at = projectToImage({p[0], p[1], p[2]}, camera.pose, camera.intrinsics);
        if (!at) return std::nullopt;
        x0 = std::min(x0, at->x), y0 = std::min(y0, at->y), x1 = std::max(x1, at->x), y1 = std::max(y1, at->y);
    }
    // Pixel centres to pixel edges.
    return cv::Rect(cv::Point(static_cast<int>(std::floor(x0 + 0.5)), static_cast<int>(std::floor(y0 + 0.5))),
                    cv::Point(static_cast<int>(std::ceil(x1 + 0.5)), static_cast<int>(std::ceil(y1 + 0.5))));
}

struct Scene {
    std::vector<MaskView> cameras;
    std::vector<UnplacedView> views;
};

Scene circleAround(const std::vector<Thing>& things, int frames) {
    Scene scene;
    for (int f = 0; f < frames; ++f) {
        double angle = 2 * std::numbers::pi * f / frames;
        cv::Vec3d eye(3.5 * std::cos(angle), 3.5 * std::sin(angle), 1.5);
        scene.cameras.push_back({static_cast<std::uint32_t>(f), cv::Mat(), kCamera, lookAt(eye, {0, 0, 0.4})});
        std::uint16_t instance = 0;
        for (const auto& thing : things) {
            ++instance;
            auto box = boxOf(thing, scene.cameras.back());
            if (!box) continue;
            Observation view;
            view.frame = static_cast<std::uint32_t>(f);
            view.instance = instance;
            view.bounds = *box;
            view.pixels = box->area();
            scene.views.push_back({view, thing.category, {}});
        }
    }
    return scene;
}

cv::Vec3d centreOf(const ObjectTrack& track) {
    cv::Vec3d sum(0, 0, 0);
    std::size_t n = 0;
    for (const auto& v : track.views)
        for (const auto& p : v.points) sum += cv::Vec3d(p.x, p.y, p.z), ++n;
    REQUIRE(n > 0);
    return sum / static_cast<double>(n);
}

const std::vector<Thing> kThings = {
    {"chair", {-0.8, 0, 0.45}, 0.5}, {"chair", {0.8, 0, 0.45}, 0.5}, {"lamp", {0, 0.9, 0.3}, 0.2}};

}  // namespace

TEST_CASE("placeByRays: each thing becomes one track at its place, two of one category apart", "[ingest][rays]") {
    Scene scene = circleAround(kThings, 12);
    const std::size_t detections = scene.views.size();
    std::vector<ObjectTrack> tracks;
    CHECK(placeByRays(scene.views, scene.cameras, tracks) == detections);
    REQUIRE(tracks.size() == 3);
    for (const auto& thing : kThings) {
        auto placed = std::find_if(tracks.begin(), tracks.end(), [&](const ObjectTrack& t) {
            return t.category == thing.category && cv::norm(centreOf(t) - thing.centre) < 0.15;
        });
        INFO(thing.category << " at " << thing.centre);
        REQUIRE(placed != tracks.end());
        // One view per frame, and the hull reaches the cube's faces but not far past them.
        std::vector<std::uint32_t> frames;
        for (const auto& v : placed->views) frames.push_back(v.frame);
        std::sort(frames.begin(), frames.end());
        CHECK(std::adjacent_find(frames.begin(), frames.end()) == frames.end());
        double lo = 1e9, hi = -1e9;
        for (const auto& p : placed->views.front().points) lo = std::min(lo, p.x), hi = std::max(hi, p.x);
        CHECK(hi - lo > 0.8 * thing.side);
        CHECK(hi - lo < 1.6 * thing.side);
    }
}

TEST_CASE("placeByRays: views of an already placed thing join its track", "[ingest][rays]") {
    Scene scene = circleAround(kThings, 12);
    // The first chair was placed by its sparse points in frames 0 and 1.
    ObjectTrack chair;
    chair.category = "chair";
    for (std::uint32_t f : {0U, 1U}) {
        Observation view;
        view.frame = f;
        chair.views.push_back(view);
    }
    chair.views.front().points = {{-0.9, -0.1, 0.3}, {-0.7, 0.1, 0.6}};
    std::erase_if(scene.views, [](const UnplacedView& v) { return v.view.frame <= 1 && v.view.instance == 1; });
    std::vector<ObjectTrack> tracks = {chair};
    placeByRays(scene.views, scene.cameras, tracks);
    REQUIRE(tracks.size() == 3);
    CHECK(tracks.front().views.size() == 12);
    CHECK(std::count_if(tracks.begin(), tracks.end(), [](const ObjectTrack& t) { return t.category == "chair"; }) == 2);
}

TEST_CASE("placeByRays: a thing seen in one frame only stays unplaced", "[ingest][rays]") {
    Scene scene = circleAround({{"plant", {0, 0, 0.3}, 0.3}}, 12);
    std::erase_if(scene.views, [](const UnplacedView& v) { return v.view.frame != 4; });
    std::vector<ObjectTrack> tracks;
    CHECK(placeByRays(scene.views, scene.cameras, tracks) == 0);
    CHECK(tracks.empty());
}

TEST_CASE("placeByRays: one thing carved as two tracks, one reaching far along its views, becomes one",
          "[ingest][rays]") {
    // A table seen from frames 0-5 and, associated apart, from frames 6-11 (the red kitchen's table in
    // photos without depth: one track 1.8 m long, one 2.5 x 2.1 m where the later frames carved little). The
    // long track's centre lies outside the short one's bounds, the short one's inside the long one's; the
    // two never share a frame, so they are one thing, carved again from all twelve views.
    const Thing table{"table", {0, 0, 0.4}, 0.8};
    Scene scene = circleAround({table}, 12);
    auto trackOf = [&](std::uint32_t first, std::uint32_t last, double reach) {
        ObjectTrack track;
        track.category = "table";
        track.carved = true;
        for (const auto& v : scene.views)
            if (v.view.frame >= first && v.view.frame <= last) track.views.push_back(v.view);
        for (double x = -0.4; x <= 0.4 + reach; x += 0.05)
            for (double y = -0.4; y <= 0.4; y += 0.05)
                for (double z = 0; z <= 0.8; z += 0.05) track.views.front().points.push_back({x, y, z});
        return track;
    };
    std::vector<ObjectTrack> tracks = {trackOf(0, 5, 0), trackOf(6, 11, 1.0)};
    placeByRays({}, scene.cameras, tracks);
    REQUIRE(tracks.size() == 1);
    CHECK(tracks.front().views.size() == 12);
    CHECK(cv::norm(centreOf(tracks.front()) - table.centre) < 0.1);
    double lo = 1e9, hi = -1e9;
    for (const auto& p : tracks.front().views.front().points) lo = std::min(lo, p.x), hi = std::max(hi, p.x);
    CHECK(hi - lo < 1.3 * table.side);
}
