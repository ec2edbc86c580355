#include "engine/parser/parser.hpp"

#include <atomic>
#include <mutex>

#include <fmt/format.h>

#include "engine/parser/ast_builder.hpp"
#include "engine/parser/normalise.hpp"
#include "engine/parser/source.hpp"
#include "engine/parser/statement_parser.hpp"
#include "engine/parser/vocabulary.hpp"

namespace smql::parser {

namespace {

std::atomic<std::uint64_t> parsedCount{0};

// The 4.9 C++ runtime shares its DFA cache between parser instances and is
// known to race when several threads parse at once; a statement parses in
// microseconds, so callers (shell, C API, tests) simply take turns.
std::mutex& antlrMutex() {
    static std::mutex mutex;
    return mutex;
}

// Rejects a statement too long or too deeply nested to parse safely, before
// ANTLR sees it. Nesting is what the recursive rules will recurse on: each
// open parenthesis (conditions and sub-queries alike) and each NOT of a chain
// (`NOT NOT x` recurses without parentheses).
void checkLimits(const Source& source, const StatementSlice& slice) {
    const auto& tokens = source.tokens();
    const antlr4::Token& first = *tokens[slice.begin];
    const antlr4::Token& last = *tokens[slice.end - 1];
    const std::size_t length = last.getStopIndex() + 1 - first.getStartIndex();
    if (length > kMaxStatementLength)
        throw Error(ErrorKind::Syntax,
                    fmt::format("the statement is {} characters long; the limit is {}", length, kMaxStatementLength),
                    locationOf(first), "split it into shorter statements");

    std::vector<std::size_t> opened;  // the levels each open parenthesis added (its NOTs and itself)
    std::size_t depth = 0, nots = 0;
    for (std::size_t i = slice.begin; i < slice.end; ++i) {
        const antlr4::Token& token = *tokens[i];
        switch (token.getType()) {
            case SmqlLexer::NOT:
                ++nots;
                break;
            case SmqlLexer::LPAREN:
                opened.push_back(nots + 1);
                depth += nots + 1;
                nots = 0;
                break;
            case SmqlLexer::RPAREN:
                if (!opened.empty()) {
                    depth -= opened.back();
                    opened.pop_back();
                }
                nots = 0;
                break;
            default:
                nots = 0;
                break;
        }
        if (depth + nots > kMaxNestingDepth)
            throw Error(ErrorKind::Syntax,
                        fmt::format("the statement nests more than {} levels deep (parentheses, sub-queries and NOT "
                                    "together)",
                                    kMaxNestingDepth),
                        locationOf(token),
                        "write the condition with fewer levels, or split it into several statements");
    }
}

// parse(), with placeholders marked as node ids as buildStatement says; with `stopAtError`, the
// statements before the first error instead of the error.
std::vector<ast::Statement> parseStatements(std::string_view text, const std::vector<bool>& nodeIdPlaceholders,
                                            bool stopAtError = false) {
    std::lock_guard lock(antlrMutex());
    Source source(text);
    std::vector<StatementSlice> slices = source.statements();
    if (slices.empty())
        throw Error(ErrorKind::Syntax, "empty input: there is no statement to run", SourceLocation{1, 1, 1},
                    "write a statement, as in FIND object;");

    // Statement by statement, so the error reported is the first one in the text.
    std::vector<ast::Statement> statements;
    for (const StatementSlice& slice : slices) {
        try {
            checkLimits(source, slice);
            StatementParser parser(source, slice);
            statements.push_back(buildStatement(parser.parse(), source, nodeIdPlaceholders));
        } catch (const Error& e) {
            if (stopAtError && e.kind() == ErrorKind::Syntax) break;
            throw;
        }
        ++parsedCount;
    }
    return statements;
}

}  // namespace

std::vector<ast::Statement> parse(std::string_view text) { return parseStatements(text, {}); }

std::vector<ast::Statement> parseBeforeError(std::string_view text) {
    try {
        return parseStatements(text, {}, true);
    } catch (const Error& e) {
        if (e.kind() == ErrorKind::Syntax) return {};  // no statement: an empty text, or not UTF-8
        throw;
    }
}

ast::Statement parseShape(const StatementShape& shape) {
    std::vector<bool> nodeIds;
    for (const ShapeLiteral& literal : shape.literals) nodeIds.push_back(literal.kind == ShapeLiteral::Kind::NodeId);
    std::vector<ast::Statement> statements = parseStatements(shape.placeholderText(), nodeIds);
    if (statements.size() != 1)
        throw Error(ErrorKind::Syntax, "a statement shape holds one statement", statements.at(1).where);
    return std::move(statements.front());
}

std::uint64_t statementsParsed() { return parsedCount.load(); }

bool isIncomplete(std::string_view text) {
    std::lock_guard lock(antlrMutex());
    try {
        Source source(text);
        const auto& tokens = source.tokens();
        if (tokens.empty()) return false;  // blank or only comments: nothing to continue
        int depth = 0;
        for (const auto& token : tokens) {
            switch (token->getType()) {
                case SmqlLexer::UNTERMINATED_STRING:
                    return true;
                case SmqlLexer::LPAREN:
                    ++depth;
                    break;
                case SmqlLexer::RPAREN:
                    depth = std::max(0, depth - 1);
                    break;
                default:
                    break;
            }
        }
        return depth > 0 || tokens.back()->getType() != SmqlLexer::SEMI;
    } catch (const Error&) {
        return false;  // not UTF-8: more lines will not fix it; parse() says why
    }
}

const std::vector<std::string>& keywords() {
    static const std::vector<std::string> all = [] {
        std::vector<std::string> words;
        for (std::size_t type = SmqlLexer::FIND; isKeyword(type); ++type) words.push_back(tokenName(type));
        return words;
    }();
    return all;
}

const std::vector<std::string>& sides() {
    static const std::vector<std::string> all{"left", "right", "front", "back"};
    return all;
}

}  // namespace smql::parser
