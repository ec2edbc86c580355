// FIND and COUNT: in the current scene, or by category across every scene (USE SCENE '*').
#include <fmt/format.h>

#include "engine/binder/binder.hpp"
#include "model/error.hpp"
#include "model/names.hpp"
#include "storage/database.hpp"

namespace smql::binder {

BoundFind Binder::bindFind(const ast::FindStmt& find) {
    BoundFind out;
    out.view = bindView(find.view);
    out.target = bindTarget(find.target);
    if (find.where) out.where = bindExpr(*find.where);
    if (find.nearestTo && find.orderBy)
        throw Error(ErrorKind::Binding, "NEAREST TO and ORDER BY both set an order", find.orderBy->where,
                    "keep one: NEAREST TO x is ORDER BY distance(x) without x itself");
    if (find.nearestTo) {
        out.distanceTo = bindRef(*find.nearestTo);
        out.nearest = true;
    } else if (find.orderBy) {
        out.distanceTo = bindRef(find.orderBy->distanceTo);
        out.descending = find.orderBy->descending;
    }
    out.limit = find.limit;
    out.path = find.path;
    return out;
}

BoundCatalogFind Binder::bindCatalogFind(const ast::Ref& target, const std::optional<ast::Expr>& where,
                                         const std::optional<ast::View>& view, std::optional<std::int64_t> limit,
                                         bool countOnly) {
    if (target.kind != ast::Ref::Kind::Name)
        throw Error(ErrorKind::Binding, "across all scenes, FIND and COUNT take a category", target.where,
                    "USE SCENE 'name' to query one scene by id, side or sub-query");
    if (where)
        throw Error(ErrorKind::Binding, "across all scenes, FIND and COUNT take no WHERE", where->where,
                    "metric predicates need one scene: USE SCENE 'name'");
    if (view)
        throw Error(ErrorKind::Binding, "across all scenes, FIND and COUNT take no VIEW", view->where,
                    "a viewpoint belongs to one scene: USE SCENE 'name'");
    if (ctx_.txn.countWithCategory(target.name) == 0) {
        std::vector<std::string> names;
        for (const auto& [name, count] : ctx_.txn.categories()) names.push_back(name);
        auto close = model::nearestNames(target.name, names);
        throw Error(ErrorKind::Binding, fmt::format("unknown category '{}' in any scene", target.name), target.where,
                    close.empty() ? "" : "did you mean " + model::joinAlternatives(close) + "?");
    }
    return BoundCatalogFind{target.name, limit, countOnly};
}

void Binder::bindStatement(const ast::FindStmt& find, BoundStatement& out) {
    if (ctx_.session.allScenes) {
        if (find.nearestTo || find.orderBy || find.path)
            throw Error(ErrorKind::Binding, "across all scenes, FIND takes no NEAREST TO, ORDER BY or PATH",
                        find.target.where, "these measure within one scene: USE SCENE 'name'");
        out.body = bindCatalogFind(find.target, find.where, find.view, find.limit, false);
        return;
    }
    out.body = bindFind(find);
}

// COUNT is a FIND without order, limit or path that returns only how many.
void Binder::bindStatement(const ast::CountStmt& count, BoundStatement& out) {
    if (ctx_.session.allScenes) {
        out.body = bindCatalogFind(count.target, count.where, count.view, std::nullopt, true);
        return;
    }
    ast::FindStmt find;
    find.target = count.target;
    find.view = count.view;
    find.where = count.where;
    BoundFind bound = bindFind(find);
    bound.countOnly = true;
    out.body = std::move(bound);
}

}  // namespace smql::binder
