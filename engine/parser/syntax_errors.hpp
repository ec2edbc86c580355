// The wording of syntax errors: what went wrong at the first bad token of a
// statement, and a hint built from the tokens that would have fitted there.
#pragma once

#include <cstddef>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "engine/parser/source.hpp"

namespace smql::parser {

// `failedAt` counts tokens from the start of the statement; the statement's
// own length means "at its end". `expected` holds the token types that would
// have let the parse get past that point (Token::EOF: the statement could
// end there).
Error syntaxError(const Source& source, const StatementSlice& slice, std::size_t failedAt,
                  const std::set<std::size_t>& expected);

// `3 km`, or `3 LIMT`: a word after a number is its unit, so a misspelt
// keyword there lands here too.
Error notAUnit(const antlr4::Token& word);

// The keyword closest to `word` among `candidates` (token types), if one is
// close enough to be a likely misspelling; empty otherwise.
std::string closestKeyword(std::string_view word, const std::vector<std::size_t>& candidates);

}  // namespace smql::parser
