// DESCRIBE x: every field of the nodes x names.
#include "engine/binder/binder.hpp"

namespace smql::binder {

void Binder::bindStatement(const ast::DescribeStmt& describe, BoundStatement& out) {
    out.body = BoundDescribe{bindRef(describe.target)};
}

}  // namespace smql::binder
