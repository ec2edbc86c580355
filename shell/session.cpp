#include "shell/session.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <iostream>
#include <sstream>

#include <fmt/format.h>

#include "engine/format.hpp"
#include "engine/parser/parser.hpp"
#include "shell/interrupt.hpp"

namespace smql::shell {

namespace {

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

constexpr std::string_view kHelp = R"(Statements end with ';' and may span lines. Examples:
  FIND cushion WHERE on(sofa) PATH;
  FIND object WHERE near(wall.left, 1 m) ORDER BY distance(door) LIMIT 5;
  RELATE src#72 TO src#73;       COUNT chair WHERE near(table);
  DESCRIBE #12;  SHOW SCENES;  USE SCENE 'room0';  SHOW TREE;  SHOW SETTINGS;
  SET near = 0.8 m;  EXPLAIN FIND lamp WHERE on(table);
Meta commands:
  .help                    this text
  .scenes                  the scenes (SHOW SCENES)
  .categories              the categories of every scene
  .tree [#id]              the current scene's tree (SHOW TREE)
  .mode MODE               output mode: table, box, markdown, csv, tsv, json, jsonl (.format too)
  .headers on|off          column names in table, box, markdown, csv and tsv
  .output [FILE]           results into FILE (none: back to standard output)
  .once FILE               the next statement's results into FILE
  .read FILE               run the statements and meta commands of FILE
  .open DIR                switch to the database in DIR
  .timer on|off            each statement's time, on standard error
  .echo on|off             print each statement before its result
  .bail on|off             leave the shell at the first error
  .quit, .exit, .q         leave (Ctrl-D too)
Ctrl-C cancels the running statement or the line being typed.
The language: docs/language.md; predicates and thresholds: docs/relations.md.
)";

bool onOff(const std::string& command, const std::string& arg) {
    if (arg == "on") return true;
    if (arg == "off") return false;
    throw Error(ErrorKind::Usage, fmt::format("{} takes on or off", command), std::nullopt, command + " on");
}

// Lines that hold no statement: blank, or a `--` comment.
bool onlyComments(std::string_view text) {
    std::istringstream lines{std::string(text)};
    for (std::string line; std::getline(lines, line);) {
        std::string t = trim(line);
        if (!t.empty() && t.rfind("--", 0) != 0) return false;
    }
    return true;
}

std::size_t terminalColumns() {
    winsize size{};
    if (ioctl(STDOUT_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
    return 0;
}

}  // namespace

Session::Session(std::unique_ptr<Engine> engine, std::ostream& out, std::ostream& err, SessionOptions options)
    : engine_(std::move(engine)), stdout_(out), err_(err), options_(options) {
    interrupt::watch(engine_.get());
}

Session::~Session() {
    interrupt::watch(nullptr);
    finishOutput();
}

std::ostream& Session::out() { return file_.is_open() ? file_ : stdout_; }

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
    file_.open(path, std::ios::trunc);
    if (!file_)
        throw Error(ErrorKind::Usage, fmt::format("cannot write {}", path), std::nullopt, "check that the folder exists");
    once_ = once;
}

void Session::print(const ResultSet& result) {
    if (options_.output.mode == OutputMode::Json) {
        // One JSON document per script: the results as one array, opened by the first of them.
        out() << (documentOpen_ ? ",\n" : "[") << resultJson(result).dump();
        documentOpen_ = true;
    } else {
        OutputOptions output = options_.output;
        bool toTerminal = options_.fitTerminal && !file_.is_open();
        output.maxWidth = toTerminal ? terminalColumns() : 0;
        out() << renderResult(result, output);
    }
    // The time goes to standard error, so that standard output stays one parseable document.
    if (options_.timer) err_ << fmt::format("time: {:.1f} us\n", result.elapsedMicroseconds) << std::flush;
}

void Session::printError(const Error& e, std::string_view source) {
    out().flush();
    if (options_.output.mode == OutputMode::Json || options_.output.mode == OutputMode::Jsonl) {
        nlohmann::json j = {{"error", {{"kind", toString(e.kind())}, {"message", e.message()}}}};
        if (e.where()) j["error"]["line"] = e.where()->line, j["error"]["column"] = e.where()->column;
        if (!e.hint().empty()) j["error"]["hint"] = e.hint();
        err_ << j.dump() << "\n";
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
        engine_->execute(text, [&](ResultSet&& result) {
            if (interrupt::requested()) throw interruptedBetweenStatements();
            print(result);
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

Session::Step Session::feed(Pending& pending, std::string_view line, int lineNumber, std::string_view source) {
    if (pending.text.empty()) {
        std::string first = trim(line);
        if (first.empty()) return Step::Done;
        if (first[0] == '.') return runMeta(first) ? Step::Done : Step::Failed;
        pending.firstLine = lineNumber;
    }
    pending.text += pending.text.empty() ? std::string(line) : "\n" + std::string(line);
    if (onlyComments(pending.text)) {
        pending = {};
        return Step::Done;
    }
    if (parser::isIncomplete(pending.text)) return Step::More;
    Pending statement = std::exchange(pending, {});
    return runStatements(statement.text, statement.firstLine, source.empty() ? statement.text : source)
               ? Step::Done
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

bool Session::runMeta(std::string_view line) {
    std::string command = trim(line);
    std::string name = command.substr(0, command.find_first_of(" \t"));
    std::string arg = trim(std::string_view(command).substr(name.size()));
    try {
        if (name == ".help") {
            out() << kHelp;
        } else if (name == ".quit" || name == ".exit" || name == ".q") {
            quit_ = true;
        } else if (name == ".scenes") {
            return runStatements("SHOW SCENES", 1, {});
        } else if (name == ".tree") {
            std::string statement = arg.empty() ? "SHOW TREE" : "SHOW TREE " + arg;
            return runStatements(statement, 1, statement);
        } else if (name == ".categories") {
            ResultSet categories;
            categories.columns.push_back({"category", ValueType::Text});
            for (const auto& c : engine_->knownCategories()) categories.rows.push_back({c});
            print(categories);
            if (once_) finishOutput();
        } else if (name == ".mode" || name == ".format") {
            if (arg.empty()) {
                out() << "output mode: " << toString(options_.output.mode) << "\n";
            } else {
                OutputMode mode = parseOutputMode(arg);
                finishOutput();
                options_.output.mode = mode;
            }
        } else if (name == ".headers") {
            options_.output.headers = onOff(name, arg);
        } else if (name == ".timer") {
            options_.timer = onOff(name, arg);
        } else if (name == ".echo") {
            options_.echo = onOff(name, arg);
        } else if (name == ".bail") {
            options_.bail = onOff(name, arg);
        } else if (name == ".output") {
            redirect(arg, false);
        } else if (name == ".once") {
            if (arg.empty()) throw Error(ErrorKind::Usage, ".once needs a file", std::nullopt, ".once results.csv");
            redirect(arg, true);
        } else if (name == ".read") {
            if (arg.empty()) throw Error(ErrorKind::Usage, ".read needs a file", std::nullopt, ".read queries.smql");
            std::ifstream in(arg);
            if (!in) throw Error(ErrorKind::Usage, fmt::format("cannot read {}", arg));
            std::stringstream text;
            text << in.rdbuf();
            return runScript(text.str());
        } else if (name == ".open") {
            if (arg.empty()) throw Error(ErrorKind::Usage, ".open needs a database folder", std::nullopt, ".open /tmp/r0");
            auto engine = Engine::open(arg, options_.readOnly);
            finishOutput();
            interrupt::watch(engine.get());
            engine_ = std::move(engine);
        } else {
            throw Error(ErrorKind::Usage, fmt::format("unknown command {}", name), std::nullopt,
                        ".help lists the commands");
        }
        return true;
    } catch (const Error& e) {
        printError(e, {});
        return false;
    }
}

}  // namespace smql::shell
