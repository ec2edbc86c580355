// SMQL statements end to end over a small hand-built room whose answers are known.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>

#include "engine/format.hpp"
#include "engine_support.hpp"
#include "ingest/import/importers.hpp"

using namespace smql;
using namespace smql::testing;
using model::GeometryKind;
using model::NodeKind;

namespace {

// A 6 x 4 m room; the door is in the south wall (y = 0), the viewer stands inside it looking north (+y).
// The west wall (x = 0) is on the viewer's left. Source ids are the local ids.
model::SceneData handBuiltRoom(const std::string& name) {
    model::SceneData s;
    s.info.name = name;
    s.info.viewpoint = {{3, 0.5, 1.6}, M_PI / 2};
    auto add = [&](NodeKind kind, std::string category, GeometryKind g, model::Box box,
                   std::vector<model::Attribute> attributes = {}, bool hidden = false) {
        model::Node n;
        n.id = s.nodes.size() + 1;
        n.kind = kind;
        n.category = std::move(category);
        n.geometry = g;
        n.box = box;
        n.attributes = std::move(attributes);
        n.sourceId = static_cast<std::int64_t>(n.id);
        n.hidden = hidden;
        s.nodes.push_back(n);
    };
    add(NodeKind::Anchor, "floor", GeometryKind::Plane, {{3, 2, -0.01}, {6, 4, 0.02}, 0});           // 1
    add(NodeKind::Anchor, "wall", GeometryKind::Plane, {{3, -0.05, 1.3}, {6, 0.1, 2.6}, 0});         // 2 south
    add(NodeKind::Anchor, "wall", GeometryKind::Plane, {{3, 4.05, 1.3}, {6, 0.1, 2.6}, 0});          // 3 north
    add(NodeKind::Anchor, "wall", GeometryKind::Plane, {{-0.05, 2, 1.3}, {4, 0.1, 2.6}, M_PI / 2});  // 4 west
    add(NodeKind::Anchor, "wall", GeometryKind::Plane, {{6.05, 2, 1.3}, {4, 0.1, 2.6}, M_PI / 2});   // 5 east
    add(NodeKind::Anchor, "door", GeometryKind::Plane, {{3, -0.05, 1.0}, {0.9, 0.1, 2.0}, 0});       // 6
    add(NodeKind::Anchor, "window", GeometryKind::Plane, {{1.5, 4.05, 1.5}, {1.2, 0.1, 1.2}, 0});    // 7
    add(NodeKind::Object, "desk", GeometryKind::Box, {{0.5, 2, 0.375}, {0.6, 1.2, 0.75}, 0});        // 8 west wall
    add(NodeKind::Object, "mug", GeometryKind::Box, {{0.5, 1.8, 0.8}, {0.1, 0.1, 0.1}, 0}, {{"color", "red"}});  // 9
    add(NodeKind::Object, "book", GeometryKind::Box, {{0.5, 2.3, 0.77}, {0.2, 0.25, 0.04}, 0},
        {{"color", "blue"}});                                                                 // 10
    add(NodeKind::Object, "chair", GeometryKind::Box, {{1.1, 2, 0.45}, {0.5, 0.5, 0.9}, 0});  // 11
    add(NodeKind::Object, "sofa", GeometryKind::Box, {{5.4, 2, 0.45}, {0.9, 2.0, 0.9}, 0});   // 12 east wall
    add(NodeKind::Object, "cushion", GeometryKind::Box, {{5.4, 1.6, 0.7}, {0.4, 0.4, 0.3}, 0},
        {{"color", "red"}});                                                                   // 13
    add(NodeKind::Object, "plant", GeometryKind::Box, {{1.5, 3.6, 0.4}, {0.4, 0.4, 0.8}, 0});  // 14 by the window
    add(NodeKind::Object, "undefined", GeometryKind::Box, {{3, 2, 2.5}, {0.1, 0.1, 0.1}, 0}, {}, true);  // 15
    return s;
}

std::vector<std::int64_t> sources(const ResultSet& rs) {
    std::vector<std::int64_t> out;
    int col = rs.columnIndex("source_id");
    for (const auto& row : rs.rows) out.push_back(std::get<std::int64_t>(row[col]));
    return out;
}

struct Fixture {
    TempDir dir;
    std::unique_ptr<Engine> engine = Engine::open(dir.path.string());
    Fixture() { engine->importScene(handBuiltRoom("test")); }
    ResultSet q(const std::string& s) { return run(*engine, s); }
};

}  // namespace

TEST_CASE_METHOD(Fixture, "FIND with metric predicates, attributes and paths") {
    CHECK(sources(q("FIND mug WHERE on(desk)")) == std::vector<std::int64_t>{9});
    CHECK(sources(q("FIND object WHERE on(desk)")) == std::vector<std::int64_t>{9, 10});
    CHECK(sources(q("FIND object WHERE color = 'RED'")) == std::vector<std::int64_t>{9, 13});
    CHECK(sources(q("FIND object WHERE color = 'red' AND on(sofa)")) == std::vector<std::int64_t>{13});
    CHECK(sources(q("FIND object WHERE on(desk) AND NOT color = 'red'")) == std::vector<std::int64_t>{10});
    CHECK(sources(q("FIND object WHERE category LIKE 'cu%'")) == std::vector<std::int64_t>{13});
    CHECK(sources(q("FIND mugs")) == std::vector<std::int64_t>{9});  // plural of a known category
    auto rs = q("FIND mug WHERE on(desk) PATH");
    CHECK(std::get<std::string>(rs.rows[0][rs.columnIndex("path")]) == "test / wall#5 / desk#9 / mug#10");
}

TEST_CASE_METHOD(Fixture, "hidden parts stay out unless named") {
    auto all = sources(q("FIND object"));
    CHECK(std::find(all.begin(), all.end(), 15) == all.end());
    CHECK(sources(q("FIND undefined")) == std::vector<std::int64_t>{15});
    CHECK(std::get<std::int64_t>(q("COUNT object").rows[0][0]) == 7);
}

TEST_CASE_METHOD(Fixture, "ordering by distance and NEAREST TO") {
    auto rs = q("FIND object NEAREST TO door LIMIT 2");
    REQUIRE(rs.rows.size() == 2);
    CHECK(rs.columnIndex("distance") >= 0);
    auto d0 = std::get<double>(rs.rows[0][rs.columnIndex("distance")]);
    auto d1 = std::get<double>(rs.rows[1][rs.columnIndex("distance")]);
    CHECK(d0 <= d1);
    auto far = q("FIND object ORDER BY distance(window) DESC LIMIT 1");
    CHECK(sources(far) == std::vector<std::int64_t>{13});  // the cushion, across the room
    CHECK(sources(q("FIND object NEAREST TO plant LIMIT 1")).size() == 1);
    auto self = sources(q("FIND object NEAREST TO plant"));
    CHECK(std::find(self.begin(), self.end(), 14) == self.end());  // not itself
}

TEST_CASE_METHOD(Fixture, "sides of the room follow the viewpoint") {
    CHECK(sources(q("FIND object WHERE near(wall.left, 1 m)")) == std::vector<std::int64_t>{8, 9, 10, 11});
    CHECK(sources(q("FIND object WHERE near(wall.right)")) == std::vector<std::int64_t>{12, 13});
    CHECK(sources(q("FIND object WHERE near(wall.front, 0.6 m)")) == std::vector<std::int64_t>{14});
    // Looking from the window towards the door, left and right swap.
    CHECK(sources(q("FIND object VIEW FROM window FACING door WHERE near(wall.left)")) ==
          std::vector<std::int64_t>{12, 13});
    CHECK(sources(q("FIND object WHERE left_of(sofa) AND on(desk)")) == std::vector<std::int64_t>{9, 10});
}

TEST_CASE_METHOD(Fixture, "RELATE names the most specific relation with the distance") {
    auto rs = q("RELATE mug TO desk");
    REQUIRE_FALSE(rs.rows.empty());
    CHECK(std::get<std::string>(rs.rows[0][1]) == "on");
    CHECK(rs.message.find("mug#10 is on desk#9") == 0);
    CHECK(rs.message.find("near desk#9 (0.0 m)") != std::string::npos);
    auto lateral = q("RELATE desk TO sofa");
    bool left = false;
    for (const auto& row : lateral.rows) left |= std::get<std::string>(row[1]) == "left_of";
    CHECK(left);
}

TEST_CASE_METHOD(Fixture, "sub-queries, ids and source ids") {
    CHECK(sources(q("FIND object WHERE near((FIND mug WHERE color = 'red'), 0.5 m)")) ==
          std::vector<std::int64_t>{8, 10, 11});
    CHECK(sources(q("FIND object WHERE on(src#8)")) == std::vector<std::int64_t>{9, 10});
    CHECK(sources(q("FIND object WHERE on(#9)")) == std::vector<std::int64_t>{9, 10});
    CHECK(q("DESCRIBE src#9").rows.size() >= 6);
}

TEST_CASE_METHOD(Fixture, "EXPLAIN shows the R-tree push-down") {
    auto rs = q("EXPLAIN FIND object WHERE on(desk) AND color = 'red'");
    std::string plan;
    for (const auto& row : rs.rows) plan += std::get<std::string>(row[0]) + "\n";
    CHECK(plan.find("R-tree probe for on(desk (1 node))") != std::string::npos);
    CHECK(plan.find("Filter on(desk (1 node)) AND color = 'red'") != std::string::npos);
    auto scan = q("EXPLAIN FIND mug WHERE left_of(sofa)");
    CHECK(std::get<std::string>(scan.rows.back()[0]).find("view") != std::string::npos);
}

namespace {
std::string planText(const ResultSet& rs) {
    std::string plan;
    for (const auto& row : rs.rows) plan += std::get<std::string>(row[0]) + "\n";
    return plan;
}
}  // namespace

TEST_CASE_METHOD(Fixture, "EXPLAIN prints the plan that runs: top-k, sub-queries, all scenes") {
    auto nearest = planText(q("EXPLAIN FIND object NEAREST TO door LIMIT 5"));
    CHECK(nearest.find("Top 5 nearest to door (1 node), without itself: R-tree nearest-first search") !=
          std::string::npos);
    CHECK(nearest.find("Scan") == std::string::npos);
    // Several reference nodes: every candidate is measured and sorted.
    auto sorted = planText(q("EXPLAIN FIND object ORDER BY distance(wall) LIMIT 2"));
    CHECK(sorted.find("Sort by distance to wall (4 nodes)") != std::string::npos);
    CHECK(sorted.find("Scan object") != std::string::npos);
    auto sub = planText(q("EXPLAIN FIND object WHERE near((FIND mug WHERE color = 'red'))"));
    CHECK(sub.find("Sub-query 1, run once before its first use:") != std::string::npos);
    CHECK(sub.find("Filter color = 'red'") != std::string::npos);
    CHECK(planText(q("EXPLAIN RELATE mug TO desk")).find("Relate each node of mug (1 node)") != std::string::npos);
    CHECK(planText(q("EXPLAIN SET near = 3 m")).find("Set near.distance = 3") != std::string::npos);
    // EXPLAIN runs nothing: the setting is unchanged.
    for (const auto& row : q("SHOW SETTINGS").rows)
        if (std::get<std::string>(row[0]) == "near.distance") CHECK(std::get<double>(row[1]) == Approx(1.0));
    q("USE SCENE '*'");
    auto across = planText(q("EXPLAIN FIND mug LIMIT 3"));
    CHECK(across.find("Label index scan of 'mug' across all scenes") != std::string::npos);
    CHECK(planText(q("EXPLAIN COUNT mug")).find("Count 'mug' in every scene") != std::string::npos);
    CHECK_THROWS_WITH(q("FIND mug NEAREST TO door LIMIT 1"), Catch::Contains("across all scenes"));
}

TEST_CASE_METHOD(Fixture, "LIMIT 0 answers no rows") {
    CHECK(q("FIND object NEAREST TO door LIMIT 0").rows.empty());
    CHECK(q("FIND object WHERE on(desk) LIMIT 0").rows.empty());
    q("USE SCENE '*'");
    CHECK(q("FIND mug LIMIT 0").rows.empty());
}

TEST_CASE_METHOD(Fixture, "SET and SHOW SETTINGS change the thresholds") {
    q("SET near = 0.5 m");
    CHECK(sources(q("FIND object WHERE near(plant)")).empty());
    q("SET near = 2.5 m");
    CHECK_FALSE(sources(q("FIND object WHERE near(plant)")).empty());
    auto settings = q("SHOW SETTINGS");
    bool seen = false;
    for (const auto& row : settings.rows)
        if (std::get<std::string>(row[0]) == "near.distance") seen = std::get<double>(row[1]) == Approx(2.5);
    CHECK(seen);
    CHECK_THROWS_AS(q("SET on.min_overlap = 2"), Error);
    CHECK_THROWS_AS(q("SET on.min_overlap = 2 m"), Error);
    CHECK_THROWS_AS(q("SET nearr = 1 m"), Error);
}

TEST_CASE_METHOD(Fixture, "a script runs the statements before one that does not parse, then reports it") {
    // As sqlite3_exec: the SET before the misspelt statement has run, the one after it has not.
    std::vector<ResultSet> printed;
    try {
        engine->execute("SET near = 0.5 m; COUNT mug;\nFND lamp; SET near = 2.5 m",
                        [&](ResultSet&& result) { printed.push_back(std::move(result)); });
        FAIL("the misspelt statement was run");
    } catch (const Error& e) {
        CHECK(e.kind() == ErrorKind::Syntax);
        REQUIRE(e.where());
        CHECK(e.where()->line == 2);
        CHECK(e.where()->column == 1);
    }
    REQUIRE(printed.size() == 2);
    CHECK(std::get<std::int64_t>(printed[1].rows.at(0).at(0)) == 1);
    CHECK(sources(q("FIND object WHERE near(plant)")).empty());  // near is still 0.5 m
}

TEST_CASE_METHOD(Fixture, "binding errors carry a location and a hint") {
    try {
        q("FIND mug WHERE on(dsk)");
        FAIL("expected an error");
    } catch (const Error& e) {
        CHECK(e.kind() == ErrorKind::Binding);
        CHECK(e.message() == "unknown category 'dsk' in scene 'test'");
        CHECK(e.hint() == "did you mean desk?");
        REQUIRE(e.where());
        CHECK(e.where()->column == 19);
        CHECK(e.render("FIND mug WHERE on(dsk)").find("                  ^^^") != std::string::npos);
    }
    CHECK_THROWS_AS(q("FIND object WHERE on(#9999)"), Error);
    CHECK_THROWS_AS(q("FIND object WHERE on(src#9999)"), Error);
    CHECK_THROWS_AS(q("FIND object WHERE between(desk)"), Error);
    CHECK_THROWS_AS(q("FIND object WHERE on(desk, 1 m)"), Error);
    CHECK_THROWS_AS(q("FIND object WHERE onn(desk)"), Error);
    CHECK_THROWS_AS(q("USE SCENE 'nope'"), Error);
}

TEST_CASE_METHOD(Fixture, "several scenes: USE SCENE and the all-scenes category search") {
    engine->importScene(handBuiltRoom("second"));
    CHECK(engine->currentScene() == "second");
    q("USE SCENE 'test'");
    CHECK(engine->currentScene() == "test");
    auto scenes = q("SHOW SCENES");
    CHECK(scenes.rows.size() == 2);
    q("USE SCENE '*'");
    CHECK(std::get<std::int64_t>(q("COUNT mug").rows[0][0]) == 2);
    CHECK(q("FIND mug").rows.size() == 2);
    CHECK_THROWS_AS(q("FIND mug WHERE on(desk)"), Error);
    // A category another scene has is an empty answer, not an error.
    engine->importScene([] {
        auto s = handBuiltRoom("third");
        s.nodes.back().category = "piano", s.nodes.back().hidden = false;
        return s;
    }());
    q("USE SCENE 'test'");
    CHECK(q("FIND piano").rows.empty());
    CHECK_THROWS_AS(engine->importScene(handBuiltRoom("test")), Error);  // the name is taken
}

TEST_CASE_METHOD(Fixture, "a scene exported to JSON imports back with the same answers") {
    std::string json = import::writeSceneJson(engine->exportScene("test"));
    auto path = dir.path / "test.json";
    std::ofstream(path) << json;
    auto copy = import::readSceneJson(path.string());
    copy.info.name = "copy";
    engine->importScene(copy);
    q("USE SCENE 'copy'");
    CHECK(sources(q("FIND object WHERE on(desk)")) == std::vector<std::int64_t>{9, 10});
    CHECK(std::get<std::string>(q("FIND mug PATH").rows[0][4]).find("copy / wall#") == 0);
}

TEST_CASE_METHOD(Fixture, "result sets as JSON and CSV") {
    auto rs = q("FIND mug PATH");
    auto j = rowJson(rs, 0);
    CHECK(j["category"] == "mug");
    CHECK(j["box"]["size"][0].get<double>() == Approx(0.1));
    CHECK(j["path"].get<std::string>().find("mug#") != std::string::npos);
    CHECK(formatCsv(rs).rfind("id,category,source_id,box,path\n", 0) == 0);
}
