// What a statement returns: named, typed columns and rows of values.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <new>
#include <string>
#include <variant>
#include <vector>

#include "model/types.hpp"

namespace smql {

enum class ValueType { Null, Integer, Real, Text, Box };

using Value = std::variant<std::monostate, std::int64_t, double, std::string, model::Box>;

ValueType typeOf(const Value& value);

// One row's values, as a vector of them whose first kInline values are held in the row itself:
// a statement's rows (most have five values or fewer) are then one block of memory, with no
// allocation per row; a wider row moves its values to the heap as a vector does when it grows.
class Row {
public:
    static constexpr std::size_t kInline = 5;
    using value_type = Value;
    using size_type = std::size_t;
    using reference = Value&;
    using const_reference = const Value&;
    using iterator = Value*;
    using const_iterator = const Value*;

    Row() noexcept {}  // user-provided: a value-initialised row does not zero its inline values
    Row(std::initializer_list<Value> values);
    explicit Row(const std::vector<Value>& values);
    explicit Row(std::vector<Value>&& values);
    Row(const Row& other);
    Row(Row&& other) noexcept;
    Row& operator=(const Row& other);
    Row& operator=(Row&& other) noexcept;
    ~Row();

    std::size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    std::size_t capacity() const { return capacity_; }
    Value* data() { return data_; }
    const Value* data() const { return data_; }
    Value* begin() { return data_; }
    Value* end() { return data_ + size_; }
    const Value* begin() const { return data_; }
    const Value* end() const { return data_ + size_; }
    const Value* cbegin() const { return data_; }
    const Value* cend() const { return data_ + size_; }
    Value& operator[](std::size_t i) { return data_[i]; }
    const Value& operator[](std::size_t i) const { return data_[i]; }
    Value& at(std::size_t i);
    const Value& at(std::size_t i) const;
    Value& front() { return data_[0]; }
    const Value& front() const { return data_[0]; }
    Value& back() { return data_[size_ - 1]; }
    const Value& back() const { return data_[size_ - 1]; }

    void reserve(std::size_t n) {
        if (n > capacity_) grow(n);
    }
    template <class... Args>
    Value& emplace_back(Args&&... args) {
        if (size_ == capacity_) {
            Value value(std::forward<Args>(args)...);  // before growing: it may be one of this row's
            grow(std::size_t{capacity_} * 2);
            return *::new (static_cast<void*>(data_ + size_++)) Value(std::move(value));
        }
        return *::new (static_cast<void*>(data_ + size_++)) Value(std::forward<Args>(args)...);
    }
    void push_back(const Value& v) { emplace_back(v); }
    void push_back(Value&& v) { emplace_back(std::move(v)); }
    void pop_back() { data_[--size_].~Value(); }
    void clear();
    void resize(std::size_t n);
    // Inserts `value` before `at`; returns where it is.
    Value* insert(const Value* at, Value value);
    Value* erase(const Value* at);

    std::vector<Value> toVector() const { return {begin(), end()}; }

    friend bool operator==(const Row& a, const Row& b);
    friend bool operator==(const Row& a, const std::vector<Value>& b);

private:
    bool isInline() const { return data_ == inlineValues(); }
    Value* inlineValues() { return std::launder(reinterpret_cast<Value*>(inline_)); }
    const Value* inlineValues() const { return std::launder(reinterpret_cast<const Value*>(inline_)); }
    void grow(std::size_t atLeast);
    void takeFrom(Row& other) noexcept;
    void release() noexcept;

    alignas(Value) unsigned char inline_[kInline * sizeof(Value)];
    Value* data_ = inlineValues();
    std::uint32_t size_ = 0, capacity_ = kInline;
};

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
    double elapsedMicroseconds = 0;

    int columnIndex(std::string_view name) const;  // -1 when absent
};

}  // namespace smql
