// CHECK a pred b [AND c] [distance] [VIEW ...]: one predicate over single nodes, yes or no.
#include <fmt/format.h>

#include "engine/binder/binder.hpp"
#include "model/error.hpp"
#include "model/names.hpp"

namespace smql::binder {

void Binder::bindStatement(const ast::CheckStmt& check, BoundStatement& out) {
    const auto* spec = relations::predicateNamed(check.predicate);
    if (!spec) {
        auto words = relations::predicateWords();
        auto close = model::nearestNames(check.predicate, words);
        throw Error(ErrorKind::Binding, fmt::format("unknown predicate '{}'", check.predicate), check.predicateWhere,
                    close.empty() ? "predicates: " + model::joinAlternatives(words)
                                  : "did you mean " + model::joinAlternatives(close) + "?");
    }
    if (static_cast<int>(check.args.size()) != spec->arity)
        throw Error(ErrorKind::Binding,
                    fmt::format("{} takes {} reference{} after it, got {}", check.predicate, spec->arity,
                                spec->arity == 1 ? "" : "s", check.args.size()),
                    check.predicateWhere,
                    spec->arity == 1 ? fmt::format("as in CHECK lamp {} window", check.predicate)
                                     : fmt::format("as in CHECK lamp {} sofa AND desk", check.predicate));
    BoundCheck bound;
    bound.predicate = spec->predicate;
    if (check.threshold) {
        if (!spec->takesDistance)
            throw Error(ErrorKind::Binding, fmt::format("{} takes no distance", check.predicate),
                        check.threshold->where, "near takes one, as in CHECK mug near window 1 m");
        bound.nearDistance = check.threshold->metres;
    }
    bound.view = bindView(check.view);
    bound.subject = bindSingle(check.subject, "CHECK");
    for (const auto& arg : check.args) bound.args.push_back(bindSingle(arg, "CHECK"));
    out.body = std::move(bound);
}

}  // namespace smql::binder
