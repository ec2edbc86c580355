#include "shell/session.hpp"

#include <sys/ioctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <sstream>

#include <fmt/format.h>

#include "engine/format.hpp"
#include "model/names.hpp"
#include "shell/interrupt.hpp"
#include "shell/output_file.hpp"
#include "storage/output_guard.hpp"

namespace smql::shell {

namespace {

// A separator as sqlite3 takes it: quotes around it dropped, \t and \n as a tab and a line break.
std::string unquoted(std::string text) {
    if (text.size() >= 2 && (text.front() == '"' || text.front() == '\'') && text.back() == text.front())
        text = text.substr(1, text.size() - 2);
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '\\' && i + 1 < text.size() && (text[i + 1] == 't' || text[i + 1] == 'n')) {
            out += text[++i] == 't' ? '\t' : '\n';
            continue;
        }
        out += text[i];
    }
    return out;
}

std::string trim(std::string_view s) {
    auto b = s.find_first_not_of(" \t\r\n");
    if (b == std::string_view::npos) return {};
    auto e = s.find_last_not_of(" \t\r\n");
    return std::string(s.substr(b, e - b + 1));
}

// Ctrl-C between two statements of one input (the engine stops a statement that is running):
// the statements not yet run are dropped.
Error interruptedBetweenStatements() {
    return Error(ErrorKind::Interrupted, "the statement was interrupted", std::nullopt,
                 "the statements after it in the input did not run");
}

constexpr std::string_view kHelpStatements = R"(Statements end with ';' and may span lines. Examples:
  FIND cushion WHERE on(sofa) PATH;
  FIND object WHERE near(wall.left, 1 m) ORDER BY distance(door) LIMIT 5;
  RELATE src#72 TO src#73;       COUNT chair WHERE near(table);
  DESCRIBE #12;  SHOW SCENES;  USE SCENE 'room0';  SHOW TREE;  SHOW SETTINGS;
  SET near = 0.8 m;  EXPLAIN FIND lamp WHERE on(table);
  ASK 'what is on the sofa?';    .mode ask: each line is a question in English
Meta commands:
)";
constexpr std::string_view kHelpEnd = R"(Ctrl-C cancels the running statement or the line being typed.
The language: docs/language.md; predicates and thresholds: docs/relations.md.
)";

bool onOff(const std::string& command, const std::string& arg) {
    if (arg == "on") return true;
    if (arg == "off") return false;
    throw Error(ErrorKind::Usage, fmt::format("{} takes on or off", command), std::nullopt, command + " on");
}

std::size_t terminalColumns() {
    winsize size{};
    if (ioctl(STDOUT_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
    return 0;
}

}  // namespace

bool holdsStatement(std::string_view text) {
    std::istringstream lines{std::string(text)};
    for (std::string line; std::getline(lines, line);) {
        std::string t = trim(line);
        if (!t.empty() && t.rfind("--", 0) != 0) return true;
    }
    return false;
}

std::string readScriptFile(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw Error(ErrorKind::Usage, fmt::format("cannot read {}: it is a folder", path), std::nullopt,
                    "name a script file");
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw Error(ErrorKind::Usage, fmt::format("cannot read {}: {}", path, std::strerror(errno)), std::nullopt,
                    "check the path");
    // Read in pieces, as far as the bound: what a script is costs memory, not what it might be
    // (a .read within .read, 16 deep, held 16 MiB a level before).
    std::string text;
    std::array<char, 1 << 16> piece{};
    while (text.size() <= kMaxScriptBytes && in.read(piece.data(), piece.size()).gcount() > 0)
        text.append(piece.data(), static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxScriptBytes)
        throw Error(
            ErrorKind::Limit,
            fmt::format("{} is more than {} MiB: a script holds statements, not data", path, kMaxScriptBytes >> 20),
            std::nullopt, "split it, or import data with smql import");
    return text;
}

Session::Session(std::unique_ptr<Engine> engine, std::ostream& out, std::ostream& err, SessionOptions options)
    : engine_(std::move(engine)), stdout_(out), err_(err), options_(options) {
    interrupt::watch(engine_.get());
}

Session::~Session() {
    interrupt::watch(nullptr);
    finishOutput();
}

std::ostream& Session::out() { return file_.is_open() ? file_ : stdout_; }

std::string Session::outName() const { return file_.is_open() ? filePath_ : std::string("standard output"); }

void Session::finishOutput() {
    if (documentOpen_) out() << "]\n";
    documentOpen_ = false;
    out().flush();
    if (once_) file_.close(), once_ = false;
}

void Session::redirect(const std::string& path, bool once) {
    finishOutput();
    if (file_.is_open()) file_.close();
    once_ = false;
    if (path.empty()) return;
    storage::refuseDatabaseFile(path, options_.database);
    errno = 0;
    file_.open(path, std::ios::trunc);
    if (!file_)
        throw Error(ErrorKind::Usage,
                    fmt::format("cannot write {}{}", path, errno ? std::string(": ") + std::strerror(errno) : ""),
                    std::nullopt, "check that the folder exists and can be written");
    filePath_ = path;
    once_ = once;
}

void Session::print(const ResultSet& result, std::optional<double> microseconds) {
    if (options_.output.mode == OutputMode::Json) {
        // One JSON document per script: the results as one array, opened by the first of them.
        out() << (documentOpen_ ? ",\n" : "[") << jsonText(resultJson(result));
        documentOpen_ = true;
    } else {
        OutputOptions output = options_.output;
        bool toTerminal = options_.fitTerminal && !file_.is_open();
        output.maxWidth = toTerminal ? terminalColumns() : 0;
        out() << renderResult(result, output);
    }
    // A result that cannot be written is an error, not a silent empty file.
    checkWritten(out(), outName());
    // The time goes to standard error, so that standard output stays one parseable document.
    if (options_.timer && microseconds) err_ << fmt::format("time: {:.1f} us\n", *microseconds) << std::flush;
}

void Session::printError(const Error& e, std::string_view source) {
    out().flush();
    if (options_.output.mode == OutputMode::Json || options_.output.mode == OutputMode::Jsonl) {
        nlohmann::json j = {{"error", {{"kind", toString(e.kind())}, {"message", e.message()}}}};
        if (e.where()) j["error"]["line"] = e.where()->line, j["error"]["column"] = e.where()->column;
        if (!e.hint().empty()) j["error"]["hint"] = e.hint();
        err_ << jsonText(j) << "\n";
    } else {
        err_ << e.render(source) << "\n";
    }
    err_.flush();
}

bool Session::runStatements(std::string_view text, int firstLine, std::string_view source) {
    if (options_.echo) out() << trim(text) << "\n";
    interrupt::clear();
    bool ok = true;
    try {
        // As sqlite3's .timer: the shell times each statement, from the end of the one before (its
        // output written) to its answer.
        auto started = std::chrono::steady_clock::now();
        engine_->execute(text, [&](ResultSet&& result) {
            const double microseconds =
                std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - started).count();
            if (interrupt::requested()) throw interruptedBetweenStatements();
            print(result, microseconds);
            started = std::chrono::steady_clock::now();
        });
    } catch (const Error& e) {
        // On a terminal the ^C was echoed where the cursor was: the message starts a line of its own.
        if (e.kind() == ErrorKind::Interrupted && isatty(STDERR_FILENO)) err_ << "\n";
        // Locations are within `text`, which starts at line `firstLine` of `source`.
        std::optional<SourceLocation> where = e.where();
        if (where && where->line > 0) where->line += firstLine - 1;
        printError(Error(e.kind(), e.message(), where, e.hint()), source);
        ok = false;
    }
    interrupt::clear();
    if (once_) finishOutput();
    return ok;
}

bool Session::runQuestion(std::string_view line, int lineNumber) {
    std::string question(line);
    if (question.starts_with("--")) return true;  // a comment, as in SMQL
    while (!question.empty() && question.back() == ';') question.pop_back();
    std::string statement = "ASK " + model::quoted(question);
    return runStatements(statement, lineNumber, statement);
}

Session::Step Session::feed(Pending& pending, std::string_view line, int lineNumber, std::string_view source) {
    if (pending.text.empty()) {
        std::string first = trim(line);
        if (first.empty()) return Step::Done;
        if (first[0] == '.') return runMeta(first) ? Step::Done : Step::Failed;
        if (askMode_) return runQuestion(first, lineNumber) ? Step::Done : Step::Failed;
        pending.firstLine = lineNumber;
    }
    pending.text += pending.text.empty() ? std::string(line) : "\n" + std::string(line);
    if (!holdsStatement(pending.text)) {
        pending = {};
        return Step::Done;
    }
    if (!statementComplete(pending.text)) return Step::More;
    Pending statement = std::exchange(pending, {});
    return runStatements(statement.text, statement.firstLine, source.empty() ? statement.text : source) ? Step::Done
                                                                                                        : Step::Failed;
}

bool Session::runScript(std::string_view text) {
    Pending pending;
    int lineNumber = 0;
    std::size_t start = 0;
    while (start <= text.size() && !quit_) {
        std::size_t end = text.find('\n', start);
        std::string_view line = text.substr(start, end == std::string_view::npos ? text.npos : end - start);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        if (feed(pending, line, ++lineNumber, text) == Step::Failed) return false;
        if (end == std::string_view::npos) break;
        start = end + 1;
    }
    // The end of the script ends the last statement, `;` or not.
    if (!pending.text.empty() && !quit_) return runStatements(pending.text, pending.firstLine, text);
    return true;
}

Session::Step Session::feedLine(std::string_view line) {
    // Each statement typed is its own text: error locations count from its first line.
    return feed(pending_, line, 1, {});
}

// Every meta command, in the order .help lists them: the dispatcher, the help text and the
// shell's completion all read this table.
const std::vector<Session::MetaCommand>& Session::metaCommands() {
    using Arg = MetaArgument;
    static const std::vector<MetaCommand> table{
        {{".help"},
         "",
         "this text",
         Arg::None,
         [](Session& s, const std::string&) {
             s.out() << kHelpStatements;
             for (const auto& c : metaCommands()) {
                 std::string names;
                 for (const auto& n : c.names) names += (names.empty() ? "" : ", ") + std::string(n);
                 s.out() << fmt::format("  {:<24} {}\n", names + (c.usage.empty() ? "" : " " + std::string(c.usage)),
                                        c.does);
             }
             s.out() << kHelpEnd;
             return true;
         }},
        {{".scenes"},
         "",
         "the scenes (SHOW SCENES)",
         Arg::None,
         [](Session& s, const std::string&) { return s.runStatements("SHOW SCENES", 1, {}); }},
        {{".categories"},
         "",
         "the categories of every scene",
         Arg::None,
         [](Session& s, const std::string&) {
             ResultSet categories;
             categories.columns.push_back({"category", ValueType::Text});
             for (const auto& c : s.engine_->knownCategories()) categories.rows.push_back({c});
             s.print(categories);
             if (s.once_) s.finishOutput();
             return true;
         }},
        {{".tree"},
         "[#id]",
         "the current scene's tree (SHOW TREE)",
         Arg::None,
         [](Session& s, const std::string& arg) {
             // One reference (#12, sofa#50, src#93, lamp), never more text: `.tree #1; DROP SCENE 'x'`
             // is no tree.
             const bool oneReference = std::all_of(arg.begin(), arg.end(), [](unsigned char c) {
                 return std::isalnum(c) || c == '#' || c == '_' || c == '-' || c == '.';
             });
             if (!oneReference)
                 throw Error(ErrorKind::Usage, fmt::format(".tree takes one node, not '{}'", arg), std::nullopt,
                             ".tree #12, .tree sofa#50 or .tree with no argument");
             std::string statement = arg.empty() ? "SHOW TREE" : "SHOW TREE " + arg;
             return s.runStatements(statement, 1, statement);
         }},
        {{".mode", ".format"},
         "MODE",
         "output mode: table (column), box, markdown, csv, tsv, list, line, json, jsonl, html; ask: lines are "
         "questions",
         Arg::Mode,
         [](Session& s, const std::string& arg) {
             if (arg.empty()) {
                 s.out() << "output mode: " << toString(s.options_.output.mode)
                         << (s.askMode_ ? " (lines are questions: .mode ask)" : "") << "\n";
                 return true;
             }
             if (arg == kAskMode) {
                 s.askMode_ = true;
                 return true;
             }
             OutputMode mode = parseOutputMode(arg);
             s.finishOutput();
             s.options_.output.mode = mode;
             s.askMode_ = false;
             return true;
         }},
        {{".headers"},
         "on|off",
         "column names in table, box, markdown, csv, tsv and list",
         Arg::OnOff,
         [](Session& s, const std::string& arg) { return s.options_.output.headers = onOff(".headers", arg), true; }},
        {{".separator"},
         "SEP",
         "what list mode puts between values (default |)",
         Arg::None,
         [](Session& s, const std::string& arg) {
             if (arg.empty())
                 throw Error(ErrorKind::Usage, ".separator needs a separator", std::nullopt, "as in .separator ,");
             s.options_.output.separator = unquoted(arg);
             return true;
         }},
        {{".nullvalue"},
         "TEXT",
         "what a missing value prints as (default nothing; json keeps null)",
         Arg::None,
         [](Session& s, const std::string& arg) { return s.options_.output.nullValue = unquoted(arg), true; }},
        {{".show"},
         "",
         "the output settings and the database",
         Arg::None,
         [](Session& s, const std::string&) {
             auto onOffText = [](bool on) { return on ? "on" : "off"; };
             const std::pair<std::string_view, std::string> settings[] = {
                 {"mode", std::string(s.askMode_ ? kAskMode : toString(s.options_.output.mode))},
                 {"headers", onOffText(s.options_.output.headers)},
                 {"separator", model::quoted(s.options_.output.separator)},
                 {"nullvalue", model::quoted(s.options_.output.nullValue)},
                 {"output", s.file_.is_open() ? s.filePath_ + (s.once_ ? " (once)" : "") : "stdout"},
                 {"echo", onOffText(s.options_.echo)},
                 {"timer", onOffText(s.options_.timer)},
                 {"bail", onOffText(s.options_.bail)},
                 {"safe", onOffText(s.options_.safe)},
                 {"database", s.options_.database.empty() ? "(transient)" : s.options_.database},
             };
             for (const auto& [name, value] : settings) s.out() << fmt::format("{:>9}: {}\n", name, value);
             s.out().flush();
             return true;
         }},
        {{".print"},
         "TEXT",
         "print TEXT (quotes removed), as a script's heading",
         Arg::None,
         [](Session& s, const std::string& arg) {
             s.out() << unquoted(arg) << "\n";
             checkWritten(s.out(), s.outName());
             return true;
         }},
        {{".system", ".shell"},
         "COMMAND",
         "run COMMAND in /bin/sh (not in safe mode)",
         Arg::Command,
         [](Session& s, const std::string& arg) {
             if (arg.empty()) throw Error(ErrorKind::Usage, ".system needs a command", std::nullopt, ".system ls -l");
             s.out().flush();
             const int status = std::system(arg.c_str());
             if (status != 0)
                 throw Error(
                     ErrorKind::Usage,
                     fmt::format("the command exited with status {}", WIFEXITED(status) ? WEXITSTATUS(status) : status),
                     std::nullopt, {});
             return true;
         }},
        {{".output"},
         "[FILE]",
         "results into FILE (none: back to standard output)",
         Arg::Path,
         [](Session& s, const std::string& arg) { return s.redirect(arg, false), true; }},
        {{".once"},
         "FILE",
         "the next statement's results into FILE",
         Arg::Path,
         [](Session& s, const std::string& arg) {
             if (arg.empty()) throw Error(ErrorKind::Usage, ".once needs a file", std::nullopt, ".once results.csv");
             return s.redirect(arg, true), true;
         }},
        {{".read"},
         "FILE",
         "run the statements and meta commands of FILE",
         Arg::Path,
         [](Session& s, const std::string& arg) {
             if (arg.empty()) throw Error(ErrorKind::Usage, ".read needs a file", std::nullopt, ".read queries.smql");
             if (s.readDepth_ >= kMaxReadDepth)
                 throw Error(
                     ErrorKind::Limit,
                     fmt::format(".read {}: scripts read within each other more than {} deep", arg, kMaxReadDepth),
                     std::nullopt, "a script that reads itself never ends: check its .read lines");
             const std::string text = readScriptFile(arg);
             ++s.readDepth_;
             const bool ok = s.runScript(text);
             --s.readDepth_;
             return ok;
         }},
        {{".open"},
         "DIR",
         "switch to the database in DIR",
         Arg::Path,
         [](Session& s, const std::string& arg) {
             if (arg.empty())
                 throw Error(ErrorKind::Usage, ".open needs a database folder", std::nullopt, ".open /tmp/r0");
             auto engine = Engine::open(arg, s.options_.readOnly);
             s.finishOutput();
             interrupt::watch(engine.get());
             s.engine_ = std::move(engine);
             s.options_.database = arg;
             return true;
         }},
        {{".timer"},
         "on|off",
         "each statement's time, on standard error",
         Arg::OnOff,
         [](Session& s, const std::string& arg) { return s.options_.timer = onOff(".timer", arg), true; }},
        {{".echo"},
         "on|off",
         "print each statement before its result",
         Arg::OnOff,
         [](Session& s, const std::string& arg) { return s.options_.echo = onOff(".echo", arg), true; }},
        {{".bail"},
         "on|off",
         "leave the shell at the first error",
         Arg::OnOff,
         [](Session& s, const std::string& arg) { return s.options_.bail = onOff(".bail", arg), true; }},
        {{".safe"},
         "on",
         "safe mode from now on: no meta command reads or writes files or opens a database",
         Arg::OnOff,
         [](Session& s, const std::string& arg) {
             if (!onOff(".safe", arg) && s.options_.safe)
                 throw Error(ErrorKind::Usage, "safe mode cannot be left", std::nullopt,
                             "start another smql without -safe");
             s.options_.safe = s.options_.safe || onOff(".safe", arg);
             return true;
         }},
        {{".quit", ".exit", ".q"},
         "",
         "leave (Ctrl-D too)",
         Arg::None,
         [](Session& s, const std::string&) { return s.quit_ = true, true; }},
    };
    return table;
}

namespace {

// sqlite3's commands that smql has under another name: its users' hands type them first.
constexpr std::array<std::pair<std::string_view, std::string_view>, 8> kSqliteCommands{{
    {".tables", ".scenes lists the scenes (SHOW SCENES); .categories the kinds of things in them"},
    {".schema", "SHOW ATTRIBUTES lists what a node has; .categories the kinds of things"},
    {".indexes", "EXPLAIN shows the index a statement uses"},
    {".indices", "EXPLAIN shows the index a statement uses"},
    {".dump", "smql export json DB --scene NAME writes a scene out"},
    {".import", "smql import FORMAT FILE --db DB reads a scene in"},
    {".databases", "the shell has one database open: .open DIR opens another"},
    {".width", "table mode sizes each column to its values and the terminal's width"},
}};

}  // namespace

std::string Session::unknownCommandHint(const std::string& name) {
    for (const auto& [sqlite, smql] : kSqliteCommands)
        if (sqlite == name) return std::string(smql);
    std::vector<std::string> known;
    for (const auto& meta : metaCommands())
        for (auto n : meta.names) known.emplace_back(n);
    if (auto close = model::nearestNames(name, known, 1); !close.empty())
        return fmt::format("did you mean {}? (.help lists the commands)", close.front());
    return ".help lists the commands";
}

bool Session::runMeta(std::string_view line) {
    std::string command = trim(line);
    std::string name = command.substr(0, command.find_first_of(" \t"));
    std::string arg = trim(std::string_view(command).substr(name.size()));
    try {
        for (const auto& meta : metaCommands()) {
            if (std::find(meta.names.begin(), meta.names.end(), name) == meta.names.end()) continue;
            // Safe mode: .output with no file (back to standard output) is the one file command left.
            if (options_.safe && meta.argument == MetaArgument::Path && !(name == ".output" && arg.empty()))
                throw Error(ErrorKind::Usage, fmt::format("{} is not allowed in safe mode: it reaches files", name),
                            std::nullopt, "safe mode (-safe, .safe on) runs statements only");
            if (options_.safe && meta.argument == MetaArgument::Command)
                throw Error(ErrorKind::Usage, fmt::format("{} is not allowed in safe mode: it runs a program", name),
                            std::nullopt, "safe mode (-safe, .safe on) runs statements only");
            return meta.run(*this, arg);
        }
        throw Error(ErrorKind::Usage, fmt::format("unknown command {}", name), std::nullopt, unknownCommandHint(name));
    } catch (const Error& e) {
        printError(e, {});
        return false;
    }
}

}  // namespace smql::shell
