#include "engine/binder/category_counts.hpp"

namespace smql::binder {

const CategoryCount* CategoryCounts::find(std::string_view name, std::uint64_t transaction) const {
    if (transaction != transaction_ || counts_.empty()) return nullptr;
    auto it = counts_.find(name);
    return it == counts_.end() ? nullptr : &it->second;
}

void CategoryCounts::keep(std::string_view name, std::uint64_t transaction, CategoryCount counted) {
    if (counted.count == 0) return;
    if (transaction != transaction_ || counts_.size() >= kCapacity) counts_.clear();
    transaction_ = transaction;
    counts_.insert_or_assign(std::string(name), std::move(counted));
}

}  // namespace smql::binder
