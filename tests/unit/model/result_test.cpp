// A result row holds its first values in itself and the rest on the heap, and behaves as the
// vector of values it stands for: copies, moves, growth and comparison keep every value.
#include <catch2/catch.hpp>

#include <string>
#include <utility>
#include <vector>

#include "model/result.hpp"

using smql::Row;
using smql::Value;

namespace {

// A text too long for the string's own buffer, so that a lost or doubled value shows.
std::string longText(int i) { return "a text long enough to live on the heap, number " + std::to_string(i); }

Row rowOf(int n) {
    Row row;
    for (int i = 0; i < n; ++i) {
        if (i % 3 == 0)
            row.emplace_back(longText(i));
        else if (i % 3 == 1)
            row.emplace_back(static_cast<std::int64_t>(i));
        else
            row.emplace_back(smql::model::Box{{1.0 * i, 2, 3}, {1, 1, 1}, 0.5});
    }
    return row;
}

std::vector<Value> valuesOf(int n) { return rowOf(n).toVector(); }

}  // namespace

TEST_CASE("a result row keeps its values inline and on the heap alike", "[model][result]") {
    for (int n : {0, 1, static_cast<int>(Row::kInline), static_cast<int>(Row::kInline) + 1, 23}) {
        CAPTURE(n);
        Row row = rowOf(n);
        REQUIRE(row.size() == static_cast<std::size_t>(n));
        REQUIRE(row == valuesOf(n));
        CHECK(row.capacity() >= row.size());

        Row copy = row;
        CHECK(copy == row);
        Row moved = std::move(copy);
        CHECK(moved == row);
        CHECK(copy.empty());  // NOLINT(bugprone-use-after-move): a moved-from row is empty
        copy.emplace_back(std::int64_t{7});
        CHECK(copy.size() == 1);

        Row assigned = rowOf(3);
        assigned = row;
        CHECK(assigned == row);
        Row moveAssigned = rowOf(static_cast<int>(Row::kInline) + 4);
        moveAssigned = std::move(assigned);
        CHECK(moveAssigned == row);

        // Rows in a vector of rows survive its growth (each row moved to the new block).
        std::vector<Row> rows;
        for (int k = 0; k < 40; ++k) rows.push_back(rowOf(n));
        for (const Row& r : rows) CHECK(r == row);
        CHECK(Row(valuesOf(n)) == row);
    }
}

TEST_CASE("a result row edits as a vector does", "[model][result]") {
    Row row{std::int64_t{1}, longText(2), 3.0};
    row.push_back(row[1]);  // a value of the row itself, copied before any growth
    row.push_back(row[1]);
    row.push_back(row[1]);  // past the inline values
    REQUIRE(row.size() == 6);
    CHECK(std::get<std::string>(row.back()) == longText(2));
    row.insert(row.begin() + 1, std::int64_t{9});
    CHECK(row.toVector() == std::vector<Value>{std::int64_t{1}, std::int64_t{9}, longText(2), 3.0, longText(2),
                                               longText(2), longText(2)});
    row.erase(row.begin());
    CHECK(std::get<std::int64_t>(row.front()) == 9);
    row.resize(2);
    CHECK(row.size() == 2);
    row.resize(4);
    CHECK(std::holds_alternative<std::monostate>(row.at(3)));
    CHECK_THROWS_AS(row.at(4), std::out_of_range);
    row.clear();
    CHECK(row.empty());
    CHECK(Row{} == Row());
    CHECK_FALSE(Row{std::int64_t{1}} == Row{std::int64_t{2}});
}
