// EXPLAIN statement: the inner statement is bound as it would run; the planner plans it and the
// executor prints that plan instead of running it.
#include "engine/binder/binder.hpp"

namespace smql::binder {

void Binder::bindStatement(const ast::ExplainStmt& explain, BoundStatement& out) {
    BoundStatement inner;
    std::visit([&](const auto& body) { bindStatement(body, inner); }, explain.inner->body);
    inner.scene = scene_;
    inner.setCount = nextSetId_;
    out.body = BoundExplain{std::make_shared<const BoundStatement>(std::move(inner))};
}

}  // namespace smql::binder
