// Names -> node sets. Resolves categories (with "did you mean" hints for
// unknown ones), kind words, sides of the room (`wall.left`), node and source
// ids, sub-queries, units and the viewpoint, against one scene snapshot.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "engine/binder/bound.hpp"

namespace smql::binder {

struct BindContext {
    const exec::SceneSnapshot& scene;
    const relations::Thresholds& thresholds;
    // Is the category known anywhere in the database (so an empty match is an answer, not a typo)?
    std::function<bool(const std::string&)> categoryExistsElsewhere;
    // Runs a sub-query's FIND in the same scene and read transaction.
    std::function<std::vector<Slot>(const ast::FindStmt&)> runSubquery;
};

class Binder {
public:
    explicit Binder(BindContext context) : ctx_(std::move(context)) {}

    BoundFind bindFind(const ast::FindStmt& find) const;
    BoundFind bindCount(const ast::CountStmt& count) const;
    BoundRelate bindRelate(const ast::RelateStmt& relate) const;
    NodeSet bindRef(const ast::Ref& ref, const relations::Frame& frame) const;

private:
    Target bindTarget(const ast::Ref& ref, const relations::Frame& frame) const;
    relations::Frame bindView(const std::optional<ast::View>& view, std::string& description) const;
    BoundExpr bindExpr(const ast::Expr& expr, const relations::Frame& frame) const;
    NodeSet bindName(const ast::Ref& ref) const;
    NodeSet bindSide(const ast::Ref& ref, const relations::Frame& frame) const;
    std::string resolveCategory(const ast::Ref& ref) const;

    BindContext ctx_;
};

}  // namespace smql::binder
