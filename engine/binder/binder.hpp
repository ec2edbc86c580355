// AST -> bound statement. Resolves categories (with "did you mean" hints for
// unknown ones), kind words, node and source ids, sub-queries (bound here,
// planned and run later), units, settings and scene names. One file per
// statement (bind_<statement>.cpp); references, expressions and views, which
// every statement shares, are bound in binder.cpp.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "engine/binder/bound.hpp"
#include "engine/exec/session.hpp"

namespace smql::storage { class ReadTransaction; }

namespace smql::binder {

struct BindContext {
    const storage::ReadTransaction& txn;
    const exec::Session& session;
    // The current scene's snapshot, loaded when a statement first needs one.
    std::function<std::shared_ptr<const exec::SceneSnapshot>()> currentScene;
};

class Binder {
public:
    explicit Binder(BindContext context) : ctx_(std::move(context)) {}

    BoundStatement bind(const ast::Statement& statement);

private:
    // One per statement kind; each lives in bind_<statement>.cpp.
    void bindStatement(const ast::FindStmt& find, BoundStatement& out);
    void bindStatement(const ast::CountStmt& count, BoundStatement& out);
    void bindStatement(const ast::RelateStmt& relate, BoundStatement& out);
    void bindStatement(const ast::DescribeStmt& describe, BoundStatement& out);
    void bindStatement(const ast::ShowStmt& show, BoundStatement& out);
    void bindStatement(const ast::UseStmt& use, BoundStatement& out);
    void bindStatement(const ast::SetStmt& set, BoundStatement& out);
    void bindStatement(const ast::ExplainStmt& explain, BoundStatement& out);

    BoundFind bindFind(const ast::FindStmt& find);
    BoundCatalogFind bindCatalogFind(const ast::Ref& target, const std::optional<ast::Expr>& where,
                                     const std::optional<ast::View>& view, std::optional<std::int64_t> limit,
                                     bool countOnly);

    // Shared by the statements (binder.cpp).
    const exec::SceneSnapshot& scene();
    NodeSet bindRef(const ast::Ref& ref);
    Target bindTarget(const ast::Ref& ref);
    BoundView bindView(const std::optional<ast::View>& view);
    BoundExpr bindExpr(const ast::Expr& expr);
    NodeSet bindName(const ast::Ref& ref);
    std::string resolveCategory(const ast::Ref& ref);
    NodeSet numbered(NodeSet set);

    BindContext ctx_;
    std::shared_ptr<const exec::SceneSnapshot> scene_;
    std::size_t nextSetId_ = 0;
};

}  // namespace smql::binder
