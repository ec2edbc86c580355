// Statement shapes: a statement's text with its literals taken out, so that statements that differ
// only in their literals (names in quotes, numbers, lengths, node ids) can share one parse, as
// PostgreSQL's and MySQL's statement normalisation do. A hand-written scan, no ANTLR: it runs on
// every new text, and the parse it stands in for costs 5-35 us.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/parser/ast.hpp"

namespace smql::parser {

// One literal taken out of a statement's text, with its value as the parser reads it.
struct ShapeLiteral {
    // The kind decides which token types stood there, so it is part of the shape.
    enum class Kind : char {
        Text = 's',     // 'indoor plant', "it's": the text between the quotes, doubled quotes undone
        Integer = 'i',  // 5: digits without a point
        Real = 'r',     // 1.5, .5, 2.
        Length = 'l',   // 1.5 m, 30 cm, 300 mm: in metres, as the parser converts it
        NodeId = 'n',   // #12
    };
    Kind kind = Kind::Text;
    std::string text;          // Text
    std::int64_t integer = 0;  // Integer, NodeId
    double number = 0;         // Real, Length (metres)
};

struct StatementShape {
    // The statement's tokens joined by single spaces, words in lower case (SMQL's words are
    // case-insensitive), comments and a closing `;` left out, literal k (from 1, in text order)
    // written `$k`; then a newline and the literals' kinds. Two texts with the same key have the
    // same tokens but for their literals' values.
    std::string key;
    std::vector<ShapeLiteral> literals;
    // Where the statement's own text lies in the scanned text ([begin, end): first token to last),
    // and where the text after a leading EXPLAIN begins.
    std::size_t begin = 0, end = 0, afterExplain = 0;

    // The key's first line: a statement with placeholders $1..$n where the literals were.
    std::string_view placeholderText() const { return std::string_view(key).substr(0, key.find('\n')); }
};

// The shape of `text`, or nothing when the text is not one to share a parse: not one statement of
// FIND, COUNT, RELATE, CHECK or DESCRIBE (EXPLAIN of them included); placeholders of its own; a
// literal the parser would refuse (a number out of range, an overlong text); anything the lexer
// would not read as a token (an unterminated string, a stray character, bytes that are not UTF-8).
// The full parser reads such texts, and says what is wrong with them.
std::optional<StatementShape> statementShape(std::string_view text);

// Parses a shape's placeholder text: `$k` of a node-id literal stands for the node id itself
// (ast::Placeholder::nodeId), every other `$k` as a placeholder written there would.
// Throws smql::Error as parse() does.
ast::Statement parseShape(const StatementShape& shape);

// Whether two statements say the same: equal but for where things were written and the source
// text. Only the statements a shape may have (FIND, COUNT, RELATE, CHECK, DESCRIBE, EXPLAIN of
// them) are compared; any other is never the same.
bool sameStatement(const ast::Statement& a, const ast::Statement& b);

}  // namespace smql::parser
