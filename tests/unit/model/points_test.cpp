// The capture's points as a scene keeps them (model/points.hpp): the PLY written is read back
// point for point, and a damaged one is refused.
#include <catch2/catch.hpp>

#include "model/error.hpp"
#include "model/points.hpp"

using namespace smql;

TEST_CASE("points: a PLY of coloured points is read back as written", "[model][points]") {
    model::ScenePoints points;
    for (int i = 0; i < 100; ++i) {
        points.positions.push_back({i * 0.05, -i * 0.01, 1.25});
        points.colours.push_back({static_cast<std::uint8_t>(i), 200, static_cast<std::uint8_t>(255 - i)});
    }
    const std::string ply = model::pointsPly(points, "smql points\nof a test");
    CHECK(ply.starts_with("ply\nformat binary_little_endian 1.0\ncomment smql points of a test\nelement vertex 100\n"));
    const model::ScenePoints back = model::readPointsPly(ply);
    REQUIRE(back.positions.size() == 100);
    for (std::size_t i = 0; i < 100; ++i) {
        CHECK(back.positions[i].x == Approx(points.positions[i].x).margin(1e-6));
        CHECK(back.positions[i].y == Approx(points.positions[i].y).margin(1e-6));
        CHECK(back.colours[i] == points.colours[i]);
    }
    CHECK(model::readPointsPly(model::pointsPly({}, "none")).positions.empty());
}

TEST_CASE("points: a damaged PLY is refused, not read past its end", "[model][points]") {
    model::ScenePoints points{{{1, 2, 3}, {4, 5, 6}}, {{1, 2, 3}, {4, 5, 6}}};
    const std::string ply = model::pointsPly(points, "two");
    CHECK_THROWS_AS(model::readPointsPly(ply.substr(0, ply.size() - 1)), Error);
    CHECK_THROWS_AS(model::readPointsPly(ply + "x"), Error);
    CHECK_THROWS_AS(model::readPointsPly("ply\nformat ascii 1.0\nend_header\n"), Error);
    std::string huge = ply;
    huge.replace(huge.find("vertex 2"), 8, "vertex 99999999999999999999");
    CHECK_THROWS_AS(model::readPointsPly(huge), Error);
}
