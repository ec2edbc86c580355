#include "fleet/query_sql.hpp"

#include <fmt/format.h>

#include "engine/ask/lexicon.hpp"
#include "engine/catalog/attributes.hpp"
#include "engine/parser/ast.hpp"
#include "engine/parser/parser.hpp"
#include "model/category.hpp"
#include "model/error.hpp"
#include "model/names.hpp"
#include "relations/predicates.hpp"
#include "relations/viewer.hpp"

namespace smql::fleet {

Error notYet(const std::string& what) {
    return Error(ErrorKind::Usage, fmt::format("the fleet store does not run {} yet", what), std::nullopt,
                 "it runs COUNT and FIND with WHERE, NEAREST TO, ORDER BY and LIMIT, and SET of thresholds "
                 "(docs/fleet.md, \"SMQL on the store\"); pull the scene to ask anything else");
}

namespace {

// Text as a number where all of it is one ("2" captures), as the engine reads stored attributes.
std::string numberIn(const std::string& text) {
    return fmt::format(
        "CASE WHEN {0} ~ '^\\s*[-+]?([0-9]+[.]?[0-9]*|[.][0-9]+)([eE][-+]?[0-9]+)?$' THEN "
        "{0}::float8 END",
        text);
}

// A node's label as RELATE and PATH write it ("sofa#12"; a scene's root by its name), in SQL.
std::string labelSql(const std::string& a) { return fmt::format("{0}.category || '#' || {0}.id", a); }

// An attribute of the row `a` as SQL: its value (NULL where the node has none) as the engine's
// catalog::attributeValue gives it, typed as its RETURN column. Stored attributes are text.
struct AttributeSql {
    std::string value;
    ValueType type = ValueType::Text;
    bool number() const { return type == ValueType::Integer || type == ValueType::Real; }
    // As WHERE and ORDER BY compare it: numbers as float8.
    std::string comparable() const { return number() ? fmt::format("({})::float8", value) : value; }
};

std::string rootName(const std::string& a) {
    return fmt::format("(SELECT name FROM smql.scenes WHERE id = {}.scene)", a);
}

// The way from the scene down to the node: "room0 / wall#3 / sofa#12".
std::string pathSql(const std::string& a) {
    return fmt::format(
        "(WITH RECURSIVE up(id, parent, label, depth) AS (SELECT {0}.id, {0}.parent, {1}, 0 UNION ALL SELECT p.id, "
        "p.parent, {2}, up.depth + 1 FROM up JOIN smql.nodes p ON p.scene = {0}.scene AND p.id = up.parent) SELECT "
        "{3} || ' / ' || string_agg(label, ' / ' ORDER BY depth DESC) FROM up)",
        a, labelSql(a), labelSql("p"), rootName(a));
}

// A stored attribute of the row `a`, its name the parameter `name`.
std::string storedSql(const std::string& a, const std::string& name) {
    return fmt::format(
        "(SELECT t.value FROM smql.attributes t WHERE t.scene = {0}.scene AND t.node = {0}.id AND "
        "t.name = {1} ORDER BY t.position LIMIT 1)",
        a, name);
}

std::optional<AttributeSql> builtInSql(std::string_view name, const std::string& a) {
    using T = ValueType;
    // The measures of a box need a box.
    const auto placed = [&](const std::string& v, T type = T::Real) {
        return AttributeSql{fmt::format("CASE WHEN {}.geometry <> 0 THEN {} END", a, v), type};
    };
    if (name == "id") return AttributeSql{a + ".id", T::Integer};
    if (name == "category") return AttributeSql{a + ".category"};
    if (name == "text") return AttributeSql{a + ".text"};
    if (name == "source_id") return AttributeSql{a + ".source_id", T::Integer};
    if (name == "confidence") return AttributeSql{a + ".confidence::float8", T::Real};
    if (name == "kind") {
        std::string cases;
        for (int k = 0; k <= static_cast<int>(model::NodeKind::Frame); ++k)
            cases += fmt::format(" WHEN {} THEN '{}'", k, model::toString(static_cast<model::NodeKind>(k)));
        return AttributeSql{fmt::format("(CASE {}.kind{} END)", a, cases)};
    }
    if (name == "height") return placed(a + ".sz");
    if (name == "width") return placed(fmt::format("greatest({0}.sx, {0}.sy)", a));
    if (name == "depth") return placed(fmt::format("least({0}.sx, {0}.sy)", a));
    if (name == "volume") return placed(fmt::format("{0}.sx * {0}.sy * {0}.sz", a));
    if (name == "x") return placed(a + ".cx");
    if (name == "y") return placed(a + ".cy");
    if (name == "z") return placed(a + ".cz");
    if (name == "center")
        return placed(fmt::format("'(' || round({0}.cx::numeric, 3) || ', ' || round({0}.cy::numeric, 3) || ', ' || "
                                  "round({0}.cz::numeric, 3) || ')'",
                                  a),
                      T::Text);
    if (name == "box")
        return placed(fmt::format("ARRAY[{0}.cx, {0}.cy, {0}.cz, {0}.sx, {0}.sy, {0}.sz, {0}.yaw]", a), T::Box);
    if (name == "parent")
        return AttributeSql{
            fmt::format("CASE WHEN {0}.parent = 0 THEN {1} ELSE (SELECT {2} FROM smql.nodes p WHERE "
                        "p.scene = {0}.scene AND p.id = {0}.parent) END",
                        a, rootName(a), labelSql("p"))};
    if (name == "path") return AttributeSql{pathSql(a)};
    return std::nullopt;
}

// One statement compiled to one SQL query. Candidates are `n<k>` aliases of smql.nodes, references
// `r<k>` and `s<k>`; every alias of a statement has its own number. $1 is the scene versions'
// keys; literals follow as parameters, so no text of the statement is spliced into the SQL.
class Compiler {
public:
    Compiler(const QueryScope& scope, const relations::Thresholds& thresholds)
        : scope_(scope), thresholds_(thresholds), frame_(relations::viewFrame(scope.viewpoint)) {}

    CompiledQuery statement(const ast::Statement& statement) {
        CompiledQuery out;
        std::string select;
        if (const auto* find = std::get_if<ast::FindStmt>(&statement.body)) {
            resolveView(find->view);
            select = this->find(*find, &out);
        } else if (const auto* c = std::get_if<ast::CountStmt>(&statement.body)) {
            resolveView(c->view);
            select =
                fmt::format("SELECT count(*) FROM ({}) counted", nodesOf(c->target, c->where, nullptr, ids, false));
            out.shape = CompiledQuery::Shape::Count;
        } else if (const auto* r = std::get_if<ast::RelateStmt>(&statement.body)) {
            select = relate(*r, out);
            out.shape = CompiledQuery::Shape::Relate;
        } else if (const auto* c = std::get_if<ast::CheckStmt>(&statement.body)) {
            select = check(*c, out);
            out.shape = CompiledQuery::Shape::Check;
        } else if (const auto* d = std::get_if<ast::DescribeStmt>(&statement.body)) {
            if (scope_.allScenes) throw notYet("DESCRIBE across all scenes");
            select = nodesOf(d->target, std::nullopt, nullptr, [](const std::string& n, const std::string&) {
                return fmt::format(
                    "{0}.id, {0}.kind, {0}.category, {0}.geometry, {0}.cx, {0}.cy, {0}.cz, {0}.sx, "
                    "{0}.sy, {0}.sz, {0}.yaw, {0}.hidden, {0}.confidence, {0}.source_id, {0}.text, {0}.scene, {1}",
                    n, pathSql(n));
            });
            out.shape = CompiledQuery::Shape::Describe;
        } else if (const auto* show = std::get_if<ast::ShowStmt>(&statement.body);
                   show && show->what == ast::ShowStmt::What::Tree) {
            select = tree(*show, out);
            out.shape = CompiledQuery::Shape::Tree;
        } else {
            throw notYet(fmt::format("'{}'", statement.text));
        }
        out.sql = withContext(select);
        out.parameters = std::move(parameters_);
        return out;
    }

private:
    // A query with the CTE its predicates read, if they do: the frame of the view-relative
    // predicates (the scene's viewpoint) and the nodes that may stand between (near's walls,
    // visible_from's obstacles: the visible nodes with geometry, as the engine's R-tree holds
    // them), once per scene version.
    std::string withContext(const std::string& select) {
        if (!usesContext_) return select;
        // VIEW FROM's viewer, resolved here, or each scene's own viewpoint.
        const std::string viewpoint =
            view_ ? parameter(fmt::format("{{{},{},{},{},{}}}", view_->position.x, view_->position.y, view_->position.z,
                                          view_->facingYaw, frame_.headingGiven ? 1 : 0)) +
                        "::float8[]"
                  : "ARRAY[s.viewpoint_x, s.viewpoint_y, s.viewpoint_z, s.viewpoint_yaw]";
        return fmt::format(
                   "WITH context AS (SELECT s.id AS scene, {} AS viewpoint, (SELECT coalesce(array_agg(o ORDER BY "
                   "o.id), '{{}}') FROM smql.nodes o WHERE o.scene = s.id AND o.geometry <> 0 AND NOT o.hidden) AS "
                   "others, (SELECT coalesce(array_agg(o ORDER BY o.id), '{{}}') FROM smql.nodes o WHERE o.scene = "
                   "s.id AND o.geometry <> 0 AND NOT o.hidden AND o.category = '{}') AS walls FROM smql.scenes s "
                   "WHERE s.id = ANY($1::int8[])) ",
                   viewpoint, relations::kWall) +
               select;
    }

    // A compiler for a part of this statement that runs on its own (its own parameters), with
    // this statement's viewer.
    Compiler part() const {
        Compiler part(scope_, thresholds_);
        part.view_ = view_;
        part.frame_ = frame_;
        return part;
    }

    // A query of the nodes `ref` names, with parameters of its own, for a side that must be one node.
    CompiledQuery::Single single(std::string role, const ast::Ref& ref) const {
        Compiler nodes = part();
        const std::string select = nodes.nodesOf(ref, std::nullopt, nullptr, ids);
        return {std::move(role), nodes.withContext(select), std::move(nodes.parameters_)};
    }

    // The nodes `ref` names, located, in id order.
    std::vector<QueryScope::Located> located(const ast::Ref& ref) const {
        Compiler nodes = part();
        const std::string select =
            nodes.nodesOf(ref, std::nullopt, nullptr, [](const std::string& n, const std::string&) {
                return fmt::format("{0}.id, {0}.cx, {0}.cy, {0}.cz, {0}.geometry <> 0 AND NOT {0}.hidden", n);
            });
        return scope_.locate(nodes.withContext(select), nodes.parameters_);
    }

    // One node `ref` names, for `role` (VIEW FROM, FACING).
    QueryScope::Located oneLocated(const ast::Ref& ref, std::string_view role) const {
        const std::vector<QueryScope::Located> nodes = located(ref);
        if (nodes.size() != 1)
            throw Error(ErrorKind::Binding, fmt::format("{} must be one node; it names {}", role, nodes.size()),
                        ref.where, "name one, as in door#12, or pick one by place with a sub-query");
        return nodes.front();
    }

    // VIEW FROM x [FACING y]: the viewer at x's centre, looking at y or into the room (the middle of
    // the visible boxes), as the engine's executor places it (relations/viewer.hpp).
    void resolveView(const std::optional<ast::View>& view) {
        if (!view) return;
        if (scope_.allScenes)
            throw Error(ErrorKind::Binding, "a viewpoint belongs to one scene", view->where, "USE SCENE 'name'");
        const model::Vec3 origin = oneLocated(view->from, "VIEW FROM").centre;
        model::Vec2 towards;
        if (view->facing) {
            const model::Vec3 facing = oneLocated(*view->facing, "FACING").centre;
            towards = {facing.x, facing.y};
        } else {
            std::vector<model::Vec2> centres;
            ast::Ref everything{ast::Ref::Kind::Name, "node", {}, 0, nullptr, {}, view->where};
            for (const auto& node : located(everything))
                if (node.shown) centres.push_back({node.centre.x, node.centre.y});
            towards = relations::middleOf(centres, origin);
        }
        view_ = relations::lookingAt(origin, towards);
        if (!view_)
            throw Error(ErrorKind::Binding, "VIEW: the viewer and what it faces are at the same place", view->where);
        frame_ = relations::viewFrame(*view_);
        frame_.headingGiven = view->facing.has_value();
    }

    // `wall.left`: of the nodes the name names, the one farthest out on that side of the viewer.
    std::string side(const ast::Ref& ref, const std::string& a) {
        if (scope_.allScenes)
            throw Error(ErrorKind::Binding, "a side of the room belongs to one scene's viewpoint", ref.where,
                        "USE SCENE 'name'");
        ast::Ref named = ref;
        named.kind = ast::Ref::Kind::Name;
        named.side.clear();
        std::vector<QueryScope::Located> candidates;
        std::vector<model::Vec2> centres;
        for (const auto& node : located(named))
            if (node.shown) candidates.push_back(node), centres.push_back({node.centre.x, node.centre.y});
        const std::optional<std::size_t> chosen = relations::farthestOnSide(frame_, ref.side, centres);
        if (!chosen)
            throw Error(
                ErrorKind::Binding,
                fmt::format("no {} on the {} side of the viewpoint in scene '{}'", ref.name, ref.side, scope_.name),
                ref.where, "SHOW SCENES gives the default viewpoint; VIEW FROM x FACING y sets another");
        return fmt::format("{}.id = {}", a, parameter(std::to_string(candidates[*chosen].id)));
    }

    static std::string ids(const std::string& n, const std::string&) { return n + ".id"; }

    // The relations that hold from one node to another.
    std::string relate(const ast::RelateStmt& relate, CompiledQuery& out) {
        if (scope_.allScenes) throw notYet("RELATE across all scenes");
        resolveView(relate.view);
        usesContext_ = true;
        out.singles.push_back(single("RELATE's subject", relate.subject));
        out.singles.push_back(single("RELATE's object", relate.object));
        const std::string a = alias('a'), b = alias('b');
        return fmt::format(
            "SELECT {0}.id, {0}.category, {0}.kind, {1}.id, {1}.category, {1}.kind, smql.relate({0}, {1}, "
            "context.viewpoint, context.others, {2}), smql.box_distance({0}, {1}) FROM smql.nodes {0} JOIN context ON "
            "context.scene = {0}.scene JOIN smql.nodes {1} ON {1}.scene = {0}.scene AND {1}.id <> {0}.id WHERE "
            "{0}.scene = ANY($1::int8[]) AND {3} AND {4} ORDER BY {0}.id, {1}.id",
            a, b, thresholds(), refers(relate.subject, a), refers(relate.object, b));
    }

    // Whether one predicate holds over single nodes (0 for a node paired with itself).
    std::string check(const ast::CheckStmt& check, CompiledQuery& out) {
        if (scope_.allScenes) throw notYet("CHECK across all scenes");
        resolveView(check.view);
        const relations::PredicateSpec& spec =
            predicateSpec(check.predicate, check.args.size(), check.threshold.has_value(), check.predicateWhere);
        usesContext_ = true;
        out.relation = spec.name();
        out.third = spec.arity == 2;
        const std::string a = alias('a'), b = alias('b'), c = alias('c');
        out.singles.push_back(single("CHECK's subject", check.subject));
        for (const ast::Ref& arg : check.args) out.singles.push_back(single("CHECK's object", arg));
        std::string columns = fmt::format("{0}.id, {0}.category, {0}.kind, {1}.id, {1}.category, {1}.kind", a, b);
        std::string from = fmt::format(
            "smql.nodes {0} JOIN context ON context.scene = {0}.scene JOIN smql.nodes {1} "
            "ON {1}.scene = {0}.scene",
            a, b);
        std::string where = fmt::format("{} AND {}", refers(check.subject, a), refers(check.args[0], b));
        std::string same = fmt::format("{0}.id = {1}.id", a, b);
        std::string arguments = fmt::format("{}, {}", a, b);
        if (out.third) {
            columns += fmt::format(", {0}.id, {0}.category, {0}.kind", c);
            from += fmt::format(" JOIN smql.nodes {0} ON {0}.scene = {1}.scene", c, a);
            where += " AND " + refers(check.args[1], c);
            same += fmt::format(" OR {0}.id = {1}.id OR {2}.id = {1}.id", a, c, b);
            arguments += ", " + c;
        }
        const std::string distance =
            check.threshold ? fmt::format(", {}::float8", parameter(fmt::format("{}", check.threshold->metres))) : "";
        return fmt::format(
            "SELECT {0}, CASE WHEN {1} THEN 0 ELSE smql.\"{2}\"({3}, context.viewpoint, {10}{4}, {5}) END, "
            "smql.box_distance({6}, {7}) FROM {8} WHERE {6}.scene = ANY($1::int8[]) AND {9}",
            columns, same, spec.name(), arguments, spec.takesDistance ? distance.empty() ? ", NULL" : distance : "",
            thresholds(), a, b, from, where, occluders(spec, a));
    }

    // The nodes that may stand between, as far as the predicate's formula asks (the table's
    // occluders): every call gets them whole, so a predicate that asks nothing gets nothing, and one that
    // asks for every node only where `subject` is of a spreading kind gets the walls elsewhere: PostgreSQL
    // hands each call its array, and a FIND on(table) of 200 objects took 8.3 ms with every node for every
    // pair and 3.9-4.1 ms with them for lamps and plants alone (docs/benchmarks.md).
    std::string occluders(const relations::PredicateSpec& spec, const std::string& subject) {
        switch (spec.occluders) {
            case relations::Occluders::Walls:
                return "context.walls";
            case relations::Occluders::WallsOrAllWhenSpreading: {
                std::string kinds;
                for (std::string_view kind : relations::spreadingKinds())
                    kinds += fmt::format("{}\"{}\"", kinds.empty() ? "" : ",", kind);
                return fmt::format("CASE WHEN {}.category = ANY({}::text[]) THEN context.others ELSE context.walls END",
                                   subject, parameter("{" + kinds + "}"));
            }
            case relations::Occluders::All:
                return "context.others";
            case relations::Occluders::None:
                break;
        }
        return "NULL::smql.nodes[]";
    }

    // SHOW TREE [x]: the scene's tree (its root is 0 on the store) or the subtree under one node,
    // depth-first with children in id order; hidden nodes, descriptions and frames left out, with
    // what hangs below them.
    std::string tree(const ast::ShowStmt& show, CompiledQuery& out) {
        if (scope_.allScenes) throw notYet("SHOW TREE across all scenes");
        const std::string shown =
            fmt::format("NOT {{0}}.hidden AND {{0}}.kind NOT IN ({}, {})",
                        static_cast<int>(model::NodeKind::Description), static_cast<int>(model::NodeKind::Frame));
        std::string start = fmt::format("SELECT 0, 0, ARRAY[0], {}", rootName("s"));
        std::string startFrom = " FROM (SELECT min(id) AS scene FROM unnest($1::int8[]) AS id) s";
        if (show.root) {
            out.singles.push_back(single("SHOW TREE's node", *show.root));
            const std::string r = alias('r');
            start = fmt::format("SELECT {0}.id, 0, ARRAY[{0}.id], {1}", r, labelSql(r));
            startFrom = fmt::format(" FROM smql.nodes {0} WHERE {0}.scene = ANY($1::int8[]) AND {1} AND {2}", r,
                                    refers(*show.root, r), fmt::format(fmt::runtime(shown), r));
        }
        return fmt::format(
            "WITH RECURSIVE tree(id, depth, trail, label) AS ({0}{1} UNION ALL SELECT c.id, t.depth + 1, t.trail || "
            "c.id, {2} FROM tree t JOIN smql.nodes c ON c.scene = ANY($1::int8[]) AND c.parent = t.id WHERE {3}) "
            "SELECT id, depth, repeat('  ', depth) || label FROM tree ORDER BY trail",
            start, startFrom, labelSql("c"), fmt::format(fmt::runtime(shown), "c"));
    }

    // The predicate a WHERE or CHECK names, checked for its references and distance as the binder does.
    static const relations::PredicateSpec& predicateSpec(const std::string& name, std::size_t references, bool distance,
                                                         SourceLocation where) {
        const relations::PredicateSpec* spec = relations::predicateNamed(name);
        if (!spec) throw Error(ErrorKind::Binding, fmt::format("no predicate named '{}'", name), where);
        if (references != static_cast<std::size_t>(spec->arity))
            throw Error(ErrorKind::Binding,
                        fmt::format("{} takes {} reference{}", spec->name(), spec->arity, spec->arity == 1 ? "" : "s"),
                        where);
        if (distance && !spec->takesDistance)
            throw Error(ErrorKind::Binding, fmt::format("{} takes no distance", spec->name()), where);
        return *spec;
    }

    // A FIND, with its columns when `out` is the statement's (a sub-query's answer is its nodes).
    std::string find(const ast::FindStmt& find, CompiledQuery* out) {
        // AS OF chose the scene version the scope holds (fleet/query.cpp); a sub-query's is refused
        // where it is written.
        if (find.similarTo || find.limitParam) throw notYet("FIND with SIMILAR TO");
        if (find.nearestTo && find.orderBy)
            throw Error(ErrorKind::Binding, "NEAREST TO and ORDER BY both set an order", find.orderBy->where,
                        "keep one: NEAREST TO x is ORDER BY distance(x) without x itself");
        const bool distance = find.nearestTo || (find.orderBy && find.orderBy->distanceTo);
        Columns columns = [](const std::string& n, const std::string&) { return fmt::format("{0}.scene, {0}.id", n); };
        if (out) {
            out->distance = distance;
            out->path = find.path;
            columns = find.columns.empty() ? defaultColumns(*out) : returnedColumns(find, *out);
        }
        std::string limit = find.limit ? fmt::format(" LIMIT {}", *find.limit) : "";
        return nodesOf(find.target, find.where, &find, columns) + limit;
    }

    // The SELECT list of a FIND's candidates `n`, given the distance's SQL (empty without one).
    using Columns = std::function<std::string(const std::string& n, const std::string& distance)>;

    // FIND's own columns: id (the scene's local id), category, the scene when all scenes are
    // asked, source id, whether placed and the box; then the distance and the path when asked.
    Columns defaultColumns(const CompiledQuery& out) const {
        return [this, &out](const std::string& n, const std::string& distance) {
            std::string list = fmt::format("{0}.id, {0}.category, ", n);
            if (scope_.allScenes) list += rootName(n) + ", ";
            list += fmt::format(
                "{0}.source_id, {0}.geometry <> 0, {0}.cx, {0}.cy, {0}.cz, {0}.sx, {0}.sy, {0}.sz, "
                "{0}.yaw",
                n);
            if (out.distance) list += ", " + distance;
            if (out.path) list += ", " + pathSql(n);
            return list;
        };
    }

    // RETURN a, b: each an attribute (typed as SHOW ATTRIBUTES says) or the distance; then the path.
    Columns returnedColumns(const ast::FindStmt& find, CompiledQuery& out) {
        out.shape = CompiledQuery::Shape::Return;
        std::vector<std::function<std::string(const std::string&, const std::string&)>> values;
        for (const std::string& column : find.columns) {
            const bool builtIn = catalog::builtInAttribute(column) != nullptr;
            if (column == "distance" && out.distance && !builtIn) {
                out.returned.emplace_back(column, ValueType::Real);
                values.emplace_back([](const std::string&, const std::string& distance) { return distance; });
                continue;
            }
            if (!builtIn && !scope_.attributes.count(column)) {
                std::vector<std::string> names;
                for (const auto& attribute : catalog::builtInAttributes()) names.emplace_back(attribute.name);
                names.insert(names.end(), scope_.attributes.begin(), scope_.attributes.end());
                if (out.distance) names.emplace_back("distance");
                const auto close = model::nearestNames(column, names);
                throw Error(ErrorKind::Binding, fmt::format("unknown column '{}' in RETURN", column), find.returnWhere,
                            close.empty() ? "SHOW ATTRIBUTES lists the columns"
                                          : fmt::format("did you mean {}? SHOW ATTRIBUTES lists the columns",
                                                        model::joinAlternatives(close)));
            }
            // Stored attributes are text; the name is a parameter, fixed now.
            const std::string stored = builtIn ? "" : parameter(column);
            out.returned.emplace_back(column, builtIn ? builtInSql(column, "n")->type : ValueType::Text);
            values.emplace_back([column, stored](const std::string& n, const std::string&) {
                return stored.empty() ? builtInSql(column, n)->value : storedSql(n, stored);
            });
        }
        return [values, &out](const std::string& n, const std::string& distance) {
            std::string list;
            for (const auto& value : values) list += (list.empty() ? "" : ", ") + value(n, distance);
            if (out.path) list += (list.empty() ? "" : ", ") + pathSql(n);
            return list;
        };
    }

    // The target's nodes that meet `where`, in the order FIND gives them (in no order, for COUNT,
    // when neither `order` nor `sortedById`).
    std::string nodesOf(const ast::Ref& target, const std::optional<ast::Expr>& where, const ast::FindStmt* order,
                        const Columns& columns, bool sortedById = true) {
        const std::string n = alias('n');
        std::string conditions = fmt::format("{0}.scene = ANY($1::int8[]) AND {1}", n, refers(target, n));
        if (where) conditions += " AND " + condition(*where, n);
        std::string from;
        std::string sorted = fmt::format("{0}.scene, {0}.id", n);
        std::string distance;
        if (order) distance = orderBy(*order, n, from, conditions, sorted);
        if (usesContext_) from = fmt::format(" JOIN context ON context.scene = {}.scene", n) + from;
        return fmt::format("SELECT {} FROM smql.nodes {}{} WHERE {}{}", columns(n, distance), n, from, conditions,
                           sortedById || order ? " ORDER BY " + sorted : "");
    }

    // NEAREST TO x, ORDER BY distance(x), ORDER BY an attribute: the engine's orders, ties in id
    // order. Returns the distance's SQL, when there is one.
    std::string orderBy(const ast::FindStmt& find, const std::string& n, std::string& from, std::string& conditions,
                        std::string& sorted) {
        const ast::Ref* to = find.nearestTo                             ? &*find.nearestTo
                             : find.orderBy && find.orderBy->distanceTo ? &*find.orderBy->distanceTo
                                                                        : nullptr;
        const bool descending = find.orderBy && find.orderBy->descending;
        if (to) {
            const std::string d = alias('d'), x = alias('x');
            from += fmt::format(
                " CROSS JOIN LATERAL (SELECT min(smql.box_distance({0}, {1})) AS distance FROM smql.nodes {1} "
                "WHERE {1}.scene = {0}.scene AND {1}.id <> {0}.id AND {2}) {3}",
                n, x, refers(*to, x), d);
            // A node's distance is to the others of x, as in the engine: nodes without a place, or
            // with nothing else to measure to, have none; NEAREST TO x leaves x itself out.
            conditions += fmt::format(" AND {}.geometry <> 0 AND {}.distance IS NOT NULL", n, d);
            if (find.nearestTo) conditions += fmt::format(" AND NOT ({})", refers(*to, n));
            sorted = fmt::format("{}.distance{}, {}", d, descending ? " DESC" : "", sorted);
            return d + ".distance";
        }
        if (!find.orderBy) return "";
        const std::string& name = find.orderBy->attribute;
        if (name == "distance" && !catalog::builtInAttribute(name))
            throw Error(ErrorKind::Binding, "ORDER BY distance needs what to measure from", find.orderBy->where,
                        "as in ORDER BY distance(door)");
        const AttributeSql value = attribute(name, n, find.orderBy->where);
        // Numbers, then text (case-insensitively), then nodes without the attribute, in either direction.
        const std::string number = value.number() ? value.comparable() : numberIn(value.value);
        const std::string text = value.number() ? "NULL::text" : fmt::format("lower({} COLLATE \"C\")", value.value);
        const char* direction = descending ? " DESC" : "";
        sorted = fmt::format(
            "CASE WHEN {0} IS NOT NULL THEN 0 WHEN {1} IS NOT NULL THEN 1 ELSE 2 END, {0}{3}, {2} "
            "COLLATE \"C\"{3}, {4}",
            number, value.value, text, direction, sorted);
        return "";
    }

    std::string condition(const ast::Expr& expr, const std::string& candidate) {
        switch (expr.kind) {
            case ast::Expr::Kind::And:
            case ast::Expr::Kind::Or: {
                std::string out;
                for (const ast::Expr& child : expr.children)
                    out += (out.empty()                         ? ""
                            : expr.kind == ast::Expr::Kind::And ? " AND "
                                                                : " OR ") +
                           condition(child, candidate);
                return "(" + out + ")";
            }
            case ast::Expr::Kind::Not:
                return "NOT " + condition(expr.children.front(), candidate);
            case ast::Expr::Kind::Predicate:
                return predicate(expr, candidate);
            case ast::Expr::Kind::Compare:
                return comparison(expr, candidate);
        }
        return "false";
    }

    // Whether some reference (some pair, for the predicates of two) other than the candidate makes
    // the predicate hold. The references of a predicate that holds only near them are probed with
    // the region the predicate's table row gives (smql.predicate_region), as the engine's planner does.
    std::string predicate(const ast::Expr& expr, const std::string& n) {
        const relations::PredicateSpec* spec =
            &predicateSpec(expr.predicate, expr.args.size(), expr.threshold.has_value(), expr.where);
        usesContext_ = true;
        const std::string distance =
            expr.threshold ? fmt::format("{}::float8", parameter(fmt::format("{}", expr.threshold->metres))) : "NULL";
        const std::string r = alias('r');
        std::string from = fmt::format("smql.nodes {}", r);
        std::string where =
            fmt::format("{0}.scene = {1}.scene AND {0}.id <> {1}.id AND {2}", r, n, refers(expr.args[0], r));
        std::string arguments = fmt::format("{}, {}", n, r);
        if (spec->arity == 2) {
            const std::string s = alias('s');
            from += fmt::format(" JOIN smql.nodes {0} ON {0}.scene = {1}.scene", s, r);
            where +=
                fmt::format(" AND {0}.id <> {1}.id AND {0}.id <> {2}.id AND {3}", s, n, r, refers(expr.args[1], s));
            arguments += ", " + s;
        } else if (spec->local()) {
            const std::string g = alias('g');
            from += fmt::format(", LATERAL smql.predicate_region({}, {}, {}, {}) AS {}(g)",
                                static_cast<int>(spec->predicate), r, distance, thresholds(), g);
            where += fmt::format(
                " AND {0}.footprint && ST_MakeEnvelope({1}.g[1], {1}.g[2], {1}.g[4], {1}.g[5]) AND "
                "{0}.max_z >= {1}.g[3] AND {0}.min_z <= {1}.g[6]",
                n, g);
        }
        return fmt::format("EXISTS (SELECT 1 FROM {} WHERE {} AND smql.\"{}\"({}, context.viewpoint, {}{}, {}) > 0)",
                           from, where, spec->name(), arguments, occluders(*spec, n),
                           spec->takesDistance ? ", " + distance : "", thresholds());
    }

    // `color = 'red'`, `height > 80 cm`, `distance(sofa) < 2 m`: false where the node has no such
    // value, as in the engine (and never NULL, so NOT reads it as the engine does).
    std::string comparison(const ast::Expr& expr, const std::string& n) {
        // `color IS NULL`: whether the node has it, of any attribute (a box too), as in the engine.
        if (expr.op == ast::CompareOp::IsNull || expr.op == ast::CompareOp::IsNotNull) {
            const catalog::AttributeInfo* builtIn = catalog::builtInAttribute(expr.attribute);
            const std::string value = builtIn && builtIn->measure == catalog::AttributeMeasure::None
                                          ? builtInSql(expr.attribute, n)->value
                                          : attribute(expr.attribute, n, expr.where).value;
            return fmt::format("({}) {}", value, ast::toString(expr.op));
        }
        if (expr.literalParam) throw notYet("placeholders");
        const catalog::LiteralForm form{std::holds_alternative<std::string>(expr.literal), expr.literalHasUnit,
                                        expr.literalBound};
        AttributeSql value;
        std::string placed;
        if (expr.distanceTo) {
            catalog::checkLiteral(catalog::AttributeMeasure::Length, form, "distance()", expr.where);
            const std::string r = alias('r');
            value = {fmt::format("(SELECT min(smql.box_distance({0}, {1})) FROM smql.nodes {1} WHERE {1}.scene = "
                                 "{0}.scene AND {1}.id <> {0}.id AND {2})",
                                 n, r, refers(*expr.distanceTo, r)),
                     ValueType::Real};
            placed = fmt::format("{}.geometry <> 0 AND ", n);
        } else {
            // The store's ids are the scene's local ids, not the device's a statement would compare with.
            if (expr.attribute == "id") throw notYet("comparisons of id");
            value = attribute(expr.attribute, n, expr.where);
            const catalog::AttributeInfo* builtIn = catalog::builtInAttribute(expr.attribute);
            catalog::checkLiteral(builtIn ? builtIn->measure : catalog::AttributeMeasure::Text, form, expr.attribute,
                                  expr.where);
        }
        if (const auto* text = std::get_if<std::string>(&expr.literal)) {
            const std::string have = value.number() ? value.comparable() + "::text" : value.value;
            // A category compares by its canonical name, as in the engine's binder ('Trash Bins' is
            // trash-bin; a LIKE pattern 'Trash Bin%' is trash-bin%).
            const bool category = expr.attribute == "category";
            if (expr.op == ast::CompareOp::Like)
                return fmt::format("coalesce({}{} ILIKE {} ESCAPE '', false)", placed, have,
                                   parameter(category ? model::categoryPattern(*text) : *text));
            return fmt::format("coalesce({}lower({} COLLATE \"C\") {} {} COLLATE \"C\", false)", placed, have,
                               ast::toString(expr.op),
                               parameter(category ? model::categoryName(*text) : parser::lowerCase(*text)));
        }
        if (expr.op == ast::CompareOp::Like) return "false";
        const std::string literal = std::holds_alternative<double>(expr.literal)
                                        ? fmt::format("{}", std::get<double>(expr.literal))
                                        : fmt::format("{}", std::get<std::int64_t>(expr.literal));
        return fmt::format("coalesce({}{} {} {}::float8, false)", placed,
                           value.number() ? value.comparable() : numberIn(value.value), ast::toString(expr.op),
                           parameter(literal));
    }

    // An attribute a comparison or ORDER BY can use, as the engine's binder allows it.
    AttributeSql attribute(const std::string& name, const std::string& a, SourceLocation where) {
        if (const catalog::AttributeInfo* builtIn = catalog::builtInAttribute(name)) {
            if (builtIn->measure == catalog::AttributeMeasure::None)
                throw Error(ErrorKind::Binding, fmt::format("{} cannot be compared or ordered", name), where,
                            "compare its parts: x, y, z, height, width, depth, volume; RETURN shows it");
            return *builtInSql(name, a);
        }
        if (!scope_.attributes.count(name)) {
            std::vector<std::string> names;
            for (const auto& attribute : catalog::builtInAttributes())
                if (attribute.measure != catalog::AttributeMeasure::None) names.emplace_back(attribute.name);
            names.insert(names.end(), scope_.attributes.begin(), scope_.attributes.end());
            const auto close = model::nearestNames(name, names);
            throw Error(
                ErrorKind::Binding, fmt::format("unknown attribute '{}' in scene '{}'", name, scope_.name), where,
                close.empty()
                    ? "SHOW ATTRIBUTES lists them"
                    : fmt::format("did you mean {}? SHOW ATTRIBUTES lists them", model::joinAlternatives(close)));
        }
        return {storedSql(a, parameter(name))};
    }

    // The condition that the node `a` is one of those `ref` names.
    std::string refers(const ast::Ref& ref, const std::string& a) {
        switch (ref.kind) {
            case ast::Ref::Kind::Name:
                if (auto kind = ast::kindWord(ref.name))
                    return fmt::format("{0}.kind = {1} AND NOT {0}.hidden", a, static_cast<int>(*kind));
                if (ast::anyNodeWord(ref.name))
                    return fmt::format("{0}.kind <> {1} AND NOT {0}.hidden", a,
                                       static_cast<int>(model::NodeKind::Scene));
                if (ast::thingWord(ref.name))
                    return fmt::format(
                        "{0}.kind IN ({1}, {2}, {3}) AND NOT {0}.hidden", a, static_cast<int>(model::NodeKind::Object),
                        static_cast<int>(model::NodeKind::Anchor), static_cast<int>(model::NodeKind::Room));
                // Naming a category asks for its nodes, hidden ones included, as in the engine.
                return fmt::format("{}.category = {}", a, parameter(category(ref)));
            case ast::Ref::Kind::NodeId:
            case ast::Ref::Kind::SourceId:
                return fmt::format("{}.{} = {}", a, numbered(ref), parameter(std::to_string(ref.number)));
            case ast::Ref::Kind::SubQuery:
                if (ref.subquery->asOf)
                    throw Error(ErrorKind::Binding, "AS OF belongs to the whole statement, not to a sub-query",
                                ref.subquery->asOf->where, "write AS OF once, after the outer statement's target");
                return fmt::format("({0}.scene, {0}.id) IN ({1})", a, find(*ref.subquery, nullptr));
            case ast::Ref::Kind::Side:
                return side(ref, a);
            case ast::Ref::Kind::Here:
                throw notYet("HERE (each scene's viewpoint)");
            case ast::Ref::Kind::Param:
                break;
        }
        throw notYet("placeholders");
    }

    // `#12` (the scene's local id on the store) or `src#93`: the column to match, once the node is
    // known to be there (and of the category written with it: `chair#12`).
    const char* numbered(const ast::Ref& ref) {
        if (scope_.allScenes) throw notYet("ids across all scenes");
        const bool source = ref.kind == ast::Ref::Kind::SourceId;
        const char* column = source ? "source_id" : "id";
        const std::optional<std::string> category = scope_.nodeCategory(column, ref.number);
        if (!category)
            throw Error(ErrorKind::Binding,
                        fmt::format("no node {}#{} in scene '{}'", source ? "src" : "", ref.number, scope_.name),
                        ref.where);
        if (!ref.name.empty() && ref.name != *category)
            throw Error(ErrorKind::Binding, fmt::format("#{} is a {}, not a {}", ref.number, *category, ref.name),
                        ref.where);
        return column;
    }

    // A category as the engine's binder resolves it: as written, or in one scene the singular of
    // a plural it holds; a category other scenes hold, or an English noun for a physical thing no
    // category stands for ("piano"), is an empty answer; anything else an error with hints.
    std::string category(const ast::Ref& ref) {
        const std::string& name = ref.name;
        if (scope_.categories.count(name)) return name;
        if (!scope_.allScenes)
            for (std::string_view suffix : {"es", "s"})
                if (name.size() > suffix.size() + 1 && name.ends_with(suffix)) {
                    std::string singular = name.substr(0, name.size() - suffix.size());
                    if (scope_.categories.count(singular)) return singular;
                }
        if (!scope_.allScenes && scope_.knownElsewhere && scope_.knownElsewhere(name)) return name;
        const std::vector<std::string> known(scope_.categories.begin(), scope_.categories.end());
        const ask::WordMatch match = ask::Lexicon(known).lookUp(name);
        if (auto noun = ask::absentThing(name, match)) return *noun;
        std::vector<std::string> close = model::nearestNames(name, known);
        if (close.empty() && !scope_.allScenes) close = match.categories;  // a synonym or a broader word
        if (scope_.allScenes)
            throw Error(ErrorKind::Binding, fmt::format("unknown category '{}' in any scene", name), ref.where,
                        close.empty() ? "" : fmt::format("did you mean {}?", model::joinAlternatives(close)));
        throw Error(ErrorKind::Binding, fmt::format("unknown category '{}' in scene '{}'", name, scope_.name),
                    ref.where,
                    close.empty() ? fmt::format("this scene has: {}", model::joinAlternatives(known))
                                  : fmt::format("did you mean {}?", model::joinAlternatives(close)));
    }

    // The session's thresholds, one parameter for the whole statement.
    std::string thresholds() {
        if (thresholdsParameter_.empty()) thresholdsParameter_ = parameter(thresholdsArray(thresholds_)) + "::float8[]";
        return thresholdsParameter_;
    }

    std::string parameter(std::string value) {
        parameters_.push_back(std::move(value));
        return fmt::format("${}", parameters_.size() + 1);
    }
    std::string alias(char letter) { return fmt::format("{}{}", letter, ++aliases_); }

    const QueryScope& scope_;
    const relations::Thresholds& thresholds_;
    std::vector<std::string> parameters_;
    std::string thresholdsParameter_;
    int aliases_ = 0;
    bool usesContext_ = false;
    std::optional<model::Viewpoint> view_;  // VIEW FROM's viewer, when the statement has one
    relations::Frame frame_;                // the viewer's frame: VIEW FROM's or the scene's
};

}  // namespace

CompiledQuery compileQuery(const ast::Statement& statement, const QueryScope& scope,
                           const relations::Thresholds& thresholds) {
    return Compiler(scope, thresholds).statement(statement);
}

std::string thresholdsArray(const relations::Thresholds& thresholds) {
    std::string out = "{";
    for (const auto& setting : relations::settingsCatalogue())
        out += fmt::format("{}{}", out.size() > 1 ? "," : "", thresholds.*(setting.field));
    return out + "}";
}

}  // namespace smql::fleet
