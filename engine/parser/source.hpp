// A query text after lexing: its tokens, split into statements, and the
// helpers that turn token positions into SourceLocations. Private to
// engine/parser (it exposes ANTLR types).
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "SmqlLexer.h"
#include "antlr4-runtime.h"
#include "model/error.hpp"

namespace smql::parser {

// The tokens of one statement: [begin, end) in Source::tokens. The token at
// `end`, when there is one, is the `;` that closed the statement.
struct StatementSlice {
    std::size_t begin = 0;
    std::size_t end = 0;
};

class Source {
public:
    // Throws smql::Error when the text is not valid UTF-8. Never fails
    // otherwise: characters the language does not know become UNKNOWN_CHAR
    // tokens that the parser rejects with a location.
    explicit Source(std::string_view text);

    const std::vector<std::unique_ptr<antlr4::Token>>& tokens() const { return tokens_; }

    // The statements, empty ones (`;;`) left out.
    std::vector<StatementSlice> statements() const;

    // The exact text between two tokens, both included.
    std::string textBetween(const antlr4::Token& first, const antlr4::Token& last) const;

    // Where a statement ends: its `;`, or the spot just after its last token.
    SourceLocation endOf(const StatementSlice& slice) const;
    bool hasTerminator(const StatementSlice& slice) const { return slice.end < tokens_.size(); }

private:
    std::unique_ptr<antlr4::ANTLRInputStream> input_;
    // Tokens read their text lazily from the lexer's input, so both stay alive.
    std::unique_ptr<grammar::SmqlLexer> lexer_;
    std::vector<std::unique_ptr<antlr4::Token>> tokens_;
};

SourceLocation locationOf(const antlr4::Token& token);
// From the start of `first` to the end of `last`; on different lines the
// underline stops at the end of `first`.
SourceLocation span(const antlr4::Token& first, const antlr4::Token& last);
SourceLocation span(antlr4::ParserRuleContext& context);

// Names are case-insensitive: the AST holds them in lower case (ASCII only).
std::string lowerCase(std::string_view text);

}  // namespace smql::parser
