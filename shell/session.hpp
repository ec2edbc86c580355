// A shell session over one database: runs statement text and meta commands and prints the results
// in the chosen output mode. The interactive shell, -c, -f, -cmd, piped input and `smql demo` all
// go through it, so they read statements and print results the same way.
#pragma once

#include <fstream>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/engine.hpp"
#include "model/error.hpp"
#include "shell/output.hpp"

namespace smql::shell {

struct SessionOptions {
    OutputOptions output;
    bool fitTerminal = false;  // standard output is a terminal: table and box fit its width
    bool timer = false;        // each statement's time on standard error
    bool echo = false;         // each statement printed before its result
    bool bail = false;         // the interactive shell ends at the first error (scripts always do)
    bool readOnly = false;     // databases opened with .open are read-only too
    // Safe mode (-safe, .safe on), for statements and scripts from someone else: no meta command
    // reads or writes a file or opens another database (.read, .output FILE, .once, .open).
    bool safe = false;
    std::string database;  // the open database's folder: no output is written into it
};

// Bounds on what a script may be (docs/shell.md, "Bounds"): .read and -f read at most this much,
// and .read nests at most this deep (a script that reads itself stops there).
inline constexpr std::size_t kMaxScriptBytes = 16 << 20;
inline constexpr int kMaxReadDepth = 16;

// A script file's text: an error for a missing file, a folder, or one of more than kMaxScriptBytes
// (a device such as /dev/zero is read no further than that).
std::string readScriptFile(const std::string& path);
// Whether a text holds a statement or a meta command, not only blank lines and `--` comments.
bool holdsStatement(std::string_view text);

class Session {
public:
    Session(std::unique_ptr<Engine> engine, std::ostream& out, std::ostream& err, SessionOptions options);
    ~Session();

    Engine& engine() { return *engine_; }
    const SessionOptions& options() const { return options_; }

    // Runs a script (-c, -f, a statement argument, piped input, .read): statements end with ';' and
    // may span lines; a line that starts with '.' where no statement is open is a meta command.
    // Stops at the first error, which is printed with its line in `text`; false then.
    bool runScript(std::string_view text);

    // The interactive shell, a line at a time. More: the statement goes on on the next line.
    enum class Step { Done, More, Failed };
    Step feedLine(std::string_view line);
    // Ctrl-C at the prompt: forgets the statement being typed.
    void discardPending() { pending_ = {}; }
    bool quitRequested() const { return quit_; }

    // The meta commands (.mode, .read ...): names (the first is the main one), how the argument is
    // written, what the command does, what may complete the argument, and the command itself.
    // Path and Command reach outside the database: safe mode refuses both.
    enum class MetaArgument { None, Mode, OnOff, Path, Command };
    // `.mode ask`: each line is a question in English, run as ASK '<line>'; `.mode MODE` returns
    // to SMQL. The output mode stays what it was.
    static constexpr std::string_view kAskMode = "ask";
    struct MetaCommand {
        std::vector<std::string_view> names;
        std::string_view usage;
        std::string_view does;
        MetaArgument argument;
        bool (*run)(Session& session, const std::string& argument);  // false on error
    };
    static const std::vector<MetaCommand>& metaCommands();
    // What to say of a command the shell does not have: sqlite3's name for one it has, or the
    // nearest name.
    static std::string unknownCommandHint(const std::string& name);

    // Ends the output document: json's one array closes (a script is one document, as is each
    // input of the interactive shell). Also ends a .once redirection.
    void finishOutput();

private:
    struct Pending {
        std::string text;
        int firstLine = 1;
    };
    Step feed(Pending& pending, std::string_view line, int lineNumber, std::string_view source);
    bool runStatements(std::string_view text, int firstLine, std::string_view source);
    bool runQuestion(std::string_view line, int lineNumber);
    bool runMeta(std::string_view line);
    // `microseconds`: the statement's time, for .timer (none for what no statement answered).
    void print(const ResultSet& result, std::optional<double> microseconds = std::nullopt);
    void printError(const Error& e, std::string_view source);
    std::ostream& out();
    // What out() writes to, for messages: the .output file or "standard output".
    std::string outName() const;
    void redirect(const std::string& path, bool once);

    std::unique_ptr<Engine> engine_;
    std::ostream& stdout_;
    std::ostream& err_;
    SessionOptions options_;
    std::ofstream file_;         // .output / .once target while one is open
    std::string filePath_;       // its path, for errors
    bool once_ = false;          // file_ closes after the next statement
    bool documentOpen_ = false;  // json: the array has begun
    bool quit_ = false;
    bool askMode_ = false;  // .mode ask: lines are English questions
    Pending pending_;       // the interactive shell's statement being typed
    int readDepth_ = 0;     // .read within .read
};

}  // namespace smql::shell
