// RELATE a TO b [VIEW ...]: every relation that holds between the two sets' nodes.
#include "engine/binder/binder.hpp"

namespace smql::binder {

void Binder::bindStatement(const ast::RelateStmt& relate, BoundStatement& out) {
    BoundRelate bound;
    bound.view = bindView(relate.view);
    bound.subject = bindSingle(relate.subject, "RELATE");
    bound.object = bindSingle(relate.object, "RELATE");
    out.body = std::move(bound);
}

}  // namespace smql::binder
