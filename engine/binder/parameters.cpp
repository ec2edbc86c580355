#include "engine/binder/parameters.hpp"

#include <cmath>
#include <memory>
#include <optional>
#include <type_traits>

#include <fmt/format.h>

#include "engine/parser/parser.hpp"
#include "model/embedding.hpp"
#include "model/error.hpp"
#include "relations/predicates.hpp"

namespace smql::binder {

namespace {

constexpr unsigned kNumberValue = kIntegerValue | kRealValue | kLengthValue;
constexpr unsigned kAnyValue = kTextValue | kNumberValue;
constexpr unsigned kSimilarValue = kTextValue | kVectorValue;

[[noreturn]] void fail(const ast::Placeholder& placeholder, std::string message, std::string hint) {
    throw Error(ErrorKind::Usage, std::move(message), placeholder.where, std::move(hint));
}

std::string_view kindName(const ParameterValue& value) {
    static constexpr std::string_view kNames[] = {"NULL",     "an integer", "a real number",
                                                  "a length", "text",       "a vector"};
    return kNames[value.index()];
}

unsigned kindBit(const ParameterValue& value) {
    static constexpr unsigned kBits[] = {0, kIntegerValue, kRealValue, kLengthValue, kTextValue, kVectorValue};
    return kBits[value.index()];
}

std::string_view placeName(unsigned accepts) {
    if (accepts == kTextValue) return "a name";
    if (accepts == kIntegerValue) return "LIMIT's whole number";
    if (accepts == kNumberValue) return "a distance";
    if (accepts == kSimilarValue) return "SIMILAR TO's text or vector";
    return "a value";
}

std::string_view bindHint(unsigned accepts) {
    if (accepts == kTextValue) return "bind text, as in smql_bind_text(stmt, i, \"mug\")";
    if (accepts == kIntegerValue) return "bind a whole number of 0 or more, as in smql_bind_int(stmt, i, 5)";
    if (accepts == kNumberValue) return "bind a length in metres, as in smql_bind_double(stmt, i, 1.5)";
    if (accepts == kSimilarValue)
        return "bind text, as in smql_bind_text(stmt, i, \"soft thing\"), or a vector, as in "
               "smql_bind_vector(stmt, i, values, 512)";
    return "bind text, a number or a length";
}

// A predicate's last argument may be its distance (`near(?, ?)`): when the predicate takes one
// and has more arguments than references, a placeholder there stands for the distance.
bool isDistanceSlot(const ast::Expr& predicate, std::size_t argument) {
    const relations::PredicateSpec* spec = relations::predicateNamed(predicate.predicate);
    const ast::Ref& ref = predicate.args[argument];
    return spec && spec->takesDistance && !predicate.threshold && argument + 1 == predicate.args.size() &&
           predicate.args.size() > static_cast<std::size_t>(spec->arity) && ref.kind == ast::Ref::Kind::Param &&
           ref.side.empty();
}

// Every place a placeholder can stand, in one walk over a statement that callers may change:
// `onName(ref)` for a reference, `onDistance(predicate)` for a predicate's trailing distance,
// `onLiteral(comparison)`, `onLimit(find)`, `onSimilar(similarTo)`. Sub-queries and EXPLAIN's statement are shared
// pointers in the AST; the walk copies them first, so changing the copy leaves the prepared
// statement as it was.
template <class Visitor>
class PlaceholderWalk {
public:
    explicit PlaceholderWalk(Visitor& visitor) : visitor_(visitor) {}

    void statement(ast::Statement& statement) {
        std::visit([&](auto& body) { this->body(body); }, statement.body);
    }

private:
    Visitor& visitor_;

    void body(ast::FindStmt& find) {
        ref(find.target);
        view(find.view);
        if (find.where) expr(*find.where);
        if (find.nearestTo) ref(*find.nearestTo);
        if (find.orderBy && find.orderBy->distanceTo) ref(*find.orderBy->distanceTo);
        if (find.limitParam) visitor_.onLimit(find);
        if (find.similarTo && find.similarTo->param) visitor_.onSimilar(*find.similarTo);
    }
    void body(ast::CountStmt& count) {
        ref(count.target);
        view(count.view);
        if (count.where) expr(*count.where);
    }
    void body(ast::RelateStmt& relate) {
        ref(relate.subject);
        ref(relate.object);
        view(relate.view);
    }
    void body(ast::CheckStmt& check) {
        ref(check.subject);
        for (ast::Ref& arg : check.args) ref(arg);
        view(check.view);
    }
    void body(ast::DescribeStmt& describe) { ref(describe.target); }
    void body(ast::ShowStmt& show) {
        if (show.root) ref(*show.root);
    }
    void body(ast::GuideStmt& guide) {
        if (guide.from) ref(*guide.from);
        ref(guide.to);
    }
    void body(ast::ExplainStmt& explain) {
        explain.inner = std::make_shared<ast::Statement>(*explain.inner);
        statement(*explain.inner);
    }
    // USE, SET, ASK, DROP and RENAME take no placeholder.
    template <class Other>
    void body(Other& /*statement*/) {}

    void view(std::optional<ast::View>& view) {
        if (!view) return;
        ref(view->from);
        if (view->facing) ref(*view->facing);
    }

    void ref(ast::Ref& ref) {
        if (ref.kind == ast::Ref::Kind::Param) visitor_.onName(ref);
        if (ref.kind != ast::Ref::Kind::SubQuery) return;
        ref.subquery = std::make_shared<ast::FindStmt>(*ref.subquery);
        body(*ref.subquery);
    }

    void expr(ast::Expr& expr) {
        for (ast::Expr& child : expr.children) this->expr(child);
        if (expr.kind == ast::Expr::Kind::Compare && expr.distanceTo) ref(*expr.distanceTo);
        if (expr.kind == ast::Expr::Kind::Compare && expr.literalParam) visitor_.onLiteral(expr);
        if (expr.kind != ast::Expr::Kind::Predicate) return;
        const bool distance = !expr.args.empty() && isDistanceSlot(expr, expr.args.size() - 1);
        const std::size_t names = distance ? expr.args.size() - 1 : expr.args.size();
        for (std::size_t i = 0; i < names; ++i) ref(expr.args[i]);
        if (distance) visitor_.onDistance(expr);
    }
};

// What each placeholder accepts, gathered over its places.
struct SlotCollector {
    std::vector<ParameterSlot> slots;

    void add(const ast::Placeholder& placeholder, unsigned accepts) {
        ParameterSlot& slot = slots.at(placeholder.index - 1);
        if (slot.placeholder.index == 0) {
            slot = ParameterSlot{placeholder, accepts};
        } else {
            slot.accepts &= accepts;
        }
    }
    void onName(const ast::Ref& ref) { add(ref.placeholder, ref.placeholder.nodeId ? kIntegerValue : kTextValue); }
    void onDistance(const ast::Expr& predicate) { add(predicate.args.back().placeholder, kNumberValue); }
    void onLiteral(const ast::Expr& comparison) { add(*comparison.literalParam, kAnyValue); }
    void onLimit(const ast::FindStmt& find) { add(*find.limitParam, kIntegerValue); }
    void onSimilar(const ast::SimilarTo& similar) { add(*similar.param, kSimilarValue); }
};

// What a statement's text cannot hold, a bound value cannot either: NaN and infinities (no
// comparison answers for them), and texts longer than a quoted string may be.
std::optional<std::string> unusableValue(const ast::Placeholder& placeholder, const ParameterValue& value) {
    if (const double* number = std::get_if<double>(&value); number && !std::isfinite(*number))
        return fmt::format("placeholder {} is bound to {}, which is not a number SMQL compares", placeholder.name(),
                           *number);
    if (const auto* length = std::get_if<Length>(&value); length && !std::isfinite(length->metres))
        return fmt::format("placeholder {} is bound to a length of {} m", placeholder.name(), length->metres);
    if (const auto* text = std::get_if<std::string>(&value); text && text->size() > parser::kMaxTextValue)
        return fmt::format("placeholder {} is bound to {} bytes of text: at most {}", placeholder.name(), text->size(),
                           parser::kMaxTextValue);
    return std::nullopt;
}

// Puts the values in, checking each against its place.
struct ValueFiller {
    const std::vector<std::optional<ParameterValue>>& values;

    const ParameterValue& valueOf(const ast::Placeholder& placeholder, unsigned accepts) const {
        const std::size_t i = placeholder.index - 1;
        if (i >= values.size() || !values[i])
            fail(placeholder, fmt::format("placeholder {} has no value", placeholder.name()),
                 fmt::format("bind one before running the statement: {}", bindHint(accepts)));
        const ParameterValue& value = *values[i];
        if (std::holds_alternative<std::monostate>(value))
            fail(placeholder, fmt::format("placeholder {} is bound to NULL, which SMQL cannot use", placeholder.name()),
                 std::string(bindHint(accepts)));
        if ((kindBit(value) & accepts) == 0)
            fail(placeholder,
                 fmt::format("placeholder {} stands for {}, not {}", placeholder.name(), placeholderPlace(accepts),
                             kindName(value)),
                 std::string(bindHint(accepts)));
        if (auto problem = unusableValue(placeholder, value))
            fail(placeholder, *problem, "bind a value SMQL text could hold");
        return value;
    }

    static std::string_view placeholderPlace(unsigned accepts) { return placeName(accepts); }

    void onName(ast::Ref& ref) const {
        if (ref.placeholder.nodeId) {
            ref.number = std::get<std::int64_t>(valueOf(ref.placeholder, kIntegerValue));
            ref.kind = ast::Ref::Kind::NodeId;
            return;
        }
        const auto& text = std::get<std::string>(valueOf(ref.placeholder, kTextValue));
        if (text.empty())
            fail(ref.placeholder, fmt::format("placeholder {} is bound to an empty name", ref.placeholder.name()),
                 "bind a category or a kind word, as in \"mug\" or \"object\"");
        ref.name = parser::lowerCase(text);
        ref.kind = ref.side.empty() ? ast::Ref::Kind::Name : ast::Ref::Kind::Side;
    }

    void onDistance(ast::Expr& predicate) const {
        const ast::Ref placeholderRef = predicate.args.back();
        const double metres = std::visit(
            [](const auto& value) -> double {
                using T = std::decay_t<decltype(value)>;
                if constexpr (std::is_same_v<T, Length>) return value.metres;
                if constexpr (std::is_same_v<T, std::int64_t> || std::is_same_v<T, double>)
                    return static_cast<double>(value);
                return 0;
            },
            valueOf(placeholderRef.placeholder, kNumberValue));
        if (!(metres >= 0))
            fail(
                placeholderRef.placeholder,
                fmt::format("placeholder {} is a distance and cannot be {}", placeholderRef.placeholder.name(), metres),
                "bind a length of 0 m or more");
        predicate.args.pop_back();
        predicate.threshold = ast::Distance{metres, placeholderRef.where};
    }

    void onLiteral(ast::Expr& comparison) const {
        std::visit(
            [&](const auto& value) {
                using T = std::decay_t<decltype(value)>;
                if constexpr (std::is_same_v<T, Length>) {
                    comparison.literal = value.metres;
                    comparison.literalHasUnit = true;
                } else if constexpr (!std::is_same_v<T, std::monostate> && !std::is_same_v<T, std::vector<float>>) {
                    // A vector never gets here: a comparison does not accept one.
                    comparison.literal = value;  // text keeps its case, as a quoted string does
                    comparison.literalBound = true;
                }
            },
            valueOf(*comparison.literalParam, kAnyValue));
        comparison.literalParam.reset();
    }

    void onLimit(ast::FindStmt& find) const {
        const std::int64_t limit = std::get<std::int64_t>(valueOf(*find.limitParam, kIntegerValue));
        if (limit < 0)
            fail(*find.limitParam,
                 fmt::format("placeholder {} is LIMIT and cannot be negative", find.limitParam->name()),
                 "bind a whole number of 0 or more");
        find.limit = limit;
        find.limitParam.reset();
    }

    void onSimilar(ast::SimilarTo& similar) const {
        const ParameterValue& value = valueOf(*similar.param, kSimilarValue);
        if (const auto* vector = std::get_if<std::vector<float>>(&value)) {
            if (auto problem = model::embeddingProblem(*vector))
                fail(*similar.param,
                     fmt::format("placeholder {} is bound to a vector SIMILAR TO cannot use: {}", similar.param->name(),
                                 *problem),
                     "bind the query's embedding from the model that made the scene's embeddings");
            similar.vector = *vector;
        } else {
            similar.text = std::get<std::string>(value);
        }
        similar.param.reset();
    }
};

}  // namespace

std::vector<ParameterSlot> parameterSlots(const ast::Statement& statement) {
    SlotCollector collector{std::vector<ParameterSlot>(statement.parameterCount)};
    ast::Statement copy = statement;
    PlaceholderWalk(collector).statement(copy);
    return collector.slots;
}

std::optional<std::string> rejectedValue(const ParameterSlot& slot, const ParameterValue& value) {
    if (std::holds_alternative<std::monostate>(value) || slot.placeholder.index == 0) return std::nullopt;
    if (auto problem = unusableValue(slot.placeholder, value)) return problem;
    if (kindBit(value) & slot.accepts) return std::nullopt;
    return fmt::format("placeholder {} stands for {}, not {}: {}", slot.placeholder.name(), placeName(slot.accepts),
                       kindName(value), bindHint(slot.accepts));
}

ast::Statement withParameters(const ast::Statement& statement,
                              const std::vector<std::optional<ParameterValue>>& values) {
    ast::Statement bound = statement;
    ValueFiller filler{values};
    PlaceholderWalk(filler).statement(bound);
    bound.parameterCount = 0;
    return bound;
}

}  // namespace smql::binder
