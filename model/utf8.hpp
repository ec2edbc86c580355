// UTF-8 validation. Text enters smql as statements and as names in imported
// files; everything downstream (JSON output, the C API, terminals) expects
// UTF-8, so malformed bytes are caught at the door and reported by position.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace smql::model {

// The offset of the first byte that does not belong to a well-formed UTF-8
// sequence (RFC 3629: no overlong forms, no surrogates, nothing above
// U+10FFFF), or std::nullopt when the whole text is valid.
std::optional<std::size_t> invalidUtf8At(std::string_view text);

// `text` with every byte that is not part of a well-formed UTF-8 character
// written as \xNN, for messages that quote what a file holds.
std::string escapeInvalidUtf8(std::string_view text);

}  // namespace smql::model
