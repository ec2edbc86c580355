#include "fleet/query.hpp"

#include <fmt/format.h>

#include "engine/parser/parser.hpp"
#include "fleet/schema.hpp"
#include "model/error.hpp"

namespace smql::fleet {

namespace {

// The categories the chosen scene versions hold, and whether any other stored scene holds a name.
QueryScope scopeOf(Store& store, const std::vector<StoredVersion>& scenes, bool allScenes) {
    QueryScope scope;
    scope.allScenes = allScenes;
    scope.name = allScenes ? "*" : scenes.front().scene;
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
    scope.nodeCategory = [&store, keys = scope.keys](const char* column,
                                                     std::int64_t value) -> std::optional<std::string> {
        pg::Result node = store.connection().exec(
            fmt::format("SELECT category FROM smql.nodes WHERE scene = ANY($1::int8[]) AND {} = $2 ORDER BY id LIMIT 1",
                        column),
            pg::Parameters().add(keys).add(value), "looking a node up");
        if (node.rows() == 0) return std::nullopt;
        return std::string(node.text(0, 0));
    };
    scope.knownElsewhere = [&store](const std::string& category) {
        return store.connection()
                   .exec("SELECT 1 FROM smql.nodes WHERE category = $1 LIMIT 1", pg::Parameters().add(category),
                         "looking a category up in the store")
                   .rows() > 0;
    };
    return scope;
}

ResultSet run(Store& store, const QueryScope& scope, const relations::Thresholds& thresholds,
              const ast::Statement& statement) {
    CompiledQuery query = compileQuery(statement, scope, thresholds);
    pg::Parameters parameters;
    parameters.add(scope.keys);
    for (const auto& p : query.parameters) parameters.add(p);
    pg::Result r = store.connection().exec(query.sql, parameters, fmt::format("running `{}`", statement.text));
    ResultSet out;
    if (query.count) {
        out.columns = {{"count", ValueType::Integer}};
        out.rows.push_back({r.integer(0, 0)});
        return out;
    }
    // FIND's columns, as the engine answers: id (here the scene's local id), category, the scene
    // when all scenes are asked, source id, box (none for a node without one), and NEAREST TO's distance.
    out.columns = {{"id", ValueType::Integer}, {"category", ValueType::Text}};
    if (scope.allScenes) out.columns.push_back({"scene", ValueType::Text});
    out.columns.push_back({"source_id", ValueType::Integer});
    out.columns.push_back({"box", ValueType::Box});
    if (query.distance) out.columns.push_back({"distance", ValueType::Real});
    const int shift = scope.allScenes ? 1 : 0;
    for (int i = 0; i < r.rows(); ++i) {
        std::vector<Value>& row = out.rows.emplace_back();
        row.emplace_back(r.integer(i, 0));
        row.emplace_back(std::string(r.text(i, 1)));
        if (scope.allScenes) row.emplace_back(std::string(r.text(i, 2)));
        if (r.null(i, 2 + shift))
            row.emplace_back();
        else
            row.emplace_back(r.integer(i, 2 + shift));
        auto at = [&](int column) { return r.real(i, column + shift); };
        if (r.text(i, 3 + shift) == "t")
            row.emplace_back(model::Box{{at(4), at(5), at(6)}, {at(7), at(8), at(9)}, at(10)});
        else
            row.emplace_back();
        if (query.distance) row.emplace_back(at(11));
    }
    return out;
}

const ast::Statement& oneStatement(const std::vector<ast::Statement>& statements) {
    if (statements.size() != 1) throw Error(ErrorKind::Usage, "the fleet store runs one statement at a time");
    return statements.front();
}

}  // namespace

QueryAnswer runQuery(Store& store, const StoredVersion& scene, const std::string& statement) {
    const std::vector<ast::Statement> statements = parser::parse(statement);
    ResultSet result = run(store, scopeOf(store, {scene}, false), relations::Thresholds(), oneStatement(statements));
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
        if (const auto* set = std::get_if<ast::SetStmt>(&statement.body)) {
            onResult(this->set(*set));
            continue;
        }
        if (!scope_)
            throw Error(ErrorKind::Usage, "no scene chosen on the fleet store", std::nullopt,
                        "begin with USE SCENE 'name' (and --device ID when several devices hold that name)");
        onResult(run(store_, *scope_, thresholds_, statement));
    }
}

// SET of a threshold, checked as the engine checks it; the session's other settings are the shell's.
ResultSet StoreSession::set(const ast::SetStmt& set) {
    const relations::SettingInfo* setting = relations::findSetting(set.name);
    if (!setting) throw notYet(fmt::format("SET {}", set.name));
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
    scope_ = scopeOf(store_, {chosen}, false);
    out.message = fmt::format("using scene '{}', version {} of device {}", scene, chosen.version, chosen.device);
    return out;
}

}  // namespace smql::fleet
