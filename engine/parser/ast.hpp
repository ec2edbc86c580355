// The SMQL abstract syntax tree: what the parser hands the binder. ANTLR
// types never leave engine/parser; this is the boundary.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "model/error.hpp"
#include "model/types.hpp"

namespace smql::ast {

struct FindStmt;

// A placeholder, `?` or `$2`, standing for a value bound when a prepared statement runs
// (engine/binder/parameters.hpp puts the values in). `?` are numbered in order of appearance.
struct Placeholder {
    std::size_t index = 0;  // 1-based
    bool numbered = false;  // `$2` rather than `?`
    // Made by a statement shape for a node id taken out of the text (`#12`; parser/normalise.hpp):
    // it binds an integer as the node id. A placeholder written in a statement never is one.
    bool nodeId = false;
    SourceLocation where;
    // How messages name it: "$2", or "? number 2" for the second `?`.
    std::string name() const { return numbered ? "$" + std::to_string(index) : "? number " + std::to_string(index); }
};

// Something a query points at.
struct Ref {
    enum class Kind {
        Name,      // a category (`sofa`, `'indoor plant'`) or a kind word (`object`, `anchor`, `node`)
        Side,      // `wall.left`: `name` = "wall", `side` = "left"
        NodeId,    // `#42`, or `sofa#42` as results print it (`name` holds the category to check)
        SourceId,  // `src#93`
        SubQuery,  // `(FIND mug WHERE on(desk))`
        Param,     // `?`, `$1`, `?.left`: a name bound later (`placeholder`; `side` when written)
        Here,      // `HERE` in `distance(HERE)` and `NEAREST TO HERE`: where the viewer stands, not a node
    };
    Kind kind = Kind::Name;
    std::string name;  // lower-cased; Name and Side, and NodeId's category when written
    std::string side;  // left | right | front | back
    std::int64_t number = 0;
    std::shared_ptr<FindStmt> subquery;
    Placeholder placeholder;  // Param
    SourceLocation where;
};

// Kind words: a Name that is one stands for every shown node of that kind (`object`, `anchors`,
// `rooms`, `frame`, `descriptions`); plurals are accepted.
inline std::optional<model::NodeKind> kindWord(std::string_view name) {
    constexpr std::pair<std::string_view, model::NodeKind> words[] = {{"object", model::NodeKind::Object},
                                                                      {"objects", model::NodeKind::Object},
                                                                      {"anchor", model::NodeKind::Anchor},
                                                                      {"anchors", model::NodeKind::Anchor},
                                                                      {"room", model::NodeKind::Room},
                                                                      {"rooms", model::NodeKind::Room},
                                                                      {"frame", model::NodeKind::Frame},
                                                                      {"frames", model::NodeKind::Frame},
                                                                      {"description", model::NodeKind::Description},
                                                                      {"descriptions", model::NodeKind::Description}};
    for (const auto& [word, kind] : words)
        if (name == word) return kind;
    return std::nullopt;
}

// Words for every shown node of any kind but the scene itself.
inline bool anyNodeWord(std::string_view name) { return name == "node" || name == "nodes"; }

// Words for what a person calls a thing in a place: its objects, anchors and rooms, not the camera
// frames or the descriptions an ingest stores beside them.
inline bool thingWord(std::string_view name) { return name == "thing" || name == "things"; }
constexpr bool isThing(model::NodeKind kind) {
    return kind == model::NodeKind::Object || kind == model::NodeKind::Anchor || kind == model::NodeKind::Room;
}

// A length as written (`1.5 m`, `30 cm`, `2`): converted to metres by the parser.
struct Distance {
    double metres = 0;
    SourceLocation where;
};

using Literal = std::variant<std::int64_t, double, std::string>;

// IsNull, IsNotNull: whether the node has the attribute at all (no literal).
enum class CompareOp { Eq, Ne, Lt, Le, Gt, Ge, Like, IsNull, IsNotNull };

// As SMQL writes it (and SQL reads it): =, !=, <, <=, >, >=, LIKE, IS NULL, IS NOT NULL.
constexpr std::string_view toString(CompareOp op) {
    switch (op) {
        case CompareOp::Eq:
            return "=";
        case CompareOp::Ne:
            return "!=";
        case CompareOp::Lt:
            return "<";
        case CompareOp::Le:
            return "<=";
        case CompareOp::Gt:
            return ">";
        case CompareOp::Ge:
            return ">=";
        case CompareOp::Like:
            return "LIKE";
        case CompareOp::IsNull:
            return "IS NULL";
        case CompareOp::IsNotNull:
            return "IS NOT NULL";
    }
    return "?";
}

struct Expr {
    enum class Kind { And, Or, Not, Predicate, Compare };
    Kind kind = Kind::Predicate;
    std::vector<Expr> children;  // And / Or: two or more; Not: one

    // Predicate: `near(wall.left, 1.5 m)`, `between(lamp, sofa)`
    std::string predicate;  // lower-cased
    std::vector<Ref> args;
    std::optional<Distance> threshold;

    // Compare: `color = 'red'`, `source_id = 93`, `confidence >= 0.5`, `height > 1 m`,
    // `distance(sofa) < 2 m` (`distanceTo` set, `attribute` empty). BETWEEN is two of them under And.
    std::string attribute;  // lower-cased
    std::optional<Ref> distanceTo;
    CompareOp op = CompareOp::Eq;
    Literal literal;
    bool literalHasUnit = false;              // `2 m` rather than `2`: the binder checks it against lengths
    bool literalBound = false;                // bound to a placeholder: a number there is metres where a length goes
    std::optional<Placeholder> literalParam;  // `color = ?`: the literal is bound later

    SourceLocation where;
};

// `VIEW FROM door FACING window`
struct View {
    Ref from;
    std::optional<Ref> facing;
    SourceLocation where;
};

// `ORDER BY distance(door) DESC`, `ORDER BY height`: one of the two is set.
struct OrderBy {
    std::optional<Ref> distanceTo;
    std::string attribute;  // lower-cased
    bool descending = false;
    SourceLocation where;
};

// `AS OF '2026-11-20'`: the instant, in model::utcInstant's form.
struct AsOf {
    std::string instant;
    SourceLocation where;
};

// `SIMILAR TO 'soft thing to sit on'` or `SIMILAR TO ?` (text or a vector bound later).
struct SimilarTo {
    std::string text;
    std::optional<Placeholder> param;
    SourceLocation where;
    std::vector<float> vector;  // a bound vector (then `text` is empty)
};

struct FindStmt {
    Ref target;
    std::optional<AsOf> asOf;
    std::optional<View> view;
    std::optional<Expr> where;
    std::optional<Ref> nearestTo;  // NEAREST TO x: order by distance to x, ascending
    std::optional<OrderBy> orderBy;
    std::optional<SimilarTo> similarTo;  // rank by similarity, most similar first
    std::optional<std::int64_t> limit;
    std::optional<Placeholder> limitParam;  // `LIMIT ?`: the limit is bound later
    bool path = false;
    std::vector<std::string> columns;  // RETURN a, b: lower-cased, in order; empty for the default columns
    SourceLocation returnWhere;
};

struct CountStmt {
    Ref target;
    std::optional<AsOf> asOf;
    std::optional<View> view;
    std::optional<Expr> where;
};

struct RelateStmt {
    Ref subject;
    Ref object;
    std::optional<View> view;
};

// `CHECK lamp left_of window`, `CHECK mug near window 1 m`, `CHECK lamp between sofa AND desk`
struct CheckStmt {
    Ref subject;
    std::string predicate;  // lower-cased
    SourceLocation predicateWhere;
    std::vector<Ref> args;  // one, or two for between
    std::optional<Distance> threshold;
    std::optional<View> view;
};

struct DescribeStmt {
    Ref target;
};

struct ShowStmt {
    enum class What { Scenes, Tree, Settings, Changes, Graph, Categories, Attributes };
    What what = What::Scenes;
    std::optional<Ref> root;           // SHOW TREE #12: the subtree under a node
    std::optional<std::string> since;  // SHOW CHANGES SINCE '...': the instant (model::utcInstant)
};

// `DROP SCENE name`
struct DropSceneStmt {
    std::string scene;
    SourceLocation where;
};

// `GUIDE FROM door TO mug`, `GUIDE FROM HERE TO ...`, `GUIDE FROM (1.5, 2) TO ...`
struct GuideStmt {
    std::optional<Ref> from;                         // a node; neither this nor `point`: HERE
    std::optional<std::pair<double, double>> point;  // (x, y) in metres
    Ref to;
    SourceLocation where;
};

// `RENAME SCENE a TO b`
struct RenameSceneStmt {
    std::string scene;
    std::string newName;
    SourceLocation where;
};

struct UseStmt {
    std::string scene;
    SourceLocation where;
};

// `SET near = 0.8 m`, `SET format = 'json'`, `SET on.min_overlap = 0.4`
struct SetStmt {
    std::string name;  // lower-cased, may contain dots
    std::variant<Distance, double, std::string> value;
    SourceLocation where;
};

// `ASK 'what is on the sofa?'`: the question as written (quotes removed, case kept).
struct AskStmt {
    std::string question;
    SourceLocation where;  // the quoted question
};

struct Statement;

struct ExplainStmt {
    std::shared_ptr<Statement> inner;
};

struct Statement {
    std::variant<FindStmt, CountStmt, RelateStmt, DescribeStmt, ShowStmt, UseStmt, SetStmt, ExplainStmt, AskStmt,
                 DropSceneStmt, RenameSceneStmt, GuideStmt, CheckStmt>
        body;
    std::string text;  // the statement's own source text, for EXPLAIN and errors
    SourceLocation where;
    // The highest placeholder index (0: none); a statement with placeholders runs only prepared.
    std::size_t parameterCount = 0;
    // Made from a cached statement shape with this text's literals bound as values, rather than
    // parsed (parser/normalise.hpp); EXPLAIN says so.
    bool fromShape = false;
};

}  // namespace smql::ast
