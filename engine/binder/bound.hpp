// Bound statements: names resolved to node sets of one scene, units to
// metres, settings and scenes checked. What the planner consumes. A bound
// statement is immutable once made; plans share it, so nothing in a plan can
// outlive what it points at.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "engine/ask/translator.hpp"
#include "engine/catalog/attributes.hpp"
#include "engine/catalog/scene_snapshot.hpp"
#include "engine/catalog/session.hpp"
#include "engine/parser/ast.hpp"
#include "relations/predicates.hpp"

namespace smql::binder {

using catalog::Slot;
struct BoundFind;

// The nodes a reference stands for, and how to say it ("sofa (2 nodes)"). Names, ids and kind
// words are resolved by the binder. A side of the room (`wall.left`) depends on the viewpoint and a
// sub-query on its own answer: both are resolved by the executor when the statement runs.
struct NodeSet {
    // Here: no node but where the viewer stands (distance(HERE), NEAREST TO HERE, near(HERE)); the executor measures
    // to the statement's viewpoint, and relates to a person standing there (relations::viewerAt).
    enum class Source { Nodes, Side, SubQuery, Here };
    Source source = Source::Nodes;
    std::vector<Slot> slots;  // Nodes: the nodes; Side: the candidates, in id order
    // A set that is one of the snapshot's own lists (a category, a kind word) refers to it rather
    // than copying it into `slots` for every statement (a hall's 2,000 objects): the bound
    // statement holds the snapshot, so the list outlives the set. Read the nodes through nodes().
    const std::vector<Slot>* shared = nullptr;
    const std::vector<Slot>& nodes() const { return shared ? *shared : slots; }
    std::string side;                           // Side: left | right | front | back
    std::shared_ptr<const BoundFind> subquery;  // SubQuery: planned and run by the executor
    std::size_t id = 0;                         // numbered per statement; the executor's caches use it
    std::string description;
    // Where one node is needed (RELATE's sides, VIEW FROM, FACING, CHECK): what needs it, as
    // "RELATE's first side". Empty for sets that may hold any number. The binder checks named sets;
    // the executor checks a sub-query's answer.
    std::string singleFor;
    SourceLocation where;

    // How many nodes it holds, or at most holds, for the planner's choices.
    std::size_t estimate() const;
};

// What FIND / COUNT range over: a category, a kind of node, or given nodes.
struct Target {
    enum class Kind { Category, NodeKind, AnyNode, Thing, Nodes };
    Kind kind = Kind::AnyNode;
    std::string category;
    model::NodeKind nodeKind = model::NodeKind::Object;
    NodeSet nodes;  // the candidates, in id order (for every kind)
};

struct BoundExpr {
    enum class Kind { And, Or, Not, Predicate, Compare };
    Kind kind = Kind::Predicate;
    std::vector<BoundExpr> children;

    relations::Predicate predicate = relations::Predicate::Near;
    std::vector<NodeSet> args;
    std::optional<double> nearDistance;

    // Compare: a built-in field or a stored attribute (exec/attributes.hpp), or the distance to a
    // set, against a literal; lengths in metres.
    std::string attribute;
    // The built-in attribute `attribute` names, resolved once here rather than per row; null for a
    // stored attribute (color ...) or a distance.
    const catalog::AttributeInfo* builtIn = nullptr;
    std::optional<NodeSet> distanceTo;
    ast::CompareOp op = ast::CompareOp::Eq;
    ast::Literal literal;
    std::string literalFolded;  // a text literal in lower case, folded once here rather than per row
};

// How a comparison's literal was written, for catalog::checkLiteral.
catalog::LiteralForm literalForm(const ast::Expr& comparison);

// Where the viewer stands for the lateral predicates and sides: the scene's default viewpoint, or
// `VIEW FROM x [FACING y]` (resolved in the default viewpoint's frame).
struct BoundView {
    std::optional<NodeSet> from;
    std::optional<NodeSet> facing;
    std::string description;
};

// SIMILAR TO: a text, compared in the built-in text embedder's space, or a bound vector, compared
// with the vectors an external model gave the scene's nodes at ingest (docs/similarity.md).
struct BoundSimilarTo {
    std::string text;           // empty for a vector
    std::vector<float> vector;  // unit length, as long as the scene's embeddings; empty for a text
    bool stored() const { return !vector.empty(); }
};

struct BoundFind {
    Target target;
    BoundView view;
    std::optional<BoundExpr> where;
    std::optional<NodeSet> distanceTo;        // ORDER BY distance(x) / NEAREST TO x
    bool nearest = false;                     // NEAREST TO: the reference nodes themselves are left out
    std::string orderAttribute;               // ORDER BY height: a comparable built-in or stored attribute
    std::optional<BoundSimilarTo> similarTo;  // ranked by similarity, most similar first
    bool descending = false;
    std::vector<std::string> columns;  // RETURN: checked names; empty for the default columns
    std::optional<std::int64_t> limit;
    bool path = false;
    bool countOnly = false;
};

// FIND / COUNT of a category under USE SCENE '*': every scene, through the label index.
struct BoundCatalogFind {
    std::string category;
    // The label keys that name it (storage's labelKeys), worked out once for binder and executor.
    std::vector<std::string> keys;
    std::optional<std::int64_t> limit;
    bool countOnly = false;
    // The label index's count of the category, read by the binder in the statement's read
    // transaction (which is COUNT's answer, so the executor does not read it again).
    std::uint64_t count = 0;
};

struct BoundRelate {
    NodeSet subject;
    NodeSet object;
    BoundView view;
};

// CHECK a pred b [AND c] [distance]: one predicate over single nodes, answered yes or no.
struct BoundCheck {
    NodeSet subject;
    relations::Predicate predicate = relations::Predicate::Near;
    std::vector<NodeSet> args;
    std::optional<double> nearDistance;
    BoundView view;
};

struct BoundDescribe {
    NodeSet nodes;
};

struct BoundShowScenes {};
// SHOW CATEGORIES: category and count, in the current scene or (allScenes) per scene.
struct BoundShowCategories {
    bool allScenes = false;
};
struct BoundShowAttributes {};
struct BoundShowSettings {};
struct BoundShowTree {
    std::optional<NodeSet> root;  // one node (checked when it runs), or the scene root
};

// SHOW CHANGES [SINCE t]: the changes of the updates of one scene, from its history.
struct BoundShowChanges {
    std::string scene;
    std::optional<std::string> since;  // an instant (model::utcInstant)
};

// GUIDE FROM origin TO goal: each end one node when it runs (else an ambiguity error); the origin
// may instead be a floor point, or the scene's viewpoint (HERE: neither).
struct BoundGuide {
    std::optional<NodeSet> from;
    std::optional<std::pair<double, double>> point;
    NodeSet to;
};

// SHOW GRAPH: the decision points and edges guidance routes on.
struct BoundShowGraph {};

struct BoundDropScene {
    std::string scene;
};

struct BoundRenameScene {
    std::string scene;
    std::string newName;
};

struct BoundUse {
    std::string scene;  // a stored scene's name; empty with allScenes
    bool allScenes = false;
};

// SET: a threshold of the predicates or a limit of the session (one of the two).
struct BoundSet {
    const relations::SettingInfo* threshold = nullptr;
    const catalog::LimitSetting* limit = nullptr;
    double value = 0;
    // SET translator = 'http://...' (or 'built-in', null): ASK's translator for the session.
    bool setsTranslator = false;
    std::shared_ptr<const ask::Translator> translator;
    std::string translatorUrl;

    std::string_view name() const {
        if (setsTranslator) return "translator";
        return threshold ? std::string_view(threshold->name) : limit->name;
    }
};

struct BoundStatement;
struct BoundExplain {
    std::shared_ptr<const BoundStatement> inner;
    bool fromShape = false;  // the statement came from a cached statement shape (ast::Statement::fromShape)
};

// ASK: the question's translation and, when it runs, its SMQL bound like any statement.
struct BoundAsk {
    ask::Translation translation;
    std::shared_ptr<const BoundStatement> inner;  // null when nothing runs (an unknown word, GUIDE)
};

struct BoundStatement {
    std::variant<BoundFind, BoundCatalogFind, BoundRelate, BoundDescribe, BoundShowScenes, BoundShowSettings,
                 BoundShowTree, BoundShowChanges, BoundShowGraph, BoundUse, BoundSet, BoundExplain, BoundAsk,
                 BoundDropScene, BoundRenameScene, BoundGuide, BoundCheck, BoundShowCategories, BoundShowAttributes>
        body;
    // The scene the names were bound in; null for statements that need none (USE, SET, SHOW SCENES ...).
    std::shared_ptr<const catalog::SceneSnapshot> scene;
    std::size_t setCount = 0;  // NodeSet ids run from 0 to setCount - 1
    std::string note;          // said under the answer: "no piano in scene 'room0'"
};

}  // namespace smql::binder
