// Placeholders (`?`, `$1`): the values a prepared statement is run with, what each placeholder
// accepts, and the stage that puts the values into a copy of the parsed statement. A value goes
// into the AST as data (a name, a literal, a distance, a limit), never as SMQL text, so no value
// can change the statement or make it fail to parse.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "engine/parser/ast.hpp"

namespace smql {

// A length in metres, for a distance (`near(?, ?)`) or a quantity compared with (`height > ?`).
struct Length {
    double metres = 0;
    friend bool operator==(const Length&, const Length&) = default;
};

// One bound value: NULL (std::monostate), an integer, a real number, a length, text, or a vector
// (for SIMILAR TO: compared with the vectors an external model gave the scene's nodes).
using ParameterValue = std::variant<std::monostate, std::int64_t, double, Length, std::string, std::vector<float>>;

}  // namespace smql

namespace smql::binder {

// The kinds of value a placeholder accepts, as bits: a name takes text; a distance a number or a
// length; LIMIT a whole number; a comparison any of those; SIMILAR TO text or a vector.
enum ParameterKind : unsigned {
    kTextValue = 1U << 0U,
    kIntegerValue = 1U << 1U,
    kRealValue = 1U << 2U,
    kLengthValue = 1U << 3U,
    kVectorValue = 1U << 4U,
};

struct ParameterSlot {
    ast::Placeholder placeholder;  // where it is first written (index 0 when the statement skips it)
    unsigned accepts = 0;          // ParameterKind bits; a `$n` written twice accepts what both places do
};

// One slot per index 1..statement.parameterCount, in index order (slot 0 is placeholder 1).
std::vector<ParameterSlot> parameterSlots(const ast::Statement& statement);

// Why `value` cannot go into `slot`, or nothing when it can. NULL always can (it fails when the
// statement runs, naming the placeholder).
std::optional<std::string> rejectedValue(const ParameterSlot& slot, const ParameterValue& value);

// The statement with its placeholders replaced by `values` (values[0] for placeholder 1; a missing
// entry is an unbound placeholder). Throws Error(Usage), located at the placeholder, for one
// without a value, bound to NULL, or bound to a value its place cannot take.
ast::Statement withParameters(const ast::Statement& statement,
                              const std::vector<std::optional<ParameterValue>>& values);

}  // namespace smql::binder
