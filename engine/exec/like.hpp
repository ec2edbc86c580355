// SQL's LIKE as SMQL's comparisons use it (docs/language.md, "Comparisons").
#pragma once

#include <string_view>

namespace smql::exec {

// Whether `text` matches `pattern`: % any run of bytes, _ any one byte, letters compared without
// case. In at most length(text) x length(pattern) steps, whatever the pattern (no backtracking).
bool like(std::string_view text, std::string_view pattern);

}  // namespace smql::exec
