// What a statement returns: named, typed columns and rows of values.
#pragma once

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include <boost/container/small_vector.hpp>

#include "model/types.hpp"

namespace smql {

enum class ValueType { Null, Integer, Real, Text, Box };

using Value = std::variant<std::monostate, std::int64_t, double, std::string, model::Box>;

ValueType typeOf(const Value& value);

// One row's values. Most rows have five values or fewer, which a small_vector holds in itself: a
// statement's rows are one block of memory, with no allocation per row.
using Row = boost::container::small_vector<Value, 5>;

struct Column {
    std::string name;
    ValueType type = ValueType::Text;
};

struct ResultSet {
    std::vector<Column> columns;
    std::vector<Row> rows;
    // A sentence for statements that answer in words (RELATE, SET, USE),
    // shown by the shell under the table.
    std::string message;

    int columnIndex(std::string_view name) const;  // -1 when absent
};

// What COUNT answers: one column, `count`, and one row, built where the caller receives it: its two
// allocations are the only ones of a COUNT the engine remembers.
ResultSet countAnswer(std::uint64_t count);

}  // namespace smql
