#include "fleet/query.hpp"

#include <fmt/format.h>

#include "engine/parser/parser.hpp"
#include "fleet/schema.hpp"
#include "model/error.hpp"
#include "relations/predicates.hpp"

namespace smql::fleet {

namespace {

Error notYet(const std::string& what) {
    return Error(ErrorKind::Usage, fmt::format("the fleet store does not run {} yet", what), std::nullopt,
                 "it runs COUNT and FIND of a category in one scene, with at most one predicate on a category "
                 "(docs/fleet.md, \"SMQL on the store\"); pull the scene to ask anything else");
}

// A category as written: kind words (object, anchor, node) and sub-queries are the engine's yet.
std::string categoryOf(const ast::Ref& ref) {
    if (ref.kind != ast::Ref::Kind::Name) throw notYet("a reference other than a category");
    return ref.name;
}

struct Target {
    const ast::Ref* ref;
    const std::optional<ast::Expr>* where;
};

// The statement's shape, or notYet for everything the compiler does not cover.
Target targetOf(const ast::Statement& statement, bool& count) {
    if (const auto* find = std::get_if<ast::FindStmt>(&statement.body)) {
        if (find->asOf || find->view || find->nearestTo || find->orderBy || find->similarTo || find->limit ||
            find->limitParam || find->path || !find->columns.empty())
            throw notYet("FIND with AS OF, VIEW FROM, NEAREST TO, ORDER BY, SIMILAR TO, LIMIT, PATH or RETURN");
        count = false;
        return {&find->target, &find->where};
    }
    if (const auto* c = std::get_if<ast::CountStmt>(&statement.body)) {
        if (c->asOf || c->view) throw notYet("COUNT with AS OF or VIEW FROM");
        count = true;
        return {&c->target, &c->where};
    }
    throw notYet(fmt::format("'{}'", statement.text));
}

// The candidates' GiST probe: a's world bounds meet the region the predicate's table row gives
// around the reference (computed in the server by the same function the engine's planner uses).
constexpr const char* kProbe =
    "CROSS JOIN LATERAL (SELECT smql.predicate_region({0}, r, scene.distance) AS g) region "
    "JOIN smql.nodes n ON n.scene = $1 AND n.category = $2 "
    "AND n.footprint && ST_MakeEnvelope(region.g[1], region.g[2], region.g[4], region.g[5]) "
    "AND n.max_z >= region.g[3] AND n.min_z <= region.g[6] ";
constexpr const char* kScan = "JOIN smql.nodes n ON n.scene = $1 AND n.category = $2 ";
// FIND's columns, as the engine answers: id (here the scene's local id), category, source id, box.
constexpr const char* kFoundColumns =
    "DISTINCT n.id, n.category, n.source_id, n.cx, n.cy, n.cz, n.sx, n.sy, n.sz, n.yaw";

std::string predicateSql(const ast::Expr& expr, bool count, std::vector<std::string>& parameters) {
    if (expr.kind != ast::Expr::Kind::Predicate) throw notYet("a WHERE other than one predicate");
    const relations::PredicateSpec* spec = relations::predicateNamed(expr.predicate);
    if (!spec) throw Error(ErrorKind::Binding, fmt::format("no predicate named '{}'", expr.predicate));
    if (spec->arity != 1 || expr.args.size() != 1) throw notYet(fmt::format("{} with two references", spec->name()));
    if (expr.threshold && !spec->takesDistance)
        throw Error(ErrorKind::Usage, fmt::format("{} takes no distance", spec->name()));
    parameters.push_back(categoryOf(expr.args.front()));
    parameters.push_back(expr.threshold ? fmt::format("{}", expr.threshold->metres) : "");  // "": none
    // The scene's viewpoint gives the view-relative predicates their frame; `others`, the nodes
    // that may stand between, are every visible node with geometry, as the engine's R-tree holds them.
    return fmt::format(
        "WITH scene AS (SELECT ARRAY[viewpoint_x, viewpoint_y, viewpoint_z, viewpoint_yaw] AS viewpoint, "
        "NULLIF($4, '')::float8 AS distance FROM smql.scenes WHERE id = $1), "
        "others AS (SELECT coalesce(array_agg(o ORDER BY o.id), '{{}}') AS nodes FROM smql.nodes o "
        "WHERE o.scene = $1 AND o.geometry <> 0 AND NOT o.hidden) "
        "SELECT {0} FROM scene CROSS JOIN others CROSS JOIN smql.nodes r {1}"
        "WHERE r.scene = $1 AND r.category = $3 AND smql.\"{2}\"(n, r, scene.viewpoint, others.nodes{3}) > 0 {4}",
        count ? "count(DISTINCT n.id)" : kFoundColumns,
        spec->local() ? fmt::format(kProbe, static_cast<int>(spec->predicate)) : kScan, spec->name(),
        spec->takesDistance ? ", scene.distance" : "", count ? "" : "ORDER BY n.id");
}

}  // namespace

CompiledQuery compileQuery(const ast::Statement& statement) {
    CompiledQuery out;
    Target target = targetOf(statement, out.count);
    out.parameters.push_back(categoryOf(*target.ref));
    if (!*target.where) {
        out.sql = out.count ? "SELECT count(*) FROM smql.nodes WHERE scene = $1 AND category = $2"
                            : fmt::format("SELECT {} FROM smql.nodes n WHERE scene = $1 AND category = $2 ORDER BY id",
                                          kFoundColumns);
        return out;
    }
    out.sql = predicateSql(**target.where, out.count, out.parameters);
    return out;
}

CompiledQuery compileQuery(const std::string& text) {
    std::vector<ast::Statement> statements = parser::parse(text);
    if (statements.size() != 1) throw Error(ErrorKind::Usage, "the fleet store runs one statement at a time");
    return compileQuery(statements.front());
}

namespace {

ResultSet run(Store& store, const StoredVersion& scene, const ast::Statement& statement) {
    CompiledQuery query = compileQuery(statement);
    pg::Parameters parameters;
    parameters.add(scene.key);
    for (const auto& p : query.parameters) parameters.add(p);
    pg::Result r = store.connection().exec(query.sql, parameters, fmt::format("running `{}`", statement.text));
    ResultSet out;
    if (query.count) {
        out.columns = {{"count", ValueType::Integer}};
        out.rows.push_back({r.integer(0, 0)});
        return out;
    }
    out.columns = {{"id", ValueType::Integer},
                   {"category", ValueType::Text},
                   {"source_id", ValueType::Integer},
                   {"box", ValueType::Box}};
    for (int i = 0; i < r.rows(); ++i) {
        Value source = r.null(i, 2) ? Value() : Value(r.integer(i, 2));
        model::Box box{
            {r.real(i, 3), r.real(i, 4), r.real(i, 5)}, {r.real(i, 6), r.real(i, 7), r.real(i, 8)}, r.real(i, 9)};
        out.rows.push_back({r.integer(i, 0), std::string(r.text(i, 1)), source, box});
    }
    return out;
}

}  // namespace

QueryAnswer runQuery(Store& store, const StoredVersion& scene, const std::string& statement) {
    std::vector<ast::Statement> statements = parser::parse(statement);
    if (statements.size() != 1) throw Error(ErrorKind::Usage, "the fleet store runs one statement at a time");
    ResultSet result = run(store, scene, statements.front());
    QueryAnswer answer;
    if (result.columns.front().name == "count") {
        answer.count = std::get<std::int64_t>(result.rows.front().front());
        return answer;
    }
    for (const auto& row : result.rows) answer.ids.push_back(std::get<std::int64_t>(row.front()));
    return answer;
}

StoreSession::StoreSession(const std::string& url, std::string device) : store_(url), device_(std::move(device)) {
    requireCurrentSchema(store_.connection());
}

void StoreSession::execute(const std::string& text, const std::function<void(ResultSet&&)>& onResult) {
    for (const ast::Statement& statement : parser::parse(text)) {
        if (const auto* chosen = std::get_if<ast::UseStmt>(&statement.body)) {
            onResult(use(chosen->scene));
            continue;
        }
        if (!scene_)
            throw Error(ErrorKind::Usage, "no scene chosen on the fleet store", std::nullopt,
                        "begin with USE SCENE 'name' (and --device ID when several devices hold that name)");
        onResult(run(store_, *scene_, statement));
    }
}

ResultSet StoreSession::use(const std::string& scene) {
    if (scene == "*") throw notYet("USE SCENE '*'");
    std::vector<StoredVersion> versions = store_.versionsNamed(scene, device_);
    if (versions.empty())
        throw Error(ErrorKind::Binding, fmt::format("the fleet store has no scene named '{}'", scene));
    for (const auto& v : versions)
        if (v.device != versions.front().device)
            throw Error(ErrorKind::Binding, fmt::format("several devices hold a scene named '{}'", scene), std::nullopt,
                        "say whose with --device ID (the start of the id is enough)");
    scene_ = versions.back();
    ResultSet out;
    out.message = fmt::format("using scene '{}', version {} of device {}", scene, scene_->version, scene_->device);
    return out;
}

}  // namespace smql::fleet
