// ASK 'question': the translator turns the question into one SMQL statement, which is parsed and
// bound here like any statement (in the same scene, numbered with the same sets), so the planner
// and the executor run it in the ASK's read transaction. A plugged-in translator (a language
// model's endpoint) whose statement fails to bind is asked once to repair it; where it cannot
// answer, or its repair fails too, the built-in reader answers, and a note says so.
#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <set>
#include "engine/ask/answer.hpp"

#include "engine/binder/binder.hpp"
#include "engine/catalog/attributes.hpp"
#include "engine/catalog/scene_snapshot.hpp"
#include "engine/parser/parser.hpp"
#include "model/category.hpp"
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
// walls, doors, windows or ceilings (what is on them hangs there), and the ones it holds several of.
ask::Question questionAbout(const std::string& text, const catalog::SceneSnapshot& snap) {
    ask::Question q{text, snap.info().name, snap.categories(), {}, {}, snap.attributeNames()};
    std::map<std::string, std::pair<int, bool>> seen;  // category -> count, all vertical planes
    std::set<std::string> anchors, rooms;
    std::size_t roots = 0;
    for (const auto& node : snap.nodes()) {
        if (node.kind == model::NodeKind::Scene && ++roots == 1) q.sceneRoot = node.id;
        if (node.kind == model::NodeKind::Room) rooms.insert(node.category);
        if (node.kind != model::NodeKind::Object && node.kind != model::NodeKind::Anchor) continue;
        if (node.kind == model::NodeKind::Anchor) anchors.insert(node.category);
        auto [it, fresh] = seen.try_emplace(node.category, 0, true);
        ++it->second.first;
        it->second.second = it->second.second && (relations::isVerticalPlane(node) || relations::isCeiling(node));
    }
    if (roots != 1) q.sceneRoot = model::kNoNode;
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

// SMQL in brief for a language model, from the tables: the predicates' usage lines and the
// attributes' meanings.
const std::string& grammarSummary() {
    static const std::string summary = [] {
        std::string out =
            "SMQL statements (one per answer; names are categories, bare or quoted):\n"
            "  FIND <target> [WHERE <condition>] [ORDER BY <measure> [DESC]] [LIMIT n] [PATH]\n"
            "  COUNT <target> [WHERE <condition>]\n"
            "  RELATE <ref> TO <ref>\n"
            "  GUIDE FROM <ref> TO <ref>\n"
            "<target>: a category (sofa), object, anchor or thing. <ref>: a category, wall.left (a side), "
            "sofa#12 or #12 (a node by id), or a sub-query (FIND ...).\n"
            "<condition>: a predicate, <attribute> <op> <value> (=, !=, <, <=, >, >=, LIKE; lengths with m or cm), "
            "<attribute> IS [NOT] NULL, category = 'name', NOT <condition>, <condition> AND <condition>, "
            "<condition> OR <condition>, (...).\n"
            "<measure>: an attribute, or distance(<ref>).\n"
            "Predicates:\n";
        for (const auto& p : relations::predicates()) out += fmt::format("  {}\n", p.usage);
        out += "Attributes:\n";
        for (const auto& a : catalog::builtInAttributes()) out += fmt::format("  {}: {}\n", a.name, a.meaning);
        out +=
            "Examples: what is on the sofa? FIND object WHERE on(sofa). How many chairs are near the table? "
            "COUNT chair WHERE near(table). Which cushion is closest to the window? FIND cushion ORDER BY "
            "distance(window) LIMIT 1.";
        return out;
    }();
    return summary;
}

}  // namespace

std::shared_ptr<const BoundStatement> Binder::bindTranslation(const ask::Translation& translation) {
    auto statements = parser::parse(translation.smql);
    // A question reads: a translator (perhaps a language model's) may not switch the scene,
    // change settings or ask again.
    if (statements.size() != 1 || !reads(statements.front()))
        throw Error(ErrorKind::Binding, "a question must translate to one statement that reads", std::nullopt,
                    "FIND, COUNT, RELATE, DESCRIBE, SHOW or GUIDE; not USE, SET, DROP, RENAME, EXPLAIN or ASK");
    // A translation with placeholders has no values for them: an error naming the first.
    if (statements.front().parameterCount > 0) withParameters(statements.front(), {});
    BoundStatement inner;
    inQuestion_ = true;
    try {
        std::visit([&](const auto& body) { bindStatement(body, inner); }, statements.front().body);
    } catch (...) {
        inQuestion_ = false;
        throw;
    }
    inQuestion_ = false;
    inner.scene = scene_;
    inner.setCount = nextSetId_;
    return std::make_shared<const BoundStatement>(std::move(inner));
}

void Binder::bindStatement(const ast::AskStmt& ask, BoundStatement& out) {
    const auto& snap = scene();
    const ask::Translator& builtIn = ask::ruleTranslator();
    const ask::Translator& translator = ctx_.session.askTranslator ? *ctx_.session.askTranslator : builtIn;
    ask::Question question = questionAbout(ask.question, snap);
    // Across every scene (USE SCENE '*') there is no one room to sum up.
    if (ctx_.session.allScenes) question.sceneRoot = model::kNoNode;
    question.sceneCount = ctx_.txn.scenes().size();
    question.grammar = grammarSummary();
    BoundAsk bound;
    // The built-in reader's translation, with a note of why it answers instead.
    auto readByBuiltIn = [&](const std::string& why) {
        try {
            bound.translation = builtIn.translate(question);
        } catch (const Error& e) {
            throw Error(e.kind(), e.message() + " (" + why + ")", ask.where, e.hint());
        }
        bound.translation.notes.push_back(why + ": the built-in reader answered");
        return &builtIn;
    };
    const ask::Translator* used = &translator;
    try {
        bound.translation = translator.translate(question);
    } catch (const ask::Unavailable& e) {
        used = readByBuiltIn(fmt::format("the translator at {} failed ({})", translator.name(), e.what()));
    } catch (const Error& e) {
        throw Error(e.kind(), e.message(), ask.where, e.hint());
    }
    // Whatever translated it, the answer may say that a kind the scene has none of may be a thing it could not name.
    auto finish = [&] {
        bound.translation.unnamedThings = std::find(question.categories.begin(), question.categories.end(),
                                                    model::kUnnamedCategory) != question.categories.end();
        out.body = std::move(bound);
    };
    if (!bound.translation.runnable) {
        finish();
        return;
    }
    try {
        bound.inner = bindTranslation(bound.translation);
    } catch (const Error& e) {
        if (used == &builtIn) throw ask::failedTranslation(e, bound.translation.smql, ask.where);
        // A plugged-in translator that repairs (a model's) is told the error once; its repair must
        // bind, else the built-in reader answers.
        std::optional<ask::Translation> repaired;
        std::string failure = e.message();
        bool asked = false;
        try {
            repaired = translator.repair(question, bound.translation, e.message());
        } catch (const ask::Unavailable& u) {
            failure += std::string("; its repair failed: ") + u.what();
            asked = true;
        }
        // A translator that does not repair (one plugged in through the C++ API) keeps its error.
        if (!repaired && !asked) throw ask::failedTranslation(e, bound.translation.smql, ask.where);
        if (repaired) {
            try {
                bound.inner = bindTranslation(*repaired);
                bound.translation = std::move(*repaired);
            } catch (const Error& again) {
                failure = fmt::format("{}; its repair ({}) failed too: {}", failure, repaired->smql, again.message());
            }
        }
        if (!bound.inner) {
            used =
                readByBuiltIn(fmt::format("the SMQL of the translator at {} failed ({})", translator.name(), failure));
            if (bound.translation.runnable) {
                try {
                    bound.inner = bindTranslation(bound.translation);
                } catch (const Error& builtInError) {
                    throw ask::failedTranslation(builtInError, bound.translation.smql, ask.where);
                }
            }
        }
    }
    finish();
}

}  // namespace smql::binder
