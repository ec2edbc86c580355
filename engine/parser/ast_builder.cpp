#include "engine/parser/ast_builder.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <optional>

#include <fmt/format.h>

#include "engine/parser/parser.hpp"
#include "engine/parser/syntax_errors.hpp"
#include "engine/parser/vocabulary.hpp"

namespace smql::parser {

using grammar::SmqlParser;

namespace {

[[noreturn]] void fail(SourceLocation where, std::string message, std::string hint = {}) {
    throw Error(ErrorKind::Syntax, std::move(message), where, std::move(hint));
}

std::string nameOf(SmqlParser::NameContext& name) {
    return lowerCase(name.getText());
}

// 'it''s' -> it's
std::string unquote(const antlr4::Token& token) {
    std::string text = token.getText();
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
    explicit AstBuilder(const Source& source) : source_(source) {}

    ast::Statement statement(SmqlParser::StatementContext& tree) {
        SmqlParser::CommandContext& command = *tree.command();
        if (!tree.EXPLAIN()) return statement(command, *tree.getStart());
        ast::ExplainStmt explain{std::make_shared<ast::Statement>(statement(command, *command.getStart()))};
        return wrap(std::move(explain), *tree.getStart(), *command.getStop());
    }

private:
    const Source& source_;

    ast::Statement statement(SmqlParser::CommandContext& command, const antlr4::Token& first) {
        const antlr4::Token& last = *command.getStop();
        if (auto* find = command.findStmt()) return wrap(findStmt(*find->ref(), find->findClause()), first, last);
        if (auto* count = command.countStmt()) return wrap(countStmt(*count), first, last);
        if (auto* relate = command.relateStmt()) return wrap(relateStmt(*relate), first, last);
        if (auto* describe = command.describeStmt())
            return wrap(ast::DescribeStmt{ref(*describe->ref())}, first, last);
        if (auto* show = command.showStmt()) return wrap(showStmt(*show), first, last);
        if (auto* use = command.useStmt()) return wrap(useStmt(*use), first, last);
        return wrap(setStmt(*command.setStmt()), first, last);
    }

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
                 "write the clauses in the order VIEW FROM, WHERE, NEAREST TO, ORDER BY, LIMIT; PATH may go anywhere "
                 "after the target");
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
            } else if (auto* view = clause->viewClause()) {
                checkOrder(0, span(*clause), lastRank);
                find.view = viewClause(*view);
            } else if (auto* where = clause->whereClause()) {
                checkOrder(1, span(*clause), lastRank);
                find.where = expr(*where->orExpr());
            } else if (auto* nearest = clause->nearestClause()) {
                checkOrder(2, span(*clause), lastRank);
                find.nearestTo = ref(*nearest->ref());
            } else if (auto* order = clause->orderClause()) {
                checkOrder(3, span(*clause), lastRank);
                find.orderBy = ast::OrderBy{ref(*order->ref()), order->DESC() != nullptr, span(*order)};
            } else {
                checkOrder(4, span(*clause), lastRank);
                find.limit = limit(*clause->limitClause());
            }
        }
        return find;
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
            if (auto* view = clause->viewClause()) {
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

    ast::ShowStmt showStmt(SmqlParser::ShowStmtContext& context) {
        ast::ShowStmt show;
        if (context.SCENES()) show.what = ast::ShowStmt::What::Scenes;
        if (context.SETTINGS()) show.what = ast::ShowStmt::What::Settings;
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

    ast::Ref ref(SmqlParser::RefContext& context) {
        ast::Ref ref;
        ref.where = span(context);
        if (auto* named = context.namedRef()) {
            namedRef(*named, ref);
        } else if (auto* node = context.NODE_ID()) {
            ref.kind = ast::Ref::Kind::NodeId;
            ref.number = wholeNumber(node->getText().substr(1), *node->getSymbol(), "node id");
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
        if (auto* string = context.STRING()) {
            ref.name = lowerCase(unquote(*string->getSymbol()));
            if (ref.name.empty())
                fail(locationOf(*string->getSymbol()), "a quoted name cannot be empty", "as in 'indoor plant'");
        } else {
            ref.name = nameOf(*context.name(0));
        }
        if (!context.side) return;
        ref.kind = ast::Ref::Kind::Side;
        ref.side = nameOf(*context.side);
        if (std::find(sides().begin(), sides().end(), ref.side) == sides().end())
            fail(span(*context.side), fmt::format("unknown side '{}'", context.side->getText()),
                 fmt::format("a side is left, right, front or back, as in {}.left", ref.name));
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
        return comparison(*context.comparison());
    }

    ast::Expr predicate(SmqlParser::PredicateContext& context) {
        ast::Expr call;
        call.kind = ast::Expr::Kind::Predicate;
        call.predicate = nameOf(*context.name());
        for (auto* arg : context.ref()) call.args.push_back(ref(*arg));
        if (auto* distance = context.distance()) {
            const antlr4::Token& number = *distance->NUMBER()->getSymbol();
            call.threshold = ast::Distance{realNumber(number) / perMetre(distance->unit), span(*distance)};
        } else if (call.args.size() > 1) {
            // `near(window, cm)`: the unit parsed as a second name.
            const ast::Ref& last = call.args.back();
            SmqlParser::RefContext& lastArg = *context.ref().back();
            if (last.kind == ast::Ref::Kind::Name && lastArg.namedRef() && !lastArg.namedRef()->STRING() &&
                isUnitWord(last.name))
                fail(last.where, fmt::format("missing number before '{}'", last.name),
                     fmt::format("write the distance as a number and a unit, as in {}({}, 1.5 m)", call.predicate,
                                 call.args[0].name));
        }
        call.where = span(context);
        return call;
    }

    ast::Expr comparison(SmqlParser::ComparisonContext& context) {
        ast::Expr compare;
        compare.kind = ast::Expr::Kind::Compare;
        compare.attribute = nameOf(*context.name());
        SmqlParser::CompareOpContext& op = *context.compareOp();
        compare.op = op.EQ()   ? ast::CompareOp::Eq
                     : op.NE() ? ast::CompareOp::Ne
                     : op.LT() ? ast::CompareOp::Lt
                     : op.LE() ? ast::CompareOp::Le
                     : op.GT() ? ast::CompareOp::Gt
                     : op.GE() ? ast::CompareOp::Ge
                               : ast::CompareOp::Like;
        SmqlParser::QuantityOrStringContext& value = *context.quantityOrString();
        if (auto* string = value.STRING()) {
            compare.literal = unquote(*string->getSymbol());  // values keep their case
        } else {
            SmqlParser::QuantityContext& quantity = *value.quantity();
            const antlr4::Token& number = *quantity.NUMBER()->getSymbol();
            const bool negative = quantity.MINUS() != nullptr;
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
        compare.where = span(context);
        return compare;
    }
};

}  // namespace

ast::Statement buildStatement(SmqlParser::StatementContext& tree, const Source& source) {
    return AstBuilder(source).statement(tree);
}

}  // namespace smql::parser
