// GUIDE FROM origin TO goal: both ends are bound as node sets; the executor checks that each is one
// node, since a sub-query's answer is known only when it runs.
#include "engine/binder/binder.hpp"
#include "model/error.hpp"

namespace smql::binder {

void Binder::bindStatement(const ast::GuideStmt& guide, BoundStatement& out) {
    if (ctx_.session.allScenes)
        throw Error(ErrorKind::Binding, "GUIDE finds a way within one scene", guide.where, "USE SCENE 'name' first");
    BoundGuide bound;
    if (guide.from) bound.from = bindRef(*guide.from);
    bound.point = guide.point;
    bound.to = bindRef(guide.to);
    scene();
    out.body = std::move(bound);
}

}  // namespace smql::binder
