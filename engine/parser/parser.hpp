// Text -> AST. The only place that knows about ANTLR.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "engine/parser/ast.hpp"

namespace smql::parser {

// Limits on one statement (docs/language.md, "Limits"). The parser is a
// recursive descent: each level of nesting costs stack in ANTLR's rules, the
// tree walker, the binder and the executor, so nesting is bounded before any
// of them runs, as SQLite bounds expression depth (SQLITE_MAX_EXPR_DEPTH).
// Real statements nest a handful of levels and run to a few hundred characters.
inline constexpr std::size_t kMaxNestingDepth = 100;        // parentheses, sub-queries and NOTs together
inline constexpr std::size_t kMaxStatementLength = 100000;  // characters
inline constexpr std::size_t kMaxPlaceholder = 999;         // the highest $n, as SQLite's default
// A quoted string or a text bound to a placeholder (a name, a value, a question, SIMILAR TO's
// text): what is compared per row, or embedded, costs no more than this many bytes.
inline constexpr std::size_t kMaxTextValue = 4096;

// Parses one or more `;`-separated statements. Throws smql::Error
// (ErrorKind::Syntax) with the line, column and a hint at the first error;
// never returns a partial list.
std::vector<ast::Statement> parse(std::string_view text);

// The statements of `text` before its first syntax error (all of them when there is none): a
// script runs those, then reports the error, as sqlite3_exec does.
std::vector<ast::Statement> parseBeforeError(std::string_view text);

// How many statements this process has parsed: a prepared statement's executions add none
// (the engine's unit tests read it to prove so).
std::uint64_t statementsParsed();

// True when `text` ends inside an unfinished statement (no closing `;`,
// open parenthesis or string): the shell keeps reading lines.
bool isIncomplete(std::string_view text);

// Names as the parser folds them (ASCII lower case), so that a name bound to a placeholder
// matches the same name written in the statement.
std::string lowerCase(std::string_view text);

// Keywords, for shell completion and "did you mean" hints.
const std::vector<std::string>& keywords();

// The sides a reference can name (`wall.left`), for the parser's check and shell completion.
const std::vector<std::string>& sides();

}  // namespace smql::parser
