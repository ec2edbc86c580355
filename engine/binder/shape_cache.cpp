#include "engine/binder/shape_cache.hpp"

#include <vector>

#include "engine/binder/parameters.hpp"
#include "model/error.hpp"

namespace smql::binder {

namespace {

using parser::ShapeLiteral;

// The literals as the values of the shape's placeholders: $k takes literal k.
std::vector<std::optional<ParameterValue>> valuesOf(const parser::StatementShape& shape) {
    std::vector<std::optional<ParameterValue>> values;
    values.reserve(shape.literals.size());
    for (const ShapeLiteral& literal : shape.literals) {
        switch (literal.kind) {
            case ShapeLiteral::Kind::Text:
                values.emplace_back(literal.text);
                break;
            case ShapeLiteral::Kind::Integer:
            case ShapeLiteral::Kind::NodeId:
                values.emplace_back(literal.integer);
                break;
            case ShapeLiteral::Kind::Real:
                values.emplace_back(literal.number);
                break;
            case ShapeLiteral::Kind::Length:
                values.emplace_back(Length{literal.number});
                break;
        }
    }
    return values;
}

// The statement's own text, and EXPLAIN's statement's, as the parser would have cut them from `text`.
void takeText(ast::Statement& statement, const parser::StatementShape& shape, std::string_view text) {
    statement.text = std::string(text.substr(shape.begin, shape.end - shape.begin));
    if (auto* explain = std::get_if<ast::ExplainStmt>(&statement.body))
        explain->inner->text = std::string(text.substr(shape.afterExplain, shape.end - shape.afterExplain));
}

}  // namespace

std::optional<ast::Statement> ShapeCache::statementOf(const parser::StatementShape& shape, std::string_view text) {
    auto found = byKey_.find(shape.key);
    if (found == byKey_.end()) return std::nullopt;
    entries_.splice(entries_.begin(), entries_, found->second);
    const std::shared_ptr<const ast::Statement>& cached = found->second->statement;
    if (!cached) return std::nullopt;
    try {
        // withParameters copies what it changes (EXPLAIN's statement and sub-queries too), so the
        // cached statement stays as it was.
        ast::Statement statement = withParameters(*cached, valuesOf(shape));
        takeText(statement, shape, text);
        statement.fromShape = true;
        ++stats_.hits;
        return statement;
    } catch (const Error&) {
        return std::nullopt;  // a literal its place refuses: the parser words the error
    }
}

void ShapeCache::learn(const parser::StatementShape& shape, const ast::Statement& parsed) {
    if (capacity_ == 0 || byKey_.count(shape.key) != 0) return;
    std::shared_ptr<const ast::Statement> statement;
    try {
        auto shaped = std::make_shared<const ast::Statement>(parser::parseShape(shape));
        if (parser::sameStatement(withParameters(*shaped, valuesOf(shape)), parsed)) statement = std::move(shaped);
    } catch (const Error&) {
        // A placeholder cannot stand where a literal is (USE SCENE 'x', AS OF '...', CHECK's distance).
    }
    ++(statement ? stats_.learned : stats_.refused);
    keep(shape.key, std::move(statement));
}

void ShapeCache::keep(const std::string& key, std::shared_ptr<const ast::Statement> statement) {
    entries_.push_front(Entry{key, std::move(statement)});
    byKey_.emplace(entries_.front().key, entries_.begin());
    setCapacity(capacity_);
}

void ShapeCache::setCapacity(std::size_t capacity) {
    capacity_ = capacity;
    while (entries_.size() > capacity_) {
        byKey_.erase(entries_.back().key);
        entries_.pop_back();
        ++stats_.evicted;
    }
}

ShapeCacheStats ShapeCache::stats() const {
    ShapeCacheStats out = stats_;
    out.size = entries_.size();
    return out;
}

}  // namespace smql::binder
