#include "engine/parser/syntax_errors.hpp"

#include <algorithm>
#include <cctype>
#include <set>

#include <fmt/format.h>

#include "engine/parser/vocabulary.hpp"

namespace smql::parser {

namespace {

// Optimal string alignment distance (Levenshtein plus adjacent swaps, so
// "DESCIRBE" is one edit from DESCRIBE), case-insensitive.
std::size_t editDistance(std::string_view a, std::string_view b) {
    std::string x = lowerCase(a), y = lowerCase(b);
    std::vector<std::vector<std::size_t>> d(x.size() + 1, std::vector<std::size_t>(y.size() + 1));
    for (std::size_t i = 0; i <= x.size(); ++i) d[i][0] = i;
    for (std::size_t j = 0; j <= y.size(); ++j) d[0][j] = j;
    for (std::size_t i = 1; i <= x.size(); ++i) {
        for (std::size_t j = 1; j <= y.size(); ++j) {
            std::size_t cost = x[i - 1] == y[j - 1] ? 0 : 1;
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
            if (i > 1 && j > 1 && x[i - 1] == y[j - 2] && x[i - 2] == y[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    }
    return d[x.size()][y.size()];
}

// A token as quoted in a message; strings bring their own quotes, long ones
// are cut short.
std::string quoted(const antlr4::Token& token) {
    std::string text = token.getText();
    std::size_t cut = std::min(text.find('\n'), std::size_t{24});
    if (cut < text.size()) text = text.substr(0, cut) + "...";
    bool isString = token.getType() == SmqlLexer::STRING || token.getType() == SmqlLexer::UNTERMINATED_STRING;
    return isString ? text : "'" + text + "'";
}

std::string joinAlternatives(const std::vector<std::string>& items) {
    std::string out;
    for (std::size_t i = 0; i < items.size(); ++i) {
        if (i > 0) out += i + 1 == items.size() ? " or " : ", ";
        out += items[i];
    }
    return out;
}

// Token types that users think of as one thing, named together.
struct Group {
    std::vector<std::size_t> members;
    const char* words;
};

const std::vector<Group>& groups() {
    static const std::vector<Group> all = {
        {{SmqlLexer::IDENT, SmqlLexer::STRING, SmqlLexer::NODE_ID, SmqlLexer::SOURCE_ID, SmqlLexer::LABELLED_ID,
          SmqlLexer::LPAREN},
         "a reference (a name, 'quoted name', #id, sofa#id, src#id or (FIND ...))"},
        {{SmqlLexer::NOT, SmqlLexer::LPAREN, SmqlLexer::IDENT}, "a condition such as on(desk) or color = 'red'"},
        {{SmqlLexer::EQ, SmqlLexer::NE, SmqlLexer::LT, SmqlLexer::LE, SmqlLexer::GT, SmqlLexer::GE, SmqlLexer::LIKE},
         "a comparison (=, !=, <, <=, >, >=, LIKE)"},
        {{SmqlLexer::STRING, SmqlLexer::NUMBER, SmqlLexer::MINUS}, "a quoted string or a number"},
        {{SmqlLexer::NUMBER, SmqlLexer::MINUS}, "a number"},
    };
    return all;
}

std::string describeToken(std::size_t type, bool afterNumber) {
    switch (type) {
        case SmqlLexer::VIEW:
            return "VIEW FROM";
        case SmqlLexer::IS:
            return "IS [NOT] NULL";
        case SmqlLexer::NEAREST:
            return "NEAREST TO";
        case SmqlLexer::SIMILAR:
            return "SIMILAR TO";
        case SmqlLexer::ORDER:
            return "ORDER BY";
        case SmqlLexer::AS:
            return "AS OF";
        case SmqlLexer::DISTANCE:
            return "distance(...)";
        // After a number an identifier can only be its unit.
        case SmqlLexer::IDENT:
            return afterNumber ? "a unit (m, cm or mm)" : "a name";
        case SmqlLexer::STRING:
            return "a quoted string";
        case SmqlLexer::NUMBER:
            return "a number";
        case SmqlLexer::NODE_ID:
            return "#id";
        case SmqlLexer::SOURCE_ID:
            return "src#id";
        case SmqlLexer::LABELLED_ID:
            return "name#id";
        case SmqlLexer::EQ:
            return "'='";
        case SmqlLexer::NE:
            return "'!='";
        case SmqlLexer::LE:
            return "'<='";
        case SmqlLexer::GE:
            return "'>='";
        case SmqlLexer::LT:
            return "'<'";
        case SmqlLexer::GT:
            return "'>'";
        case SmqlLexer::LPAREN:
            return "'('";
        case SmqlLexer::RPAREN:
            return "')'";
        case SmqlLexer::COMMA:
            return "','";
        case SmqlLexer::DOT:
            return "'.'";
        case SmqlLexer::MINUS:
            return "'-'";
        case SmqlLexer::STAR:
            return "'*'";
        case SmqlLexer::PARAM:
            return "a placeholder (? or $1)";
        case antlr4::Token::EOF:
            return "';'";
        default:
            return tokenName(type);
    }
}

// The keywords in `expected` that stand for themselves (not for a name).
std::vector<std::size_t> meaningfulTypes(std::set<std::size_t> expected, bool afterNumber) {
    // Where a name fits, keywords fit too (as names): listing them would bury
    // the hint. After a number the identifier is a unit, and keywords there
    // are clause keywords, so they stay.
    if (expected.count(SmqlLexer::IDENT) && !afterNumber)
        std::erase_if(expected, [](std::size_t type) { return isSoftKeyword(type); });
    // `desk.left` makes '.' fit after nearly every name; it is almost never
    // what was missing.
    if (expected.size() > 1) expected.erase(SmqlLexer::DOT);
    // A placeholder fits wherever a value does, but only prepared statements can use one; the
    // hint names what can be written.
    if (expected.size() > 1) expected.erase(SmqlLexer::PARAM);
    return {expected.begin(), expected.end()};
}

std::string expectedWords(const std::vector<std::size_t>& types, bool afterNumber) {
    std::vector<std::size_t> rest = types;
    std::vector<std::pair<std::size_t, std::string>> items;  // (sort key, words)
    for (const Group& group : groups()) {
        bool all = std::all_of(group.members.begin(), group.members.end(), [&](std::size_t member) {
            return std::find(rest.begin(), rest.end(), member) != rest.end();
        });
        if (!all) continue;
        std::erase_if(rest, [&](std::size_t type) {
            return std::find(group.members.begin(), group.members.end(), type) != group.members.end();
        });
        items.emplace_back(*std::min_element(group.members.begin(), group.members.end()), group.words);
    }
    for (std::size_t type : rest) items.emplace_back(type, describeToken(type, afterNumber));
    // AND and OR continue the condition just written: they go first.
    auto rank = [](std::size_t type) {
        return type == SmqlLexer::AND || type == SmqlLexer::OR ? std::size_t{0} : type;
    };
    std::stable_sort(items.begin(), items.end(),
                     [&](const auto& a, const auto& b) { return rank(a.first) < rank(b.first); });
    std::vector<std::string> words;
    for (auto& item : items) words.push_back(std::move(item.second));
    return joinAlternatives(words);
}

// NaN and infinity are words to the lexer, so `near(door, NaN m)` would read
// as a name followed by an unexpected unit.
bool isNotANumberWord(const antlr4::Token* token) {
    if (!token || token->getType() != SmqlLexer::IDENT) return false;
    std::string word = lowerCase(token->getText());
    return word == "nan" || word == "inf" || word == "infinity";
}

bool isUnitToken(const antlr4::Token* token) {
    return token && token->getType() == SmqlLexer::IDENT && unitsPerMetre(lowerCase(token->getText()));
}

std::string commandList() {
    std::vector<std::string> words;
    for (std::size_t type = SmqlLexer::FIND; startsCommand(type); ++type) words.push_back(tokenName(type));
    words.push_back(tokenName(SmqlLexer::EXPLAIN));
    return joinAlternatives(words);
}

}  // namespace

std::string closestKeyword(std::string_view word, const std::vector<std::size_t>& candidates) {
    // One slip in a short word, two in a longer one; more is another word.
    std::size_t allowed = word.size() <= 4 ? 1 : 2;
    std::string best;
    std::size_t bestDistance = allowed + 1;
    for (std::size_t type : candidates) {
        if (!isKeyword(type)) continue;
        std::size_t distance = editDistance(word, tokenName(type));
        if (distance < bestDistance) {
            bestDistance = distance;
            best = tokenName(type);
        }
    }
    return best;
}

Error notAUnit(const antlr4::Token& word) {
    std::vector<std::size_t> keywords;
    for (std::size_t type = SmqlLexer::FIND; isKeyword(type); ++type) keywords.push_back(type);
    std::string keyword = closestKeyword(word.getText(), keywords);
    return Error(ErrorKind::Syntax, fmt::format("'{}' is not a unit", word.getText()), locationOf(word),
                 keyword.empty() ? "the units are m, cm and mm, as in 30 cm"
                                 : fmt::format("the units are m, cm and mm; did you mean {}?", keyword));
}

// 'what's on the table?': an apostrophe ended the quoted text, and the word after it is what failed. The hint
// says how to write it; empty for any other mistake.
std::string apostropheHint(const antlr4::Token* previous, const antlr4::Token* offending, std::size_t type) {
    if (type != SmqlLexer::IDENT || !previous || !offending || previous->getType() != SmqlLexer::STRING) return {};
    const std::string quotedText = previous->getText();
    if (quotedText.front() != '\'' || previous->getStopIndex() + 1 != offending->getStartIndex()) return {};
    return fmt::format(
        "a quote inside quoted text is written twice ({}''{} ...'), or the text goes in double quotes (\"{}'{} ...\")",
        quotedText.substr(0, quotedText.size() - 1), offending->getText(), quotedText.substr(1, quotedText.size() - 2),
        offending->getText());
}

Error syntaxError(const Source& source, const StatementSlice& slice, std::size_t failedAt,
                  const std::set<std::size_t>& expected) {
    const auto& tokens = source.tokens();
    const bool atEnd = failedAt >= slice.end - slice.begin;
    const antlr4::Token* offending = atEnd ? nullptr : tokens[slice.begin + failedAt].get();
    const antlr4::Token* previous = failedAt > 0 ? tokens[slice.begin + failedAt - 1].get() : nullptr;
    const std::size_t type = offending ? offending->getType() : antlr4::Token::EOF;
    const SourceLocation where = offending ? locationOf(*offending) : source.endOf(slice);
    const bool afterNumber = previous && previous->getType() == SmqlLexer::NUMBER;
    const std::vector<std::size_t> fitting = meaningfulTypes(expected, afterNumber);
    const std::string expectedHint = fitting.empty() ? "" : "expected " + expectedWords(fitting, afterNumber);

    // Lexical trouble first: the grammar rejects these tokens everywhere.
    if (type == SmqlLexer::UNTERMINATED_STRING) {
        char quote = offending->getText().front();
        SourceLocation at = where;
        at.length = 1;
        return Error(
            ErrorKind::Syntax, "unterminated string", at,
            fmt::format("close it with {0}; a {0} inside a string is written twice, as in {0}it{0}{0}s{0}", quote));
    }
    if (type == SmqlLexer::UNKNOWN_CHAR) {
        if (offending->getText() == "#")
            return Error(ErrorKind::Syntax, "'#' must be followed by a node id", where,
                         "write #42 for node 42, or src#93 for the node with source id 93");
        return Error(ErrorKind::Syntax, fmt::format("unexpected character {}", quoted(*offending)), where,
                     expectedHint);
    }

    // Parentheses: an extra ')' or a '(' the statement never closes.
    std::vector<const antlr4::Token*> open;
    for (std::size_t i = slice.begin; i < slice.begin + failedAt; ++i) {
        if (tokens[i]->getType() == SmqlLexer::LPAREN) open.push_back(tokens[i].get());
        if (tokens[i]->getType() == SmqlLexer::RPAREN && !open.empty()) open.pop_back();
    }
    if (type == SmqlLexer::RPAREN && open.empty())
        return Error(ErrorKind::Syntax, "')' has no matching '('", where, "remove it, or add the '(' it closes");
    if (atEnd && !open.empty() && expected.count(SmqlLexer::RPAREN))
        return Error(ErrorKind::Syntax, "'(' is never closed", locationOf(*open.back()),
                     source.hasTerminator(slice) ? "add ')' before the ';'" : "add ')' at the end");

    // Numbers that are not finite, and negative distances: say what is wrong
    // with the number rather than with the unit after it.
    const antlr4::Token* next =
        !atEnd && failedAt + 1 < slice.end - slice.begin ? tokens[slice.begin + failedAt + 1].get() : nullptr;
    const antlr4::Token* notANumber = isNotANumberWord(offending) && expected.count(SmqlLexer::NUMBER) ? offending
                                      : isUnitToken(offending) && isNotANumberWord(previous)           ? previous
                                                                                                       : nullptr;
    if (notANumber)
        return Error(ErrorKind::Syntax, fmt::format("'{}' is not a number", notANumber->getText()),
                     locationOf(*notANumber), "distances and values are finite numbers, as in 1.5 m");
    if (type == SmqlLexer::MINUS && expected.count(SmqlLexer::NUMBER) && !expected.count(SmqlLexer::MINUS) && next &&
        next->getType() == SmqlLexer::NUMBER) {
        const antlr4::Token* unit =
            failedAt + 2 < slice.end - slice.begin ? tokens[slice.begin + failedAt + 2].get() : nullptr;
        return Error(ErrorKind::Syntax, "a distance cannot be negative",
                     span(*offending, isUnitToken(unit) ? *unit : *next),
                     "write a distance of 0 or more, as in near(door, 1.5 m)");
    }

    // The grammar took the word after a number as its unit, so the parse
    // failed one token later than the real mistake.
    if (failedAt >= 2 && previous->getType() == SmqlLexer::IDENT &&
        tokens[slice.begin + failedAt - 2]->getType() == SmqlLexer::NUMBER &&
        !unitsPerMetre(lowerCase(previous->getText())))
        return notAUnit(*previous);

    std::string suggestion;
    if (type == SmqlLexer::IDENT) suggestion = closestKeyword(offending->getText(), fitting);

    // The first word of a statement.
    if (offending && std::find(fitting.begin(), fitting.end(), SmqlLexer::FIND) != fitting.end()) {
        // A question in English typed as it is: ASK takes it ("where is the bed?").
        static const std::set<std::string, std::less<>> kQuestionWords{
            "where", "what", "what's", "whats", "how",  "which", "who",  "is",   "are",      "can",
            "could", "does", "do",     "tell",  "take", "guide", "list", "give", "navigate", "please"};
        if (kQuestionWords.count(lowerCase(offending->getText()))) {
            std::string question =
                source.textBetween(*tokens[slice.begin], *tokens[std::max(slice.begin + 1, slice.end) - 1]);
            while (!question.empty() && std::isspace(static_cast<unsigned char>(question.back()))) question.pop_back();
            std::string quotedQuestion;
            for (char c : question) quotedQuestion += c == '\'' ? std::string("''") : std::string(1, c);
            return Error(ErrorKind::Syntax, fmt::format("{} does not start a statement", quoted(*offending)), where,
                         fmt::format("to ask in English, write ASK '{}'", quotedQuestion));
        }
        return Error(ErrorKind::Syntax, fmt::format("{} does not start a statement", quoted(*offending)), where,
                     suggestion.empty() ? "a statement starts with " + commandList()
                                        : fmt::format("did you mean {}?", suggestion));
    }

    std::string message;
    if (offending)
        message = "unexpected " + quoted(*offending);
    else
        message = source.hasTerminator(slice) ? "unexpected ';'" : "unexpected end of input";
    if (!offending && previous) message += " after " + quoted(*previous);

    std::string hint = expectedHint;
    if (std::string apostrophe = apostropheHint(previous, offending, type); !apostrophe.empty()) {
        hint = std::move(apostrophe);
    } else if (!suggestion.empty()) {
        hint = fmt::format("did you mean {}? ({})", suggestion, expectedHint);
    } else if (type == SmqlLexer::IDENT && expected.count(SmqlLexer::STRING) && !expected.count(SmqlLexer::IDENT)) {
        hint = fmt::format("text goes in quotes: '{}'", offending->getText());
    } else if (type == SmqlLexer::EQ && previous && previous->getType() == SmqlLexer::EQ) {
        hint = "compare with a single '='";
    } else if (startsCommand(type) && expected.count(antlr4::Token::EOF)) {
        hint = fmt::format("end the statement before {} with ';'", tokenName(type));
    }
    return Error(ErrorKind::Syntax, message, where, hint);
}

}  // namespace smql::parser
