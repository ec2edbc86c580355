// "Did you mean": the known names closest to a misspelt one.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace smql::model {

// Edit (Levenshtein) distance, case-insensitive.
std::size_t editDistance(std::string_view a, std::string_view b);

// Up to `limit` candidates within a distance that scales with the word's
// length (a third of it, at least 2), closest first; prefix matches count as close.
std::vector<std::string> nearestNames(std::string_view word, const std::vector<std::string>& candidates,
                                      std::size_t limit = 3);

// "a, b or c"
std::string joinAlternatives(const std::vector<std::string>& names);

// Text as an SMQL string literal: in single quotes, a quote inside doubled ("it's" -> 'it''s').
std::string quoted(std::string_view text);

}  // namespace smql::model
