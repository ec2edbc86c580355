// Facts about token types that the error messages and keywords() share.
// Relies on the grammar declaring the keywords first, FIND .. LIKE.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "SmqlLexer.h"

namespace smql::parser {

using grammar::SmqlLexer;

inline bool isKeyword(std::size_t type) { return type >= SmqlLexer::FIND && type <= SmqlLexer::LIKE; }

// The keywords a name may also be (grammar rule `name`): all but IS, NULL and the logical ones.
inline bool isSoftKeyword(std::size_t type) { return type >= SmqlLexer::FIND && type <= SmqlLexer::GRAPH; }

// Keywords that begin a command (the grammar declares them first, FIND .. GUIDE).
inline bool startsCommand(std::size_t type) { return type >= SmqlLexer::FIND && type <= SmqlLexer::GUIDE; }

// How many of a length unit make a metre (m, cm, mm; lower case), or
// nothing for a word that is not a unit. Dividing by it rather than
// multiplying by 0.01 keeps 30 cm exactly equal to 0.3 m.
inline std::optional<double> unitsPerMetre(std::string_view unit) {
    constexpr std::array units{std::pair{"m", 1.0}, std::pair{"cm", 100.0}, std::pair{"mm", 1000.0}};
    for (const auto& [name, perMetre] : units)
        if (unit == name) return perMetre;
    return std::nullopt;
}

// The grammar's name for a token type: "FIND", "WHERE", "IDENT", ...
const std::string& tokenName(std::size_t type);

}  // namespace smql::parser
