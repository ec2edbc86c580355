#include "bench/sqlite_baseline.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string_view>
#include <unordered_map>
#include <unordered_set>

#include <fmt/format.h>
#include <sqlite3.h>

#include "model/geometry.hpp"

namespace smql::bench {

using model::Node;
using relations::Predicate;

namespace {

// The schema mirrors what smql stores: scenes, nodes with their boxes and
// tree parent, attributes, and the indexes smql keeps (category per scene and
// across scenes, children by parent, boxes, counts per category). The two
// category indexes cover the columns their queries read, so neither visits
// the table; (category, id) also hands LIMIT its rows in id order.
// `category_counts` is kept by triggers, so COUNT reads one row.
// The R*Tree's first dimension is the scene, so a probe in one room does not
// return the same spot of every other room (all generated rooms share the
// origin); each box spans its scene id +-0.5 on it, because a dimension where
// every entry has zero extent gives every entry zero volume and blinds the
// R*Tree's split heuristics (probes were 1.6x slower). The R*Tree holds only
// the bounds: with the node columns as auxiliary columns (`+kind, ...`, SQLite
// 3.24+) a probe needs no join, but measured 2-4.6x slower on the FIND and
// NEAREST classes (SQLite 3.40.1, 20 x 2,000 objects), so the probe joins
// `nodes` by primary key. R*Tree coordinates are 32-bit floats rounded outwards, so its
// answers are a superset that the exact check then filters; scene ids stay
// exact below 2^23.
constexpr const char* kSchema = R"sql(
CREATE TABLE scenes(id INTEGER PRIMARY KEY, name TEXT NOT NULL UNIQUE, source TEXT,
                    vx REAL, vy REAL, vz REAL, vyaw REAL);
CREATE TABLE nodes(id INTEGER PRIMARY KEY, scene INTEGER NOT NULL, parent INTEGER, kind INTEGER NOT NULL,
                   category TEXT NOT NULL, geometry INTEGER NOT NULL,
                   cx REAL, cy REAL, cz REAL, sx REAL, sy REAL, sz REAL, yaw REAL,
                   hidden INTEGER NOT NULL, confidence REAL, source_id INTEGER, text TEXT);
CREATE TABLE attributes(node INTEGER NOT NULL, name TEXT NOT NULL, value TEXT NOT NULL,
                        PRIMARY KEY(node, name)) WITHOUT ROWID;
CREATE INDEX nodes_by_scene_category ON nodes(scene, category, kind, geometry, cx, cy, cz, sx, sy, sz, yaw, hidden);
CREATE INDEX nodes_by_category ON nodes(category, id, scene, source_id, cx, cy, cz, sx, sy, sz, yaw);
CREATE INDEX nodes_by_parent ON nodes(parent);
CREATE TABLE category_counts(category TEXT PRIMARY KEY, count INTEGER NOT NULL) WITHOUT ROWID;
CREATE TRIGGER nodes_counted AFTER INSERT ON nodes BEGIN
  INSERT INTO category_counts(category, count) VALUES (new.category, 1)
    ON CONFLICT(category) DO UPDATE SET count = count + 1;
END;
CREATE TRIGGER nodes_uncounted AFTER DELETE ON nodes BEGIN
  UPDATE category_counts SET count = count - 1 WHERE category = old.category;
END;
CREATE TRIGGER nodes_recounted AFTER UPDATE OF category ON nodes BEGIN
  UPDATE category_counts SET count = count - 1 WHERE category = old.category;
  INSERT INTO category_counts(category, count) VALUES (new.category, 1)
    ON CONFLICT(category) DO UPDATE SET count = count + 1;
END;
CREATE VIRTUAL TABLE node_boxes USING rtree(id, min_s, max_s, min_x, max_x, min_y, max_y, min_z, max_z);
)sql";

constexpr double kLargestSceneId = 8388608.0;  // 2^23: larger ids +-0.5 would not be exact in the R*Tree's floats

// The columns a predicate needs, in the order readNode() expects them (in nodes and in node_boxes).
constexpr const char* kNodeColumns = "id, kind, category, geometry, cx, cy, cz, sx, sy, sz, yaw, hidden";
constexpr const char* kJoinedColumns =
    "id, n.kind, n.category, n.geometry, n.cx, n.cy, n.cz, n.sx, n.sy, n.sz, n.yaw, n.hidden";

// NEAREST TO grows its search radius from this until it holds enough answers;
// beyond the largest radius every object of the scene has been seen.
constexpr double kFirstRadius = 1.0;
constexpr double kLargestRadius = 1e4;

[[noreturn]] void fail(sqlite3* db, std::string_view what) {
    throw std::runtime_error(fmt::format("sqlite: {}: {}", what, sqlite3_errmsg(db)));
}

}  // namespace

// A prepared statement, named outside the file's anonymous namespace: SqliteBaseline::Impl, declared in
// the header, holds some, and a field of an anonymous namespace's type would give it internal linkage
// in part (GCC's -Wsubobject-linkage).
namespace sqlite {

class Statement {
public:
    Statement(sqlite3* db, std::string_view sql) : db_(db) {
        if (sqlite3_prepare_v3(db, sql.data(), static_cast<int>(sql.size()), SQLITE_PREPARE_PERSISTENT, &stmt_,
                               nullptr) != SQLITE_OK)
            fail(db, fmt::format("preparing `{}`", sql));
    }
    ~Statement() { sqlite3_finalize(stmt_); }
    Statement(const Statement&) = delete;
    Statement& operator=(const Statement&) = delete;

    Statement& bind(int index, double value) {
        check(sqlite3_bind_double(stmt_, index, value));
        return *this;
    }
    Statement& bind(int index, std::int64_t value) {
        check(sqlite3_bind_int64(stmt_, index, value));
        return *this;
    }
    Statement& bind(int index, std::string_view value) {
        check(sqlite3_bind_text(stmt_, index, value.data(), static_cast<int>(value.size()), SQLITE_STATIC));
        return *this;
    }
    Statement& bindNull(int index) {
        check(sqlite3_bind_null(stmt_, index));
        return *this;
    }

    // True while there is a row; resets the statement when it is done, so it is ready for the next binds.
    bool step() {
        int rc = sqlite3_step(stmt_);
        if (rc == SQLITE_ROW) return true;
        sqlite3_reset(stmt_);
        if (rc != SQLITE_DONE) fail(db_, "stepping a statement");
        return false;
    }
    // Runs a statement that returns no rows.
    void run() {
        while (step()) {
        }
    }
    // Drops the rest of the rows (LIMIT-style early exits).
    void reset() { sqlite3_reset(stmt_); }

    std::int64_t integer(int column) const { return sqlite3_column_int64(stmt_, column); }
    double real(int column) const { return sqlite3_column_double(stmt_, column); }
    std::string_view text(int column) const {
        const auto* p = reinterpret_cast<const char*>(sqlite3_column_text(stmt_, column));
        return p ? std::string_view(p, static_cast<std::size_t>(sqlite3_column_bytes(stmt_, column)))
                 : std::string_view();
    }

private:
    void check(int rc) {
        if (rc != SQLITE_OK) fail(db_, "binding a parameter");
    }
    sqlite3* db_;
    sqlite3_stmt* stmt_ = nullptr;
};

}  // namespace sqlite

using sqlite::Statement;

namespace {

void exec(sqlite3* db, const char* sql) {
    char* message = nullptr;
    if (sqlite3_exec(db, sql, nullptr, nullptr, &message) != SQLITE_OK) {
        std::string text = message ? message : "unknown error";
        sqlite3_free(message);
        throw std::runtime_error(fmt::format("sqlite: {}: {}", sql, text));
    }
}

// Reads the kNodeColumns of a row into `node`, reusing its category's capacity.
void readNode(const Statement& s, int first, Node& node) {
    node.id = static_cast<model::NodeId>(s.integer(first));
    node.kind = static_cast<model::NodeKind>(s.integer(first + 1));
    node.category.assign(s.text(first + 2));
    node.geometry = static_cast<model::GeometryKind>(s.integer(first + 3));
    node.box = {{s.real(first + 4), s.real(first + 5), s.real(first + 6)},
                {s.real(first + 7), s.real(first + 8), s.real(first + 9)},
                s.real(first + 10)};
    node.hidden = s.integer(first + 11) != 0;
}

}  // namespace

struct SqliteBaseline::Impl {
    struct Close {
        void operator()(sqlite3* db) const { sqlite3_close(db); }
    };
    std::unique_ptr<sqlite3, Close> db;  // first member: closed after every statement is finalized
    relations::Thresholds thresholds;
    std::int64_t sceneId = 0;
    relations::Frame frame;

    std::unique_ptr<Statement> insertScene, insertNode, insertBox, insertAttribute;
    std::unique_ptr<Statement> sceneByName, nodesOfCategory, twoNodesInScene, objectsInRegion, categoryAll, countAll;

    explicit Impl(const std::string& file) {
        sqlite3* handle = nullptr;
        int rc = sqlite3_open_v2(file.c_str(), &handle, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr);
        db.reset(handle);
        if (rc != SQLITE_OK)
            throw std::runtime_error(
                fmt::format("sqlite: cannot open {}: {}", file, handle ? sqlite3_errmsg(handle) : "out of memory"));
    }

    void prepare() {
        insertScene = std::make_unique<Statement>(
            db.get(), "INSERT INTO scenes(id, name, source, vx, vy, vz, vyaw) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7)");
        insertNode = std::make_unique<Statement>(
            db.get(),
            "INSERT INTO nodes(id, scene, parent, kind, category, geometry, cx, cy, cz, sx, sy, sz, yaw, hidden, "
            "confidence, source_id, text) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14, ?15, "
            "?16, ?17)");
        insertBox = std::make_unique<Statement>(
            db.get(), "INSERT INTO node_boxes VALUES (?1, ?2 - 0.5, ?2 + 0.5, ?3, ?4, ?5, ?6, ?7, ?8)");
        insertAttribute =
            std::make_unique<Statement>(db.get(), "INSERT INTO attributes(node, name, value) VALUES (?1, ?2, ?3)");
        sceneByName = std::make_unique<Statement>(db.get(), "SELECT id, vx, vy, vz, vyaw FROM scenes WHERE name = ?1");
        nodesOfCategory = std::make_unique<Statement>(
            db.get(), fmt::format("SELECT {} FROM nodes WHERE scene = ?1 AND category = ?2", kNodeColumns));
        twoNodesInScene = std::make_unique<Statement>(
            db.get(), fmt::format("SELECT {} FROM nodes WHERE id IN (?1, ?2) AND scene = ?3", kNodeColumns));
        objectsInRegion = std::make_unique<Statement>(
            db.get(), fmt::format("SELECT n.{} FROM node_boxes AS r JOIN nodes AS n ON n.id = r.id "
                                  "WHERE r.min_s <= ?1 AND r.max_s >= ?1 AND r.max_x >= ?2 AND r.min_x <= ?3 "
                                  "AND r.max_y >= ?4 AND r.min_y <= ?5 AND r.max_z >= ?6 AND r.min_z <= ?7 "
                                  "AND n.kind = {} AND n.hidden = 0",
                                  kJoinedColumns, static_cast<int>(model::NodeKind::Object)));
        categoryAll =
            std::make_unique<Statement>(db.get(),
                                        "SELECT id, category, scene, source_id, cx, cy, cz, sx, sy, sz, yaw FROM nodes "
                                        "WHERE category = ?1 ORDER BY id LIMIT ?2");
        countAll = std::make_unique<Statement>(db.get(), "SELECT count FROM category_counts WHERE category = ?1");
    }

    std::vector<Node> nodesOf(const std::string& category) {
        std::vector<Node> out;
        nodesOfCategory->bind(1, sceneId).bind(2, category);
        while (nodesOfCategory->step()) readNode(*nodesOfCategory, 0, out.emplace_back());
        return out;
    }

    // Calls visit(node) for each visible object of the current scene whose bounds meet `region`.
    template <class Visit>
    void forEachObjectIn(const model::Aabb& region, Node& scratch, Visit&& visit) {
        auto& s = *objectsInRegion;
        s.bind(1, sceneId)
            .bind(2, region.min.x)
            .bind(3, region.max.x)
            .bind(4, region.min.y)
            .bind(5, region.max.y)
            .bind(6, region.min.z)
            .bind(7, region.max.z);
        while (s.step()) {
            readNode(s, 0, scratch);
            visit(scratch);
        }
    }
};

SqliteBaseline::SqliteBaseline(const std::string& path, bool create) : impl_(std::make_unique<Impl>(path)) {
    // LMDB syncs every commit, so SQLite does too (WAL with synchronous=FULL);
    // reads go through the memory map and a 64 MiB page cache, as a tuned application would set them.
    exec(impl_->db.get(),
         "PRAGMA journal_mode = WAL; PRAGMA synchronous = FULL; PRAGMA mmap_size = 1099511627776; "
         "PRAGMA cache_size = -65536");
    if (create) exec(impl_->db.get(), kSchema);
    impl_->prepare();
}

SqliteBaseline::~SqliteBaseline() = default;

void SqliteBaseline::importScene(const model::SceneInfo& info, const std::vector<Node>& nodes) {
    auto& m = *impl_;
    if (static_cast<double>(info.id) >= kLargestSceneId)
        throw std::runtime_error(fmt::format("scene id {} is too large for the R*Tree's float coordinates", info.id));
    exec(m.db.get(), "BEGIN");
    m.insertScene->bind(1, static_cast<std::int64_t>(info.id))
        .bind(2, info.name)
        .bind(3, info.source)
        .bind(4, info.viewpoint.position.x)
        .bind(5, info.viewpoint.position.y)
        .bind(6, info.viewpoint.position.z)
        .bind(7, info.viewpoint.facingYaw)
        .run();
    for (const Node& n : nodes) {
        if (n.kind == model::NodeKind::Scene) continue;
        auto id = static_cast<std::int64_t>(n.id);
        auto& s = *m.insertNode;
        s.bind(1, id).bind(2, static_cast<std::int64_t>(n.scene));
        if (n.parent == model::kNoNode)
            s.bindNull(3);
        else
            s.bind(3, static_cast<std::int64_t>(n.parent));
        s.bind(4, static_cast<std::int64_t>(n.kind))
            .bind(5, n.category)
            .bind(6, static_cast<std::int64_t>(n.geometry))
            .bind(7, n.box.center.x)
            .bind(8, n.box.center.y)
            .bind(9, n.box.center.z)
            .bind(10, n.box.size.x)
            .bind(11, n.box.size.y)
            .bind(12, n.box.size.z)
            .bind(13, n.box.yaw)
            .bind(14, static_cast<std::int64_t>(n.hidden))
            .bind(15, static_cast<double>(n.confidence));
        if (n.sourceId)
            s.bind(16, *n.sourceId);
        else
            s.bindNull(16);
        s.bind(17, n.text).run();
        if (n.geometry != model::GeometryKind::None) {
            model::Aabb b = model::worldAabb(n.box);
            m.insertBox->bind(1, id)
                .bind(2, static_cast<double>(n.scene))
                .bind(3, b.min.x)
                .bind(4, b.max.x)
                .bind(5, b.min.y)
                .bind(6, b.max.y)
                .bind(7, b.min.z)
                .bind(8, b.max.z)
                .run();
        }
        for (const auto& a : n.attributes) m.insertAttribute->bind(1, id).bind(2, a.name).bind(3, a.value).run();
    }
    exec(m.db.get(), "COMMIT");
}

void SqliteBaseline::checkpoint() { exec(impl_->db.get(), "PRAGMA wal_checkpoint(TRUNCATE)"); }

void SqliteBaseline::useScene(const std::string& scene) {
    auto& s = *impl_->sceneByName;
    s.bind(1, scene);
    if (!s.step()) throw std::runtime_error(fmt::format("sqlite: no scene named '{}'", scene));
    impl_->sceneId = s.integer(0);
    model::Viewpoint vp{{s.real(1), s.real(2), s.real(3)}, s.real(4)};
    s.reset();
    impl_->frame = relations::viewFrame(vp);
}

Answer SqliteBaseline::findObjects(const PredicateTerm& first, const PredicateTerm& second) {
    auto& m = *impl_;
    const TwoTermFind find(first, m.nodesOf(first.category), second, m.nodesOf(second.category), m.thresholds, m.frame);
    std::unordered_set<std::int64_t> seen;
    Answer ids;
    Node candidate;
    for (const Node& ref : find.probeReferences()) {
        if (ref.geometry == model::GeometryKind::None) continue;
        m.forEachObjectIn(probeRegion(find.probeTerm(), ref, m.thresholds), candidate, [&](const Node& a) {
            auto id = static_cast<std::int64_t>(a.id);
            if (seen.contains(id) || !find.meetsProbe(a, ref)) return;
            seen.insert(id);
            if (find.meetsCheck(a)) ids.push_back(id);
        });
    }
    std::sort(ids.begin(), ids.end());
    return ids;
}

Answer SqliteBaseline::relate(model::NodeId a, model::NodeId b) {
    auto& m = *impl_;
    auto& s = *m.twoNodesInScene;
    s.bind(1, static_cast<std::int64_t>(a)).bind(2, static_cast<std::int64_t>(b)).bind(3, m.sceneId);
    std::vector<Node> rows;
    while (s.step()) readNode(s, 0, rows.emplace_back());
    std::vector<Node> around;
    Node scratch;
    m.forEachObjectIn(aroundPair(rows, m.thresholds), scratch, [&](const Node& n) { around.push_back(n); });
    return relateRows("sqlite", a, b, rows, around, m.thresholds, m.frame);
}

Answer SqliteBaseline::nearestObjects(const std::string& category, int limit) {
    auto& m = *impl_;
    std::vector<Node> refs = m.nodesOf(category);
    std::unordered_set<model::NodeId> refIds;
    for (const Node& r : refs) refIds.insert(r.id);
    // Distances found so far, by id: each candidate's exact distance is computed once.
    std::unordered_map<model::NodeId, double> distances;
    Node candidate;
    for (double radius = kFirstRadius;; radius *= 4) {
        for (const Node& ref : refs) {
            if (ref.geometry == model::GeometryKind::None) continue;
            model::Aabb region = model::worldAabb(ref.box);
            region.min = {region.min.x - radius, region.min.y - radius, region.min.z - radius};
            region.max = {region.max.x + radius, region.max.y + radius, region.max.z + radius};
            m.forEachObjectIn(region, candidate, [&](const Node& a) {
                if (refIds.contains(a.id) || distances.contains(a.id)) return;
                double best = std::numeric_limits<double>::infinity();
                for (const Node& r : refs)
                    if (r.id != a.id) best = std::min(best, model::distance(a.box, r.box));
                distances.emplace(a.id, best);
            });
        }
        // Box distance is at least the bounds' distance, so every object within
        // `radius` of a reference has been probed: the nearest `limit` of those are final.
        std::vector<std::pair<double, model::NodeId>> within;
        for (const auto& [id, d] : distances)
            if (d <= radius || radius >= kLargestRadius) within.emplace_back(d, id);
        if (within.size() < static_cast<std::size_t>(limit) && radius < kLargestRadius) continue;
        std::sort(within.begin(), within.end());
        Answer out;
        for (std::size_t i = 0; i < within.size() && i < static_cast<std::size_t>(limit); ++i)
            out.push_back(static_cast<std::int64_t>(within[i].second));
        return out;
    }
}

Answer SqliteBaseline::findCategoryAll(const std::string& category, int limit) {
    auto& s = *impl_->categoryAll;
    s.bind(1, category).bind(2, static_cast<std::int64_t>(limit));
    Answer out;
    // The application reads the same columns smql returns (id, category, scene, source id, box).
    Node row;
    while (s.step()) {
        out.push_back(s.integer(0));
        row.category.assign(s.text(1));
        row.scene = static_cast<model::NodeId>(s.integer(2));
        row.sourceId = s.integer(3);
        row.box = {{s.real(4), s.real(5), s.real(6)}, {s.real(7), s.real(8), s.real(9)}, s.real(10)};
    }
    return out;
}

Answer SqliteBaseline::countCategoryAll(const std::string& category) {
    auto& s = *impl_->countAll;
    s.bind(1, category);
    // A category never stored has no row: its count is 0.
    Answer out{0};
    if (s.step()) out.front() = s.integer(0);
    s.reset();
    return out;
}

}  // namespace smql::bench
