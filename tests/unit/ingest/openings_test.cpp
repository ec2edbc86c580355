// Doors and windows as openings in a wall (ingest/geometry/openings.cpp): a
// depth camera looks at a wall with holes in it and a room behind.
#include <catch2/catch.hpp>

#include <algorithm>

#include "ingest/geometry/openings.hpp"

using namespace smql;
using namespace smql::ingest;

namespace {

struct Rect {
    double x0, x1, z0, z1;
    bool holds(double x, double z) const { return x0 <= x && x < x1 && z0 <= z && z < z1; }
};

// The wall y = 3, x -3 .. 3, 2.5 m tall, facing a camera at (0, 0, 1.5); the room behind ends at y = 5.
// Each depth reading aims at a point of the wall every 2 cm: through a hole it reaches the room behind,
// and a cabinet (its front at y = 2.5) stops the readings that meet it.
PointCloud lookAtWall(const std::vector<Rect>& holes, const std::optional<Rect>& cabinet) {
    const model::Vec3 camera{0, 0, 1.5};
    PointCloud cloud;
    for (double x = -3 + 0.01; x < 3; x += 0.02)
        for (double z = 0.01; z < 2.5; z += 0.02) {
            auto along = [&](double y) {
                double t = y / 3;
                return model::Vec3{camera.x + t * x, y, camera.z + t * (z - camera.z)};
            };
            model::Vec3 front = along(2.5);
            if (cabinet && cabinet->holds(front.x, front.z)) {
                cloud.push(front, {90, 60, 30}, 0);
                continue;
            }
            bool open = std::any_of(holes.begin(), holes.end(), [&](const Rect& h) { return h.holds(x, z); });
            cloud.push(open ? along(5) : along(3), {200, 200, 200}, 0);
        }
    return cloud;
}

WallSegment backWall() {
    WallSegment w;
    w.normal = {0, -1, 0};  // into the room
    w.offset = 3;           // -y + 3 = 0
    w.along0 = -3, w.along1 = 3;
    w.z0 = 0, w.z1 = 2.5;
    return w;
}

const WallOpening* near(const std::vector<WallOpening>& found, double along) {
    for (const auto& o : found)
        if (o.along0 - 0.05 <= along && along <= o.along1 + 0.05) return &o;
    return nullptr;
}

}  // namespace

TEST_CASE("openings: a door, a window, and a passage behind a cabinet", "[ingest][openings]") {
    const Rect door{-2, -1.1, 0, 2.0}, window{0.5, 1.5, 0.9, 1.9}, passage{1.8, 2.8, 0, 2.1};
    const Rect cabinet{1.45, 2.45, 0, 0.9};  // at y = 2.5, in front of the passage's lower part
    PointCloud cloud = lookAtWall({door, window, passage}, cabinet);
    auto found = findOpenings(cloud, {{0, {0, 0, 1.5}}}, {backWall()});
    REQUIRE(found.size() == 3);

    const WallOpening* d = near(found, -1.55);
    REQUIRE(d);
    CHECK(d->category == "door");
    CHECK(d->along0 == Approx(-2).margin(0.1));
    CHECK(d->along1 == Approx(-1.1).margin(0.1));
    CHECK(d->z0 == 0);
    CHECK(d->z1 == Approx(2.0).margin(0.1));
    CHECK(d->through > 100);

    const WallOpening* w = near(found, 1.0);
    REQUIRE(w);
    CHECK(w->category == "window");
    CHECK(w->along0 == Approx(0.5).margin(0.1));
    CHECK(w->along1 == Approx(1.5).margin(0.1));
    CHECK(w->z0 == Approx(0.9).margin(0.1));
    CHECK(w->z1 == Approx(1.9).margin(0.1));

    // The cabinet hides the passage's lower part and the wall under it: still a door, from the floor.
    const WallOpening* p = near(found, 2.3);
    REQUIRE(p);
    CHECK(p->category == "door");
    CHECK(p->z0 == 0);
    CHECK(p->z1 == Approx(2.1).margin(0.1));

    // In the wall's plane, at the door.
    model::Box box = d->box(backWall());
    CHECK(box.center.y == Approx(3));
    CHECK(box.center.x == Approx(-1.55).margin(0.1));
    CHECK(box.size.z == Approx(2.0).margin(0.1));
}

TEST_CASE("openings: a solid wall, a narrow slot and readings without their camera give none", "[ingest][openings]") {
    CHECK(findOpenings(lookAtWall({}, std::nullopt), {{0, {0, 0, 1.5}}}, {backWall()}).empty());
    // A slot 0.3 m wide is neither a door nor a window.
    CHECK(findOpenings(lookAtWall({{0, 0.3, 0, 2.0}}, std::nullopt), {{0, {0, 0, 1.5}}}, {backWall()}).empty());
    // A reading whose frame has no camera cannot say where it crossed the wall.
    CHECK(findOpenings(lookAtWall({{-2, -1.1, 0, 2.0}}, std::nullopt), {{7, {0, 0, 1.5}}}, {backWall()}).empty());
}
