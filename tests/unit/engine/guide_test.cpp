// Guidance: free space, the decision-point graph, routes and their steps (engine/guide), and the
// GUIDE and SHOW GRAPH statements over them.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/guide/route_graph.hpp"
#include "engine/guide/route_steps.hpp"
#include "engine_support.hpp"
#include "ingest/import/importers.hpp"
#include "model/geometry.hpp"
#include "relations/hierarchy.hpp"

using namespace smql;
using namespace smql::testing;
using model::NodeKind;

namespace {

model::Node node(model::NodeId id, NodeKind kind, std::string category, model::Vec3 centre, model::Vec3 size,
                 double yaw = 0) {
    model::Node n;
    n.id = id;
    n.kind = kind;
    n.category = std::move(category);
    n.geometry = kind == NodeKind::Anchor ? model::GeometryKind::Plane : model::GeometryKind::Box;
    n.box = {centre, size, yaw};
    return n;
}

// Two rooms side by side, 4 m x 4 m each, split by a wall at x = 4 with a door at y = 1 (when
// `door`); a table stands in the left room, a mug on it; a lamp stands in the right room.
model::SceneData twoRooms(bool door) {
    model::SceneData s;
    s.info.name = "flat";
    s.info.viewpoint = {{1, 3, 1.6}, 0};
    model::NodeId id = 1;
    s.nodes.push_back(node(id++, NodeKind::Anchor, "floor", {4, 2, 0}, {8, 4, 0.02}));
    s.nodes.push_back(node(id++, NodeKind::Anchor, "wall", {4, 0, 1.25}, {8, 0.1, 2.5}));
    s.nodes.push_back(node(id++, NodeKind::Anchor, "wall", {4, 4, 1.25}, {8, 0.1, 2.5}));
    s.nodes.push_back(node(id++, NodeKind::Anchor, "wall", {0, 2, 1.25}, {0.1, 4, 2.5}));
    s.nodes.push_back(node(id++, NodeKind::Anchor, "wall", {8, 2, 1.25}, {0.1, 4, 2.5}));
    s.nodes.push_back(node(id++, NodeKind::Anchor, "wall", {4, 2, 1.25}, {0.1, 4, 2.5}));  // the split
    if (door) s.nodes.push_back(node(id++, NodeKind::Anchor, "door", {4, 1, 1.05}, {0.1, 0.9, 2.1}));
    s.nodes.push_back(node(id++, NodeKind::Object, "table", {2, 2, 0.4}, {1.2, 0.8, 0.8}));
    s.nodes.push_back(node(id++, NodeKind::Object, "mug", {2, 2, 0.85}, {0.1, 0.1, 0.1}));
    s.nodes.push_back(node(id++, NodeKind::Object, "lamp", {6.5, 3, 0.8}, {0.3, 0.3, 1.6}));
    return s;
}

std::vector<model::Node> nodesOf(const model::SceneData& s) { return s.nodes; }

}  // namespace

TEST_CASE("free space: walls and standing things block, things on them do not, doors open walls", "[guide]") {
    guide::GraphOptions options;
    auto withDoor = nodesOf(twoRooms(true));
    guide::FreeSpace space(withDoor, options);
    CHECK(space.free({1, 1}));
    CHECK_FALSE(space.free({2, 2}));    // under the table
    CHECK_FALSE(space.free({2.7, 2}));  // within a body's radius of it
    CHECK(space.free({3.0, 2}));        // beyond
    CHECK_FALSE(space.free({4, 3}));    // the split wall
    CHECK(space.free({4, 1}));          // the door in it
    CHECK_FALSE(space.free({0.1, 1}));  // against the outer wall
    CHECK_FALSE(space.free({9, 1}));    // outside the floor
    CHECK(space.clear({1, 1}, {3.5, 1}));
    CHECK_FALSE(space.clear({3.5, 3}, {4.5, 3}));
    guide::FreeSpace closed(nodesOf(twoRooms(false)), options);
    CHECK_FALSE(closed.free({4, 1}));
}

TEST_CASE("the shortest route goes through the door; without one there is none", "[guide]") {
    guide::GraphOptions options;
    auto nodes = nodesOf(twoRooms(true));
    guide::FreeSpace space(nodes, options);
    auto graph = guide::buildGraph(nodes, space, options);
    std::size_t doors = 0, approaches = 0;
    for (const auto& p : graph.points) {
        doors += p.kind == guide::PointKind::Door;
        approaches += p.kind == guide::PointKind::Approach;
    }
    CHECK(doors == 2);       // one on each side
    CHECK(approaches == 3);  // table, mug, lamp
    auto route = guide::shortestRoute(graph, space, {1, 3}, {6.5, 2.5}, options);
    REQUIRE(route);
    bool throughDoor = false;
    for (std::size_t i = 1; i < route->waypoints.size(); ++i) {
        auto a = route->waypoints[i - 1], b = route->waypoints[i];
        if ((a.x - 4) * (b.x - 4) <= 0) {  // this leg crosses the wall's line
            double y = a.y + (b.y - a.y) * (4 - a.x) / (b.x - a.x);
            throughDoor = std::abs(y - 1) < 0.45;
        }
    }
    CHECK(throughDoor);
    CHECK(route->length > std::hypot(5.5, 0.5));  // longer than the straight line through the wall

    auto closedNodes = nodesOf(twoRooms(false));
    guide::FreeSpace closed(closedNodes, options);
    auto closedGraph = guide::buildGraph(closedNodes, closed, options);
    CHECK_FALSE(guide::shortestRoute(closedGraph, closed, {1, 3}, {6.5, 2.5}, options));
}

TEST_CASE("steps turn relative to the walker's heading and end by saying where the goal is", "[guide]") {
    auto nodes = nodesOf(twoRooms(true));
    const model::Node& lamp = nodes.back();
    // East 3 m, then north 2 m; the lamp is then ahead-right... of a walker facing north at (4, 3)?
    guide::Route route{{{1, 1}, {4, 1}, {4, 3}}, 5};
    auto steps = guide::describeRoute(route, nodes, lamp, /*startHeading=*/M_PI / 2);  // facing north at first
    REQUIRE(steps.size() == 3);
    CHECK(steps[0].instruction.rfind("Turn right. Walk about 3 m", 0) == 0);
    CHECK(steps[1].instruction.rfind("Turn left. Walk about 2 m", 0) == 0);
    CHECK(steps[2].instruction == "The lamp is 2.5 m on your right.");
    CHECK(steps[2].landmark == lamp.id);
    auto noHeading = guide::describeRoute(route, nodes, lamp, std::nullopt);
    CHECK(noHeading[0].instruction.rfind("Walk about 3 m", 0) == 0);
    // A way that swings by 45 degrees, then back: the walker bears right, then left, and never turns.
    guide::Route swing{{{1, 1}, {3, 1}, {4, 2}, {5, 2}}, 2 + std::sqrt(2.0) + 1};
    auto swinging = guide::describeRoute(swing, nodes, lamp, /*startHeading=*/0);
    REQUIRE(swinging.size() == 4);
    CHECK(swinging[1].instruction.rfind("Bear left. Walk about 1 m", 0) == 0);
    CHECK(swinging[2].instruction.rfind("Bear right. Walk about 1 m", 0) == 0);
}

TEST_CASE("a thing no model named is a landmark only where no named one is near, said by its size and colour",
          "[guide]") {
    auto nodes = nodesOf(twoRooms(true));
    const model::Node lamp = nodes.back();
    // A cabinet no model named, stored as a capture stores it, at the end of the first leg (4, 1).
    model::Node thing = node(20, NodeKind::Object, "object", {3.3, 0.4, 0.5}, {0.8, 0.6, 1.0});
    thing.attributes = {{"color", "white"}, {"size", "large"}};
    nodes.push_back(thing);
    guide::Route route{{{1, 1}, {4, 1}, {4, 3}}, 5};
    auto steps = guide::describeRoute(route, nodes, lamp, std::nullopt);
    REQUIRE(steps.size() == 3);
    CHECK(steps[0].instruction == "Walk about 3 m toward the door.");  // the door is named: it comes first
    nodes.push_back(node(21, NodeKind::Object, "object", {4.6, 3.2, 0.5}, {0.8, 0.6, 1.0}));
    nodes.back().attributes = {{"color", "red"}};
    steps = guide::describeRoute(route, nodes, lamp, std::nullopt);
    CHECK(steps[1].instruction == "Turn left. Walk about 2 m toward the red thing.");  // nothing named near (4, 3)
}

TEST_CASE("GUIDE answers in steps; ambiguous ends and closed-off goals are errors that say why", "[guide]") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    engine->importScene(twoRooms(true));
    auto rs = run(*engine, "GUIDE FROM door TO lamp");
    REQUIRE(rs.rows.size() >= 2);
    CHECK(rs.rows.front()[1] == Value(std::string("Start at the door.")));
    const auto& last = rs.rows.back();
    CHECK_THAT(std::get<std::string>(last[1]), Catch::StartsWith("The lamp by the wall is"));
    CHECK(std::get<std::string>(last[2]).rfind("lamp#", 0) == 0);
    CHECK_THAT(rs.message, Catch::Contains("from door#"));

    auto here = run(*engine, "GUIDE FROM HERE TO (FIND object WHERE on(table))");
    CHECK_THAT(std::get<std::string>(here.rows.back()[1]), Catch::StartsWith("The mug on the table is"));
    CHECK(run(*engine, "GUIDE FROM (1, 1) TO lamp").rows.size() >= 2);
    CHECK(run(*engine, "SHOW GRAPH").rows.size() > 5);
    CHECK_THAT(std::get<std::string>(run(*engine, "EXPLAIN GUIDE FROM door TO lamp").rows[0][0]),
               Catch::Contains("Dijkstra"));

    try {
        engine->execute("GUIDE FROM door TO wall");
        FAIL("an ambiguous goal was routed to");
    } catch (const Error& e) {
        CHECK_THAT(e.message(), Catch::Contains("the goal is ambiguous: wall (5 nodes)"));
        CHECK_THAT(e.hint(), Catch::Contains("name one: wall#"));
    }

    TempDir closedDir;
    auto closed = Engine::open(closedDir.path.string());
    closed->importScene(twoRooms(false));
    try {
        closed->execute("GUIDE FROM table TO lamp");
        FAIL("a route through a wall");
    } catch (const Error& e) {
        // It says what closes the goal's side off: the walls around the right room.
        CHECK_THAT(e.message(), Catch::Contains("no route") && Catch::Contains("lamp#") &&
                                    Catch::Contains("closed off by") && Catch::Contains("wall#"));
        CHECK_THAT(e.hint(), Catch::Contains("smql map"));
        // The one thing that closes the way: the wall between the rooms, which has no door.
        CHECK_THAT(e.message(), Catch::Matches(".*wall#[0-9]+ alone closes the way.*"));
    }

    // A cabinet standing in the doorway: it alone closes the way, though walls border the room too.
    TempDir blockedDir;
    auto blocked = Engine::open(blockedDir.path.string());
    model::SceneData withCabinet = twoRooms(true);
    withCabinet.nodes.push_back(node(20, NodeKind::Object, "cabinet", {4.45, 1, 0.9}, {0.6, 1.4, 1.8}));
    blocked->importScene(withCabinet);
    try {
        blocked->execute("GUIDE FROM table TO lamp");
        FAIL("a route through the cabinet");
    } catch (const Error& e) {
        CHECK_THAT(e.message(), Catch::Matches(".*cabinet#[0-9]+ alone closes the way.*"));
    }
}

namespace {

// A bedroom 6 m x 4 m with its door in the left wall: a rug in the middle, a bed by the right
// wall under a blanket that spills 0.4 m over its sides to the floor, a pillow on the bed, a
// light on the ceiling. Parents are set as the tree sets them.
std::vector<model::Node> bedroom(bool blanketOnBed) {
    std::vector<model::Node> n;
    n.push_back(node(1, NodeKind::Anchor, "floor", {3, 2, -0.01}, {6, 4, 0.02}));
    n.push_back(node(2, NodeKind::Anchor, "wall", {3, 0, 1.25}, {6, 0.1, 2.5}));
    n.push_back(node(3, NodeKind::Anchor, "wall", {3, 4, 1.25}, {6, 0.1, 2.5}));
    n.push_back(node(4, NodeKind::Anchor, "wall", {0, 2, 1.25}, {0.1, 4, 2.5}));
    n.push_back(node(5, NodeKind::Anchor, "wall", {6, 2, 1.25}, {0.1, 4, 2.5}));
    n.push_back(node(6, NodeKind::Anchor, "door", {0, 1, 1.05}, {0.1, 0.9, 2.1}));
    n.push_back(node(7, NodeKind::Object, "rug", {2.5, 2, 0.005}, {2.5, 1.8, 0.01}));
    n.push_back(node(8, NodeKind::Object, "bed", {4.9, 2.5, 0.25}, {2.0, 1.6, 0.5}));
    n.push_back(node(9, NodeKind::Object, "blanket", {4.9, 2.5, 0.3}, {2.0, 2.4, 0.6}));
    n.push_back(node(10, NodeKind::Object, "pillow", {5.6, 2.5, 0.57}, {0.4, 0.6, 0.15}));
    n.push_back(node(11, NodeKind::Object, "lamp", {2.5, 2, 2.45}, {0.6, 0.6, 0.05}));
    if (blanketOnBed) n[8].parent = 8;
    n[9].parent = 8;
    return n;
}

}  // namespace

TEST_CASE("free space as in a real room: rugs are walked over, what lies on furniture leaves the floor to it",
          "[guide]") {
    guide::GraphOptions options;
    auto nodes = bedroom(true);
    guide::FreeSpace space(nodes, options);
    CHECK(space.free({2.5, 2}));  // on the rug
    CHECK(space.open({2.5, 2}));
    // 0.3 m from the bed's side, 0.1 m from the blanket's edge: free, for the blanket is on the bed.
    CHECK(space.free({4.9, 1.4}));
    CHECK_FALSE(space.free({4.9, 1.6}));  // within a body's radius of the bed
    auto loose = bedroom(false);
    CHECK_FALSE(guide::FreeSpace(loose, options).free({4.9, 1.4}));  // a blanket on the floor blocks

    // The pillow on the bed is approached beside the bed, on the side nearest the pillow.
    auto graph = guide::buildGraph(nodes, space, options);
    std::optional<guide::Point> pillow;
    for (const auto& p : graph.points)
        if (p.kind == guide::PointKind::Approach && p.node == 10) pillow = p.at;
    REQUIRE(pillow);
    CHECK(space.open(*pillow));
    CHECK(std::hypot(pillow->x - 5.6, pillow->y - 2.5) < 1.2);  // the bed is 1.6 m wide: from its near side
    // No approach to the rug: it is the floor one walks on.
    for (const auto& p : graph.points) CHECK_FALSE((p.kind == guide::PointKind::Approach && p.node == 7));

    // Steps name what a walker sees at eye level: not the ceiling light, not the rug under foot.
    guide::Route route{{{0.5, 1}, {2.5, 2}, {4.5, 1.3}}, 4.4};
    for (const auto& step : guide::describeRoute(route, nodes, nodes[9], std::nullopt)) {
        CHECK(step.landmark != 11);
        CHECK(step.landmark != 7);
    }
}

TEST_CASE("two places the free floor joins are joined by a route, on real rooms", "[guide]") {
    // ScanNet's rooms (VSI-Bench's boxes): winding ways between chairs that the decision points,
    // 1 m apart, do not see through are walked on the free cells themselves.
    const std::string file = std::string(SMQL_SHARED_DATA) + "/real-layouts/scannet_meta_info_val.json";
    auto rooms = import::readVsiBenchAll(file);
    guide::GraphOptions options;
    std::size_t pairs = 0;
    for (std::size_t r = 0; r < rooms.size(); r += 4) {
        const auto& nodes = rooms[r].nodes;
        guide::FreeSpace space(nodes, options);
        auto graph = guide::buildGraph(nodes, space, options);
        std::vector<guide::Point> ends;
        for (const auto& p : graph.points)
            if (p.kind == guide::PointKind::Approach || p.kind == guide::PointKind::Door) ends.push_back(p.at);
        for (std::size_t i = 0; i < ends.size(); i += 3)
            for (std::size_t j = i + 1; j < ends.size(); j += 5) {
                if (!space.connected(ends[i], ends[j])) continue;
                ++pairs;
                auto route = guide::shortestRoute(graph, space, ends[i], ends[j], options);
                INFO(rooms[r].info.name << ": (" << ends[i].x << ", " << ends[i].y << ") to (" << ends[j].x << ", "
                                        << ends[j].y << ")");
                REQUIRE(route);
                for (std::size_t k = 1; k < route->waypoints.size(); ++k)
                    CHECK(space.clear(route->waypoints[k - 1], route->waypoints[k]));
            }
    }
    CHECK(pairs > 150);
}

TEST_CASE("a layout without walls is the hull of its things, not the rectangle around them", "[guide]") {
    // Two beds along a room turned 45 degrees: the rectangle's corners are outside the room.
    std::vector<model::Node> nodes;
    const double yaw = M_PI / 4;
    nodes.push_back(node(1, NodeKind::Object, "bed", {0, 0, 0.3}, {2, 1.6, 0.6}, yaw));
    nodes.push_back(node(2, NodeKind::Object, "bed", {3, 3, 0.3}, {2, 1.6, 0.6}, yaw));
    nodes.push_back(node(3, NodeKind::Object, "chair", {3, 0, 0.4}, {0.5, 0.5, 0.8}, yaw));
    nodes.push_back(node(4, NodeKind::Object, "chair", {0, 3, 0.4}, {0.5, 0.5, 0.8}, yaw));
    guide::FreeSpace space(nodes, guide::GraphOptions{});
    CHECK(space.free({1.5, 1.5}));          // between the beds
    CHECK_FALSE(space.free({-0.9, -0.9}));  // the rectangle's corner, outside the room
}

namespace {

// A box's world centre as Replica gives it: R * abb.center + translation, R from the quaternion (x, y, z, w).
model::Vec3 replicaCentre(const nlohmann::json& object) {
    const auto& box = object.at("oriented_bbox");
    const auto q = box.at("orientation").at("rotation").get<std::vector<double>>();
    const auto c = box.at("abb").at("center").get<std::vector<double>>();
    const auto t = box.at("orientation").at("translation").get<std::vector<double>>();
    // v + 2w (u x v) + 2 u x (u x v), u the quaternion's vector part.
    const double ux = q[0], uy = q[1], uz = q[2], w = q[3];
    const double cx = uy * c[2] - uz * c[1], cy = uz * c[0] - ux * c[2], cz = ux * c[1] - uy * c[0];
    const double dx = uy * cz - uz * cy, dy = uz * cx - ux * cz, dz = ux * cy - uy * cx;
    return {c[0] + 2 * w * cx + 2 * dx + t[0], c[1] + 2 * w * cy + 2 * dy + t[1], c[2] + 2 * w * cz + 2 * dz + t[2]};
}

// The real Replica room0 with three of its walls, the south one (which holds the door), the west and the
// north, as one wall instance, the way Replica boxes an L or a U of wall: one box around all three,
// 7.6 m x 4.6 m, the whole room. Wall 23, a 5 cm speck labelled wall, is left out: the sides of the room
// are then its walls.
std::string room0WithThreeFacedWall(const std::filesystem::path& dir) {
    std::ifstream in(replicaRoom0());
    auto j = nlohmann::json::parse(in);
    nlohmann::json kept = nlohmann::json::array();
    model::Vec3 lo{1e9, 1e9, 1e9}, hi{-1e9, -1e9, -1e9};
    for (const auto& o : j.at("objects")) {
        const auto id = o.at("id").get<int>();
        if (id == 23) continue;
        if (id != 33 && id != 48 && id != 57) {
            kept.push_back(o);
            continue;
        }
        // These walls are upright and turned by a right angle or none: their world extents are their
        // sizes, swapped when the box is turned.
        const model::Vec3 centre = replicaCentre(o);
        const auto sizes = o.at("oriented_bbox").at("abb").at("sizes").get<std::vector<double>>();
        const auto q = o.at("oriented_bbox").at("orientation").at("rotation").get<std::vector<double>>();
        const bool turned = std::abs(q[2]) > 0.5;  // about 90 degrees about z
        const double ex = turned ? sizes[1] : sizes[0], ey = turned ? sizes[0] : sizes[1];
        lo = {std::min(lo.x, centre.x - ex / 2), std::min(lo.y, centre.y - ey / 2),
              std::min(lo.z, centre.z - sizes[2] / 2)};
        hi = {std::max(hi.x, centre.x + ex / 2), std::max(hi.y, centre.y + ey / 2),
              std::max(hi.z, centre.z + sizes[2] / 2)};
    }
    kept.push_back({{"id", 33},
                    {"class_name", "wall"},
                    {"oriented_bbox",
                     {{"abb", {{"center", {0, 0, 0}}, {"sizes", {hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}}}},
                      {"orientation",
                       {{"rotation", {0, 0, 0, 1}},
                        {"translation", {(lo.x + hi.x) / 2, (lo.y + hi.y) / 2, (lo.z + hi.z) / 2}}}}}}});
    j["objects"] = kept;
    const auto path = dir / "info_semantic.json";
    std::ofstream(path) << j.dump();
    return path.string();
}

}  // namespace

TEST_CASE("a wall instance of three faces becomes its faces; the door routes to every thing on the floor",
          "[guide][walls]") {
    TempDir dir;
    const model::SceneData scene = import::readReplica(room0WithThreeFacedWall(dir.path), "room0-u");
    std::vector<const model::Node*> faces;
    for (const auto& n : scene.nodes)
        if (n.category == "wall" && (n.sourceId == 33 || n.text.find("of wall #33") != std::string::npos))
            faces.push_back(&n);
    // The south face (cut at the door: what is left west of it is too short), the west and the north;
    // the box's east side crosses no outline of the room and is discarded.
    REQUIRE(faces.size() == 3);
    for (const auto* f : faces) {
        INFO(f->text);
        CHECK(std::min(f->box.size.x, f->box.size.y) < 0.2);  // a face, not the 4.6 m box
        CHECK(std::max(f->box.size.x, f->box.size.y) > 4);
        CHECK_THAT(f->text, Catch::Matches("face [123] of 3 of wall #33"));
    }

    auto engine = Engine::open((dir.path / "db").string());
    engine->importScene(scene);
    // Acceptance: from the door to every thing that stands on the floor.
    guide::GraphOptions options;
    const guide::Footing footing(scene.nodes, options);
    std::size_t goals = 0;
    for (const auto& n : scene.nodes) {
        if (n.kind != NodeKind::Object || !footing.stands(n)) continue;
        ++goals;
        INFO(n.category << " #" << *n.sourceId);
        CHECK_NOTHROW(run(*engine, fmt::format("GUIDE FROM door TO src#{}", *n.sourceId)));
    }
    CHECK(goals >= 15);

    // near(wall.left) picks a face: seen from just inside the door, facing into the room along its long
    // walls (east), the north face.
    auto ids = [&](const std::string& statement) {
        std::set<std::int64_t> out;
        for (const auto& row : run(*engine, statement).rows) out.insert(std::get<std::int64_t>(row[0]));
        return out;
    };
    const std::int64_t north = *ids("FIND wall ORDER BY y DESC LIMIT 1").begin();
    const std::int64_t south = *ids("FIND wall WHERE source_id = 33").begin();
    const auto left = ids("FIND object WHERE near(wall.left)");
    CHECK_FALSE(left.empty());
    CHECK(left == ids(fmt::format("FIND object WHERE near(#{})", north)));
    CHECK(left != ids(fmt::format("FIND object WHERE near(#{})", south)));
}

TEST_CASE("a crowded room: chairs are pushed aside and tables squeezed past when the free floor has no way",
          "[guide]") {
    // A chair in the doorway of the two rooms: the walk goes through, and says which chair to move.
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    model::SceneData withChair = twoRooms(true);
    withChair.nodes.push_back(node(20, NodeKind::Object, "chair", {4.3, 1, 0.45}, {0.5, 0.5, 0.9}));
    engine->importScene(withChair);
    auto rs = run(*engine, "GUIDE FROM table TO lamp");
    CHECK_THAT(std::get<std::string>(rs.rows.front()[1]), Catch::Contains("push aside or squeeze past chair#"));
    CHECK_THAT(rs.message, Catch::Contains("crowded: past chair#"));
    // Where the free floor has a way, no chair is moved.
    CHECK_THAT(run(*engine, "GUIDE FROM door TO table").message, !Catch::Contains("crowded"));

    // ScanNet's scene0500_00, a classroom whose door a long bench of chairs closes off (41 goals
    // without a route before): every goal is reached from the door.
    const std::string file = std::string(SMQL_SHARED_DATA) + "/real-layouts/scannet_meta_info_val.json";
    for (auto& room : import::readVsiBenchAll(file)) {
        if (room.info.name != "scene0500_00") continue;
        TempDir roomDir;
        auto classroom = Engine::open(roomDir.path.string());
        const guide::Footing footing(room.nodes, guide::GraphOptions{});
        classroom->importScene(room);
        std::size_t goals = 0, crowded = 0;
        for (const auto& n : room.nodes) {
            if (n.kind != NodeKind::Object || !footing.stands(n)) continue;
            ++goals;
            INFO(n.category << " src#" << *n.sourceId);
            ResultSet walk;
            CHECK_NOTHROW(walk = run(*classroom, fmt::format("GUIDE FROM door TO src#{}", *n.sourceId)));
            crowded += walk.message.find("crowded") != std::string::npos;
        }
        CHECK(goals >= 40);
        CHECK(crowded > 0);
    }
}

TEST_CASE("a walk ends on the side of its goal it reaches first, on the Replica room", "[guide]") {
    // Replica room 0: the scene's viewpoint stands by the door, south-west of stool#58; the stool's decision point
    // is on its east side, toward the middle of the room. Ending there, the walk went round the other stool and
    // the coffee table, 5.5 m for a stool 1.3 m away; it ends on the stool's near side now.
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    engine->importScene(import::readReplica(replicaRoom0(), "replica-room0"));
    const auto toStool = run(*engine, "GUIDE FROM HERE TO (FIND stool ORDER BY distance(HERE) LIMIT 1)");
    REQUIRE(toStool.rows.size() >= 2);
    CHECK(std::get<std::string>(toStool.rows.back()[2]).rfind("stool#", 0) == 0);
    double walked = 0;
    for (const auto& row : toStool.rows) walked += std::get<double>(row[6]);
    CHECK(walked < 2.0);
    // The end stands beside the stool, a body's radius and a little more from its footprint.
    const auto& end = toStool.rows[toStool.rows.size() - 2];
    const auto stool = run(*engine, "FIND stool ORDER BY distance(HERE) LIMIT 1 RETURN x, y");
    CHECK(std::hypot(std::get<double>(end[4]) - std::get<double>(stool.rows[0][0]),
                     std::get<double>(end[5]) - std::get<double>(stool.rows[0][1])) < 1.0);
    // A door is walked to at its own decision point, not along the wall beside it (the door then behind you).
    const auto toDoor = run(*engine, "GUIDE FROM HERE TO door");
    CHECK(std::get<std::string>(toDoor.rows.back()[1]) == "The door is right here.");
}

TEST_CASE("a thing on furniture is approached from the open floor nearest it, on real rooms", "[guide]") {
    // ScanNet's rooms: a pillow at a bed's head between two nightstands, a monitor on a desk among
    // its chairs. The outline around the support beside the thing is taken by its neighbours; the
    // walk ends on the open floor nearest the thing instead, wherever that is.
    const std::string file = std::string(SMQL_SHARED_DATA) + "/real-layouts/scannet_meta_info_val.json";
    auto rooms = import::readVsiBenchAll(file);
    guide::GraphOptions options;
    std::size_t onFurniture = 0, within = 0;
    for (auto& room : rooms) {
        relations::assignParents(room);
        const auto& nodes = room.nodes;
        const guide::Footing footing(nodes, options);
        guide::FreeSpace space(nodes, options);
        auto graph = guide::buildGraph(nodes, space, options);
        for (const auto& p : graph.points) {
            if (p.kind != guide::PointKind::Approach) continue;
            const auto& goal = *std::find_if(nodes.begin(), nodes.end(), [&](const auto& n) { return n.id == p.node; });
            if (&footing.support(goal) == &goal) continue;
            ++onFurniture;
            const guide::Point at{goal.box.center.x, goal.box.center.y};
            INFO(room.info.name << ": " << goal.category << "#" << goal.id);
            if (auto nearest = space.nearestFree(at, 1.0); nearest && space.open(*nearest))
                CHECK(std::hypot(p.at.x - at.x, p.at.y - at.y) <=
                      std::hypot(nearest->x - at.x, nearest->y - at.y) + 1e-9);
            const double c = std::cos(goal.box.yaw), s = std::sin(goal.box.yaw), dx = p.at.x - at.x, dy = p.at.y - at.y;
            within += std::hypot(std::max(0.0, std::abs(c * dx + s * dy) - goal.box.size.x / 2),
                                 std::max(0.0, std::abs(-s * dx + c * dy) - goal.box.size.y / 2)) <= 1.0;
        }
    }
    std::cout << fmt::format("ScanNet: {} of {} things on furniture approached within 1 m of their footprint\n", within,
                             onFurniture);
    // 191 of 232 when this was written; 165 while the walk ended on the support's outline only.
    CHECK(onFurniture > 200);
    CHECK(within * 100 >= onFurniture * 80);
}

// Hidden from the unit_engine run: the ctest unit_guide_replica_room1 runs it where the layout is there
// (docs/guidance.md, "On real rooms").
TEST_CASE("a box turned from the walls over what stands beside it bounds a thing square to the walls",
          "[.][guide][walls][replica-room1]") {
    // Replica room_1 (sofaradkova/walkable-area at 181bf1d, data/info_semantic_room1.json): the bed's box is
    // 3.1 x 3.0 m, turned 55 degrees from the room's walls, over both nightstands; the two wall plugs behind
    // it were closed off by it and three pillows in its middle reached more than 1 m away.
    const char* given = std::getenv("SMQL_REPLICA_ROOM1");
    const std::string file = given ? given : std::string(SMQL_SHARED_DATA) + "/replica-room1/info_semantic.json";
    model::SceneData room = import::readReplica(file, "room1");
    relations::assignParents(room);
    guide::GraphOptions options;
    const guide::Footing footing(room.nodes, options);
    auto bySource = [&](std::int64_t source) -> const model::Node& {
        return *std::find_if(room.nodes.begin(), room.nodes.end(),
                             [&](const auto& n) { return n.sourceId && *n.sourceId == source; });
    };
    // The bed is the rectangle square to the walls whose bounds its box is: 2.4 x 1.9 m, its head
    // against wall 25 between the nightstands. The nightstands' smaller boxes are their own.
    const model::Node& bed = bySource(32);
    const model::Box& fitted = footing.footprint(bed);
    REQUIRE(&fitted != &bed.box);
    CHECK(std::max(fitted.size.x, fitted.size.y) == Approx(2.44).margin(0.05));
    CHECK(std::min(fitted.size.x, fitted.size.y) == Approx(1.95).margin(0.05));
    const double walls = std::atan2(std::sin(4 * bySource(25).box.yaw), std::cos(4 * bySource(25).box.yaw)) / 4;
    CHECK(std::abs(std::remainder(fitted.yaw - walls, M_PI / 2)) < 2 * M_PI / 180);
    CHECK(model::footprintArea(fitted) < 0.55 * model::footprintArea(bed.box));
    for (std::int64_t nightstand : {8, 28})
        CHECK(&footing.footprint(bySource(nightstand)) == &bySource(nightstand).box);

    // From the door to the plugs behind the bed, and to the pillows in its middle within 1 m.
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    engine->importScene(room);
    for (std::int64_t plug : {49, 16}) CHECK_NOTHROW(run(*engine, fmt::format("GUIDE FROM door TO src#{}", plug)));
    for (std::int64_t pillow : {39, 3, 13}) {
        auto rs = run(*engine, fmt::format("GUIDE FROM door TO src#{}", pillow));
        const int x = rs.columnIndex("x"), y = rs.columnIndex("y");
        const auto& end = rs.rows[rs.rows.size() - 2];
        const model::Box& box = bySource(pillow).box;
        INFO("pillow #" << pillow << ": " << rs.message);
        CHECK(model::horizontalGap(
                  box, {{std::get<double>(end[x]), std::get<double>(end[y]), box.center.z}, {0, 0, 0}, 0}) <= 1.0);
    }

    // A layout without walls (ScanNet's boxes) has no walls to be square to: every box is its own.
    const std::string scans = std::string(SMQL_SHARED_DATA) + "/real-layouts/scannet_meta_info_val.json";
    for (auto& scan : import::readVsiBenchAll(scans)) {
        const guide::Footing scanFooting(scan.nodes, options);
        for (const auto& n : scan.nodes) CHECK(&scanFooting.footprint(n) == &n.box);
    }
}

TEST_CASE("steps merge only where their one line stays on the free floor and name no landmark twice, on real rooms",
          "[guide]") {
    // ScanNet's rooms: a walk that ends against the blocked floor beside a bed or a desk, its last
    // short leg merged into the one before, cut the corner through the bed's or the desk's floor.
    // And no step names the landmark the step before it named, nor the thing the walk starts beside
    // (ScanNet's apartment, captured: "Start beside the sofa. Walk about 1 m toward the sofa.").
    const std::string file = std::string(SMQL_SHARED_DATA) + "/real-layouts/scannet_meta_info_val.json";
    auto rooms = import::readVsiBenchAll(file);
    guide::GraphOptions options;
    std::size_t steps = 0, cutting = 0;
    for (std::size_t r = 0; r < rooms.size(); r += 2) {
        relations::assignParents(rooms[r]);
        const auto& nodes = rooms[r].nodes;
        guide::FreeSpace space(nodes, options);
        auto graph = guide::buildGraph(nodes, space, options);
        std::vector<guide::DecisionPoint> ends;
        for (const auto& p : graph.points)
            if (p.kind == guide::PointKind::Approach) ends.push_back(p);
        for (std::size_t i = 0; i + 1 < ends.size(); i += 3) {
            const auto& goal =
                *std::find_if(nodes.begin(), nodes.end(), [&](const auto& n) { return n.id == ends[i + 1].node; });
            auto route = guide::shortestRoute(graph, space, ends[i].at, ends[i + 1].at, options);
            if (!route) continue;
            guide::Point from = route->waypoints.front();
            const model::NodeId start = ends[i].node;
            auto described = guide::describeRoute(*route, nodes, goal, std::nullopt, &space, start);
            model::NodeId named = model::kNoNode;
            for (std::size_t k = 0; k + 1 < described.size(); ++k) {
                ++steps;
                INFO(rooms[r].info.name << " to " << goal.category << "#" << goal.id << ", step " << k + 1);
                CHECK(space.clear(from, described[k].at));
                from = described[k].at;
                const model::NodeId landmark = described[k].landmark;
                CHECK((landmark == model::kNoNode || (landmark != named && landmark != start)));
                named = landmark;
            }
            // Without the free floor, the merged legs may cut it.
            guide::Point before = route->waypoints.front();
            const auto merged = guide::describeRoute(*route, nodes, goal, std::nullopt);
            for (std::size_t k = 0; k + 1 < merged.size(); ++k) {
                cutting += !space.clear(before, merged[k].at);
                before = merged[k].at;
            }
        }
    }
    std::cout << fmt::format("ScanNet: {} steps on the free floor; merged regardless of it, {} would cut it\n", steps,
                             cutting);
    CHECK(steps > 300);
    CHECK(cutting > 0);  // the rooms hold such corners: the test sees them
}
