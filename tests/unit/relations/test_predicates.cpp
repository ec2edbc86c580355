// Each predicate at its threshold boundaries: just inside holds, just outside does not.
#include <catch2/catch.hpp>

#include <cmath>

#include "engine/relations/hierarchy.hpp"
#include "engine/relations/predicates.hpp"

using namespace smql;
using namespace smql::relations;
using model::Node;

namespace {

Node node(model::NodeId id, std::string category, double x, double y, double z, double sx, double sy, double sz,
          model::NodeKind kind = model::NodeKind::Object, model::GeometryKind g = model::GeometryKind::Box) {
    Node n;
    n.id = id;
    n.kind = kind;
    n.category = std::move(category);
    n.geometry = g;
    n.box = {{x, y, z}, {sx, sy, sz}, 0};
    return n;
}

// A 1 x 1 table top 0.8 m high standing on the floor.
const Node kTable = node(1, "table", 0, 0, 0.4, 1, 1, 0.8);
const Thresholds kT;
const Frame kFrame = viewFrame({{0, -3, 1.6}, M_PI / 2});  // standing at y=-3 looking along +y

double eval(Predicate p, const Node& a, const Node& b) { return evaluate(p, a, b, kT, kFrame); }

}  // namespace

TEST_CASE("on: footprint overlap boundary") {
    // A 0.2 m cube resting on the table, slid so that a share s of its footprint stays over the table.
    auto mugAt = [](double x) { return node(2, "mug", x, 0, 0.9, 0.2, 0.2, 0.2); };
    CHECK(eval(Predicate::On, mugAt(0.0), kTable) > 0);
    // The table's edge is at x = 0.5; a share s of the mug is over it when x = 0.6 - 0.2 s.
    CHECK(eval(Predicate::On, mugAt(0.6 - 0.2 * 0.51), kTable) > 0);
    CHECK(eval(Predicate::On, mugAt(0.6 - 0.2 * 0.49), kTable) == 0);
}

TEST_CASE("on: gap and rise boundaries") {
    // bottom 0.09 m above the table top: within on.max_gap (0.1 m); 0.11 m: not.
    CHECK(eval(Predicate::On, node(2, "mug", 0, 0, 0.8 + 0.09 + 0.1, 0.2, 0.2, 0.2), kTable) > 0);
    CHECK(eval(Predicate::On, node(2, "mug", 0, 0, 0.8 + 0.11 + 0.1, 0.2, 0.2, 0.2), kTable) == 0);
    // A cushion sunk into a sofa: its centre must be at least half the sofa's height up.
    Node sofa = node(3, "sofa", 0, 0, 0.45, 2, 1, 0.9);
    CHECK(eval(Predicate::On, node(4, "cushion", 0, 0, 0.46, 0.4, 0.4, 0.3), sofa) > 0);
    CHECK(eval(Predicate::On, node(4, "cushion", 0, 0, 0.44, 0.4, 0.4, 0.3), sofa) == 0);
    // Support is not symmetric.
    CHECK(eval(Predicate::On, kTable, node(2, "mug", 0, 0, 0.9, 0.2, 0.2, 0.2)) == 0);
}

TEST_CASE("in: holders take what they support, enclosures what they contain, surfaces nothing") {
    Node stand = node(5, "plant-stand", 0, 0, 0.05, 0.3, 0.3, 0.1);
    Node plant = node(6, "indoor-plant", 0, 0, 0.4, 0.5, 0.5, 0.6);
    CHECK(eval(Predicate::In, plant, stand) > 0);
    CHECK(eval(Predicate::On, plant, stand) == 0);
    Node cabinet = node(7, "cabinet", 0, 0, 0.5, 1, 0.5, 1);
    Node inside = node(8, "box", 0, 0, 0.3, 0.3, 0.3, 0.3);
    CHECK(eval(Predicate::In, inside, cabinet) > 0);
    CHECK(eval(Predicate::On, inside, cabinet) == 0);
    Node onTop = node(9, "vase", 0, 0, 1.2, 0.2, 0.2, 0.4);
    CHECK(eval(Predicate::On, onTop, cabinet) > 0);
    CHECK(eval(Predicate::In, onTop, cabinet) == 0);
    // in.min_inside: 51% of the volume inside holds, 49% does not.
    CHECK(eval(Predicate::In, node(8, "box", 0, 0, 1.0 - 0.15 + 0.3 * 0.49, 0.3, 0.3, 0.3), cabinet) > 0);
    CHECK(eval(Predicate::In, node(8, "box", 0, 0, 1.0 - 0.15 + 0.3 * 0.51, 0.3, 0.3, 0.3), cabinet) == 0);
    Node chair = node(10, "chair", 0, 0, 0.5, 0.5, 0.5, 1);
    CHECK(eval(Predicate::In, node(11, "cushion", 0, 0, 0.55, 0.4, 0.4, 0.1), chair) == 0);
    CHECK(eval(Predicate::On, node(11, "cushion", 0, 0, 0.55, 0.4, 0.4, 0.1), chair) > 0);
}

TEST_CASE("near: distance threshold and explicit distance") {
    auto at = [](double gap) { return node(2, "chair", 0.5 + gap + 0.25, 0, 0.4, 0.5, 0.5, 0.8); };
    CHECK(eval(Predicate::Near, at(0.49), kTable) > 0);
    CHECK(eval(Predicate::Near, at(0.51), kTable) == 0);
    CHECK(evaluate(Predicate::Near, at(0.9), kTable, kT, kFrame, nullptr, 1.0) > 0);
    CHECK(evaluate(Predicate::Near, at(1.1), kTable, kT, kFrame, nullptr, 1.0) == 0);
}

TEST_CASE("above and below") {
    Node lamp = node(2, "lamp", 0, 0, 2.0, 0.4, 0.4, 0.2);
    CHECK(eval(Predicate::Above, lamp, kTable) > 0);
    CHECK(eval(Predicate::Below, kTable, lamp) > 0);
    CHECK(eval(Predicate::Above, kTable, lamp) == 0);
    // above.tolerance: a bottom 4 cm under the top still counts, 6 cm does not.
    CHECK(eval(Predicate::Above, node(2, "lamp", 0, 0, 0.8 - 0.04 + 0.1, 0.4, 0.4, 0.2), kTable) > 0);
    CHECK(eval(Predicate::Above, node(2, "lamp", 0, 0, 0.8 - 0.06 + 0.1, 0.4, 0.4, 0.2), kTable) == 0);
    // above.min_overlap: beside the table is not above it.
    CHECK(eval(Predicate::Above, node(2, "lamp", 1.5, 0, 2.0, 0.4, 0.4, 0.2), kTable) == 0);
}

TEST_CASE("attached: to upright planes within the gap") {
    Node wall = node(20, "wall", 0, 2, 1.3, 4, 0.1, 2.6, model::NodeKind::Anchor, model::GeometryKind::Plane);
    Node picture = node(21, "picture", 0, 2 - 0.05 - 0.02 - 0.04, 1.5, 1, 0.04, 0.6);
    CHECK(eval(Predicate::Attached, picture, wall) > 0);
    Node far = node(21, "picture", 0, 2 - 0.05 - 0.06 - 0.02, 1.5, 1, 0.04, 0.6);
    CHECK(eval(Predicate::Attached, far, wall) == 0);
    CHECK(eval(Predicate::Attached, picture, kTable) == 0);
    CHECK(isVerticalPlane(wall));
    CHECK_FALSE(isVerticalPlane(node(22, "floor", 0, 0, 0, 4, 4, 0.05, model::NodeKind::Anchor, model::GeometryKind::Plane)));
}

TEST_CASE("lateral predicates follow the viewpoint") {
    // The viewer looks along +y: -x is on the left.
    Node left = node(2, "chair", -1, 0, 0.4, 0.5, 0.5, 0.8);
    CHECK(eval(Predicate::LeftOf, left, kTable) > 0);
    CHECK(eval(Predicate::RightOf, kTable, left) > 0);
    CHECK(eval(Predicate::RightOf, left, kTable) == 0);
    // lateral.min_offset: 0.11 m holds, 0.09 m does not.
    CHECK(eval(Predicate::LeftOf, node(2, "chair", -0.11, 0, 0.4, 0.5, 0.5, 0.8), kTable) > 0);
    CHECK(eval(Predicate::LeftOf, node(2, "chair", -0.09, 0, 0.4, 0.5, 0.5, 0.8), kTable) == 0);
    Node nearer = node(2, "chair", 0, -1, 0.4, 0.5, 0.5, 0.8);
    CHECK(eval(Predicate::InFrontOf, nearer, kTable) > 0);
    CHECK(eval(Predicate::Behind, kTable, nearer) > 0);
    // Turned around (looking along -y), left and right swap.
    Frame back = viewFrame({{0, 3, 1.6}, -M_PI / 2});
    CHECK(evaluate(Predicate::RightOf, left, kTable, kT, back) > 0);
}

TEST_CASE("between: on the segment within the offset") {
    Node a = node(2, "sofa", -2, 0, 0.4, 0.5, 0.5, 0.8), c = node(3, "lamp", 2, 0, 0.4, 0.5, 0.5, 0.8);
    CHECK(evaluate(Predicate::Between, kTable, a, kT, kFrame, &c) > 0);
    CHECK(evaluate(Predicate::Between, node(4, "x", 0, 0.49, 0, 0.1, 0.1, 0.1), a, kT, kFrame, &c) > 0);
    CHECK(evaluate(Predicate::Between, node(4, "x", 0, 0.51, 0, 0.1, 0.1, 0.1), a, kT, kFrame, &c) == 0);
    CHECK(evaluate(Predicate::Between, node(4, "x", 3, 0, 0, 0.1, 0.1, 0.1), a, kT, kFrame, &c) == 0);
}

TEST_CASE("relate lists the most specific relation first") {
    Node mug = node(2, "mug", 0, 0, 0.9, 0.2, 0.2, 0.2);
    auto hits = relate(mug, kTable, kT, kFrame);
    REQUIRE(hits.size() >= 2);
    CHECK(hits.front().predicate == Predicate::On);
    CHECK(hits.back().predicate == Predicate::Near);
}

TEST_CASE("parents: support first, else the nearest upright anchor") {
    model::SceneData scene;
    auto add = [&](Node n) { scene.nodes.push_back(n); };
    add(node(1, "wall", 0, 2, 1.3, 4, 0.1, 2.6, model::NodeKind::Anchor, model::GeometryKind::Plane));
    add(node(2, "wall", 2, 0, 1.3, 0.1, 4, 2.6, model::NodeKind::Anchor, model::GeometryKind::Plane));
    add(node(3, "floor", 0, 0, 0, 4, 4, 0.02, model::NodeKind::Anchor, model::GeometryKind::Plane));
    add(node(4, "table", 0, 1.3, 0.4, 1, 1, 0.8));
    add(node(5, "plate", 0, 1.3, 0.81, 0.3, 0.3, 0.02));
    add(node(6, "mug", 0, 1.3, 0.87, 0.1, 0.1, 0.1));
    add(node(7, "chair", 1.5, -1, 0.4, 0.5, 0.5, 0.8));
    assignParents(scene);
    CHECK(scene.nodes[3].parent == 1);  // table -> the wall it stands by
    CHECK(scene.nodes[4].parent == 4);  // plate -> table
    CHECK(scene.nodes[5].parent == 5);  // mug -> plate (the highest supporter)
    CHECK(scene.nodes[6].parent == 2);  // chair -> nearest wall
    CHECK(scene.nodes[0].parent == model::kNoNode);  // anchors stay under the root
}
