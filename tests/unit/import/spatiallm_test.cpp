#include <cmath>
#include <numbers>
#include <sstream>

#include "import_support.hpp"
#include "ingest/import/importers.hpp"
#include "model/geometry.hpp"

using smql::import::readSpatialLm;
using smql::import::test::requireInputError;
using smql::import::test::TempDir;
using namespace smql::model;
using Catch::Detail::Approx;

namespace {

constexpr const char* kRoom = R"(# a 4 m x 3 m room
wall_0=Wall(0,0,0,4,0,0,2.5,0)
wall_1=Wall(4,0,0,4,3,0,2.5,0.1)
wall_2=Wall(4,3,0,0,3,0,2.5,0)
wall_3=Wall(0,3,0,0,0,0,2.5,0)

door_0=Door(wall_0,1,0,1.0,0.9,2.0)
window_0=Window(wall_1,4,1.5,1.4,1.2,1.0)
bbox_0=Bbox(Dining_Table,2,1.5,0.4,0.5,1.6,0.9,0.8)
bbox_12=Bbox(sofa, 1, 2.5, 0.45, -0.25, 2.0, 0.9, 0.9)
)";

void checkBox(const Box& box, Vec3 center, Vec3 size, double yaw) {
    CHECK(box.center.x == Approx(center.x).margin(1e-12));
    CHECK(box.center.y == Approx(center.y).margin(1e-12));
    CHECK(box.center.z == Approx(center.z).margin(1e-12));
    CHECK(box.size.x == Approx(size.x));
    CHECK(box.size.y == Approx(size.y));
    CHECK(box.size.z == Approx(size.z));
    CHECK(box.yaw == Approx(yaw).margin(1e-12));
}

}  // namespace

TEST_CASE("SpatialLM: walls, doors, windows and bboxes", "[import][spatiallm]") {
    TempDir dir;
    std::string path = dir.write("layout.txt", kRoom);
    SceneData scene = readSpatialLm(path, "flat");
    REQUIRE(scene.nodes.size() == 8);
    CHECK(scene.info.name == "flat");
    CHECK(scene.info.source == "spatiallm:" + path);
    CHECK(scene.info.nodeCount == 8);

    for (std::size_t i = 0; i < 8; ++i) {
        CHECK(scene.nodes[i].id == i + 1);
        CHECK(scene.nodes[i].parent == kNoNode);
    }
    for (std::size_t i = 0; i < 4; ++i) {
        CHECK(scene.nodes[i].kind == NodeKind::Anchor);
        CHECK(scene.nodes[i].category == "wall");
        CHECK(scene.nodes[i].geometry == GeometryKind::Plane);
        CHECK(scene.nodes[i].sourceId == static_cast<std::int64_t>(i));
    }
    // Thickness 0 becomes 2 cm; the box spans az .. az + height.
    checkBox(scene.nodes[0].box, {2, 0, 1.25}, {4, 0.02, 2.5}, 0);
    checkBox(scene.nodes[1].box, {4, 1.5, 1.25}, {3, 0.1, 2.5}, std::numbers::pi / 2);
    checkBox(scene.nodes[2].box, {2, 3, 1.25}, {4, 0.02, 2.5}, std::numbers::pi);

    const Node& door = scene.nodes[4];
    CHECK(door.kind == NodeKind::Anchor);
    CHECK(door.category == "door");
    CHECK(door.geometry == GeometryKind::Plane);
    CHECK(door.sourceId == 1000);
    checkBox(door.box, {1, 0, 1}, {0.9, 0.02, 2}, 0);

    const Node& window = scene.nodes[5];
    CHECK(window.category == "window");
    CHECK(window.sourceId == 2000);
    checkBox(window.box, {4, 1.5, 1.4}, {1.2, 0.1, 1.0}, std::numbers::pi / 2);

    const Node& table = scene.nodes[6];
    CHECK(table.kind == NodeKind::Object);
    CHECK(table.geometry == GeometryKind::Box);
    CHECK(table.category == "dining-table");  // the canonical name of `dining_table`
    CHECK(table.sourceId == 3000);
    checkBox(table.box, {2, 1.5, 0.4}, {1.6, 0.9, 0.8}, 0.5);
    CHECK(scene.nodes[7].category == "sofa");
    CHECK(scene.nodes[7].sourceId == 3012);
    CHECK(scene.nodes[7].box.yaw == Approx(-0.25));

    // No floor: 1.6 m above the lowest wall bottom, just inside the door, facing +y into the room.
    const Viewpoint& view = scene.info.viewpoint;
    CHECK(view.position.z == Approx(1.6));
    CHECK(view.position.x > 1.0);
    CHECK(view.position.y > 0.2);
    CHECK(view.position.y < 1.0);
    CHECK(std::hypot(view.position.x - 1, view.position.y) == Approx(0.5));
    CHECK(view.facingYaw == Approx(std::numbers::pi / 2));
    CHECK_THAT(scene.info.viewpointNote, Catch::Contains("door #1000"));
}

TEST_CASE("SpatialLM: no door means the centre of all boxes, facing +y", "[import][spatiallm]") {
    TempDir dir;
    // Windows line ends and a byte order mark are fine.
    std::string path = dir.write("boxes.txt",
                                 "\xEF\xBB\xBF"
                                 "bbox_0=Bbox(chair,1,1,0.5,0,1,1,1)\r\nbbox_1=Bbox(bed,3,5,0.25,0,2,2,0.5)\r\n");
    SceneData scene = readSpatialLm(path, "boxes");
    REQUIRE(scene.nodes.size() == 2);
    CHECK(scene.info.viewpoint.position.x == Approx(2.25));
    CHECK(scene.info.viewpoint.position.y == Approx(3.25));
    CHECK(scene.info.viewpoint.position.z == Approx(1.6));  // above the lowest box bottom (0)
    CHECK(scene.info.viewpoint.facingYaw == Approx(std::numbers::pi / 2));
}

TEST_CASE("SpatialLM: a box at the coordinate limit stands on the floor; a layout too tall to is refused",
          "[import][spatiallm]") {
    // Found by fuzz_import_spatiallm: eye height above this box was past the limit.
    TempDir dir;
    std::string path = dir.write("high.txt", "bbox_0=Bbox(chair,1,1,9999.45,0,0.5,0.5,0.9)\n");
    SceneData scene = readSpatialLm(path, "high");
    CHECK(scene.nodes.at(0).box.center.z == Approx(0.45));
    CHECK(scene.info.viewpoint.position.z == Approx(1.6));
    SceneData again = smql::import::readSceneJson(dir.write("again.json", smql::import::writeSceneJson(scene)));
    CHECK(again.nodes == scene.nodes);
    CHECK(again.info == scene.info);
    // Standing on the lower box puts the higher one past the limit: an error, not a scene that
    // cannot be read back.
    std::string tall =
        dir.write("tall.txt", "bbox_0=Bbox(chair,1,1,-9999,0,0.5,0.5,0.9)\nbbox_1=Bbox(lamp,1,1,9999,0,0.5,0.5,0.9)\n");
    CHECK_THROWS_WITH(readSpatialLm(tall, "tall"), Catch::Contains("more than 10000 m"));
}

TEST_CASE("SpatialLM: malformed layouts are rejected with file:line", "[import][spatiallm][malformed]") {
    TempDir dir;
    // The room, with line `line` (1-based) replaced.
    auto withLine = [&](int line, const std::string& text) {
        std::string room = kRoom, out;
        std::istringstream in(room);
        std::string current;
        for (int n = 1; std::getline(in, current); ++n) out += (n == line ? text : current) + "\n";
        return dir.write("layout.txt", out);
    };
    auto read = [](const std::string& path) { return [path] { readSpatialLm(path, "r"); }; };

    SECTION("missing file") {
        std::string path = dir.path("nowhere.txt");
        requireInputError(read(path), {path, "no such file"});
    }
    SECTION("empty file") {
        std::string path = dir.write("empty.txt", "# only a comment\n\n");
        requireInputError(read(path), {path, "no walls, doors, windows or bboxes"});
    }
    SECTION("a bbox number past the source id range") {
        std::string path = withLine(9, "bbox_9223372036854775807=Bbox(sofa,1,2.5,0.45,0,2.0,0.9,0.9)");
        requireInputError(read(path), {path + ":9:", "bbox numbers must be at most 999999999999"}, 9);
    }
    SECTION("wrong arity") {
        std::string path = withLine(3, "wall_1=Wall(4,0,0,4,3,0,2.5)");
        requireInputError(read(path), {path + ":3:", "Wall takes 8 values", "got 7"}, 3);
    }
    SECTION("unknown wall reference") {
        std::string path = withLine(7, "door_0=Door(wall_7,1,0,1.0,0.9,2.0)");
        requireInputError(read(path), {path + ":7:", "unknown wall 'wall_7'"}, 7);
    }
    SECTION("NaN in a line") {
        std::string path = withLine(9, "bbox_0=Bbox(table,2,nan,0.4,0.5,1.6,0.9,0.8)");
        requireInputError(read(path), {path + ":9:", "position_y", "not a finite number"}, 9);
    }
    SECTION("infinity in a line") {
        std::string path = withLine(2, "wall_0=Wall(0,0,0,inf,0,0,2.5,0)");
        requireInputError(read(path), {path + ":2:", "bx", "not a finite number"}, 2);
    }
    SECTION("non-number") {
        std::string path = withLine(8, "window_0=Window(wall_1,4,1.5,high,1.2,1.0)");
        requireInputError(read(path), {path + ":8:", "position_z", "'high' is not a number"}, 8);
    }
    SECTION("unknown entity type") {
        std::string path = withLine(6, "stair_0=Stair(0,0,0,1,1,1)");
        requireInputError(read(path), {path + ":6:", "unknown entity type 'Stair'"}, 6);
    }
    SECTION("duplicate name") {
        std::string path = withLine(4, "wall_1=Wall(4,3,0,0,3,0,2.5,0)");
        requireInputError(read(path), {path + ":4:", "duplicate name 'wall_1'", "line 3"}, 4);
    }
    SECTION("negative size") {
        std::string path = withLine(10, "bbox_12=Bbox(sofa,1,2.5,0.45,0,2.0,-0.9,0.9)");
        requireInputError(read(path), {path + ":10:", "scale_y", "-0.9"}, 10);
    }
    SECTION("zero-length wall") {
        std::string path = withLine(5, "wall_3=Wall(1,1,0,1,1,0,2.5,0)");
        requireInputError(read(path), {path + ":5:", "wall length"}, 5);
    }
    SECTION("huge coordinate") {
        std::string path = withLine(9, "bbox_0=Bbox(table,2e6,1.5,0.4,0.5,1.6,0.9,0.8)");
        requireInputError(read(path), {path + ":9:", "position_x", "from the origin"}, 9);
    }
    SECTION("a name that does not fit its type") {
        std::string path = withLine(7, "bbox_5=Door(wall_0,1,0,1.0,0.9,2.0)");
        requireInputError(read(path), {path + ":7:", "expected door_<n>"}, 7);
    }
    SECTION("not an assignment") {
        std::string path = withLine(6, "this is not a layout line");
        requireInputError(read(path), {path + ":6:", "expected <name>=<Type>(<values>)"}, 6);
    }
    SECTION("a class name in Latin-1, not UTF-8") {
        // "caf\xE9": é in Latin-1. Stored, it broke every JSON answer about it.
        std::string path = withLine(9, "bbox_0=Bbox(caf\xE9,2,1.5,0.4,0.5,1.6,0.9,0.8)");
        requireInputError(read(path), {path + ":9:", "class: byte 0xE9 at column 16 is not UTF-8", "iconv"}, 9);
        path = withLine(2, "wall_\xFF=Wall(0,0,0,4,0,0,2.5,0)");
        requireInputError(read(path), {path + ":2:", "name: byte 0xFF"}, 2);
        path = withLine(8, "window_0=Window(wall_1,4,1.5,1\xB5,1.2,1.0)");
        requireInputError(read(path), {path + ":8:", "position_z: byte 0xB5"}, 8);
        path = withLine(9, "bbox_0=Bbox(caf\xC3\xA9,2,1.5,0.4,0.5,1.6,0.9,0.8)");  // é in UTF-8 is fine
        CHECK(readSpatialLm(path, "r").nodes[6].category == "caf\xC3\xA9");
    }
    SECTION("a NUL in a class name") {
        // Stored, it cut the category short in C strings and made the memory's own JSON export unreadable.
        using namespace std::string_literals;
        std::string path = withLine(9, "bbox_0=Bbox(cha\0r,2,1.5,0.4,0.5,1.6,0.9,0.8)"s);
        requireInputError(read(path), {path + ":9:", "class: a NUL byte at column 16"}, 9);
    }
    SECTION("two names for one number clash in their source id") {
        std::string path = withLine(5, "wall_01=Wall(0,3,0,0,0,0,2.5,0)");
        requireInputError(read(path),
                          {path + ":5:", "'wall_01' has the same number as 'wall_1' (line 3)", "source id 1"}, 5);
        path = withLine(10, "bbox_000=Bbox(sofa, 1, 2.5, 0.45, -0.25, 2.0, 0.9, 0.9)");
        requireInputError(read(path),
                          {path + ":10:", "'bbox_000' has the same number as 'bbox_0' (line 9)", "source id 3000"}, 10);
    }
    SECTION("an angle that is not a plausible number of radians") {
        std::string path = withLine(9, "bbox_0=Bbox(table,2,1.5,0.4,1e300,1.6,0.9,0.8)");
        requireInputError(read(path), {path + ":9:", "angle_z: 1e+300 is not an angle in radians", "4 pi"}, 9);
        path = withLine(9, "bbox_0=Bbox(table,2,1.5,0.4,90,1.6,0.9,0.8)");
        requireInputError(read(path), {path + ":9:", "angle_z: 90 is not an angle", "degrees"}, 9);
        path = withLine(9, "bbox_0=Bbox(table,2,1.5,0.4,-12.5,1.6,0.9,0.8)");  // just within two turns
        CHECK(readSpatialLm(path, "r").nodes[6].box.yaw == Approx(std::remainder(-12.5, 2 * std::numbers::pi)));
    }
    SECTION("text after the closing parenthesis") {
        std::string path = withLine(2, "wall_0=Wall(0,0,0,4,0,0,2.5,0) extra");
        requireInputError(read(path), {path + ":2:", "after ')'"}, 2);
    }
}
