// The statement shapes the engine has parsed (parser/normalise.hpp), so that a text that differs
// from one seen before only in its literals skips the parser: its literals become the bound values
// of the shape's placeholders (parameters.hpp), as data, never parsed again. Bounded; the least
// recently used shape goes first.
#pragma once

#include <cstddef>
#include <cstdint>
#include <list>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>

#include "engine/parser/ast.hpp"
#include "engine/parser/normalise.hpp"

namespace smql::binder {

struct ShapeCacheStats {
    std::uint64_t hits = 0;     // statements made from a cached shape
    std::uint64_t learned = 0;  // shapes parsed and kept
    std::uint64_t refused = 0;  // shapes found not to share a parse (kept as such, never parsed again)
    std::uint64_t evicted = 0;  // shapes dropped for the capacity
    std::size_t size = 0;       // shapes held now, refused ones included
};

class ShapeCache {
public:
    explicit ShapeCache(std::size_t capacity) : capacity_(capacity) {}

    // The statement of `text`, whose shape is `shape`: the cached shape's statement with the text's
    // literals bound into it and marked ast::Statement::fromShape. Nothing when the shape is not
    // cached, is one that does not share a parse, or refuses one of these literals (an empty name):
    // then the text goes to the parser, which says what is wrong with it, if anything.
    std::optional<ast::Statement> statementOf(const parser::StatementShape& shape, std::string_view text);

    // After `text`'s full parse gave `parsed`: parses the shape's placeholder text and keeps it when
    // binding this text's literals into it gives `parsed` again; else remembers the shape as one
    // that does not share a parse (a literal where a placeholder cannot stand, or means another thing).
    void learn(const parser::StatementShape& shape, const ast::Statement& parsed);

    // At most `capacity` shapes from now on (0: none kept, and statementOf finds none).
    void setCapacity(std::size_t capacity);
    std::size_t capacity() const { return capacity_; }
    ShapeCacheStats stats() const;

private:
    struct Entry {
        std::string key;
        std::shared_ptr<const ast::Statement> statement;  // null: the shape does not share a parse
    };
    std::size_t capacity_;
    std::list<Entry> entries_;                                                // the most recently used first
    std::unordered_map<std::string_view, std::list<Entry>::iterator> byKey_;  // views of entries_' keys
    ShapeCacheStats stats_;

    void keep(const std::string& key, std::shared_ptr<const ast::Statement> statement);
};

}  // namespace smql::binder
