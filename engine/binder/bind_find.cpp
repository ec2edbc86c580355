// FIND and COUNT: in the current scene, or by category across every scene (USE SCENE '*').
#include <fmt/format.h>

#include "engine/ask/lexicon.hpp"
#include "engine/binder/binder.hpp"
#include "engine/catalog/attributes.hpp"
#include "model/category.hpp"
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
        if (find.orderBy->distanceTo) {
            out.distanceTo = bindRef(*find.orderBy->distanceTo);
        } else if (find.orderBy->attribute == "distance") {
            throw Error(ErrorKind::Binding, "ORDER BY distance needs what to measure from", find.orderBy->where,
                        "as in ORDER BY distance(door)");
        } else {
            comparable(find.orderBy->attribute, find.orderBy->where);
            out.orderAttribute = find.orderBy->attribute;
        }
        out.descending = find.orderBy->descending;
    }
    if (find.similarTo) {
        if (find.nearestTo || find.orderBy)
            throw Error(ErrorKind::Binding,
                        fmt::format("SIMILAR TO and {} both set an order", find.nearestTo ? "NEAREST TO" : "ORDER BY"),
                        find.similarTo->where,
                        "keep one; to rank the things near x by similarity, write WHERE near(x) SIMILAR TO '...'");
        if (!find.similarTo->vector.empty()) {
            out.similarTo = BoundSimilarTo{{}, storedSpaceQuery(find.similarTo->vector, find.similarTo->where)};
        } else {
            if (find.similarTo->text.find_first_not_of(" \t\n") == std::string::npos)
                throw Error(ErrorKind::Binding, "SIMILAR TO needs words to compare with", find.similarTo->where,
                            "describe the thing, as in SIMILAR TO 'soft thing to sit on'");
            out.similarTo = BoundSimilarTo{find.similarTo->text, {}};
        }
    }
    for (const auto& column : find.columns) {
        bool known = catalog::attributeIn(scene(), column) || (column == "distance" && out.distanceTo) ||
                     (column == "similarity" && out.similarTo);
        if (!known) {
            std::vector<std::string> names;
            for (const auto& attribute : catalog::builtInAttributes()) names.emplace_back(attribute.name);
            for (const auto& stored : scene().attributeNames()) names.push_back(stored);
            if (out.distanceTo) names.emplace_back("distance");
            if (out.similarTo) names.emplace_back("similarity");
            auto close = model::nearestNames(column, names);
            throw Error(ErrorKind::Binding, fmt::format("unknown column '{}' in RETURN", column), find.returnWhere,
                        close.empty() ? "SHOW ATTRIBUTES lists the columns"
                                      : fmt::format("did you mean {}? SHOW ATTRIBUTES lists the columns",
                                                    model::joinAlternatives(close)));
        }
        out.columns.push_back(column);
    }
    out.limit = find.limit;
    out.path = find.path;
    return out;
}

// A bound vector is compared with the vectors an external model gave the scene's nodes: the scene
// must have them, of the vector's length. The query is scaled to unit length, as they are.
std::vector<float> Binder::storedSpaceQuery(const std::vector<float>& vector, SourceLocation where) {
    const similar::EmbeddingIndex* stored = scene().storedEmbeddings(ctx_.txn);
    if (!stored)
        throw Error(
            ErrorKind::Usage,
            scene().historical()
                ? fmt::format("scene '{}' as it was then has no stored embeddings to compare a vector with: "
                              "a superseded version keeps no blobs",
                              scene().info().name)
                : fmt::format("scene '{}' has no stored embeddings to compare a vector with", scene().info().name),
            where,
            "give the entries of detections.json an \"embedding\" field at ingest (docs/formats.md), or "
            "bind text to search the built-in text embedder's space");
    if (stored->dimensions() != vector.size())
        throw Error(ErrorKind::Usage,
                    fmt::format("the scene's embeddings have {} dimensions; the bound vector has {}",
                                stored->dimensions(), vector.size()),
                    where, "bind the query's embedding from the model that made the scene's embeddings");
    return similar::unitVector(vector);
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
    const std::uint64_t transaction = ctx_.txn.transactionId();
    if (ctx_.categoryCounts)
        if (const CategoryCount* kept = ctx_.categoryCounts->find(target.name, transaction))
            return BoundCatalogFind{kept->keys.front(), kept->keys, limit, countOnly, kept->count};
    std::vector<std::string> keys = ctx_.txn.labelKeys(target.name);
    const std::uint64_t count = ctx_.txn.countWithKeys(keys);
    if (count == 0) {
        std::vector<std::string> names;
        for (const auto& [name, count] : ctx_.txn.categories()) names.push_back(model::categoryName(name));
        if (auto noun = ask::absentThing(target.name, ask::Lexicon(names).lookUp(target.name))) {
            notes_.push_back(fmt::format("no {} in any scene", *noun));
            keys = ctx_.txn.labelKeys(*noun);
            const std::uint64_t nounCount = ctx_.txn.countWithKeys(keys);
            return BoundCatalogFind{*noun, std::move(keys), limit, countOnly, nounCount};
        }
        auto close = model::nearestNames(target.name, names);
        throw Error(ErrorKind::Binding, fmt::format("unknown category '{}' in any scene", target.name), target.where,
                    close.empty() ? "" : "did you mean " + model::joinAlternatives(close) + "?");
    }
    if (ctx_.categoryCounts) ctx_.categoryCounts->keep(target.name, transaction, {keys, count});
    // labelKeys' first key is the canonical name (model::categoryName).
    std::string category = keys.front();
    return BoundCatalogFind{std::move(category), std::move(keys), limit, countOnly, count};
}

void Binder::bindStatement(const ast::FindStmt& find, BoundStatement& out) {
    if (find.asOf) useVersion(*find.asOf);
    if (ctx_.session.allScenes) {
        if (find.nearestTo || find.orderBy || find.path || !find.columns.empty() || find.similarTo)
            throw Error(ErrorKind::Binding,
                        "across all scenes, FIND takes no NEAREST TO, ORDER BY, SIMILAR TO, PATH or RETURN",
                        find.target.where, "these measure within one scene: USE SCENE 'name'");
        out.body = bindCatalogFind(find.target, find.where, find.view, find.limit, false);
        return;
    }
    out.body = bindFind(find);
}

// COUNT is a FIND without order, limit or path that returns only how many.
void Binder::bindStatement(const ast::CountStmt& count, BoundStatement& out) {
    if (count.asOf) useVersion(*count.asOf);
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
