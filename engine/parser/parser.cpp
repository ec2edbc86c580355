#include "engine/parser/parser.hpp"

#include <mutex>

#include "engine/parser/ast_builder.hpp"
#include "engine/parser/source.hpp"
#include "engine/parser/statement_parser.hpp"
#include "engine/parser/vocabulary.hpp"

namespace smql::parser {

namespace {

// The 4.9 C++ runtime shares its DFA cache between parser instances and is
// known to race when several threads parse at once; a statement parses in
// microseconds, so callers (shell, C API, tests) simply take turns.
std::mutex& antlrMutex() {
    static std::mutex mutex;
    return mutex;
}

}  // namespace

std::vector<ast::Statement> parse(std::string_view text) {
    std::lock_guard lock(antlrMutex());
    Source source(text);
    std::vector<StatementSlice> slices = source.statements();
    if (slices.empty())
        throw Error(ErrorKind::Syntax, "empty input: there is no statement to run", SourceLocation{1, 1, 1},
                    "write a statement, as in FIND object;");

    // Statement by statement, so the error reported is the first one in the text.
    std::vector<ast::Statement> statements;
    for (const StatementSlice& slice : slices) {
        StatementParser parser(source, slice);
        statements.push_back(buildStatement(parser.parse(), source));
    }
    return statements;
}

bool isIncomplete(std::string_view text) {
    std::lock_guard lock(antlrMutex());
    try {
        Source source(text);
        const auto& tokens = source.tokens();
        if (tokens.empty()) return false;  // blank or only comments: nothing to continue
        int depth = 0;
        for (const auto& token : tokens) {
            switch (token->getType()) {
                case SmqlLexer::UNTERMINATED_STRING: return true;
                case SmqlLexer::LPAREN: ++depth; break;
                case SmqlLexer::RPAREN: depth = std::max(0, depth - 1); break;
                default: break;
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
