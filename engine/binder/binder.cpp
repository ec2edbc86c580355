#include "engine/binder/binder.hpp"
#include "engine/parser/parser.hpp"

#include <fmt/format.h>

#include "engine/ask/lexicon.hpp"
#include "engine/binder/singular.hpp"
#include "engine/catalog/attributes.hpp"
#include "model/category.hpp"
#include "model/error.hpp"
#include "model/names.hpp"
#include "storage/database.hpp"

namespace smql::binder {

using model::Node;
using model::NodeKind;

namespace {

// Every set a statement names gets one ("object (2000 nodes)"): put together by hand, which costs
// a fraction of a format call in a prepared statement's few microseconds.
std::string describeSet(const std::string& name, std::size_t count) {
    std::string out = name;
    out.append(" (").append(std::to_string(count)).append(count == 1 ? " node)" : " nodes)");
    return out;
}

NodeSet oneNode(Slot slot, std::string description) {
    NodeSet set;
    set.slots = {slot};
    set.description = std::move(description);
    return set;
}

}  // namespace

std::size_t NodeSet::estimate() const {
    switch (source) {
        case Source::Nodes:
            return nodes().size();
        case Source::Side:
        case Source::Here:
            return 1;
        case Source::SubQuery:
            return subquery->limit
                       ? std::min(subquery->target.nodes.estimate(), static_cast<std::size_t>(*subquery->limit))
                       : subquery->target.nodes.estimate();
    }
    return nodes().size();
}

BoundStatement Binder::bind(const ast::Statement& statement, const std::vector<std::optional<ParameterValue>>& values) {
    if (statement.parameterCount > 0) return bind(withParameters(statement, values));
    BoundStatement out;
    std::visit([&](const auto& body) { bindStatement(body, out); }, statement.body);
    if (auto* explain = std::get_if<BoundExplain>(&out.body)) explain->fromShape = statement.fromShape;
    out.scene = scene_;
    out.setCount = nextSetId_;
    for (const auto& note : notes_) out.note += (out.note.empty() ? "" : "; ") + note;
    return out;
}

const catalog::SceneSnapshot& Binder::scene() {
    if (!scene_) scene_ = ctx_.currentScene();
    return *scene_;
}

catalog::LiteralForm literalForm(const ast::Expr& comparison) {
    return {std::holds_alternative<std::string>(comparison.literal), comparison.literalHasUnit,
            comparison.literalBound};
}

NodeSet Binder::numbered(NodeSet set) {
    set.id = nextSetId_++;
    return set;
}

std::string Binder::resolveCategory(const ast::Ref& ref) {
    // A name is its canonical category however it is written: "Trash Cans" is trash-can
    // (model/category.hpp), a plural its singular.
    const std::string name = model::categoryName(ref.name);
    const auto& snap = scene();
    if (!snap.withCategory(name).empty()) return name;
    // Plurals English endings miss ("boxes" read as boxe).
    for (std::string_view suffix : {"es", "s"}) {
        if (ref.name.size() > suffix.size() + 1 && ref.name.ends_with(suffix)) {
            std::string singular = model::categoryName(ref.name.substr(0, ref.name.size() - suffix.size()));
            if (!snap.withCategory(singular).empty()) return singular;
        }
    }
    auto known = snap.categories();
    // Known in another scene, or a noun for a thing the scene does not hold ("piano"): an empty
    // match is an answer, not a typo.
    if (!ctx_.txn.nodesNamed(name, 1).empty()) return noted(name);
    const ask::WordMatch match = ask::Lexicon(known).lookUp(ref.name);
    if (auto noun = ask::absentThing(ref.name, match)) return noted(*noun);
    auto close = model::nearestNames(ref.name, known);
    if (close.empty()) close = match.categories;  // a synonym or a broader word: couch -> sofa
    std::string hint = close.empty() ? fmt::format("this scene has: {}", model::joinAlternatives(known))
                                     : fmt::format("did you mean {}?", model::joinAlternatives(close));
    // HERE is where the viewer stands, not a node: distances and predicates take it, a target or RELATE does not.
    if (ref.name == "here")
        hint =
            "HERE, where the viewer stands, is no node: measure to it (distance(HERE), NEAREST TO HERE) or relate "
            "to it in a predicate (near(HERE), visible_from(HERE))";
    throw Error(ErrorKind::Binding, fmt::format("unknown category '{}' in scene '{}'", ref.name, snap.info().name),
                ref.where, hint);
}

std::string Binder::noted(std::string category) {
    std::string note = fmt::format("no {} in scene '{}'", category, scene().info().name);
    if (std::find(notes_.begin(), notes_.end(), note) == notes_.end()) notes_.push_back(std::move(note));
    return category;
}

NodeSet Binder::bindSingle(const ast::Ref& ref, std::string_view role) {
    NodeSet set = bindRef(ref);
    if (inQuestion_) return set;
    set.singleFor = role;
    set.where = ref.where;
    if (set.source == NodeSet::Source::Nodes) binder::requireOne(scene(), set, set.nodes());
    return set;
}

NodeSet Binder::bindName(const ast::Ref& ref) {
    NodeSet set;
    const auto& snap = scene();
    if (auto kind = ast::kindWord(ref.name)) {
        set.shared = &snap.shownOfKind(*kind);
        set.description = describeSet(ref.name, set.nodes().size());
        return set;
    }
    if (ast::anyNodeWord(ref.name)) {
        set.shared = &snap.shownNodes();
        set.description = describeSet(ref.name, set.nodes().size());
        return set;
    }
    if (ast::thingWord(ref.name)) {
        for (auto slot : snap.shownNodes())
            if (ast::isThing(snap.kind(slot))) set.slots.push_back(slot);
        set.description = describeSet(ref.name, set.slots.size());
        return set;
    }
    std::string category = resolveCategory(ref);
    // Naming a category asks for its nodes, hidden ones included (`undefined`).
    set.shared = &snap.withCategory(category);
    set.description = describeSet(category, set.nodes().size());
    return set;
}

NodeSet Binder::bindRef(const ast::Ref& ref) {
    const auto& snap = scene();
    switch (ref.kind) {
        case ast::Ref::Kind::Name:
            return numbered(bindName(ref));
        case ast::Ref::Kind::Side: {
            NodeSet set = bindName(ast::Ref{ast::Ref::Kind::Name, ref.name, {}, 0, nullptr, {}, ref.where});
            set.source = NodeSet::Source::Side;
            set.side = ref.side;
            set.description = fmt::format("{}.{}", ref.name, ref.side);
            return numbered(std::move(set));
        }
        case ast::Ref::Kind::NodeId: {
            auto slot = snap.slotOf(static_cast<model::NodeId>(ref.number));
            if (!slot)
                throw Error(ErrorKind::Binding, fmt::format("no node #{} in scene '{}'", ref.number, snap.info().name),
                            ref.where, "ids are global; SHOW TREE lists this scene's nodes, USE SCENE switches scenes");
            // `chair#50` where #50 is a sofa: the name and the id disagree, so neither is trusted.
            if (const model::Node& node = snap.node(*slot);
                !ref.name.empty() && model::categoryName(ref.name) != node.category)
                throw Error(
                    ErrorKind::Binding,
                    fmt::format("#{} is {}, not a {}", ref.number, catalog::SceneSnapshot::label(node), ref.name),
                    ref.where, fmt::format("write {} or #{}", catalog::SceneSnapshot::label(node), ref.number));
            return numbered(oneNode(*slot, catalog::SceneSnapshot::label(snap.node(*slot))));
        }
        case ast::Ref::Kind::SourceId: {
            auto slot = snap.slotOfSource(ref.number);
            if (!slot)
                throw Error(ErrorKind::Binding,
                            fmt::format("no node with source id {} in scene '{}'", ref.number, snap.info().name),
                            ref.where,
                            "source ids are the ids of the imported file; they resolve in the current scene");
            return numbered(oneNode(
                *slot, fmt::format("src#{} = {}", ref.number, catalog::SceneSnapshot::label(snap.node(*slot)))));
        }
        case ast::Ref::Kind::Here: {
            NodeSet set;
            set.source = NodeSet::Source::Here;
            set.description = "HERE";
            set.where = ref.where;
            return numbered(std::move(set));
        }
        case ast::Ref::Kind::Param:
            // Binder::bind puts values in first; a placeholder left here had none.
            throw Error(ErrorKind::Usage, fmt::format("placeholder {} has no value", ref.placeholder.name()), ref.where,
                        "run the statement prepared and bind its values");
        case ast::Ref::Kind::SubQuery: {
            // Numbered before its own references, so sub-queries count in the order they are written.
            NodeSet set;
            set.source = NodeSet::Source::SubQuery;
            set = numbered(std::move(set));
            if (ref.subquery->asOf)
                throw Error(ErrorKind::Binding, "AS OF belongs to the whole statement, not to a sub-query",
                            ref.subquery->asOf->where, "write AS OF once, after the outer statement's target");
            set.subquery = std::make_shared<const BoundFind>(bindFind(*ref.subquery));
            set.description = fmt::format("sub-query {}", set.id);
            return set;
        }
    }
    return {};
}

Target Binder::bindTarget(const ast::Ref& ref) {
    Target t;
    if (ref.kind == ast::Ref::Kind::Name) {
        if (auto kind = ast::kindWord(ref.name)) {
            t.kind = Target::Kind::NodeKind, t.nodeKind = *kind;
        } else if (ast::anyNodeWord(ref.name)) {
            t.kind = Target::Kind::AnyNode;
        } else if (ast::thingWord(ref.name)) {
            t.kind = Target::Kind::Thing;
        } else {
            t.kind = Target::Kind::Category;
            t.category = resolveCategory(ref);
        }
    } else {
        t.kind = Target::Kind::Nodes;
    }
    t.nodes = bindRef(ref);
    return t;
}

BoundView Binder::bindView(const std::optional<ast::View>& view) {
    BoundView out;
    if (!view) {
        out.description = "default viewpoint of scene '" + scene().info().name + "'";
        return out;
    }
    out.from = bindSingle(view->from, "VIEW FROM");
    if (view->facing) {
        out.facing = bindSingle(*view->facing, "FACING");
        out.description = fmt::format("from {} facing {}", out.from->description, out.facing->description);
    } else {
        out.description = fmt::format("from {} facing the middle of the scene", out.from->description);
    }
    return out;
}

const relations::PredicateSpec& Binder::predicateNamed(const std::string& name, SourceLocation where) {
    if (const auto* spec = relations::predicateNamed(name)) return *spec;
    auto words = relations::predicateWords();
    auto close = model::nearestNames(name, words);
    throw Error(ErrorKind::Binding, fmt::format("unknown predicate '{}'", name), where,
                close.empty() ? "predicates: " + model::joinAlternatives(words)
                              : "did you mean " + model::joinAlternatives(close) + "?");
}

double Binder::predicateDistance(const relations::PredicateSpec& spec, const ast::Distance& distance) {
    if (spec.takesDistance) return distance.metres;
    std::string takers;
    for (const auto& row : relations::predicates())
        if (row.takesDistance) takers += fmt::format("{}{}()", takers.empty() ? "" : ", ", row.name());
    throw Error(ErrorKind::Binding, fmt::format("only {} takes a distance, not {}()", takers, spec.name()),
                distance.where, "SET changes the thresholds; SHOW SETTINGS lists them");
}

BoundExpr Binder::bindExpr(const ast::Expr& expr) {
    BoundExpr out;
    switch (expr.kind) {
        case ast::Expr::Kind::And:
            out.kind = BoundExpr::Kind::And;
            break;
        case ast::Expr::Kind::Or:
            out.kind = BoundExpr::Kind::Or;
            break;
        case ast::Expr::Kind::Not:
            out.kind = BoundExpr::Kind::Not;
            break;
        case ast::Expr::Kind::Predicate: {
            out.kind = BoundExpr::Kind::Predicate;
            const auto& spec = predicateNamed(expr.predicate, expr.where);
            out.predicate = spec.predicate;
            if (static_cast<int>(expr.args.size()) != spec.arity)
                throw Error(ErrorKind::Binding,
                            fmt::format("{}() takes {} reference{}, got {}", expr.predicate, spec.arity,
                                        spec.arity == 1 ? "" : "s", expr.args.size()),
                            expr.where, std::string(spec.usage));
            if (expr.threshold) out.nearDistance = predicateDistance(spec, *expr.threshold);
            for (const auto& arg : expr.args) out.args.push_back(bindRef(arg));
            return out;
        }
        case ast::Expr::Kind::Compare:
            out.kind = BoundExpr::Kind::Compare;
            out.attribute = expr.attribute;
            out.op = expr.op;
            out.literal = expr.literal;
            // A category compares by its canonical name (`category = 'Trash Cans'` is trash-can).
            if (const auto* text = std::get_if<std::string>(&expr.literal))
                out.literalFolded = expr.attribute != "category"      ? parser::lowerCase(*text)
                                    : expr.op == ast::CompareOp::Like ? model::categoryPattern(*text)
                                                                      : model::categoryName(*text);
            if (expr.distanceTo) {
                out.distanceTo = bindRef(*expr.distanceTo);
                catalog::checkLiteral(catalog::AttributeMeasure::Length, literalForm(expr), "distance()", expr.where);
            } else if (expr.op == ast::CompareOp::IsNull || expr.op == ast::CompareOp::IsNotNull) {
                // Whether a node has it asks no literal, of any attribute the scene knows (a box too).
                if (!catalog::attributeIn(scene(), expr.attribute)) comparable(expr.attribute, expr.where);
                out.builtIn = catalog::builtInAttribute(expr.attribute);
            } else {
                catalog::checkLiteral(comparable(expr.attribute, expr.where).measure, literalForm(expr), expr.attribute,
                                      expr.where);
                out.builtIn = catalog::builtInAttribute(expr.attribute);
            }
            return out;
    }
    for (const auto& child : expr.children) out.children.push_back(bindExpr(child));
    return out;
}

}  // namespace smql::binder

namespace smql::binder {

catalog::AttributeInfo Binder::comparable(const std::string& name, SourceLocation where) {
    if (auto attribute = catalog::attributeIn(scene(), name)) {
        if (attribute->measure == catalog::AttributeMeasure::None)
            throw Error(ErrorKind::Binding, fmt::format("{} cannot be compared or ordered", name), where,
                        "compare its parts: x, y, z, height, width, depth, volume; RETURN shows it");
        return *attribute;
    }
    // A question's attribute that no node here carries ("is the sofa grey?" where nothing records
    // colours) is a no, as ASK words it, rather than an error about SMQL the user did not write.
    if (inQuestion_) return catalog::storedAttribute(name);
    std::vector<std::string> names;
    for (const auto& attribute : catalog::builtInAttributes())
        if (attribute.measure != catalog::AttributeMeasure::None) names.emplace_back(attribute.name);
    for (const auto& stored : scene().attributeNames()) names.push_back(stored);
    auto close = model::nearestNames(name, names);
    throw Error(
        ErrorKind::Binding, fmt::format("unknown attribute '{}' in scene '{}'", name, scene().info().name), where,
        close.empty() ? "SHOW ATTRIBUTES lists them"
                      : fmt::format("did you mean {}? SHOW ATTRIBUTES lists them", model::joinAlternatives(close)));
}

}  // namespace smql::binder
