// Runs the generated parser over the tokens of one statement, stopping at
// the first error and turning it into an smql::Error worded for users.
#pragma once

#include <memory>

#include "SmqlParser.h"
#include "engine/parser/source.hpp"

namespace smql::parser {

class StatementParser {
public:
    StatementParser(const Source& source, StatementSlice slice);
    ~StatementParser();

    // The parse tree; it lives as long as this object. Throws smql::Error
    // (ErrorKind::Syntax) at the first token that does not fit.
    grammar::SmqlParser::StatementContext& parse();

private:
    const Source& source_;
    StatementSlice slice_;
    std::unique_ptr<antlr4::ListTokenSource> tokens_;
    std::unique_ptr<antlr4::CommonTokenStream> stream_;
    std::unique_ptr<grammar::SmqlParser> parser_;
};

}  // namespace smql::parser
