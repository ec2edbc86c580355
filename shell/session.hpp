// A shell session over one engine: runs statement text and meta commands and
// prints the results in the chosen format. Used by the REPL, `-c` and `-f`.
#pragma once

#include <iosfwd>
#include <string>
#include <string_view>

#include "engine/engine.hpp"

namespace smql::shell {

enum class OutputFormat { Table, Json, Csv };
OutputFormat parseFormat(std::string_view name);  // throws Error(Usage)

class Session {
public:
    Session(Engine& engine, std::ostream& out, std::ostream& err, OutputFormat format);

    // Runs statements; prints results or the error (with a caret under the spot). False on error.
    bool runStatements(std::string_view text);
    // Runs a `.command`; false on error. Sets quitRequested() for `.quit`.
    bool runMeta(std::string_view line);
    bool quitRequested() const { return quit_; }
    void setTimer(bool on) { timer_ = on; }

private:
    void print(const ResultSet& result);

    Engine& engine_;
    std::ostream& out_;
    std::ostream& err_;
    OutputFormat format_;
    bool timer_ = false;
    bool quit_ = false;
};

// The interactive loop (readline: history in ~/.smql_history, multi-line
// statements ended by `;`, completion of keywords and categories).
int runRepl(Engine& engine, const std::string& databaseDir, OutputFormat format);

}  // namespace smql::shell
