// CHECK a pred b [AND c] [distance] [VIEW ...]: one predicate over single nodes, yes or no.
#include <fmt/format.h>

#include "engine/binder/binder.hpp"
#include "model/error.hpp"
#include "model/names.hpp"

namespace smql::binder {

void Binder::bindStatement(const ast::CheckStmt& check, BoundStatement& out) {
    const auto& spec = predicateNamed(check.predicate, check.predicateWhere);
    if (static_cast<int>(check.args.size()) != spec.arity)
        throw Error(ErrorKind::Binding,
                    fmt::format("{} takes {} reference{} after it, got {}", check.predicate, spec.arity,
                                spec.arity == 1 ? "" : "s", check.args.size()),
                    check.predicateWhere,
                    spec.arity == 1 ? fmt::format("as in CHECK lamp {} window", check.predicate)
                                    : fmt::format("as in CHECK lamp {} sofa AND desk", check.predicate));
    BoundCheck bound;
    bound.predicate = spec.predicate;
    if (check.threshold) bound.nearDistance = predicateDistance(spec, *check.threshold);
    bound.view = bindView(check.view);
    bound.subject = bindSingle(check.subject, "CHECK");
    for (const auto& arg : check.args) bound.args.push_back(bindSingle(arg, "CHECK"));
    out.body = std::move(bound);
}

}  // namespace smql::binder
