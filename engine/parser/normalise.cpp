#include "engine/parser/normalise.hpp"

#include <algorithm>
#include <array>
#include <charconv>

#include "engine/parser/parser.hpp"
#include "engine/parser/vocabulary.hpp"
#include "model/utf8.hpp"

namespace smql::parser {

namespace {

bool isDigit(char c) { return c >= '0' && c <= '9'; }
bool isWordStart(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool isWordChar(char c) { return isWordStart(c) || isDigit(c); }

// The commands whose statements share parses: they read and change nothing, so a statement run
// from a shared parse can be run again from its own when it fails (engine.cpp).
constexpr std::array kShapedCommands{"find", "count", "relate", "check", "describe"};

bool isShapedCommand(std::string_view word) {
    return std::find(kShapedCommands.begin(), kShapedCommands.end(), word) != kShapedCommands.end();
}

// Reads the text as the grammar's lexer does (grammar/Smql.g4), token by token, writing the key
// as it goes. Any token the shapes do not cover ends the scan without a shape.
class Scanner {
public:
    explicit Scanner(std::string_view text) : text_(text) {}

    std::optional<StatementShape> scan() {
        if (text_.size() > kMaxStatementLength || model::invalidUtf8At(text_)) return std::nullopt;
        shape_.key.reserve(text_.size() + 16);
        for (skipBlanks(); at_ < text_.size(); skipBlanks()) {
            if (closed_) return std::nullopt;  // a second statement after the `;`
            if (!token()) return std::nullopt;
        }
        if (words_.empty() || !commandFits()) return std::nullopt;
        shape_.key += '\n';
        shape_.key += kinds_;
        return std::move(shape_);
    }

private:
    std::string_view text_;
    std::size_t at_ = 0;
    StatementShape shape_;
    std::string kinds_;
    std::vector<std::string> words_;  // the first two words, for the command check
    bool closed_ = false;             // the `;` that ends the statement was read

    char peek(std::size_t ahead = 0) const { return at_ + ahead < text_.size() ? text_[at_ + ahead] : '\0'; }

    // White space and `--` comments, which the lexer skips.
    void skipBlanks() {
        while (at_ < text_.size()) {
            const char c = text_[at_];
            if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f') {
                ++at_;
            } else if (c == '-' && peek(1) == '-') {
                while (at_ < text_.size() && text_[at_] != '\r' && text_[at_] != '\n') ++at_;
            } else {
                return;
            }
        }
    }

    // One token at at_; false when it is one no shape holds.
    bool token() {
        const std::size_t start = at_;
        if (shape_.key.empty()) shape_.begin = start;
        if (words_.size() == 1 && words_.front() == "explain" && shape_.afterExplain == 0) shape_.afterExplain = start;
        const char c = peek();
        bool ok = true;
        if (c == ';') {
            ++at_;
            closed_ = true;
            return true;  // not part of the statement's text
        }
        if (isWordStart(c)) {
            ok = word();
        } else if (isDigit(c) || (c == '.' && isDigit(peek(1)))) {
            ok = number();
        } else if (c == '\'' || c == '"') {
            ok = string(c);
        } else if (c == '#' && isDigit(peek(1))) {
            ++at_;
            ok = nodeId();
        } else {
            ok = symbol();
        }
        shape_.end = at_;
        return ok;
    }

    void append(std::string_view token) {
        if (!shape_.key.empty()) shape_.key += ' ';
        shape_.key += token;
    }

    void literal(ShapeLiteral value) {
        char number[24] = {'$'};
        const auto written = std::to_chars(number + 1, number + sizeof number, shape_.literals.size() + 1).ptr;
        append(std::string_view(number, static_cast<std::size_t>(written - number)));
        kinds_ += static_cast<char>(value.kind);
        shape_.literals.push_back(std::move(value));
    }

    // [a-zA-Z_][a-zA-Z0-9_]* with single hyphens inside (`plant-stand`); `a--b` is `a` and a comment.
    std::string_view wordAt(std::size_t& at) const {
        const std::size_t start = at;
        auto chars = [&] {
            while (at < text_.size() && isWordChar(text_[at])) ++at;
        };
        chars();
        while (at + 1 < text_.size() && text_[at] == '-' && isWordChar(text_[at + 1])) {
            ++at;
            chars();
        }
        return text_.substr(start, at - start);
    }

    // An identifier or keyword; `sofa#12` and `src#93` (LABELLED_ID, SOURCE_ID) are kept as written.
    bool word() {
        const std::string_view word = wordAt(at_);
        append({});
        const std::size_t begin = shape_.key.size();
        for (char c : word) shape_.key += static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
        if (peek() == '#' && isDigit(peek(1))) {
            ++at_;
            shape_.key += '#';
            while (isDigit(peek())) shape_.key += text_[at_++];
        }
        if (words_.size() < 2) words_.push_back(shape_.key.substr(begin));
        return true;
    }

    // NUMBER, and the unit word after it when there is one: `1.5 m` is one length.
    bool number() {
        const std::size_t start = at_;
        while (isDigit(peek())) ++at_;
        if (peek() == '.') {
            ++at_;
            while (isDigit(peek())) ++at_;
        }
        const std::string_view digits = text_.substr(start, at_ - start);
        const bool whole = digits.find('.') == std::string_view::npos;
        ShapeLiteral value;
        if (whole) {
            value.kind = ShapeLiteral::Kind::Integer;
            auto [end, status] = std::from_chars(digits.data(), digits.data() + digits.size(), value.integer);
            if (status != std::errc() || end != digits.data() + digits.size()) return false;
        }
        // As the parser reads a distance or a quantity: the digits as a double, divided by the unit.
        double real = 0;
        auto [end, status] = std::from_chars(digits.data(), digits.data() + digits.size(), real);
        if (status != std::errc() || end != digits.data() + digits.size()) return false;
        if (std::optional<double> perMetre = unitAfterNumber()) {
            value.kind = ShapeLiteral::Kind::Length;
            value.number = real / *perMetre;
        } else if (!whole) {
            value.kind = ShapeLiteral::Kind::Real;
            value.number = real;
        }
        literal(std::move(value));
        return true;
    }

    // The unit word that follows a number across white space (m, cm, mm, any case), consumed;
    // nothing, and nothing consumed, when another token follows.
    std::optional<double> unitAfterNumber() {
        std::size_t at = at_;
        while (at < text_.size() &&
               (text_[at] == ' ' || text_[at] == '\t' || text_[at] == '\r' || text_[at] == '\n' || text_[at] == '\f'))
            ++at;
        if (at >= text_.size() || !isWordStart(text_[at])) return std::nullopt;
        const std::string unit = lowerCase(wordAt(at));
        if (at < text_.size() && text_[at] == '#') return std::nullopt;  // `m#5` is a labelled id
        std::optional<double> perMetre = unitsPerMetre(unit);
        if (perMetre) at_ = at;
        return perMetre;
    }

    // A quoted string: 'it''s' or "say ""hi""", across lines; unterminated ones are the parser's.
    bool string(char quote) {
        ShapeLiteral value;
        ++at_;
        while (true) {
            if (at_ >= text_.size()) return false;
            const char c = text_[at_++];
            if (c != quote) {
                value.text += c;
            } else if (peek() == quote) {
                value.text += quote;
                ++at_;
            } else {
                break;
            }
        }
        if (value.text.size() > kMaxTextValue) return false;
        literal(std::move(value));
        return true;
    }

    bool nodeId() {
        const std::size_t start = at_;
        while (isDigit(peek())) ++at_;
        ShapeLiteral value;
        value.kind = ShapeLiteral::Kind::NodeId;
        auto [end, status] = std::from_chars(text_.data() + start, text_.data() + at_, value.integer);
        if (status != std::errc() || end != text_.data() + at_) return false;
        literal(std::move(value));
        return true;
    }

    // Operators and punctuation; anything else (`?`, `$1`, a stray character) ends the scan.
    bool symbol() {
        static constexpr std::array<std::string_view, 4> kPairs{"!=", "<>", "<=", ">="};
        for (std::string_view pair : kPairs) {
            if (text_.substr(at_, 2) == pair) {
                at_ += 2;
                append(pair);
                return true;
            }
        }
        static constexpr std::string_view kSingles = "=<>(),.-*";
        if (kSingles.find(peek()) == std::string_view::npos) return false;
        append(text_.substr(at_++, 1));
        return true;
    }

    bool commandFits() {
        if (words_.front() == "explain") return words_.size() == 2 && isShapedCommand(words_[1]);
        shape_.afterExplain = shape_.begin;
        return isShapedCommand(words_.front());
    }
};

// ------------------------------------------------------------ comparing statements

// Equal but for locations and source text (sameStatement); each overload one AST type.
struct SameMeaning {
    bool operator()(const ast::Placeholder& a, const ast::Placeholder& b) const {
        return a.index == b.index && a.numbered == b.numbered && a.nodeId == b.nodeId;
    }
    template <class T>
    bool operator()(const std::optional<T>& a, const std::optional<T>& b) const {
        return a.has_value() == b.has_value() && (!a || (*this)(*a, *b));
    }
    template <class T>
    bool operator()(const std::vector<T>& a, const std::vector<T>& b) const {
        return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                          [this](const T& x, const T& y) { return (*this)(x, y); });
    }
    bool operator()(const std::string& a, const std::string& b) const { return a == b; }
    bool operator()(const ast::Ref& a, const ast::Ref& b) const {
        // A bound value leaves its placeholder behind; only a Param reference reads it.
        const bool param = a.kind == ast::Ref::Kind::Param;
        if (a.kind != b.kind || a.name != b.name || a.side != b.side || a.number != b.number ||
            (param && !(*this)(a.placeholder, b.placeholder)) || (a.subquery == nullptr) != (b.subquery == nullptr))
            return false;
        return !a.subquery || (*this)(*a.subquery, *b.subquery);
    }
    bool operator()(const ast::Distance& a, const ast::Distance& b) const { return a.metres == b.metres; }
    bool operator()(const ast::Expr& a, const ast::Expr& b) const {
        // Whether a literal was bound matters to numbers only (binder.cpp, checkLiteral): a bound
        // number is metres where a length goes.
        const bool number = !std::holds_alternative<std::string>(a.literal);
        return a.kind == b.kind && (*this)(a.children, b.children) && a.predicate == b.predicate &&
               (*this)(a.args, b.args) && (*this)(a.threshold, b.threshold) && a.attribute == b.attribute &&
               (*this)(a.distanceTo, b.distanceTo) && a.op == b.op && a.literal == b.literal &&
               a.literalHasUnit == b.literalHasUnit && (!number || a.literalBound == b.literalBound) &&
               (*this)(a.literalParam, b.literalParam);
    }
    bool operator()(const ast::View& a, const ast::View& b) const {
        return (*this)(a.from, b.from) && (*this)(a.facing, b.facing);
    }
    bool operator()(const ast::OrderBy& a, const ast::OrderBy& b) const {
        return (*this)(a.distanceTo, b.distanceTo) && a.attribute == b.attribute && a.descending == b.descending;
    }
    bool operator()(const ast::AsOf& a, const ast::AsOf& b) const { return a.instant == b.instant; }
    bool operator()(const ast::SimilarTo& a, const ast::SimilarTo& b) const {
        return a.text == b.text && (*this)(a.param, b.param) && a.vector == b.vector;
    }
    bool operator()(const ast::FindStmt& a, const ast::FindStmt& b) const {
        return (*this)(a.target, b.target) && (*this)(a.asOf, b.asOf) && (*this)(a.view, b.view) &&
               (*this)(a.where, b.where) && (*this)(a.nearestTo, b.nearestTo) && (*this)(a.orderBy, b.orderBy) &&
               (*this)(a.similarTo, b.similarTo) && a.limit == b.limit && (*this)(a.limitParam, b.limitParam) &&
               a.path == b.path && a.columns == b.columns;
    }
    bool operator()(const ast::CountStmt& a, const ast::CountStmt& b) const {
        return (*this)(a.target, b.target) && (*this)(a.asOf, b.asOf) && (*this)(a.view, b.view) &&
               (*this)(a.where, b.where);
    }
    bool operator()(const ast::RelateStmt& a, const ast::RelateStmt& b) const {
        return (*this)(a.subject, b.subject) && (*this)(a.object, b.object) && (*this)(a.view, b.view);
    }
    bool operator()(const ast::CheckStmt& a, const ast::CheckStmt& b) const {
        return (*this)(a.subject, b.subject) && a.predicate == b.predicate && (*this)(a.args, b.args) &&
               (*this)(a.threshold, b.threshold) && (*this)(a.view, b.view);
    }
    bool operator()(const ast::DescribeStmt& a, const ast::DescribeStmt& b) const {
        return (*this)(a.target, b.target);
    }
    bool operator()(const ast::ExplainStmt& a, const ast::ExplainStmt& b) const {
        return a.inner && b.inner && (*this)(*a.inner, *b.inner);
    }
    // The statements no shape holds.
    template <class A, class B>
    bool operator()(const A& /*a*/, const B& /*b*/) const {
        return false;
    }
    bool operator()(const ast::Statement& a, const ast::Statement& b) const {
        return a.parameterCount == b.parameterCount && std::visit(*this, a.body, b.body);
    }
};

}  // namespace

std::optional<StatementShape> statementShape(std::string_view text) { return Scanner(text).scan(); }

bool sameStatement(const ast::Statement& a, const ast::Statement& b) { return SameMeaning{}(a, b); }

}  // namespace smql::parser
