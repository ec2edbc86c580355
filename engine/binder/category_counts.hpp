// The categories a statement across all scenes named, kept between statements: each name as written
// or bound, with the label keys it reads (storage's labelKeys: the canonical name folded from it,
// and names stored before names were canonical) and how many nodes carry them, as read in one
// committed transaction. While no process has committed since, a FIND or COUNT of the same name
// needs neither the name's folding nor the label index's count again. Only counts above zero are
// kept: a category in no scene answers with a note or an error, which the statement works out anew.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace smql::binder {

struct CategoryCount {
    std::vector<std::string> keys;  // the first is the canonical name
    std::uint64_t count = 0;
};

class CategoryCounts {
public:
    // What was kept of `name` in `transaction`; null when it was not, or was kept in another.
    const CategoryCount* find(std::string_view name, std::uint64_t transaction) const;
    // Keeps `counted` (above zero) for `name`, read in `transaction`; what was kept in an older
    // transaction is dropped, and at the capacity everything is.
    void keep(std::string_view name, std::uint64_t transaction, CategoryCount counted);

private:
    struct Hash {
        using is_transparent = void;
        std::size_t operator()(std::string_view text) const { return std::hash<std::string_view>{}(text); }
    };
    static constexpr std::size_t kCapacity = 1024;
    std::unordered_map<std::string, CategoryCount, Hash, std::equal_to<>> counts_;
    std::uint64_t transaction_ = 0;
};

}  // namespace smql::binder
