// Text -> AST. The only place that knows about ANTLR.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "engine/parser/ast.hpp"

namespace smql::parser {

// Parses one or more `;`-separated statements. Throws smql::Error
// (ErrorKind::Syntax) with the line, column and a hint at the first error;
// never returns a partial list.
std::vector<ast::Statement> parse(std::string_view text);

// True when `text` ends inside an unfinished statement (no closing `;`,
// open parenthesis or string): the shell keeps reading lines.
bool isIncomplete(std::string_view text);

// Keywords, for shell completion and "did you mean" hints.
const std::vector<std::string>& keywords();

// The sides a reference can name (`wall.left`), for the parser's check and shell completion.
const std::vector<std::string>& sides();

}  // namespace smql::parser
