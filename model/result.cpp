#include "model/result.hpp"

#include <algorithm>
#include <stdexcept>

namespace smql {

ValueType typeOf(const Value& value) { return static_cast<ValueType>(value.index()); }

Row::Row(std::initializer_list<Value> values) {
    reserve(values.size());
    for (const Value& v : values) emplace_back(v);
}

Row::Row(const std::vector<Value>& values) {
    reserve(values.size());
    for (const Value& v : values) emplace_back(v);
}

Row::Row(std::vector<Value>&& values) {
    reserve(values.size());
    for (Value& v : values) emplace_back(std::move(v));
}

Row::Row(const Row& other) {
    reserve(other.size_);
    for (const Value& v : other) emplace_back(v);
}

Row::Row(Row&& other) noexcept { takeFrom(other); }

Row& Row::operator=(const Row& other) {
    if (this == &other) return *this;
    clear();
    reserve(other.size_);
    for (const Value& v : other) emplace_back(v);
    return *this;
}

Row& Row::operator=(Row&& other) noexcept {
    if (this == &other) return *this;
    release();
    takeFrom(other);
    return *this;
}

Row::~Row() { release(); }

// Takes `other`'s values, leaving it empty and inline; this row holds nothing before.
void Row::takeFrom(Row& other) noexcept {
    if (other.isInline()) {
        data_ = inlineValues();
        capacity_ = kInline;
        for (std::uint32_t i = 0; i < other.size_; ++i) {
            ::new (static_cast<void*>(data_ + i)) Value(std::move(other.data_[i]));
            other.data_[i].~Value();
        }
        size_ = other.size_;
    } else {
        data_ = other.data_;
        size_ = other.size_;
        capacity_ = other.capacity_;
        other.data_ = other.inlineValues();
        other.capacity_ = kInline;
    }
    other.size_ = 0;
}

void Row::release() noexcept {
    std::destroy(data_, data_ + size_);
    if (!isInline()) ::operator delete (static_cast<void*>(data_), std::align_val_t{alignof(Value)});
    data_ = inlineValues();
    size_ = 0;
    capacity_ = kInline;
}

void Row::grow(std::size_t atLeast) {
    const std::size_t capacity = std::max<std::size_t>(atLeast, kInline);
    auto* bigger = static_cast<Value*>(::operator new (capacity * sizeof(Value), std::align_val_t{alignof(Value)}));
    for (std::uint32_t i = 0; i < size_; ++i) {
        ::new (static_cast<void*>(bigger + i)) Value(std::move(data_[i]));
        data_[i].~Value();
    }
    if (!isInline()) ::operator delete (static_cast<void*>(data_), std::align_val_t{alignof(Value)});
    data_ = bigger;
    capacity_ = static_cast<std::uint32_t>(capacity);
}

Value& Row::at(std::size_t i) {
    if (i >= size_) throw std::out_of_range("Row::at");
    return data_[i];
}

const Value& Row::at(std::size_t i) const {
    if (i >= size_) throw std::out_of_range("Row::at");
    return data_[i];
}

void Row::clear() {
    std::destroy(data_, data_ + size_);
    size_ = 0;
}

void Row::resize(std::size_t n) {
    while (size_ > n) pop_back();
    reserve(n);
    while (size_ < n) emplace_back();
}

Value* Row::insert(const Value* at, Value value) {
    const std::size_t index = static_cast<std::size_t>(at - data_);
    emplace_back(std::move(value));
    std::rotate(data_ + index, data_ + size_ - 1, data_ + size_);
    return data_ + index;
}

Value* Row::erase(const Value* at) {
    const std::size_t index = static_cast<std::size_t>(at - data_);
    std::move(data_ + index + 1, data_ + size_, data_ + index);
    pop_back();
    return data_ + index;
}

bool operator==(const Row& a, const Row& b) { return std::equal(a.begin(), a.end(), b.begin(), b.end()); }

bool operator==(const Row& a, const std::vector<Value>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end());
}

int ResultSet::columnIndex(std::string_view name) const {
    for (std::size_t i = 0; i < columns.size(); ++i)
        if (columns[i].name == name) return static_cast<int>(i);
    return -1;
}

}  // namespace smql
