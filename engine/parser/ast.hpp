// The SMQL abstract syntax tree: what the parser hands the binder. ANTLR
// types never leave engine/parser; this is the boundary.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "model/error.hpp"

namespace smql::ast {

struct FindStmt;

// Something a query points at.
struct Ref {
    enum class Kind {
        Name,      // a category (`sofa`, `'indoor plant'`) or a kind word (`object`, `anchor`, `node`)
        Side,      // `wall.left`: `name` = "wall", `side` = "left"
        NodeId,    // `#42`
        SourceId,  // `src#93`
        SubQuery,  // `(FIND mug WHERE on(desk))`
    };
    Kind kind = Kind::Name;
    std::string name;  // lower-cased; Name and Side
    std::string side;  // left | right | front | back
    std::int64_t number = 0;
    std::shared_ptr<FindStmt> subquery;
    SourceLocation where;
};

// A length as written (`1.5 m`, `30 cm`, `2`): converted to metres by the parser.
struct Distance {
    double metres = 0;
    SourceLocation where;
};

using Literal = std::variant<std::int64_t, double, std::string>;

enum class CompareOp { Eq, Ne, Lt, Le, Gt, Ge, Like };

struct Expr {
    enum class Kind { And, Or, Not, Predicate, Compare };
    Kind kind = Kind::Predicate;
    std::vector<Expr> children;  // And / Or: two or more; Not: one

    // Predicate: `near(wall.left, 1.5 m)`, `between(lamp, sofa)`
    std::string predicate;  // lower-cased
    std::vector<Ref> args;
    std::optional<Distance> threshold;

    // Compare: `color = 'red'`, `source_id = 93`, `confidence >= 0.5`
    std::string attribute;  // lower-cased
    CompareOp op = CompareOp::Eq;
    Literal literal;

    SourceLocation where;
};

// `VIEW FROM door FACING window`
struct View {
    Ref from;
    std::optional<Ref> facing;
    SourceLocation where;
};

// `ORDER BY distance(door) DESC`
struct OrderBy {
    Ref distanceTo;
    bool descending = false;
    SourceLocation where;
};

struct FindStmt {
    Ref target;
    std::optional<View> view;
    std::optional<Expr> where;
    std::optional<Ref> nearestTo;  // NEAREST TO x: order by distance to x, ascending
    std::optional<OrderBy> orderBy;
    std::optional<std::int64_t> limit;
    bool path = false;
};

struct CountStmt {
    Ref target;
    std::optional<View> view;
    std::optional<Expr> where;
};

struct RelateStmt {
    Ref subject;
    Ref object;
    std::optional<View> view;
};

struct DescribeStmt {
    Ref target;
};

struct ShowStmt {
    enum class What { Scenes, Tree, Settings };
    What what = What::Scenes;
    std::optional<Ref> root;  // SHOW TREE #12: the subtree under a node
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

struct Statement;

struct ExplainStmt {
    std::shared_ptr<Statement> inner;
};

struct Statement {
    std::variant<FindStmt, CountStmt, RelateStmt, DescribeStmt, ShowStmt, UseStmt, SetStmt, ExplainStmt> body;
    std::string text;  // the statement's own source text, for EXPLAIN and errors
    SourceLocation where;
};

}  // namespace smql::ast
