#include "model/result.hpp"

namespace smql {

ValueType typeOf(const Value& value) { return static_cast<ValueType>(value.index()); }

int ResultSet::columnIndex(std::string_view name) const {
    for (std::size_t i = 0; i < columns.size(); ++i)
        if (columns[i].name == name) return static_cast<int>(i);
    return -1;
}

}  // namespace smql
