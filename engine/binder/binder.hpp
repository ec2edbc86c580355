// AST -> bound statement. Resolves categories (with "did you mean" hints for
// unknown ones), kind words, node and source ids, sub-queries (bound here,
// planned and run later), units, settings and scene names. One file per
// statement (bind_<statement>.cpp); references, expressions and views, which
// every statement shares, are bound in binder.cpp.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "engine/ask/lexicon.hpp"
#include "engine/binder/bound.hpp"
#include "engine/binder/category_counts.hpp"
#include "engine/binder/parameters.hpp"
#include "engine/catalog/attributes.hpp"
#include "engine/catalog/session.hpp"

namespace smql::storage {
class ReadTransaction;
}

namespace smql::binder {

struct BindContext {
    const storage::ReadTransaction& txn;
    const catalog::Session& session;
    // The current scene's snapshot, loaded when a statement first needs one.
    std::function<std::shared_ptr<const catalog::SceneSnapshot>()> currentScene;
    // The current scene as it was at an instant (model::utcInstant's form): its version then.
    std::function<std::shared_ptr<const catalog::SceneSnapshot>(const std::string& instant)> sceneAsOf;
    // The categories named across all scenes in earlier statements (null: none kept); the binder
    // reads and adds to them.
    CategoryCounts* categoryCounts = nullptr;
};

class Binder {
public:
    explicit Binder(BindContext context) : ctx_(std::move(context)) {}

    // A statement with placeholders is bound with `values` put in first (parameters.hpp); without
    // them, its first placeholder is an error.
    BoundStatement bind(const ast::Statement& statement, const std::vector<std::optional<ParameterValue>>& values = {});

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
    void bindStatement(const ast::AskStmt& ask, BoundStatement& out);
    // A translation's SMQL parsed and bound as the statement a question runs.
    std::shared_ptr<const BoundStatement> bindTranslation(const ask::Translation& translation);
    void bindStatement(const ast::DropSceneStmt& drop, BoundStatement& out);
    void bindStatement(const ast::RenameSceneStmt& rename, BoundStatement& out);
    void bindStatement(const ast::GuideStmt& guide, BoundStatement& out);
    void bindStatement(const ast::CheckStmt& check, BoundStatement& out);
    // AS OF: the statement reads the version of the current scene at that instant.
    void useVersion(const ast::AsOf& asOf);

    BoundFind bindFind(const ast::FindStmt& find);
    // SIMILAR TO's bound vector checked against the scene's stored embeddings, at unit length.
    std::vector<float> storedSpaceQuery(const std::vector<float>& vector, SourceLocation where);
    BoundCatalogFind bindCatalogFind(const ast::Ref& target, const std::optional<ast::Expr>& where,
                                     const std::optional<ast::View>& view, std::optional<std::int64_t> limit,
                                     bool countOnly);

    // Shared by the statements (binder.cpp).
    const catalog::SceneSnapshot& scene();
    NodeSet bindRef(const ast::Ref& ref);
    // A reference where one node is needed (`role` says where, for the error).
    NodeSet bindSingle(const ast::Ref& ref, std::string_view role);
    Target bindTarget(const ast::Ref& ref);
    BoundView bindView(const std::optional<ast::View>& view);
    BoundExpr bindExpr(const ast::Expr& expr);
    NodeSet bindName(const ast::Ref& ref);
    std::string resolveCategory(const ast::Ref& ref);
    // A category with no node here, remembered for the answer's note.
    std::string noted(std::string category);
    // The predicate called `name` (WHERE's calls, CHECK), or an error with the closest names.
    static const relations::PredicateSpec& predicateNamed(const std::string& name, SourceLocation where);
    // A distance given to a predicate: its metres, or an error naming the predicates that take one.
    static double predicateDistance(const relations::PredicateSpec& spec, const ast::Distance& distance);
    // An attribute a comparison or ORDER BY can use, or an error with the closest names.
    catalog::AttributeInfo comparable(const std::string& name, SourceLocation where);
    NodeSet numbered(NodeSet set);

    BindContext ctx_;
    std::shared_ptr<const catalog::SceneSnapshot> scene_;
    std::size_t nextSetId_ = 0;
    // Binding an ASK's translation: a question cannot name nodes by id, so its RELATE relates every
    // pair and the answer sums them up in words (docs/ask.md).
    bool inQuestion_ = false;
    std::vector<std::string> notes_;  // said under the answer: "no piano in scene 'x'"
};

}  // namespace smql::binder
