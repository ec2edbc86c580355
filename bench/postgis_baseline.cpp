#include "bench/postgis_baseline.hpp"

#include <algorithm>
#include <charconv>
#include <limits>
#include <stdexcept>
#include <string_view>
#include <unordered_map>
#include <utility>

#include <fmt/format.h>
#include <libpq-fe.h>

#include "fleet/pg/connection.hpp"

namespace smql::bench {

using model::Node;

namespace {

// Server settings for a read-mostly benchmark on a 2-core machine: a buffer
// cache that holds the large data set, no JIT (it costs milliseconds per
// query for nothing at these sizes), generic plans for every prepared
// statement, and room for the load (WAL size, index build memory). Commits
// stay synchronous, as LMDB's and SQLite's are.
constexpr const char* kServerSettings =
    "-c shared_buffers=1GB -c jit=off -c plan_cache_mode=force_generic_plan "
    "-c max_wal_size=8GB -c maintenance_work_mem=512MB -c work_mem=64MB -c autovacuum=off";

// Statement triggers with transition tables count a whole COPY at once.
constexpr const char* kPostgisSchema = R"sql(
CREATE TABLE scenes(id bigint PRIMARY KEY, name text NOT NULL UNIQUE, source text,
                    vx float8, vy float8, vz float8, vyaw float8);
CREATE TABLE nodes(id bigint PRIMARY KEY, scene bigint NOT NULL, parent bigint, kind int NOT NULL,
                   category text NOT NULL, geometry int NOT NULL,
                   cx float8, cy float8, cz float8, sx float8, sy float8, sz float8, yaw float8,
                   hidden boolean NOT NULL, confidence float8, source_id bigint, text text,
                   min_z float8, max_z float8, footprint geometry(Polygon));
CREATE TABLE attributes(node bigint NOT NULL, name text NOT NULL, value text NOT NULL, PRIMARY KEY(node, name));
CREATE TABLE category_counts(category text PRIMARY KEY, count bigint NOT NULL);
CREATE FUNCTION count_added() RETURNS trigger LANGUAGE plpgsql AS $$ BEGIN
  INSERT INTO category_counts SELECT category, count(*) FROM added GROUP BY category
    ON CONFLICT (category) DO UPDATE SET count = category_counts.count + excluded.count;
  RETURN NULL; END $$;
CREATE FUNCTION count_removed() RETURNS trigger LANGUAGE plpgsql AS $$ BEGIN
  UPDATE category_counts c SET count = c.count - r.n
    FROM (SELECT category, count(*) AS n FROM removed GROUP BY category) r WHERE c.category = r.category;
  RETURN NULL; END $$;
CREATE TRIGGER nodes_counted AFTER INSERT ON nodes REFERENCING NEW TABLE AS added
  FOR EACH STATEMENT EXECUTE FUNCTION count_added();
CREATE TRIGGER nodes_uncounted AFTER DELETE ON nodes REFERENCING OLD TABLE AS removed
  FOR EACH STATEMENT EXECUTE FUNCTION count_removed();
)sql";

// Built after the load, as a bulk load should. The GiST index leads with the
// scene (btree_gist), so a probe stays in its room; the B-trees cover the
// columns their queries read (index-only scans once VACUUM has run).
constexpr const char* kIndexes = R"sql(
CREATE INDEX nodes_by_scene_footprint ON nodes USING gist (scene, footprint);
CREATE INDEX nodes_by_scene_category ON nodes(scene, category)
  INCLUDE (id, kind, geometry, cx, cy, cz, sx, sy, sz, yaw, hidden, min_z, max_z, footprint);
CREATE INDEX nodes_by_category ON nodes(category, id) INCLUDE (scene, source_id, cx, cy, cz, sx, sy, sz, yaw);
CREATE INDEX nodes_by_parent ON nodes(parent);
)sql";

constexpr const char* kPostgisNodeColumns =
    "n.id, n.kind, n.category, n.geometry, n.cx, n.cy, n.cz, n.sx, n.sy, n.sz, n.yaw, n.hidden";

}  // namespace

// A connection, named outside the file's anonymous namespace: PostgisBaseline::Impl, declared in the header,
// holds one (GCC's -Wsubobject-linkage; sqlite_baseline.cpp's Statement says why).
namespace postgis {

struct Connection {
    PGconn* pg = nullptr;
    explicit Connection(const std::string& info) : pg(PQconnectdb(info.c_str())) {
        if (PQstatus(pg) != CONNECTION_OK) {
            std::string why = PQerrorMessage(pg);
            PQfinish(pg);
            throw std::runtime_error(fmt::format("postgres: cannot connect ({}): {}", info, why));
        }
    }
    ~Connection() { PQfinish(pg); }
    Connection(const Connection&) = delete;
    Connection& operator=(const Connection&) = delete;
};

}  // namespace postgis

using postgis::Connection;

namespace {

struct Result {
    PGresult* r;
    explicit Result(PGresult* result) : r(result) {}
    ~Result() { PQclear(r); }
    Result(const Result&) = delete;
    Result& operator=(const Result&) = delete;
    Result(Result&& other) noexcept : r(std::exchange(other.r, nullptr)) {}
    Result& operator=(Result&&) = delete;
    int rows() const { return PQntuples(r); }
    std::string_view text(int row, int column) const {
        return {PQgetvalue(r, row, column), static_cast<std::size_t>(PQgetlength(r, row, column))};
    }
    bool null(int row, int column) const { return PQgetisnull(r, row, column) != 0; }
    std::int64_t integer(int row, int column) const {
        std::int64_t v = 0;
        auto t = text(row, column);
        std::from_chars(t.data(), t.data() + t.size(), v);
        return v;
    }
    double real(int row, int column) const {
        double v = 0;
        auto t = text(row, column);
        std::from_chars(t.data(), t.data() + t.size(), v);
        return v;
    }
};

void check(PGconn* pg, const Result& result, std::string_view what) {
    auto status = PQresultStatus(result.r);
    if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK && status != PGRES_COPY_IN)
        throw std::runtime_error(fmt::format("postgres: {}: {}", what, PQerrorMessage(pg)));
}

void exec(PGconn* pg, const char* sql) {
    Result r(PQexec(pg, sql));
    check(pg, r, sql);
}

// Reads the kPostgisNodeColumns of a row (from column `first` on) into `node`.
void readNode(const Result& r, int row, int first, Node& node) {
    node.id = static_cast<model::NodeId>(r.integer(row, first));
    node.kind = static_cast<model::NodeKind>(r.integer(row, first + 1));
    node.category.assign(r.text(row, first + 2));
    node.geometry = static_cast<model::GeometryKind>(r.integer(row, first + 3));
    node.box = {{r.real(row, first + 4), r.real(row, first + 5), r.real(row, first + 6)},
                {r.real(row, first + 7), r.real(row, first + 8), r.real(row, first + 9)},
                r.real(row, first + 10)};
    node.hidden = r.text(row, first + 11) == "t";
}

using fleet::pg::appendCopyText;

// Parameters as text: doubles in their shortest exact form, so the server reads the same value.
class Parameters {
public:
    Parameters& add(std::string value) {
        values_.push_back(std::move(value));
        return *this;
    }
    Parameters& add(double value) { return add(fmt::format("{}", value)); }
    Parameters& add(std::int64_t value) { return add(fmt::format("{}", value)); }
    std::vector<const char*> pointers() const {
        std::vector<const char*> out;
        for (const auto& v : values_) out.push_back(v.c_str());
        return out;
    }
    int size() const { return static_cast<int>(values_.size()); }

private:
    std::vector<std::string> values_;
};

}  // namespace

// --- the server -------------------------------------------------------------

std::unique_ptr<PostgresServer> startPostgres(std::string& whyNot) {
    return PostgresServer::start({.settings = kServerSettings, .prefix = "smql-bench-pg"}, whyNot);
}

// --- the baseline ------------------------------------------------------------

struct PostgisBaseline::Impl {
    Connection connection;
    relations::Thresholds thresholds;
    std::int64_t sceneId = 0;
    relations::Frame frame;
    std::string sceneRows, attributeRows, nodeRows;  // COPY text being loaded

    explicit Impl(const std::string& info) : connection(info) {}
    PGconn* pg() const { return connection.pg; }

    void prepare(const char* name, const std::string& sql) {
        Result r(PQprepare(pg(), name, sql.c_str(), 0, nullptr));
        check(pg(), r, fmt::format("preparing `{}`", sql));
    }
    void prepareAll() {
        prepare("scene_by_name", "SELECT id, vx, vy, vz, vyaw FROM scenes WHERE name = $1");
        prepare("nodes_of_category",
                fmt::format("SELECT {} FROM nodes n WHERE n.scene = $1 AND n.category = $2", kPostgisNodeColumns));
        prepare("two_nodes",
                fmt::format("SELECT {} FROM nodes n WHERE n.id IN ($1, $2) AND n.scene = $3", kPostgisNodeColumns));
        // The visible objects whose bounds meet a region: what may crowd a pair out of near.
        prepare("objects_in_region",
                fmt::format("SELECT {} FROM nodes n WHERE n.scene = $1 AND n.footprint && ST_MakeEnvelope($2::float8, "
                            "$3::float8, $4::float8, $5::float8) AND n.max_z >= $6::float8 AND n.min_z <= $7::float8 "
                            "AND n.kind = {} AND NOT n.hidden",
                            kPostgisNodeColumns, static_cast<int>(model::NodeKind::Object)));
        // Each visible object whose bounds meet the probe region of a reference
        // of category $2, with that reference's id: one round trip for the term.
        // LATERAL keeps the generic plan a GiST probe per reference (a plain
        // join was planned as a filter over every pair of the scene's nodes).
        prepare("objects_near_references",
                fmt::format("SELECT {}, r.id FROM nodes r CROSS JOIN LATERAL (SELECT * FROM nodes WHERE scene = $1 "
                            "AND footprint && ST_Expand(r.footprint, $3::float8) "
                            "AND max_z >= r.min_z - $4::float8 AND min_z <= r.max_z + $5::float8 "
                            "AND kind = {} AND NOT hidden) n "
                            "WHERE r.scene = $1 AND r.category = $2 AND r.footprint IS NOT NULL",
                            kPostgisNodeColumns, static_cast<int>(model::NodeKind::Object)));
        // Objects nearest-first by the footprints' distance to the references
        // (a GiST k-nearest-neighbour scan: the references' footprints are one
        // value computed first, so the index can order by distance to it);
        // that distance is a lower bound of the box distance.
        prepare("objects_by_footprint_distance",
                fmt::format("WITH refs AS (SELECT ST_Collect(footprint) AS g FROM nodes WHERE scene = $1 AND "
                            "category = $2) "
                            "SELECT {0}, n.footprint <-> (SELECT g FROM refs) FROM nodes n "
                            "WHERE n.scene = $1 AND n.kind = {1} AND NOT n.hidden AND n.category <> $2 "
                            "AND n.footprint IS NOT NULL ORDER BY n.footprint <-> (SELECT g FROM refs) LIMIT $3",
                            kPostgisNodeColumns, static_cast<int>(model::NodeKind::Object)));
        prepare("category_all",
                "SELECT id, category, scene, source_id, cx, cy, cz, sx, sy, sz, yaw FROM nodes "
                "WHERE category = $1 ORDER BY id LIMIT $2");
        prepare("category_count", "SELECT count FROM category_counts WHERE category = $1");
    }

    Result execute(const char* statement, const Parameters& parameters) {
        auto values = parameters.pointers();
        Result r(PQexecPrepared(pg(), statement, parameters.size(), values.data(), nullptr, nullptr, 0));
        check(pg(), r, statement);
        return r;
    }

    std::vector<Node> nodesOf(const std::string& category) {
        Result r = execute("nodes_of_category", Parameters().add(sceneId).add(category));
        std::vector<Node> out(static_cast<std::size_t>(r.rows()));
        for (int i = 0; i < r.rows(); ++i) readNode(r, i, 0, out[static_cast<std::size_t>(i)]);
        return out;
    }

    void copy(const char* sql, const std::string& rows) {
        {
            Result r(PQexec(pg(), sql));
            check(pg(), r, sql);
        }
        if (!rows.empty() && PQputCopyData(pg(), rows.data(), static_cast<int>(rows.size())) != 1)
            throw std::runtime_error(fmt::format("postgres: {}: {}", sql, PQerrorMessage(pg())));
        endCopy(sql);
    }
    void endCopy(const char* what) {
        if (PQputCopyEnd(pg(), nullptr) != 1)
            throw std::runtime_error(fmt::format("postgres: ending {}: {}", what, PQerrorMessage(pg())));
        Result r(PQgetResult(pg()));
        check(pg(), r, what);
        while (PGresult* rest = PQgetResult(pg())) PQclear(rest);
    }
};

constexpr const char* kCopyNodes =
    "COPY nodes(id, scene, parent, kind, category, geometry, cx, cy, cz, sx, sy, sz, yaw, hidden, confidence, "
    "source_id, text, min_z, max_z, footprint) FROM STDIN";

PostgisBaseline::PostgisBaseline(const std::string& connection, bool create)
    : impl_(std::make_unique<Impl>(connection)) {
    if (create) exec(impl_->pg(), kPostgisSchema);
    impl_->prepareAll();
}

PostgisBaseline::~PostgisBaseline() = default;

void PostgisBaseline::beginLoad() {
    exec(impl_->pg(), "BEGIN");
    Result r(PQexec(impl_->pg(), kCopyNodes));
    check(impl_->pg(), r, kCopyNodes);
}

void PostgisBaseline::addScene(const model::SceneInfo& info, const std::vector<Node>& nodes) {
    auto& m = *impl_;
    auto& s = m.sceneRows;
    fmt::format_to(std::back_inserter(s), "{}\t", info.id);
    appendCopyText(s, info.name);
    s += '\t';
    appendCopyText(s, info.source);
    fmt::format_to(std::back_inserter(s), "\t{}\t{}\t{}\t{}\n", info.viewpoint.position.x, info.viewpoint.position.y,
                   info.viewpoint.position.z, info.viewpoint.facingYaw);
    auto& out = m.nodeRows;
    out.clear();
    for (const Node& n : nodes) {
        if (n.kind == model::NodeKind::Scene) continue;
        auto it = std::back_inserter(out);
        fmt::format_to(it, "{}\t{}\t", n.id, n.scene);
        if (n.parent == model::kNoNode)
            out += "\\N";
        else
            fmt::format_to(it, "{}", n.parent);
        fmt::format_to(it, "\t{}\t", static_cast<int>(n.kind));
        appendCopyText(out, n.category);
        fmt::format_to(it, "\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t", static_cast<int>(n.geometry), n.box.center.x,
                       n.box.center.y, n.box.center.z, n.box.size.x, n.box.size.y, n.box.size.z, n.box.yaw,
                       n.hidden ? "t" : "f", static_cast<double>(n.confidence));
        if (n.sourceId)
            fmt::format_to(it, "{}", *n.sourceId);
        else
            out += "\\N";
        out += '\t';
        appendCopyText(out, n.text);
        if (n.geometry == model::GeometryKind::None) {
            out += "\t\\N\t\\N\t\\N\n";
        } else {
            // The footprint is the box's world bounds seen from above, exactly
            // the bounds the other systems probe with.
            model::Aabb b = model::worldAabb(n.box);
            fmt::format_to(it, "\t{}\t{}\tPOLYGON(({} {},{} {},{} {},{} {},{} {}))\n", b.min.z, b.max.z, b.min.x,
                           b.min.y, b.min.x, b.max.y, b.max.x, b.max.y, b.max.x, b.min.y, b.min.x, b.min.y);
        }
        for (const auto& a : n.attributes) {
            fmt::format_to(std::back_inserter(m.attributeRows), "{}\t", n.id);
            appendCopyText(m.attributeRows, a.name);
            m.attributeRows += '\t';
            appendCopyText(m.attributeRows, a.value);
            m.attributeRows += '\n';
        }
    }
    if (PQputCopyData(m.pg(), out.data(), static_cast<int>(out.size())) != 1)
        throw std::runtime_error(fmt::format("postgres: copying nodes: {}", PQerrorMessage(m.pg())));
}

void PostgisBaseline::endLoad() {
    auto& m = *impl_;
    m.endCopy(kCopyNodes);
    m.copy("COPY scenes(id, name, source, vx, vy, vz, vyaw) FROM STDIN", m.sceneRows);
    m.copy("COPY attributes(node, name, value) FROM STDIN", m.attributeRows);
    exec(m.pg(), "COMMIT");
    m.sceneRows = std::string();
    m.attributeRows = std::string();
    m.nodeRows = std::string();
    exec(m.pg(), kIndexes);
    exec(m.pg(), "VACUUM ANALYZE");  // statistics for the plans, the visibility map for index-only scans
}

std::uint64_t PostgisBaseline::databaseBytes() {
    Result r(PQexec(impl_->pg(), "SELECT pg_database_size(current_database())"));
    check(impl_->pg(), r, "measuring the database");
    return static_cast<std::uint64_t>(r.integer(0, 0));
}

void PostgisBaseline::useScene(const std::string& scene) {
    auto& m = *impl_;
    Result r = m.execute("scene_by_name", Parameters().add(scene));
    if (r.rows() == 0) throw std::runtime_error(fmt::format("postgres: no scene named '{}'", scene));
    m.sceneId = r.integer(0, 0);
    model::Viewpoint vp{{r.real(0, 1), r.real(0, 2), r.real(0, 3)}, r.real(0, 4)};
    m.frame = relations::viewFrame(vp);
}

Answer PostgisBaseline::findObjects(const PredicateTerm& first, const PredicateTerm& second) {
    auto& m = *impl_;
    const TwoTermFind find(first, m.nodesOf(first.category), second, m.nodesOf(second.category), m.thresholds, m.frame);
    std::unordered_map<model::NodeId, const Node*> probeById;
    for (const Node& ref : find.probeReferences()) probeById.emplace(ref.id, &ref);
    ProbeMargins margins = probeMargins(find.probeTerm(), m.thresholds);
    Result r = m.execute("objects_near_references", Parameters()
                                                        .add(m.sceneId)
                                                        .add(find.probeTerm().category)
                                                        .add(margins.horizontal)
                                                        .add(margins.below)
                                                        .add(margins.above));
    // A candidate comes once per reference whose region it meets; it passes the probe term with any of them.
    std::unordered_map<model::NodeId, bool> passed;
    Answer ids;
    Node candidate;
    const int referenceColumn = 12;
    for (int i = 0; i < r.rows(); ++i) {
        readNode(r, i, 0, candidate);
        auto [at, isNew] = passed.try_emplace(candidate.id, false);
        if (at->second) continue;
        auto ref = probeById.find(static_cast<model::NodeId>(r.integer(i, referenceColumn)));
        if (ref == probeById.end() || !find.meetsProbe(candidate, *ref->second)) continue;
        at->second = true;
        if (find.meetsCheck(candidate)) ids.push_back(static_cast<std::int64_t>(candidate.id));
    }
    std::sort(ids.begin(), ids.end());
    return ids;
}

Answer PostgisBaseline::relate(model::NodeId a, model::NodeId b) {
    auto& m = *impl_;
    Result r = m.execute(
        "two_nodes", Parameters().add(static_cast<std::int64_t>(a)).add(static_cast<std::int64_t>(b)).add(m.sceneId));
    std::vector<Node> rows(static_cast<std::size_t>(r.rows()));
    for (int i = 0; i < r.rows(); ++i) readNode(r, i, 0, rows[static_cast<std::size_t>(i)]);
    const model::Aabb region = aroundPair(rows, m.thresholds);
    Result nearby = m.execute("objects_in_region", Parameters()
                                                       .add(m.sceneId)
                                                       .add(region.min.x)
                                                       .add(region.min.y)
                                                       .add(region.max.x)
                                                       .add(region.max.y)
                                                       .add(region.min.z)
                                                       .add(region.max.z));
    std::vector<Node> around(static_cast<std::size_t>(nearby.rows()));
    for (int i = 0; i < nearby.rows(); ++i) readNode(nearby, i, 0, around[static_cast<std::size_t>(i)]);
    return relateRows("postgres", a, b, rows, around, m.thresholds, m.frame);
}

Answer PostgisBaseline::nearestObjects(const std::string& category, int limit) {
    auto& m = *impl_;
    std::vector<Node> refs = m.nodesOf(category);
    // Reads the objects nearest-first by footprint distance, a window of rows
    // at a time (growing 4x), until the next row's lower bound exceeds the
    // k-th exact distance: no row after it can enter the answer.
    for (std::int64_t window = 4 * static_cast<std::int64_t>(limit);; window *= 4) {
        Result r = m.execute("objects_by_footprint_distance", Parameters().add(m.sceneId).add(category).add(window));
        std::vector<std::pair<double, model::NodeId>> distances;
        Node candidate;
        bool complete = r.rows() < window;
        for (int i = 0; i < r.rows(); ++i) {
            double lowerBound = r.real(i, 12);
            if (static_cast<int>(distances.size()) >= limit) {
                std::vector<double> exact;
                for (const auto& d : distances) exact.push_back(d.first);
                std::nth_element(exact.begin(), exact.begin() + (limit - 1), exact.end());
                if (lowerBound > exact[static_cast<std::size_t>(limit - 1)]) {
                    complete = true;
                    break;
                }
            }
            readNode(r, i, 0, candidate);
            double best = std::numeric_limits<double>::infinity();
            for (const Node& ref : refs) best = std::min(best, model::distance(candidate.box, ref.box));
            distances.emplace_back(best, candidate.id);
        }
        if (complete) return nearestFirst(std::move(distances), limit);
    }
}

Answer PostgisBaseline::findCategoryAll(const std::string& category, int limit) {
    Result r = impl_->execute("category_all", Parameters().add(category).add(static_cast<std::int64_t>(limit)));
    Answer out;
    // The application reads the same columns smql returns (id, category, scene, source id, box).
    Node row;
    for (int i = 0; i < r.rows(); ++i) {
        out.push_back(r.integer(i, 0));
        row.category.assign(r.text(i, 1));
        row.scene = static_cast<model::NodeId>(r.integer(i, 2));
        row.sourceId = r.integer(i, 3);
        row.box = {
            {r.real(i, 4), r.real(i, 5), r.real(i, 6)}, {r.real(i, 7), r.real(i, 8), r.real(i, 9)}, r.real(i, 10)};
    }
    return out;
}

Answer PostgisBaseline::countCategoryAll(const std::string& category) {
    Result r = impl_->execute("category_count", Parameters().add(category));
    // A category never stored has no row: its count is 0.
    return {r.rows() ? r.integer(0, 0) : 0};
}

}  // namespace smql::bench
