#include <catch2/catch.hpp>

#include <cmath>

#include "model/geometry.hpp"
#include "model/names.hpp"

using namespace smql::model;

namespace {
Box box(double x, double y, double z, double sx, double sy, double sz, double yaw = 0) {
    return Box{{x, y, z}, {sx, sy, sz}, yaw};
}
}  // namespace

TEST_CASE("footprint overlap of axis-aligned and rotated boxes") {
    CHECK(footprintOverlap(box(0, 0, 0, 2, 2, 1), box(1, 1, 0, 2, 2, 1)) == Approx(1.0));
    CHECK(footprintOverlap(box(0, 0, 0, 2, 2, 1), box(3, 0, 0, 2, 2, 1)) == Approx(0.0));
    // A unit square turned 45 degrees inside a 2x2 square: the whole unit area overlaps.
    CHECK(footprintOverlap(box(0, 0, 0, 1, 1, 1, M_PI / 4), box(0, 0, 0, 2, 2, 1)) == Approx(1.0));
    // Two unit squares, one turned 45 degrees about the same centre: the regular octagon, 2(sqrt2 - 1).
    CHECK(footprintOverlap(box(0, 0, 0, 1, 1, 1, M_PI / 4), box(0, 0, 0, 1, 1, 1)) == Approx(2 * (std::sqrt(2.0) - 1)));
}

TEST_CASE("distances between prisms split into floor and height parts") {
    CHECK(horizontalGap(box(0, 0, 0, 1, 1, 1), box(3, 0, 0, 1, 1, 1)) == Approx(2.0));
    CHECK(verticalGap(box(0, 0, 0, 1, 1, 1), box(0, 0, 3, 1, 1, 1)) == Approx(2.0));
    CHECK(distance(box(0, 0, 0, 1, 1, 1), box(4, 0, 4, 1, 1, 1)) == Approx(std::sqrt(18.0)));
    CHECK(distance(box(0, 0, 0, 1, 1, 1), box(0.5, 0, 0, 1, 1, 1)) == Approx(0.0));
    // A box turned 45 degrees reaches sqrt(2)/2 from its centre along x.
    CHECK(horizontalGap(box(0, 0, 0, 1, 1, 1, M_PI / 4), box(2, 0, 0, 1, 1, 1)) ==
          Approx(2 - 0.5 - std::sqrt(2.0) / 2).margin(1e-9));
}

TEST_CASE("containment and world bounds") {
    CHECK(fractionInside(box(0, 0, 0, 1, 1, 1), box(0, 0, 0, 2, 2, 2)) == Approx(1.0));
    CHECK(fractionInside(box(0.5, 0, 0, 1, 1, 1), box(0, 0, 0, 1, 1, 1)) == Approx(0.5));
    auto a = worldAabb(box(0, 0, 0, 2, 1, 1, M_PI / 2));
    CHECK(a.max.x == Approx(0.5));
    CHECK(a.max.y == Approx(1.0));
    CHECK(footprintContains(box(0, 0, 0, 2, 1, 1, M_PI / 2), {0.0, 0.9}));
    CHECK_FALSE(footprintContains(box(0, 0, 0, 2, 1, 1, M_PI / 2), {0.9, 0.0}));
    // From a point (where a viewer stands) to a footprint: 0 over it, else to its nearest side or corner.
    CHECK(footprintGap(box(0, 0, 5, 2, 1, 1), {0.5, 0.2}) == 0.0);
    CHECK(footprintGap(box(0, 0, 5, 2, 1, 1), {3.0, 0.0}) == Approx(2.0));
    CHECK(footprintGap(box(0, 0, 5, 2, 1, 1), {4.0, 4.5}) == Approx(5.0));
    CHECK(footprintGap(box(0, 0, 0, 2, 1, 1, M_PI / 2), {0.0, 3.0}) == Approx(2.0));
}

TEST_CASE("a box's footprint grown in its own axes to take in another's") {
    // Two pieces of one chair's back side by side: the first grows along y to take in the second, its turn and
    // heights kept.
    Box back = box(0.62, 1.16, 0.49, 0.33, 0.39, 0.98);
    takeInFootprint(back, box(0.62, 0.98, 0.2, 0.33, 0.32, 0.4));
    CHECK(back.center.y == Approx((1.355 + 0.82) / 2));
    CHECK(back.size.y == Approx(1.355 - 0.82));
    CHECK(back.size.x == Approx(0.33));
    CHECK(back.center.z == 0.49);
    CHECK(back.size.z == 0.98);
    // A turned box takes in the corners of one turned otherwise, in its own axes: a unit square turned 45 degrees
    // at its centre reaches sqrt(2) / 2 along each of its axes.
    Box turned = box(0, 0, 0, 0.2, 0.2, 1, M_PI / 2);
    takeInFootprint(turned, box(0, 0, 0, 1, 1, 1, M_PI / 4));
    CHECK(turned.size.x == Approx(std::sqrt(2.0)));
    CHECK(turned.size.y == Approx(std::sqrt(2.0)));
    CHECK(turned.yaw == Approx(M_PI / 2));
}

TEST_CASE("nearest names for did-you-mean hints") {
    CHECK(editDistance("sofa", "sopha") == 2);
    auto close = nearestNames("cushon", {"cushion", "chair", "table"});
    REQUIRE_FALSE(close.empty());
    CHECK(close.front() == "cushion");
    CHECK(nearestNames("zzzzzz", {"cushion", "chair"}).empty());
    CHECK(joinAlternatives({"a", "b", "c"}) == "a, b or c");
}

TEST_CASE("SMQL string literals double their quotes") {
    CHECK(quoted("sofa") == "'sofa'");
    CHECK(quoted("it's") == "'it''s'");
    CHECK(quoted("") == "''");
}
