#include "model/result.hpp"

namespace smql {

ValueType typeOf(const Value& value) { return static_cast<ValueType>(value.index()); }

ResultSet countAnswer(std::uint64_t count) {
    ResultSet rs;
    rs.columns.push_back(Column{"count", ValueType::Integer});
    rs.rows.emplace_back().emplace_back(static_cast<std::int64_t>(count));
    return rs;
}

int ResultSet::columnIndex(std::string_view name) const {
    for (std::size_t i = 0; i < columns.size(); ++i)
        if (columns[i].name == name) return static_cast<int>(i);
    return -1;
}

}  // namespace smql
