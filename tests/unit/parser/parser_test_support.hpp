// Parsing helpers shared by the parser tests.
#pragma once

#include <stdexcept>
#include <string_view>

#include <catch2/catch.hpp>

#include "engine/parser/parser.hpp"
#include "model/error.hpp"

namespace smql::parser::testing {

// The one statement of `text`.
inline ast::Statement parseOne(std::string_view text) {
    std::vector<ast::Statement> statements = parse(text);
    REQUIRE(statements.size() == 1);
    return statements.front();
}

// The syntax error `text` must give.
inline Error syntaxErrorOf(std::string_view text) {
    try {
        parse(text);
    } catch (const Error& error) {
        CHECK(error.kind() == ErrorKind::Syntax);
        return error;
    }
    FAIL("expected a syntax error for: " << text);
    throw std::logic_error("unreachable");
}

}  // namespace smql::parser::testing
