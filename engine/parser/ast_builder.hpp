// Parse tree -> AST. Also the checks that are easier to word well on a tree
// than in the grammar: clause order, sides, units, LIMIT values.
#pragma once

#include "SmqlParser.h"
#include "engine/parser/ast.hpp"
#include "engine/parser/source.hpp"

namespace smql::parser {

// Throws smql::Error (ErrorKind::Syntax) for a statement that parses but
// does not make sense (`LIMIT 2.5`, `wall.top`, `WHERE` after `LIMIT`).
// `nodeIdPlaceholders[k - 1]` marks placeholder k as a statement shape's node id
// (ast::Placeholder::nodeId); empty for a statement as written.
ast::Statement buildStatement(grammar::SmqlParser::StatementContext& tree, const Source& source,
                              const std::vector<bool>& nodeIdPlaceholders = {});

}  // namespace smql::parser
