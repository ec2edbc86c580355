// User-facing errors. Everything a user can get wrong (a query, a file, a
// scene name) surfaces as smql::Error: what went wrong, where, and what to do.
// Programmer errors are asserts, not Errors.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace smql {

enum class ErrorKind {
    Syntax,       // the statement does not parse
    Binding,      // names that do not resolve: unknown category, scene, setting, node
    Input,        // a malformed import file or capture
    Storage,      // the database cannot be opened / written (schema version, I/O)
    Usage,        // a command used wrongly (missing argument, bad flag value)
    Limit,        // a statement would exceed a limit of the session (rows, pairs): SET raises it
    Interrupted,  // Engine::interrupt (Ctrl-C, smql_interrupt) stopped the statement
};

std::string_view toString(ErrorKind kind);

// A place in a query text (1-based line and column) or in a file (line; column 0 = whole line).
struct SourceLocation {
    int line = 0;
    int column = 0;
    int length = 1;  // characters to underline
};

class Error : public std::runtime_error {
public:
    Error(ErrorKind kind, std::string message, std::optional<SourceLocation> where = std::nullopt,
          std::string hint = {});

    ErrorKind kind() const { return kind_; }
    const std::string& message() const { return message_; }
    const std::optional<SourceLocation>& where() const { return where_; }
    const std::string& hint() const { return hint_; }

    // Multi-line text for a terminal: the message with line:column, the
    // offending line of `source` with a caret under the spot, then the hint.
    std::string render(std::string_view source = {}) const;

private:
    ErrorKind kind_;
    std::string message_;
    std::optional<SourceLocation> where_;
    std::string hint_;
};

}  // namespace smql
