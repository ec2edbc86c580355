#include "engine/parser/ast_builder.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <map>
#include <optional>

#include <fmt/format.h>

#include "engine/parser/parser.hpp"
#include "engine/parser/syntax_errors.hpp"
#include "engine/parser/vocabulary.hpp"
#include "model/instant.hpp"

namespace smql::parser {

using grammar::SmqlParser;

namespace {

[[noreturn]] void fail(SourceLocation where, std::string message, std::string hint = {}) {
    throw Error(ErrorKind::Syntax, std::move(message), where, std::move(hint));
}

std::string nameOf(SmqlParser::NameContext& name) { return lowerCase(name.getText()); }

// 'it''s' -> it's
std::string unquote(const antlr4::Token& token) {
    std::string text = token.getText();
    if (text.size() > kMaxTextValue + 2)
        fail(locationOf(token), fmt::format("a quoted text of {} bytes: names, values and questions are at most {}",
                                            text.size() - 2, kMaxTextValue));
    const char quote = text.front();
    std::string inner = text.substr(1, text.size() - 2);
    std::string out;
    for (std::size_t i = 0; i < inner.size(); ++i) {
        out += inner[i];
        if (inner[i] == quote) ++i;  // the grammar only lets quotes in doubled
    }
    return out;
}

std::int64_t wholeNumber(std::string_view digits, const antlr4::Token& token, std::string_view what) {
    std::int64_t value = 0;
    auto [end, status] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (status != std::errc() || end != digits.data() + digits.size())
        fail(locationOf(token), fmt::format("{} {} is too large", what, token.getText()));
    return value;
}

double realNumber(const antlr4::Token& token) {
    std::string text = token.getText();
    double value = 0;
    auto [end, status] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (status != std::errc() || end != text.data() + text.size())
        fail(locationOf(token), fmt::format("the number {} is out of range", text));
    return value;
}

bool isWhole(const antlr4::Token& number) { return number.getText().find('.') == std::string::npos; }

bool isUnitWord(std::string_view word) { return unitsPerMetre(word).has_value(); }

// How many of `unit` make a metre; metres when there is no unit.
double perMetre(const antlr4::Token* unit) {
    if (!unit) return 1.0;
    if (std::optional<double> factor = unitsPerMetre(lowerCase(unit->getText()))) return *factor;
    throw notAUnit(*unit);
}

class AstBuilder {
public:
    AstBuilder(const Source& source, const std::vector<bool>& nodeIdPlaceholders)
        : source_(source), nodeIdPlaceholders_(nodeIdPlaceholders) {}

    ast::Statement statement(SmqlParser::StatementContext& tree) {
        numberPlaceholders(tree);
        SmqlParser::CommandContext& command = *tree.command();
        if (!tree.EXPLAIN()) return withParameterCount(statement(command, *tree.getStart()));
        ast::ExplainStmt explain{std::make_shared<ast::Statement>(statement(command, *command.getStart()))};
        return withParameterCount(wrap(std::move(explain), *tree.getStart(), *command.getStop()));
    }

private:
    const Source& source_;
    const std::vector<bool>& nodeIdPlaceholders_;
    // Each placeholder token's index, fixed before the walk: the walk does not visit the
    // statement in text order (GUIDE reads its target first), but `?` count in text order.
    std::map<const antlr4::Token*, std::size_t> placeholderIndex_;
    std::size_t parameterCount_ = 0;

    static void collectPlaceholders(antlr4::tree::ParseTree& tree, std::vector<const antlr4::Token*>& out) {
        if (auto* terminal = dynamic_cast<antlr4::tree::TerminalNode*>(&tree)) {
            if (terminal->getSymbol()->getType() == SmqlParser::PARAM) out.push_back(terminal->getSymbol());
            return;
        }
        for (antlr4::tree::ParseTree* child : tree.children) collectPlaceholders(*child, out);
    }

    // `?` are numbered 1, 2, ... in order; `$n` carry their number. Mixing the two would leave
    // the reader guessing which value goes where, so it is an error, as in SQL drivers.
    void numberPlaceholders(SmqlParser::StatementContext& tree) {
        std::vector<const antlr4::Token*> tokens;
        collectPlaceholders(tree, tokens);
        std::sort(tokens.begin(), tokens.end(), [](const antlr4::Token* a, const antlr4::Token* b) {
            return a->getStartIndex() < b->getStartIndex();
        });
        std::size_t positional = 0;
        const antlr4::Token* firstNumbered = nullptr;
        const antlr4::Token* firstPositional = nullptr;
        for (const antlr4::Token* token : tokens) {
            const std::string text = token->getText();
            std::size_t index = 0;
            if (text == "?") {
                if (!firstPositional) firstPositional = token;
                index = ++positional;
            } else {
                if (!firstNumbered) firstNumbered = token;
                const std::int64_t number = wholeNumber(std::string_view(text).substr(1), *token, "the placeholder");
                if (number < 1 || number > static_cast<std::int64_t>(kMaxPlaceholder))
                    fail(locationOf(*token), fmt::format("placeholder {} is out of range", text),
                         fmt::format("number placeholders from $1 to ${}", kMaxPlaceholder));
                index = static_cast<std::size_t>(number);
            }
            if (firstPositional && firstNumbered) {
                const antlr4::Token& later = *std::max(firstPositional, firstNumbered, [](auto* a, auto* b) {
                    return a->getStartIndex() < b->getStartIndex();
                });
                fail(locationOf(later), "a statement cannot mix ? and $1-style placeholders",
                     "write every placeholder as ? (numbered in order) or every one as $1, $2, ...");
            }
            placeholderIndex_[token] = index;
            parameterCount_ = std::max(parameterCount_, index);
        }
    }

    ast::Placeholder placeholder(const antlr4::Token& token) const {
        const std::size_t index = placeholderIndex_.at(&token);
        const bool nodeId = index <= nodeIdPlaceholders_.size() && nodeIdPlaceholders_[index - 1];
        return ast::Placeholder{index, token.getText() != "?", nodeId, locationOf(token)};
    }

    ast::Statement withParameterCount(ast::Statement statement) const {
        statement.parameterCount = parameterCount_;
        return statement;
    }

    ast::Statement statement(SmqlParser::CommandContext& command, const antlr4::Token& first) {
        const antlr4::Token& last = *command.getStop();
        if (auto* find = command.findStmt()) return wrap(findStmt(*find->ref(), find->findClause()), first, last);
        if (auto* count = command.countStmt()) return wrap(countStmt(*count), first, last);
        if (auto* relate = command.relateStmt()) return wrap(relateStmt(*relate), first, last);
        if (auto* check = command.checkStmt()) return wrap(checkStmt(*check), first, last);
        if (auto* describe = command.describeStmt()) return wrap(ast::DescribeStmt{ref(*describe->ref())}, first, last);
        if (auto* show = command.showStmt()) return wrap(showStmt(*show), first, last);
        if (auto* use = command.useStmt()) return wrap(useStmt(*use), first, last);
        if (auto* ask = command.askStmt())
            return wrap(ast::AskStmt{unquote(*ask->STRING()->getSymbol()), locationOf(*ask->STRING()->getSymbol())},
                        first, last);
        if (auto* drop = command.dropStmt())
            return wrap(ast::DropSceneStmt{sceneName(*drop->sceneName()), span(*drop)}, first, last);
        if (auto* rename = command.renameStmt())
            return wrap(
                ast::RenameSceneStmt{sceneName(*rename->sceneName(0)), sceneName(*rename->sceneName(1)), span(*rename)},
                first, last);
        if (auto* guide = command.guideStmt()) return wrap(guideStmt(*guide), first, last);
        return wrap(setStmt(*command.setStmt()), first, last);
    }

    ast::GuideStmt guideStmt(SmqlParser::GuideStmtContext& context) {
        ast::GuideStmt guide;
        guide.where = span(context);
        guide.to = ref(*context.ref());
        SmqlParser::GuideOriginContext& origin = *context.guideOrigin();
        if (auto* point = origin.floorPoint()) {
            auto coordinate = [&](std::size_t k) {
                const antlr4::Token& number = *point->NUMBER(k)->getSymbol();
                // A minus sign belongs to the number after it: the first when it precedes the comma.
                bool negative = false;
                for (auto* minus : point->MINUS())
                    if (minus->getSymbol()->getTokenIndex() + 1 == number.getTokenIndex()) negative = true;
                double value = realNumber(number);
                return negative ? -value : value;
            };
            guide.point = std::pair{coordinate(0), coordinate(1)};
        } else if (auto* from = origin.ref()) {
            guide.from = ref(*from);
        }
        return guide;
    }

    // A bare scene name is a name like any other (lower case); a quoted one is kept as written.
    std::string sceneName(SmqlParser::SceneNameContext& context) {
        if (auto* bare = context.name()) return nameOf(*bare);
        std::string name = unquote(*context.STRING()->getSymbol());
        if (name.empty()) fail(span(context), "the scene name is empty", "SHOW SCENES lists the scene names");
        return name;
    }

    // A time as a quoted string, in the memory's UTC form.
    static std::string instant(antlr4::tree::TerminalNode& string) {
        const antlr4::Token& token = *string.getSymbol();
        std::string text = unquote(token);
        if (auto utc = model::utcInstant(text)) return *utc;
        fail(locationOf(token), fmt::format("'{}' is not a time", text),
             "write a date or a date and time in ISO 8601, as in '2026-11-20' or '2026-11-20T14:30:00Z' (UTC unless "
             "it names its offset)");
    }

    ast::AsOf asOf(SmqlParser::AsOfClauseContext& clause) { return {instant(*clause.STRING()), span(clause)}; }

    template <typename Body>
    ast::Statement wrap(Body body, const antlr4::Token& first, const antlr4::Token& last) {
        ast::Statement statement;
        statement.body = std::move(body);
        statement.text = source_.textBetween(first, last);
        statement.where = span(first, last);
        return statement;
    }

    // ------------------------------------------------------------ statements

    // The rank of each clause in the documented order; PATH has none.
    static constexpr std::array clauseNames{"VIEW FROM", "WHERE", "NEAREST TO", "ORDER BY", "LIMIT"};

    // Clauses come as a list so that a clause out of place gets a message
    // naming both clauses, rather than the grammar's "unexpected WHERE".
    static void checkOrder(std::size_t rank, SourceLocation where, std::optional<std::size_t>& lastRank) {
        if (lastRank && rank == *lastRank)
            fail(where, fmt::format("{} given twice", clauseNames[rank]),
                 rank == 1 ? "combine the conditions with AND" : "keep one of them");
        if (lastRank && rank < *lastRank)
            fail(where, fmt::format("{} must come before {}", clauseNames[rank], clauseNames[*lastRank]),
                 "write the clauses in the order VIEW FROM, WHERE, NEAREST TO, ORDER BY, LIMIT; PATH, RETURN, SIMILAR "
                 "TO "
                 "and AS OF may go anywhere after the target");
        lastRank = rank;
    }

    ast::FindStmt findStmt(SmqlParser::RefContext& target, const std::vector<SmqlParser::FindClauseContext*>& clauses) {
        ast::FindStmt find;
        find.target = ref(target);
        std::optional<std::size_t> lastRank;
        for (SmqlParser::FindClauseContext* clause : clauses) {
            if (clause->PATH()) {
                if (find.path) fail(span(*clause), "PATH given twice", "write PATH once");
                find.path = true;
            } else if (auto* asOfClause = clause->asOfClause()) {
                if (find.asOf) fail(span(*clause), "AS OF given twice", "write AS OF once");
                find.asOf = asOf(*asOfClause);
            } else if (auto* view = clause->viewClause()) {
                checkOrder(0, span(*clause), lastRank);
                find.view = viewClause(*view);
            } else if (auto* where = clause->whereClause()) {
                checkOrder(1, span(*clause), lastRank);
                find.where = expr(*where->orExpr());
            } else if (auto* nearest = clause->nearestClause()) {
                checkOrder(2, span(*clause), lastRank);
                find.nearestTo = placeRef(*nearest->placeRef());
            } else if (auto* order = clause->orderClause()) {
                checkOrder(3, span(*clause), lastRank);
                find.orderBy = orderBy(*order);
            } else if (auto* similar = clause->similarClause()) {
                if (find.similarTo)
                    fail(span(*clause), "SIMILAR TO given twice", "describe what you look for in one text");
                ast::SimilarTo similarTo{{}, std::nullopt, span(*clause), {}};
                if (auto* param = similar->PARAM())
                    similarTo.param = placeholder(*param->getSymbol());
                else
                    similarTo.text = unquote(*similar->STRING()->getSymbol());
                find.similarTo = std::move(similarTo);
            } else if (auto* columns = clause->returnClause()) {
                if (!find.columns.empty()) fail(span(*clause), "RETURN given twice", "list every column in one RETURN");
                for (SmqlParser::NameContext* column : columns->name()) find.columns.push_back(nameOf(*column));
                find.returnWhere = span(*clause);
            } else {
                checkOrder(4, span(*clause), lastRank);
                if (auto* param = clause->limitClause()->PARAM())
                    find.limitParam = placeholder(*param->getSymbol());
                else
                    find.limit = limit(*clause->limitClause());
            }
        }
        return find;
    }

    ast::OrderBy orderBy(SmqlParser::OrderClauseContext& clause) {
        ast::OrderBy order;
        SmqlParser::MeasureContext& measure = *clause.measure();
        if (auto* reference = measure.placeRef())
            order.distanceTo = placeRef(*reference);
        else
            order.attribute = nameOf(*measure.name());
        order.descending = clause.DESC() != nullptr;
        order.where = span(clause);
        return order;
    }

    std::int64_t limit(SmqlParser::LimitClauseContext& clause) {
        const antlr4::Token& number = *clause.NUMBER()->getSymbol();
        SourceLocation where = clause.MINUS() ? span(*clause.MINUS()->getSymbol(), number) : locationOf(number);
        if (clause.MINUS()) fail(where, "LIMIT cannot be negative", "write a whole number of 0 or more, as in LIMIT 5");
        if (!isWhole(number))
            fail(where, fmt::format("LIMIT needs a whole number, not {}", number.getText()), "as in LIMIT 5");
        return wholeNumber(number.getText(), number, "LIMIT");
    }

    ast::CountStmt countStmt(SmqlParser::CountStmtContext& context) {
        ast::CountStmt count;
        count.target = ref(*context.ref());
        std::optional<std::size_t> lastRank;
        for (SmqlParser::CountClauseContext* clause : context.countClause()) {
            if (auto* asOfClause = clause->asOfClause()) {
                if (count.asOf) fail(span(*clause), "AS OF given twice", "write AS OF once");
                count.asOf = asOf(*asOfClause);
            } else if (auto* view = clause->viewClause()) {
                checkOrder(0, span(*clause), lastRank);
                count.view = viewClause(*view);
            } else {
                checkOrder(1, span(*clause), lastRank);
                count.where = expr(*clause->whereClause()->orExpr());
            }
        }
        return count;
    }

    ast::RelateStmt relateStmt(SmqlParser::RelateStmtContext& context) {
        ast::RelateStmt relate{ref(*context.ref(0)), ref(*context.ref(1)), std::nullopt};
        if (auto* view = context.viewClause()) relate.view = viewClause(*view);
        return relate;
    }

    ast::CheckStmt checkStmt(SmqlParser::CheckStmtContext& context) {
        ast::CheckStmt check;
        std::vector<SmqlParser::RefContext*> refs = context.ref();
        check.subject = ref(*refs.front());
        check.predicate = nameOf(*context.name());
        check.predicateWhere = span(*context.name());
        for (std::size_t i = 1; i < refs.size(); ++i) check.args.push_back(ref(*refs[i]));
        if (auto* distance = context.distance()) {
            const antlr4::Token& number = *distance->NUMBER()->getSymbol();
            check.threshold = ast::Distance{realNumber(number) / perMetre(distance->unit), span(*distance)};
        }
        if (auto* view = context.viewClause()) check.view = viewClause(*view);
        return check;
    }

    ast::ShowStmt showStmt(SmqlParser::ShowStmtContext& context) {
        ast::ShowStmt show;
        if (context.SCENES()) show.what = ast::ShowStmt::What::Scenes;
        if (context.SETTINGS()) show.what = ast::ShowStmt::What::Settings;
        if (context.GRAPH()) show.what = ast::ShowStmt::What::Graph;
        if (context.CATEGORIES()) show.what = ast::ShowStmt::What::Categories;
        if (context.ATTRIBUTES()) show.what = ast::ShowStmt::What::Attributes;
        if (context.CHANGES()) {
            show.what = ast::ShowStmt::What::Changes;
            if (auto* since = context.STRING()) show.since = instant(*since);
        }
        if (context.TREE()) {
            show.what = ast::ShowStmt::What::Tree;
            if (auto* root = context.ref()) show.root = ref(*root);
        }
        return show;
    }

    // A bare scene name is a name like any other (lower case); a quoted one
    // is kept as written.
    ast::UseStmt useStmt(SmqlParser::UseStmtContext& context) {
        ast::UseStmt use;
        use.where = span(context);
        if (auto* name = context.name()) {
            use.scene = nameOf(*name);
        } else if (auto* all = context.STAR()) {
            use.scene = all->getText();
        } else {
            use.scene = unquote(*context.STRING()->getSymbol());
            if (use.scene.empty())
                fail(locationOf(*context.STRING()->getSymbol()), "the scene name is empty",
                     "SHOW SCENES lists the scene names");
        }
        return use;
    }

    ast::SetStmt setStmt(SmqlParser::SetStmtContext& context) {
        ast::SetStmt set;
        set.where = span(context);
        for (SmqlParser::NameContext* part : context.settingName()->name()) {
            if (!set.name.empty()) set.name += '.';
            set.name += nameOf(*part);
        }
        SmqlParser::SetValueContext& value = *context.setValue();
        if (auto* quantity = value.quantity()) {
            const antlr4::Token& number = *quantity->NUMBER()->getSymbol();
            // The range of a value is the setting's business (the engine checks it).
            double magnitude = realNumber(number) / perMetre(quantity->unit);
            if (quantity->MINUS()) magnitude = -magnitude;
            if (quantity->unit)
                set.value = ast::Distance{magnitude, span(*quantity)};
            else
                set.value = magnitude;
        } else if (auto* string = value.STRING()) {
            set.value = unquote(*string->getSymbol());
        } else {
            set.value = nameOf(*value.name());
        }
        return set;
    }

    ast::View viewClause(SmqlParser::ViewClauseContext& context) {
        ast::View view;
        view.from = ref(*context.ref(0));
        if (context.FACING()) view.facing = ref(*context.ref(1));
        view.where = span(context);
        return view;
    }

    // ------------------------------------------------------------ references

    ast::Ref placeRef(SmqlParser::PlaceRefContext& context) {
        if (!context.HERE()) return ref(*context.ref());
        ast::Ref here;
        here.kind = ast::Ref::Kind::Here;
        here.where = span(context);
        return here;
    }

    ast::Ref ref(SmqlParser::RefContext& context) {
        ast::Ref ref;
        ref.where = span(context);
        if (auto* named = context.namedRef()) {
            namedRef(*named, ref);
        } else if (auto* node = context.NODE_ID()) {
            ref.kind = ast::Ref::Kind::NodeId;
            ref.number = wholeNumber(node->getText().substr(1), *node->getSymbol(), "node id");
        } else if (auto* labelled = context.LABELLED_ID()) {
            // `sofa#50`: the node #50, which must be a sofa.
            ref.kind = ast::Ref::Kind::NodeId;
            std::string text = labelled->getText();
            std::size_t hash = text.rfind('#');
            ref.name = lowerCase(text.substr(0, hash));
            ref.number = wholeNumber(text.substr(hash + 1), *labelled->getSymbol(), "node id");
        } else if (auto* source = context.SOURCE_ID()) {
            ref.kind = ast::Ref::Kind::SourceId;
            std::string text = source->getText();
            ref.number = wholeNumber(text.substr(text.find('#') + 1), *source->getSymbol(), "source id");
        } else {
            SmqlParser::SubQueryContext& sub = *context.subQuery();
            ref.kind = ast::Ref::Kind::SubQuery;
            ref.subquery = std::make_shared<ast::FindStmt>(findStmt(*sub.ref(), sub.findClause()));
        }
        return ref;
    }

    void namedRef(SmqlParser::NamedRefContext& context, ast::Ref& ref) {
        if (auto* param = context.PARAM()) {
            ref.kind = ast::Ref::Kind::Param;
            ref.placeholder = placeholder(*param->getSymbol());
        } else if (auto* string = context.STRING()) {
            ref.name = lowerCase(unquote(*string->getSymbol()));
            if (ref.name.empty())
                fail(locationOf(*string->getSymbol()), "a quoted name cannot be empty", "as in 'indoor plant'");
        } else {
            ref.name = nameOf(*context.name(0));
        }
        if (!context.side) return;
        if (ref.kind != ast::Ref::Kind::Param) ref.kind = ast::Ref::Kind::Side;
        ref.side = nameOf(*context.side);
        if (std::find(sides().begin(), sides().end(), ref.side) == sides().end())
            fail(span(*context.side), fmt::format("unknown side '{}'", context.side->getText()),
                 fmt::format("a side is left, right, front or back, as in {}.left",
                             ref.kind == ast::Ref::Kind::Param ? context.PARAM()->getText() : ref.name));
    }

    // ------------------------------------------------------------ conditions

    ast::Expr expr(SmqlParser::OrExprContext& context) {
        std::vector<SmqlParser::AndExprContext*> terms = context.andExpr();
        if (terms.size() == 1) return andExpr(*terms.front());
        ast::Expr either;
        either.kind = ast::Expr::Kind::Or;
        for (auto* term : terms) either.children.push_back(andExpr(*term));
        either.where = span(context);
        return either;
    }

    ast::Expr andExpr(SmqlParser::AndExprContext& context) {
        std::vector<SmqlParser::NotExprContext*> factors = context.notExpr();
        if (factors.size() == 1) return notExpr(*factors.front());
        ast::Expr both;
        both.kind = ast::Expr::Kind::And;
        for (auto* factor : factors) both.children.push_back(notExpr(*factor));
        both.where = span(context);
        return both;
    }

    ast::Expr notExpr(SmqlParser::NotExprContext& context) {
        if (!context.NOT()) return atom(*context.atom());
        ast::Expr negation;
        negation.kind = ast::Expr::Kind::Not;
        negation.children.push_back(notExpr(*context.notExpr()));
        negation.where = span(context);
        return negation;
    }

    ast::Expr atom(SmqlParser::AtomContext& context) {
        if (auto* inner = context.orExpr()) return expr(*inner);
        if (auto* call = context.predicate()) return predicate(*call);
        if (auto* change = context.changedSince()) return changedSince(*change);
        return comparison(*context.comparison());
    }

    // `moved SINCE t` reads the time attribute an update keeps: moved_at >= t (docs/history.md).
    ast::Expr changedSince(SmqlParser::ChangedSinceContext& context) {
        static constexpr std::pair<std::string_view, std::string_view> kWords[] = {
            {"moved", "moved_at"}, {"added", "first_seen_at"}, {"seen", "last_seen_at"}};
        const std::string word = nameOf(*context.name());
        ast::Expr compare;
        compare.kind = ast::Expr::Kind::Compare;
        for (const auto& [name, attribute] : kWords)
            if (word == name) compare.attribute = attribute;
        if (compare.attribute.empty())
            fail(span(*context.name()), fmt::format("'{}' cannot be followed by SINCE", word),
                 "write moved SINCE, added SINCE or seen SINCE");
        compare.op = ast::CompareOp::Ge;
        compare.literal = instant(*context.STRING());
        compare.where = span(context);
        return compare;
    }

    ast::Expr predicate(SmqlParser::PredicateContext& context) {
        ast::Expr call;
        call.kind = ast::Expr::Kind::Predicate;
        call.predicate = nameOf(*context.name());
        for (auto* arg : context.placeRef()) call.args.push_back(placeRef(*arg));
        if (auto* distance = context.distance()) {
            const antlr4::Token& number = *distance->NUMBER()->getSymbol();
            call.threshold = ast::Distance{realNumber(number) / perMetre(distance->unit), span(*distance)};
        } else if (call.args.size() > 1) {
            // `near(window, cm)`: the unit parsed as a second name.
            const ast::Ref& last = call.args.back();
            SmqlParser::RefContext* lastArg = context.placeRef().back()->ref();
            if (last.kind == ast::Ref::Kind::Name && lastArg && lastArg->namedRef() && !lastArg->namedRef()->STRING() &&
                isUnitWord(last.name))
                fail(last.where, fmt::format("missing number before '{}'", last.name),
                     fmt::format("write the distance as a number and a unit, as in {}({}, 1.5 m)", call.predicate,
                                 call.args[0].name));
        }
        call.where = span(context);
        return call;
    }

    // `height BETWEEN 1 m AND 2 m` is `height >= 1 m AND height <= 2 m`.
    ast::Expr comparison(SmqlParser::ComparisonContext& context) {
        ast::Expr compare;
        compare.kind = ast::Expr::Kind::Compare;
        SmqlParser::MeasureContext& measure = *context.measure();
        if (auto* reference = measure.placeRef())
            compare.distanceTo = placeRef(*reference);
        else
            compare.attribute = nameOf(*measure.name());
        compare.where = span(context);
        if (context.BETWEEN()) {
            ast::Expr low = compare, high = compare;
            low.op = ast::CompareOp::Ge;
            quantity(*context.quantity(0), low);
            high.op = ast::CompareOp::Le;
            quantity(*context.quantity(1), high);
            ast::Expr both;
            both.kind = ast::Expr::Kind::And;
            both.children = {std::move(low), std::move(high)};
            both.where = compare.where;
            return both;
        }
        if (context.IS()) {
            compare.op = context.NOT() ? ast::CompareOp::IsNotNull : ast::CompareOp::IsNull;
            if (compare.distanceTo)
                fail(compare.where, "IS NULL takes an attribute, not a distance",
                     "write it of an attribute, as in detected_as IS NOT NULL");
            return compare;
        }
        SmqlParser::CompareOpContext& op = *context.compareOp();
        compare.op = op.EQ()   ? ast::CompareOp::Eq
                     : op.NE() ? ast::CompareOp::Ne
                     : op.LT() ? ast::CompareOp::Lt
                     : op.LE() ? ast::CompareOp::Le
                     : op.GT() ? ast::CompareOp::Gt
                     : op.GE() ? ast::CompareOp::Ge
                               : ast::CompareOp::Like;
        SmqlParser::QuantityOrStringContext& value = *context.quantityOrString();
        if (auto* string = value.STRING())
            compare.literal = unquote(*string->getSymbol());  // values keep their case
        else if (auto* param = value.PARAM())
            compare.literalParam = placeholder(*param->getSymbol());
        else
            quantity(*value.quantity(), compare);
        return compare;
    }

    // A number with or without a unit, as a comparison's literal (a length in metres).
    void quantity(SmqlParser::QuantityContext& quantity, ast::Expr& compare) {
        const antlr4::Token& number = *quantity.NUMBER()->getSymbol();
        const bool negative = quantity.MINUS() != nullptr;
        compare.literalHasUnit = quantity.unit != nullptr;
        if (quantity.unit) {
            double metres = realNumber(number) / perMetre(quantity.unit);
            compare.literal = negative ? -metres : metres;
        } else if (isWhole(number)) {
            std::int64_t whole = wholeNumber(number.getText(), number, "the number");
            compare.literal = negative ? -whole : whole;
        } else {
            double real = realNumber(number);
            compare.literal = negative ? -real : real;
        }
    }
};

}  // namespace

ast::Statement buildStatement(SmqlParser::StatementContext& tree, const Source& source,
                              const std::vector<bool>& nodeIdPlaceholders) {
    return AstBuilder(source, nodeIdPlaceholders).statement(tree);
}

}  // namespace smql::parser
