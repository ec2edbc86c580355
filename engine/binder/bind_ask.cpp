// ASK 'question': the translator turns the question into one SMQL statement, which is parsed and
// bound here like any statement (in the same scene, numbered with the same sets), so the planner
// and the executor run it in the ASK's read transaction.
#include <fmt/format.h>

#include <map>
#include <set>
#include "engine/ask/answer.hpp"

#include "engine/binder/binder.hpp"
#include "engine/catalog/scene_snapshot.hpp"
#include "engine/parser/parser.hpp"
#include "model/error.hpp"
#include "relations/predicates.hpp"
#include "storage/database.hpp"

namespace smql::binder {

namespace {

// Whether a statement only reads: the ones that answer questions. USE and SET change the session,
// DROP and RENAME the database; EXPLAIN and ASK run no answer.
bool reads(const ast::Statement& statement) {
    const auto& body = statement.body;
    return std::holds_alternative<ast::FindStmt>(body) || std::holds_alternative<ast::CountStmt>(body) ||
           std::holds_alternative<ast::RelateStmt>(body) || std::holds_alternative<ast::DescribeStmt>(body) ||
           std::holds_alternative<ast::ShowStmt>(body) || std::holds_alternative<ast::GuideStmt>(body);
}

// The question with what the translator needs of the scene: its categories, the ones that are
// walls, doors or windows, and the ones it holds several of.
ask::Question questionAbout(const std::string& text, const catalog::SceneSnapshot& snap) {
    ask::Question q{text, snap.info().name, snap.categories(), {}, {}, snap.attributeNames()};
    std::map<std::string, std::pair<int, bool>> seen;  // category -> count, all vertical planes
    std::set<std::string> anchors, rooms;
    for (const auto& node : snap.nodes()) {
        if (node.kind == model::NodeKind::Room) rooms.insert(node.category);
        if (node.kind != model::NodeKind::Object && node.kind != model::NodeKind::Anchor) continue;
        if (node.kind == model::NodeKind::Anchor) anchors.insert(node.category);
        auto [it, fresh] = seen.try_emplace(node.category, 0, true);
        ++it->second.first;
        it->second.second = it->second.second && relations::isVerticalPlane(node);
    }
    for (const auto& [category, stats] : seen) {
        if (stats.second) q.planeCategories.push_back(category);
        if (stats.first > 1) q.repeatedCategories.push_back(category);
    }
    q.anchorCategories.assign(anchors.begin(), anchors.end());
    // A room node (a layout's room, with its area) is the scene as a place, not a thing in it: "the
    // kitchen" is not read as a kind of room node.
    std::erase_if(q.categories, [&](const std::string& c) { return rooms.count(c) && !seen.count(c); });
    return q;
}

}  // namespace

void Binder::bindStatement(const ast::AskStmt& ask, BoundStatement& out) {
    const auto& snap = scene();
    const ask::Translator& translator =
        ctx_.session.askTranslator ? *ctx_.session.askTranslator : ask::ruleTranslator();
    BoundAsk bound;
    try {
        ask::Question question = questionAbout(ask.question, snap);
        question.sceneCount = ctx_.txn.scenes().size();
        bound.translation = translator.translate(question);
    } catch (const Error& e) {
        throw Error(e.kind(), e.message(), ask.where, e.hint());
    }
    if (bound.translation.runnable) {
        try {
            auto statements = parser::parse(bound.translation.smql);
            // A question reads: a translator (perhaps a language model's) may not switch the scene,
            // change settings or ask again.
            if (statements.size() != 1 || !reads(statements.front()))
                throw Error(ErrorKind::Binding, "a question must translate to one statement that reads", std::nullopt,
                            "FIND, COUNT, RELATE, DESCRIBE, SHOW or GUIDE; not USE, SET, DROP, RENAME, EXPLAIN or ASK");
            // A translation with placeholders has no values for them: an error naming the first.
            if (statements.front().parameterCount > 0) withParameters(statements.front(), {});
            BoundStatement inner;
            inQuestion_ = true;
            std::visit([&](const auto& body) { bindStatement(body, inner); }, statements.front().body);
            inQuestion_ = false;
            inner.scene = scene_;
            inner.setCount = nextSetId_;
            bound.inner = std::make_shared<const BoundStatement>(std::move(inner));
        } catch (const Error& e) {
            throw ask::failedTranslation(e, bound.translation.smql, ask.where);
        }
    }
    out.body = std::move(bound);
}

}  // namespace smql::binder
