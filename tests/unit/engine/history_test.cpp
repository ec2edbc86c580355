// The memory over time. Engine::updateScene (`smql ingest --update`): a new capture of a place
// becomes the next version of its scene; what moved, appeared and went missing is recorded, and
// concurrent updates of one scene lose nothing. The language reads it back: SHOW CHANGES, AS OF,
// moved/added/seen SINCE; DROP SCENE and RENAME SCENE manage scenes with their history.
#include <catch2/catch.hpp>

#include <cmath>
#include <thread>

#include "engine_support.hpp"
#include "storage/database.hpp"

using namespace smql;
using namespace smql::testing;

namespace {

model::Node box(model::NodeId id, model::NodeKind kind, std::string category, model::Vec3 centre, model::Vec3 size) {
    model::Node n;
    n.id = id;
    n.kind = kind;
    n.category = std::move(category);
    n.geometry = kind == model::NodeKind::Anchor ? model::GeometryKind::Plane : model::GeometryKind::Box;
    n.box = {centre, size, 0};
    return n;
}

// A 6 m x 6 m floor with a chair at (2, 1) and a table at (3, 1).
model::SceneData room(std::string time) {
    model::SceneData data;
    data.info.name = "den";
    data.info.captureTime = std::move(time);
    data.nodes = {box(1, model::NodeKind::Anchor, "floor", {3, 3, 0}, {6, 6, 0.02}),
                  box(2, model::NodeKind::Object, "chair", {2, 1, 0.45}, {0.5, 0.5, 0.9}),
                  box(3, model::NodeKind::Object, "table", {4, 1, 0.4}, {1.2, 0.8, 0.8})};
    return data;
}

const model::Node& only(const model::SceneData& scene, const std::string& category) {
    const model::Node* found = nullptr;
    for (const auto& n : scene.nodes)
        if (n.category == category) {
            REQUIRE(found == nullptr);
            found = &n;
        }
    REQUIRE(found != nullptr);
    return *found;
}

std::string attributeOf(const model::Node& node, const std::string& name) {
    const std::string* value = node.attribute(name);
    return value ? *value : "(unset)";
}

}  // namespace

TEST_CASE("an update records what was seen again, moved, added and missing") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    engine->importScene(room("2026-11-20T10:00:00Z"));
    const model::SceneData before = engine->readScene("den");
    const model::NodeId tableBefore = only(before, "table").id;

    auto observed = room("2026-11-21T10:00:00Z");
    observed.nodes[1].box.center = {2.1, 1.05, 0.45};  // the chair, in place
    observed.nodes.pop_back();                         // the table is gone
    observed.nodes.push_back(box(4, model::NodeKind::Object, "lamp", {5, 5, 0.8}, {0.3, 0.3, 1.6}));  // new
    auto report = engine->updateScene("den", observed);

    CHECK(report.scene == "den");
    CHECK(report.time == "2026-11-21T10:00:00Z");
    CHECK(report.version == 1);
    CHECK(report.unchanged == 1);
    CHECK(report.moved == 0);
    CHECK(report.added == 1);
    CHECK(report.missing == 1);
    REQUIRE(report.changes.size() == 2);

    const model::SceneData after = engine->readScene("den");
    const model::Node& chair = only(after, "chair");
    CHECK(attributeOf(chair, "captures") == "2");
    CHECK(attributeOf(chair, "last_seen_at") == "2026-11-21T10:00:00Z");
    CHECK(chair.box.center.x == 2);  // seen again in place: the stored box stays
    const model::Node& lamp = only(after, "lamp");
    CHECK(attributeOf(lamp, "first_seen_at") == "2026-11-21T10:00:00Z");
    CHECK(attributeOf(lamp, "captures") == "1");
    for (const auto& n : after.nodes) CHECK(n.category != "table");
    CHECK(after.info.captureTime == "2026-11-21T10:00:00Z");

    for (const auto& change : report.changes) {
        if (change.kind == model::ChangeKind::Missing) {
            CHECK(change.category == "table");
            CHECK(change.before == tableBefore);
            CHECK(change.from.center.x == 4);
        } else {
            CHECK(change.kind == model::ChangeKind::Added);
            CHECK(change.after == lamp.id);
        }
    }
    auto history = engine->database().beginRead().history("den");
    REQUIRE(history.size() == 1);
    CHECK(history[0].changes == report.changes);
    CHECK(only(model::SceneData{history[0].info, history[0].nodes, {}, {}}, "table").box.center.x == 4);
}

TEST_CASE("an object of the same size and colour elsewhere has moved; outside the capture it is unseen") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    auto first = room("2026-11-20T10:00:00Z");
    first.nodes.push_back(box(4, model::NodeKind::Object, "mug", {9, 9, 0.05}, {0.1, 0.1, 0.1}));  // far corner
    first.nodes[0].box.size = {12, 12, 0.02};
    first.nodes[0].box.center = {6, 6, 0};
    engine->importScene(first);
    const model::NodeId chairBefore = only(engine->readScene("den"), "chair").id;

    auto observed = room("2026-11-21T10:00:00Z");  // a 6 m floor: the mug's corner was not looked at
    observed.nodes[1].box.center = {0.8, 4.5, 0.45};
    observed.nodes[1].box.yaw = 1.2;
    auto report = engine->updateScene("den", observed);
    CHECK(report.unchanged == 1);  // the table
    CHECK(report.moved == 1);
    CHECK(report.unseen == 1);
    CHECK(report.missing == 0);
    REQUIRE(report.changes.size() == 1);
    const auto& moved = report.changes[0];
    CHECK(moved.kind == model::ChangeKind::Moved);
    CHECK(moved.before == chairBefore);
    CHECK(moved.from.center.x == 2);
    CHECK(moved.to.center.y == 4.5);

    const model::SceneData after = engine->readScene("den");
    const model::Node& chair = only(after, "chair");
    CHECK(chair.id == moved.after);
    CHECK(chair.box.center.y == 4.5);
    CHECK(attributeOf(chair, "moved_at") == "2026-11-21T10:00:00Z");
    CHECK(attributeOf(only(after, "mug"), "last_seen_at") == "2026-11-20T10:00:00Z");  // kept, not seen
}

TEST_CASE("an update of a missing scene or from an earlier time is refused and changes nothing") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    engine->importScene(room("2026-11-20T10:00:00Z"));
    try {
        engine->updateScene("attic", room("2026-11-21T10:00:00Z"));
        FAIL("updating a missing scene did not throw");
    } catch (const Error& e) {
        CHECK(e.kind() == ErrorKind::Binding);
        CHECK_THAT(e.message(), Catch::Contains("no scene named 'attic'"));
    }
    try {
        engine->updateScene("den", room("2026-11-19T10:00:00Z"));
        FAIL("an update from the past did not throw");
    } catch (const Error& e) {
        CHECK(e.kind() == ErrorKind::Input);
        CHECK_THAT(e.message(), Catch::Contains("before the stored version"));
    }
    CHECK(engine->database().beginRead().history("den").empty());
}

TEST_CASE("two updates of one scene at once lose no capture") {
    TempDir dir;
    Engine::open(dir.path.string())->importScene(room("2026-03-03T00:00:00Z"));
    const auto observed = room("2026-03-03T00:00:00Z");

    constexpr int kRounds = 15;
    auto updater = [&] {
        // Each thread its own engine, as two `smql ingest --update` processes would have.
        auto engine = Engine::open(dir.path.string());
        for (int i = 0; i < kRounds; ++i) engine->updateScene("den", observed);
    };
    std::thread first(updater), second(updater);
    first.join();
    second.join();

    auto engine = Engine::open(dir.path.string());
    const model::SceneData after = engine->readScene("den");
    // The import was the first capture; each update adds one.
    CHECK(attributeOf(only(after, "chair"), "captures") == std::to_string(1 + 2 * kRounds));
    CHECK(attributeOf(only(after, "table"), "captures") == std::to_string(1 + 2 * kRounds));
    CHECK(engine->database().beginRead().history("den").size() == 2 * kRounds);
}

namespace {

// den at 2026-11-20 10:00, then an update a day later: the chair moved, the table went, a lamp came.
std::unique_ptr<Engine> denWithOneUpdate(const TempDir& dir) {
    auto engine = Engine::open(dir.path.string());
    engine->importScene(room("2026-11-20T10:00:00Z"));
    auto observed = room("2026-11-21T10:00:00Z");
    observed.nodes[1].box.center = {1, 4.5, 0.45};
    observed.nodes.pop_back();
    observed.nodes.push_back(box(4, model::NodeKind::Object, "lamp", {5, 5, 0.8}, {0.3, 0.3, 1.6}));
    engine->updateScene("den", observed);
    return engine;
}

std::vector<std::string> column(const ResultSet& rs, const std::string& name) {
    std::vector<std::string> out;
    int c = rs.columnIndex(name);
    REQUIRE(c >= 0);
    for (const auto& row : rs.rows) out.push_back(std::get<std::string>(row[c]));
    return out;
}

double centreX(const ResultSet& rs) {
    REQUIRE(rs.rows.size() == 1);
    return std::get<model::Box>(rs.rows[0][rs.columnIndex("box")]).center.x;
}

Error errorOf(Engine& engine, const std::string& statement) {
    try {
        engine.execute(statement);
    } catch (const Error& e) {
        return e;
    }
    FAIL("no error from " << statement);
    return Error(ErrorKind::Usage, "unreachable");
}

}  // namespace

TEST_CASE("SHOW CHANGES lists each update's changes, SINCE narrows them") {
    TempDir dir;
    auto engine = denWithOneUpdate(dir);
    auto changes = run(*engine, "SHOW CHANGES");
    CHECK(column(changes, "change") == std::vector<std::string>{"missing", "moved", "added"});
    CHECK(column(changes, "category") == std::vector<std::string>{"table", "chair", "lamp"});
    CHECK(column(changes, "time") == std::vector<std::string>(3, "2026-11-21T10:00:00Z"));
    CHECK(std::get<double>(changes.rows[1][changes.columnIndex("moved")]) == Catch::Detail::Approx(std::hypot(1, 3.5)));
    CHECK(std::holds_alternative<std::monostate>(changes.rows[0][changes.columnIndex("to")]));
    CHECK(run(*engine, "SHOW CHANGES SINCE '2026-11-21'").rows.size() == 3);
    auto none = run(*engine, "SHOW CHANGES SINCE '2026-11-22'");
    CHECK(none.rows.empty());
    CHECK_THAT(none.message, Catch::Contains("no update since 2026-11-22T00:00:00Z"));
}

TEST_CASE("AS OF reads the scene as it was; moved, added and seen SINCE read the update times") {
    TempDir dir;
    auto engine = denWithOneUpdate(dir);
    CHECK(centreX(run(*engine, "FIND chair")) == 1);
    CHECK(centreX(run(*engine, "FIND chair AS OF '2026-11-20T12:00:00Z'")) == 2);
    CHECK(centreX(run(*engine, "FIND chair AS OF '2026-11-21T11:00'")) == 1);
    CHECK(std::get<std::int64_t>(run(*engine, "COUNT table AS OF '2026-11-20 12:00'").rows[0][0]) == 1);
    CHECK(run(*engine, "FIND object AS OF '2026-11-20T12:00:00Z' WHERE near(table, 3 m)").rows.size() == 1);
    auto before = errorOf(*engine, "FIND chair AS OF '2026-11-19'");
    CHECK_THAT(before.message(), Catch::Contains("first captured at 2026-11-20T10:00:00Z"));

    auto moved = run(*engine, "FIND object WHERE moved SINCE '2026-11-21'");
    REQUIRE(moved.rows.size() == 1);
    CHECK(std::get<std::string>(moved.rows[0][moved.columnIndex("category")]) == "chair");
    auto added = run(*engine, "FIND object WHERE added SINCE '2026-11-21'");
    REQUIRE(added.rows.size() == 1);
    CHECK(std::get<std::string>(added.rows[0][added.columnIndex("category")]) == "lamp");
    CHECK(run(*engine, "FIND object WHERE seen SINCE '2026-11-21'").rows.size() == 2);
    CHECK(run(*engine, "FIND object WHERE moved SINCE '2026-11-22'").rows.empty());

    auto bad = errorOf(*engine, "FIND chair AS OF 'last week'");
    CHECK_THAT(bad.message(), Catch::Contains("'last week' is not a time"));
    auto word = errorOf(*engine, "FIND object WHERE painted SINCE '2026-11-21'");
    CHECK_THAT(word.message(), Catch::Contains("'painted' cannot be followed by SINCE"));
    auto sub = errorOf(*engine, "FIND object WHERE near((FIND chair AS OF '2026-11-20T12:00'))");
    CHECK_THAT(sub.message(), Catch::Contains("AS OF belongs to the whole statement"));
}

TEST_CASE("RENAME SCENE and DROP SCENE carry and remove the history, one transaction each") {
    TempDir dir;
    auto engine = denWithOneUpdate(dir);
    auto renamed = run(*engine, "RENAME SCENE den TO study");
    CHECK(renamed.message == "renamed scene 'den' to 'study'");
    CHECK(engine->currentScene() == "study");
    CHECK(run(*engine, "SHOW CHANGES").rows.size() == 3);  // the history moved with the name
    CHECK(run(*engine, "SHOW TREE").rows[0][2] == Value(std::string("study")));
    CHECK_THAT(errorOf(*engine, "USE SCENE den").message(), Catch::Contains("no scene named 'den'"));
    CHECK_THAT(errorOf(*engine, "RENAME SCENE nowhere TO x").message(), Catch::Contains("no scene named 'nowhere'"));

    engine->importScene(room("2026-11-22T10:00:00Z"));  // a second scene named den
    CHECK_THAT(errorOf(*engine, "RENAME SCENE den TO study").message(), Catch::Contains("already exists"));

    run(*engine, "EXPLAIN DROP SCENE study");  // explains, drops nothing
    CHECK(run(*engine, "SHOW SCENES").rows.size() == 2);
    auto dropped = run(*engine, "DROP SCENE study");
    CHECK_THAT(dropped.message, Catch::Contains("dropped scene 'study'"));
    auto scenes = run(*engine, "SHOW SCENES");
    REQUIRE(scenes.rows.size() == 1);
    CHECK(scenes.rows[0][0] == Value(std::string("den")));
    CHECK(engine->database().beginRead().history("study").empty());
    CHECK(run(*engine, "USE SCENE den; SHOW CHANGES").rows.empty());

    auto readOnly = Engine::open(dir.path.string(), /*readOnly=*/true);
    CHECK(errorOf(*readOnly, "DROP SCENE den").kind() == ErrorKind::Storage);
    CHECK(run(*readOnly, "SHOW SCENES").rows.size() == 1);
}

TEST_CASE("an update that finds none of the stored objects again warns that it may be of another place") {
    TempDir dir;
    auto engine = Engine::open(dir.path.string());
    auto stored = room("2026-11-20T10:00:00Z");
    stored.nodes.push_back(box(4, model::NodeKind::Object, "lamp", {5, 5, 0.8}, {0.3, 0.3, 1.6}));
    engine->importScene(stored);

    // The same room a day later, one chair moved a little: no warning.
    auto sameRoom = stored;
    sameRoom.info.captureTime = "2026-11-21T10:00:00Z";
    sameRoom.nodes[1].box.center = {2.1, 1.05, 0.45};
    CHECK(!engine->updateScene("den", sameRoom).warning());

    // Another room: a sofa, a desk and a bed, where none of the stored things is.
    auto elsewhere = room("2026-11-22T10:00:00Z");
    elsewhere.nodes.resize(1);
    elsewhere.nodes.push_back(box(2, model::NodeKind::Object, "sofa", {1, 5, 0.4}, {2, 0.9, 0.8}));
    elsewhere.nodes.push_back(box(3, model::NodeKind::Object, "desk", {5, 3, 0.375}, {1.4, 0.7, 0.75}));
    elsewhere.nodes.push_back(box(4, model::NodeKind::Object, "bed", {2, 3, 0.3}, {2, 1.6, 0.6}));
    const auto report = engine->updateScene("den", elsewhere);
    CHECK(report.unchanged == 0);
    CHECK(report.added == 3);
    REQUIRE(report.warning());
    CHECK_THAT(*report.warning(), Catch::StartsWith("none of the 3 stored objects was seen again where it was, and 3 "
                                                    "of the 3 captured are new: a capture of another place"));
}
