// ASK 'question': the translator turns the question into one SMQL statement, which is parsed and
// bound here like any statement (in the same scene, numbered with the same sets), so the planner
// and the executor run it in the ASK's read transaction.
#include <fmt/format.h>

#include "engine/ask/answer.hpp"
#include "engine/binder/binder.hpp"
#include "engine/parser/parser.hpp"
#include "model/error.hpp"

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

}  // namespace

void Binder::bindStatement(const ast::AskStmt& ask, BoundStatement& out) {
    const auto& snap = scene();
    const ask::Translator& translator =
        ctx_.session.askTranslator ? *ctx_.session.askTranslator : ask::ruleTranslator();
    BoundAsk bound;
    try {
        bound.translation = translator.translate({ask.question, snap.info().name, snap.categories()});
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
