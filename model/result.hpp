// What a statement returns: named, typed columns and rows of values.
#pragma once

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "model/types.hpp"

namespace smql {

enum class ValueType { Null, Integer, Real, Text, Box };

using Value = std::variant<std::monostate, std::int64_t, double, std::string, model::Box>;

ValueType typeOf(const Value& value);

struct Column {
    std::string name;
    ValueType type = ValueType::Text;
};

struct ResultSet {
    std::vector<Column> columns;
    std::vector<std::vector<Value>> rows;
    // A sentence for statements that answer in words (RELATE, SET, USE),
    // shown by the shell under the table.
    std::string message;
    double elapsedMicroseconds = 0;

    int columnIndex(std::string_view name) const;  // -1 when absent
};

}  // namespace smql
