#include "fleet/query.hpp"

#include <cstdlib>

#include <fmt/format.h>

#include "engine/catalog/attributes.hpp"
#include "engine/catalog/description.hpp"
#include "engine/catalog/scene_snapshot.hpp"
#include "engine/catalog/session.hpp"
#include "engine/parser/parser.hpp"
#include "fleet/schema.hpp"
#include "model/error.hpp"
#include "model/instant.hpp"
#include "model/names.hpp"
#include "model/presentation.hpp"
#include "relations/predicates.hpp"

namespace smql::fleet {

namespace {

// The categories the chosen scene versions hold, and whether any other stored scene holds a name.
QueryScope scopeOf(Store& store, const std::vector<StoredVersion>& scenes, bool allScenes, Store* whole = nullptr) {
    QueryScope scope;
    scope.allScenes = allScenes;
    scope.name = allScenes ? "*" : scenes.front().scene;
    scope.device = allScenes ? "" : scenes.front().device;
    scope.keys = "{";
    for (const auto& s : scenes) scope.keys += fmt::format("{}{}", scope.keys.size() > 1 ? "," : "", s.key);
    scope.keys += "}";
    pg::Result r = store.connection().exec("SELECT DISTINCT category FROM smql.nodes WHERE scene = ANY($1::int8[])",
                                           pg::Parameters().add(scope.keys), "reading the scene's categories");
    for (int i = 0; i < r.rows(); ++i) scope.categories.emplace(r.text(i, 0));
    pg::Result names =
        store.connection().exec("SELECT DISTINCT name FROM smql.attributes WHERE scene = ANY($1::int8[])",
                                pg::Parameters().add(scope.keys), "reading the scene's attributes");
    for (int i = 0; i < names.rows(); ++i) scope.attributes.emplace(names.text(i, 0));
    scope.locate = [&store, keys = scope.keys](const std::string& sql, const std::vector<std::string>& parameters) {
        pg::Parameters all;
        all.add(keys);
        for (const auto& p : parameters) all.add(p);
        pg::Result r = store.connection().exec(sql, all, "locating nodes");
        std::vector<QueryScope::Located> out;
        for (int i = 0; i < r.rows(); ++i)
            out.push_back({r.integer(i, 0), {r.real(i, 1), r.real(i, 2), r.real(i, 3)}, r.text(i, 4) == "t"});
        return out;
    };
    if (!allScenes) {
        pg::Result v = store.connection().exec(
            "SELECT viewpoint_x, viewpoint_y, viewpoint_z, viewpoint_yaw FROM smql.scenes WHERE id = $1",
            pg::Parameters().add(scenes.front().key), "reading the scene's viewpoint");
        scope.viewpoint = {{v.real(0, 0), v.real(0, 1), v.real(0, 2)}, v.real(0, 3)};
    }
    scope.nodeCategory = [&store, keys = scope.keys](const char* column,
                                                     std::int64_t value) -> std::optional<std::string> {
        pg::Result node = store.connection().exec(
            fmt::format("SELECT category FROM smql.nodes WHERE scene = ANY($1::int8[]) AND {} = $2 ORDER BY id LIMIT 1",
                        column),
            pg::Parameters().add(keys).add(value), "looking a node up");
        if (node.rows() == 0) return std::nullopt;
        return std::string(node.text(0, 0));
    };
    scope.knownElsewhere = [&lookIn = whole ? *whole : store](const std::string& category) {
        return lookIn.connection()
                   .exec("SELECT 1 FROM smql.nodes WHERE category = $1 LIMIT 1", pg::Parameters().add(category),
                         "looking a category up in the store")
                   .rows() > 0;
    };
    return scope;
}

// FIND's rows, as the engine answers: id (here the scene's local id), category, the scene when all
// scenes are asked, source id, box (none for a node without one), and NEAREST TO's distance.
ResultSet foundNodes(const pg::Result& r, bool allScenes, bool distance, bool path) {
    ResultSet out;
    out.columns = {{"id", ValueType::Integer}, {"category", ValueType::Text}};
    if (allScenes) out.columns.push_back({"scene", ValueType::Text});
    out.columns.push_back({"source_id", ValueType::Integer});
    out.columns.push_back({"box", ValueType::Box});
    if (distance) out.columns.push_back({"distance", ValueType::Real});
    if (path) out.columns.push_back({"path", ValueType::Text});
    const int shift = allScenes ? 1 : 0;
    for (int i = 0; i < r.rows(); ++i) {
        Row& row = out.rows.emplace_back();
        row.emplace_back(r.integer(i, 0));
        row.emplace_back(std::string(r.text(i, 1)));
        if (allScenes) row.emplace_back(std::string(r.text(i, 2)));
        if (r.null(i, 2 + shift))
            row.emplace_back();
        else
            row.emplace_back(r.integer(i, 2 + shift));
        auto at = [&](int column) { return r.real(i, column + shift); };
        if (r.text(i, 3 + shift) == "t")
            row.emplace_back(model::Box{{at(4), at(5), at(6)}, {at(7), at(8), at(9)}, at(10)});
        else
            row.emplace_back();
        if (distance) row.emplace_back(at(11));
        if (path) row.emplace_back(std::string(r.text(i, 11 + shift + (distance ? 1 : 0))));
    }
    return out;
}

// The numbers of a float8[] literal, {1,0.5,...}.
std::vector<double> numbersOf(std::string_view array) {
    const std::string text(array);
    std::vector<double> out;
    for (const char* p = text.c_str() + 1; *p && *p != '}';) {
        char* end = nullptr;
        out.push_back(std::strtod(p, &end));
        p = *end == ',' ? end + 1 : end;
    }
    return out;
}

// FIND ... RETURN's rows: each column as its attribute's type, then the path.
ResultSet returnedColumns(const pg::Result& r, const CompiledQuery& query) {
    ResultSet out;
    for (const auto& [name, type] : query.returned) out.columns.push_back({name, type});
    if (query.path) out.columns.push_back({"path", ValueType::Text});
    for (int i = 0; i < r.rows(); ++i) {
        Row& row = out.rows.emplace_back();
        for (int c = 0; c < static_cast<int>(out.columns.size()); ++c) {
            if (r.null(i, c)) {
                row.emplace_back();
                continue;
            }
            switch (out.columns[c].type) {
                case ValueType::Integer:
                    row.emplace_back(r.integer(i, c));
                    break;
                case ValueType::Real:
                    row.emplace_back(r.real(i, c));
                    break;
                case ValueType::Box: {
                    const std::vector<double> b = numbersOf(r.text(i, c));
                    row.emplace_back(model::Box{{b.at(0), b.at(1), b.at(2)}, {b.at(3), b.at(4), b.at(5)}, b.at(6)});
                    break;
                }
                default:
                    row.emplace_back(std::string(r.text(i, c)));
            }
        }
    }
    return out;
}

// A node as RELATE and CHECK name it ("sofa#12", with the scene's local id), from its id, category
// and kind at `column`.
std::string labelAt(const pg::Result& r, int row, int column) {
    model::Node node;
    node.id = static_cast<model::NodeId>(r.integer(row, column));
    node.category = r.text(row, column + 1);
    node.kind = static_cast<model::NodeKind>(r.integer(row, column + 2));
    return catalog::SceneSnapshot::label(node);
}

// RELATE's rows: a row per relation that holds, as the engine answers.
ResultSet relationRows(const pg::Result& r) {
    ResultSet out;
    out.columns = {{"subject", ValueType::Text},
                   {"relation", ValueType::Text},
                   {"object", ValueType::Text},
                   {"score", ValueType::Real},
                   {"distance", ValueType::Real}};
    for (int i = 0; i < r.rows(); ++i) {
        const std::string subject = labelAt(r, i, 0), object = labelAt(r, i, 3);
        // The relations come as (code, score) pairs.
        const std::vector<double> values = numbersOf(r.text(i, 6));
        for (std::size_t k = 0; k + 1 < values.size(); k += 2)
            out.rows.push_back({subject, std::string(relations::toString(static_cast<relations::Predicate>(values[k]))),
                                object, values[k + 1], r.real(i, 7)});
    }
    return out;
}

// CHECK's one row: yes or no, the subject, the relation, the objects, the score and the distance.
ResultSet checked(const pg::Result& r, const CompiledQuery& query) {
    ResultSet out;
    out.columns = {{"answer", ValueType::Text}, {"subject", ValueType::Text}, {"relation", ValueType::Text},
                   {"object", ValueType::Text}, {"score", ValueType::Real},   {"distance", ValueType::Real}};
    const int score = query.third ? 9 : 6;
    const std::string subject = labelAt(r, 0, 0);
    std::string objects = labelAt(r, 0, 3);
    if (query.third) objects += " and " + labelAt(r, 0, 6);
    const bool holds = r.real(0, score) > 0;
    out.rows.push_back(
        {std::string(holds ? "yes" : "no"), subject, query.relation, objects, r.real(0, score), r.real(0, score + 1)});
    out.message =
        fmt::format("{}: {} is {}{} {}", holds ? "yes" : "no", subject, holds ? "" : "not ", query.relation, objects);
    return out;
}

// DESCRIBE's rows for each node found: its fields from the query's row, its attributes, children
// and evidence from the store's tables.
ResultSet described(pg::Connection& c, const pg::Result& r) {
    ResultSet out;
    out.columns = {{"id", ValueType::Integer}, {"field", ValueType::Text}, {"value", ValueType::Text}};
    for (int i = 0; i < r.rows(); ++i) {
        model::Node n;
        n.id = static_cast<model::NodeId>(r.integer(i, 0));
        n.kind = static_cast<model::NodeKind>(r.integer(i, 1));
        n.category = r.text(i, 2);
        n.geometry = static_cast<model::GeometryKind>(r.integer(i, 3));
        n.box = {{r.real(i, 4), r.real(i, 5), r.real(i, 6)}, {r.real(i, 7), r.real(i, 8), r.real(i, 9)}, r.real(i, 10)};
        n.hidden = r.text(i, 11) == "t";
        n.confidence = r.real4(i, 12);
        if (!r.null(i, 13)) n.sourceId = r.integer(i, 13);
        n.text = r.text(i, 14);
        pg::Parameters node;
        node.add(r.integer(i, 15)).add(r.integer(i, 0));
        pg::Result attributes =
            c.exec("SELECT name, value FROM smql.attributes WHERE scene = $1 AND node = $2 ORDER BY position", node,
                   "reading a node's attributes");
        for (int a = 0; a < attributes.rows(); ++a)
            n.attributes.push_back({std::string(attributes.text(a, 0)), std::string(attributes.text(a, 1))});
        pg::Result kids = c.exec(
            "SELECT id, kind, category, text FROM smql.nodes WHERE scene = $1 AND parent = $2 "
            "ORDER BY id",
            node, "reading a node's children");
        std::vector<model::Node> children(static_cast<std::size_t>(kids.rows()));
        std::vector<const model::Node*> childList;
        for (int k = 0; k < kids.rows(); ++k) {
            model::Node& child = children[static_cast<std::size_t>(k)];
            child.id = static_cast<model::NodeId>(kids.integer(k, 0));
            child.kind = static_cast<model::NodeKind>(kids.integer(k, 1));
            child.category = kids.text(k, 2);
            child.text = kids.text(k, 3);
            childList.push_back(&child);
        }
        pg::Result blobs = c.exec(
            "SELECT name, media_type, octet_length(bytes) FROM smql.blobs WHERE scene = $1 AND "
            "node = $2 ORDER BY name",
            node, "reading a node's evidence");
        std::vector<catalog::EvidenceInfo> evidence;
        for (int b = 0; b < blobs.rows(); ++b)
            evidence.push_back({std::string(blobs.text(b, 0)), std::string(blobs.text(b, 1)),
                                static_cast<std::uint64_t>(blobs.integer(b, 2))});
        catalog::describeNode(out, n, r.text(i, 16), childList, evidence);
    }
    return out;
}

// SHOW CATEGORIES and SHOW ATTRIBUTES of the chosen scene versions, as the engine lists them.
ResultSet shown(Store& store, const QueryScope& scope, const ast::ShowStmt& show) {
    if (show.what == ast::ShowStmt::What::Attributes)
        return catalog::attributeTable(
            scope.allScenes ? std::vector<std::string>()
                            : std::vector<std::string>(scope.attributes.begin(), scope.attributes.end()));
    if (show.what != ast::ShowStmt::What::Categories) throw notYet("SHOW SETTINGS, CHANGES and GRAPH");
    ResultSet out;
    if (scope.allScenes) {
        out.columns = {{"scene", ValueType::Text}, {"category", ValueType::Text}, {"count", ValueType::Integer}};
        pg::Result r = store.connection().exec(
            "SELECT s.name, n.category, count(*) FROM smql.nodes n JOIN smql.scenes s ON s.id = n.scene WHERE n.scene "
            "= ANY($1::int8[]) GROUP BY s.name, n.category ORDER BY s.name COLLATE \"C\", n.category COLLATE \"C\"",
            pg::Parameters().add(scope.keys), "listing the categories");
        for (int i = 0; i < r.rows(); ++i)
            out.rows.push_back({std::string(r.text(i, 0)), std::string(r.text(i, 1)), r.integer(i, 2)});
        return out;
    }
    // Descriptions and frames are about places, not places: a category only they (or hidden
    // nodes) have is not one to ask for; its count is every node of it.
    out.columns = {{"category", ValueType::Text}, {"count", ValueType::Integer}, {"colour", ValueType::Text}};
    pg::Result r = store.connection().exec(
        fmt::format("SELECT category, count(*) FROM smql.nodes WHERE scene = ANY($1::int8[]) GROUP BY category HAVING "
                    "bool_or(NOT hidden AND kind NOT IN ({}, {}, {})) ORDER BY category COLLATE \"C\"",
                    static_cast<int>(model::NodeKind::Scene), static_cast<int>(model::NodeKind::Description),
                    static_cast<int>(model::NodeKind::Frame)),
        pg::Parameters().add(scope.keys), "listing the categories");
    std::vector<std::string> categories;
    for (int i = 0; i < r.rows(); ++i) categories.emplace_back(r.text(i, 0));
    const model::Palette palette(categories);
    for (int i = 0; i < r.rows(); ++i)
        out.rows.push_back({categories[i], r.integer(i, 1), model::hexColour(palette(categories[i]))});
    return out;
}

// EXPLAIN on the store: the SQL a statement compiles to and PostgreSQL's plan for it.
ResultSet explained(Store& store, const QueryScope& scope, const relations::Thresholds& thresholds,
                    const ast::Statement& statement) {
    const CompiledQuery query = compileQuery(statement, scope, thresholds);
    pg::Parameters parameters;
    parameters.add(scope.keys);
    for (const auto& p : query.parameters) parameters.add(p);
    pg::Result r =
        store.connection().exec("EXPLAIN " + query.sql, parameters, fmt::format("explaining `{}`", statement.text));
    ResultSet out;
    out.columns = {{"plan", ValueType::Text}};
    out.rows.push_back({"SQL: " + query.sql});
    for (int i = 0; i < r.rows(); ++i) out.rows.push_back({std::string(r.text(i, 0))});
    out.message = "the fleet store's plan: PostgreSQL's, for the SQL the statement compiles to";
    return out;
}

ResultSet run(Store& store, const QueryScope& scope, const relations::Thresholds& thresholds,
              const ast::Statement& statement) {
    if (const auto* show = std::get_if<ast::ShowStmt>(&statement.body); show && show->what != ast::ShowStmt::What::Tree)
        return shown(store, scope, *show);
    if (const auto* explain = std::get_if<ast::ExplainStmt>(&statement.body))
        return explained(store, scope, thresholds, *explain->inner);
    CompiledQuery query = compileQuery(statement, scope, thresholds);
    pg::Parameters parameters;
    parameters.add(scope.keys);
    for (const auto& p : query.parameters) parameters.add(p);
    pg::Connection& c = store.connection();
    for (const auto& single : query.singles) {
        pg::Parameters own;
        own.add(scope.keys);
        for (const auto& p : single.parameters) own.add(p);
        const int count = c.exec(single.sql, own, fmt::format("running `{}`", statement.text)).rows();
        if (count != 1)
            throw Error(ErrorKind::Binding, fmt::format("{} must be one node; it names {}", single.role, count),
                        std::nullopt,
                        "name one, as in chair#12, or pick one by place, as in (FIND chair NEAREST TO door LIMIT 1)");
    }
    pg::Result r = c.exec(query.sql, parameters, fmt::format("running `{}`", statement.text));
    switch (query.shape) {
        case CompiledQuery::Shape::Count: {
            ResultSet out;
            out.columns = {{"count", ValueType::Integer}};
            out.rows.push_back({r.integer(0, 0)});
            return out;
        }
        case CompiledQuery::Shape::Find:
            return foundNodes(r, scope.allScenes, query.distance, query.path);
        case CompiledQuery::Shape::Return:
            return returnedColumns(r, query);
        case CompiledQuery::Shape::Relate:
            return relationRows(r);
        case CompiledQuery::Shape::Check:
            return checked(r, query);
        case CompiledQuery::Shape::Describe:
            return described(c, r);
        case CompiledQuery::Shape::Tree: {
            ResultSet out;
            out.columns = {{"id", ValueType::Integer}, {"depth", ValueType::Integer}, {"node", ValueType::Text}};
            for (int i = 0; i < r.rows(); ++i)
                out.rows.push_back({r.integer(i, 0), r.integer(i, 1), std::string(r.text(i, 2))});
            return out;
        }
    }
    return {};
}

// A conninfo value, quoted as libpq reads it.
std::string conninfoValue(std::string_view value) {
    std::string out = "'";
    for (char c : value) {
        if (c == '\'' || c == '\\') out += '\\';
        out += c;
    }
    return out + "'";
}

// On a coordinator (docs/fleet.md, "Shards"), where the shard that holds a scene version is: its
// foreign server's host, port and database, as the coordinator's user (a password from ~/.pgpass,
// as for any client). Nothing on a store that is not sharded.
std::optional<std::string> shardHolding(Store& store, const std::string& url, std::int64_t key) {
    pg::Result r = store.connection().exec(
        "SELECT o.option_name, o.option_value FROM smql.scenes t JOIN pg_foreign_table f ON f.ftrelid = t.tableoid "
        "JOIN pg_foreign_server s ON s.oid = f.ftserver CROSS JOIN LATERAL pg_options_to_table(s.srvoptions) o "
        "WHERE t.id = $1 AND o.option_name IN ('host', 'port', 'dbname')",
        pg::Parameters().add(key), "finding the scene's shard");
    if (r.rows() == 0) return std::nullopt;
    std::string conninfo;
    for (int i = 0; i < r.rows(); ++i) conninfo += fmt::format("{}={} ", r.text(i, 0), conninfoValue(r.text(i, 1)));
    if (const std::string user = pg::urlParts(url).user; !user.empty()) conninfo += "user=" + conninfoValue(user);
    return conninfo;
}

// The AS OF a FIND or COUNT is written with, if any.
const ast::AsOf* asOfOf(const ast::Statement& statement) {
    if (const auto* find = std::get_if<ast::FindStmt>(&statement.body); find && find->asOf) return &*find->asOf;
    if (const auto* count = std::get_if<ast::CountStmt>(&statement.body); count && count->asOf) return &*count->asOf;
    return nullptr;
}

const ast::Statement& oneStatement(const std::vector<ast::Statement>& statements) {
    if (statements.size() != 1) throw Error(ErrorKind::Usage, "the fleet store runs one statement at a time");
    return statements.front();
}

}  // namespace

QueryAnswer runQuery(Store& store, const StoredVersion& scene, const std::string& statement) {
    const std::vector<ast::Statement> statements = parser::parse(statement);
    if (asOfOf(oneStatement(statements)))
        throw Error(ErrorKind::Usage, "AS OF chooses among a scene's versions: runQuery is given one", std::nullopt,
                    "run it in a StoreSession (smql URL) after USE SCENE");
    ResultSet result = run(store, scopeOf(store, {scene}, false), relations::Thresholds(), oneStatement(statements));
    QueryAnswer answer;
    if (result.columns.front().name == "count") {
        answer.count = std::get<std::int64_t>(result.rows.front().front());
        return answer;
    }
    for (const auto& row : result.rows) answer.ids.push_back(std::get<std::int64_t>(row.front()));
    return answer;
}

StoreSession::StoreSession(const std::string& url, std::string device)
    : url_(url), store_(url), device_(std::move(device)) {
    requireCurrentSchema(store_.connection());
}

void StoreSession::execute(const std::string& text, const std::function<void(ResultSet&&)>& onResult) {
    for (const ast::Statement& statement : parser::parse(text)) {
        if (const auto* chosen = std::get_if<ast::UseStmt>(&statement.body)) {
            onResult(use(chosen->scene));
            continue;
        }
        if (const auto* set = std::get_if<ast::SetStmt>(&statement.body)) {
            onResult(this->set(*set));
            continue;
        }
        if (const auto* show = std::get_if<ast::ShowStmt>(&statement.body);
            show && show->what == ast::ShowStmt::What::Scenes) {
            onResult(scenes());
            continue;
        }
        if (!scope_)
            throw Error(ErrorKind::Usage, "no scene chosen on the fleet store", std::nullopt,
                        "begin with USE SCENE 'name' (and --device ID when several devices hold that name)");
        if (const ast::AsOf* asOf = asOfOf(statement)) {
            const QueryScope past = scopeAsOf(*asOf);
            onResult(run(store_, past, thresholds_, statement));
            continue;
        }
        onResult(run(shard_ ? *shard_ : store_, *scope_, thresholds_, statement));
    }
}

// AS OF: the scene as the store held it at an instant, as the engine reads its history: the newest
// version captured at or before it.
QueryScope StoreSession::scopeAsOf(const ast::AsOf& asOf) {
    if (scope_->allScenes)
        throw Error(ErrorKind::Binding, "AS OF reads one scene's past", asOf.where, "USE SCENE 'name' first");
    pg::Result r = store_.connection().exec(
        "SELECT id, version, capture_time FROM smql.scenes WHERE device = $1 AND name = $2 ORDER BY version DESC",
        pg::Parameters().add(scope_->device).add(scope_->name), "reading the scene's versions");
    for (int i = 0; i < r.rows(); ++i)
        if (model::comparableInstant(r.text(i, 2)) <= asOf.instant)
            return scopeOf(
                store_, {{r.integer(i, 0), scope_->device, scope_->name, static_cast<std::uint64_t>(r.integer(i, 1))}},
                false);
    throw Error(ErrorKind::Binding,
                fmt::format("scene '{}' was first captured at {}: the store holds nothing of it at {}", scope_->name,
                            r.rows() ? r.text(r.rows() - 1, 2) : "", asOf.instant),
                asOf.where, "SHOW SCENES lists the scenes and when they were captured");
}

// SHOW SCENES on the store: the newest version of every scene (of the devices chosen), whose
// device, how many versions and nodes, when captured and pushed; `*` marks the scene in use.
ResultSet StoreSession::scenes() {
    pg::Result r = store_.connection().exec(
        "SELECT DISTINCT ON (device, name) name, device, version, node_count, capture_time, pushed_at, id FROM "
        "smql.scenes WHERE starts_with(device, $1) ORDER BY device, name, version DESC",
        pg::Parameters().add(device_), "listing the scenes");
    ResultSet out;
    out.columns = {{"name", ValueType::Text},     {"device", ValueType::Text},   {"version", ValueType::Integer},
                   {"nodes", ValueType::Integer}, {"captured", ValueType::Text}, {"pushed", ValueType::Text},
                   {"current", ValueType::Text}};
    for (int i = 0; i < r.rows(); ++i) {
        const bool current = scope_ && !scope_->allScenes && scope_->keys == fmt::format("{{{}}}", r.integer(i, 6));
        out.rows.push_back({std::string(r.text(i, 0)), std::string(r.text(i, 1)), r.integer(i, 2), r.integer(i, 3),
                            std::string(r.text(i, 4)), std::string(r.text(i, 5)), std::string(current ? "*" : "")});
    }
    return out;
}

// SET of a threshold, checked as the engine checks it; the session's other settings are the shell's.
ResultSet StoreSession::set(const ast::SetStmt& set) {
    if (catalog::findLimit(set.name))
        throw notYet(fmt::format("SET {} (the store's sessions have no limits)", set.name));
    const relations::SettingInfo* setting = relations::findSetting(set.name);
    if (!setting) {
        std::vector<std::string> names;
        for (const auto& s : relations::settingsCatalogue()) names.push_back(s.name);
        const auto close = model::nearestNames(set.name, names);
        throw Error(ErrorKind::Binding, fmt::format("unknown setting '{}'", set.name), set.where,
                    close.empty() ? "" : "did you mean " + model::joinAlternatives(close) + "?");
    }
    const auto* distance = std::get_if<ast::Distance>(&set.value);
    const auto* number = std::get_if<double>(&set.value);
    thresholds_.*(setting->field) =
        relations::settingValue(*setting, distance ? std::optional(distance->metres) : std::nullopt,
                                number ? std::optional(*number) : std::nullopt, set.where);
    ResultSet out;
    out.message = fmt::format("{} = {}", setting->name, thresholds_.*(setting->field));
    return out;
}

ResultSet StoreSession::use(const std::string& scene) {
    ResultSet out;
    if (scene == "*" || scene == "all") {
        std::vector<StoredVersion> newest = store_.newestVersions(device_);
        if (newest.empty()) throw Error(ErrorKind::Binding, "the fleet store holds no scene");
        scope_.reset();
        shard_.reset();
        scope_ = scopeOf(store_, newest, true);
        out.message = fmt::format("using all {} scenes of the fleet store, each its newest version", newest.size());
        return out;
    }
    std::vector<StoredVersion> versions = store_.versionsNamed(scene, device_);
    if (versions.empty())
        throw Error(ErrorKind::Binding, fmt::format("the fleet store has no scene named '{}'", scene));
    for (const auto& v : versions)
        if (v.device != versions.front().device)
            throw Error(ErrorKind::Binding, fmt::format("several devices hold a scene named '{}'", scene), std::nullopt,
                        "say whose with --device ID (the start of the id is enough)");
    const StoredVersion& chosen = versions.back();
    scope_.reset();
    shard_.reset();
    if (std::optional<std::string> shard = shardHolding(store_, url_, chosen.key)) shard_.emplace(*shard);
    scope_ = scopeOf(shard_ ? *shard_ : store_, {chosen}, false, &store_);
    out.message = fmt::format("using scene '{}', version {} of device {}", scene, chosen.version, chosen.device);
    return out;
}

}  // namespace smql::fleet
