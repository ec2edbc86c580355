#include "shell/session.hpp"

#include <ostream>

#include <fmt/format.h>

#include "engine/error.hpp"
#include "engine/format.hpp"

namespace smql::shell {

namespace {

std::string trim(std::string_view s) {
    auto b = s.find_first_not_of(" \t\r\n");
    if (b == std::string_view::npos) return {};
    auto e = s.find_last_not_of(" \t\r\n");
    return std::string(s.substr(b, e - b + 1));
}

constexpr std::string_view kHelp = R"(Statements end with ';' and may span lines. Examples:
  FIND cushion WHERE on(sofa) PATH;
  FIND object WHERE near(wall.left, 1 m) ORDER BY distance(door) LIMIT 5;
  RELATE src#72 TO src#73;       COUNT chair WHERE near(table);
  DESCRIBE #12;  SHOW SCENES;  USE SCENE 'room0';  SHOW TREE;  SHOW SETTINGS;
  SET near = 0.8 m;  EXPLAIN FIND lamp WHERE on(table);
Meta commands:
  .help                 this text
  .scenes               SHOW SCENES
  .tree [#id]           SHOW TREE
  .format table|json|csv  output format
  .timer on|off         print each statement's time
  .quit                 leave (Ctrl-D too)
The language: docs/language.md; predicates and thresholds: docs/relations.md.
)";

}  // namespace

OutputFormat parseFormat(std::string_view name) {
    if (name == "table") return OutputFormat::Table;
    if (name == "json") return OutputFormat::Json;
    if (name == "csv") return OutputFormat::Csv;
    throw Error(ErrorKind::Usage, fmt::format("unknown output format '{}'", name), std::nullopt,
                "formats: table, json, csv");
}

Session::Session(Engine& engine, std::ostream& out, std::ostream& err, OutputFormat format)
    : engine_(engine), out_(out), err_(err), format_(format) {}

void Session::print(const ResultSet& result) {
    switch (format_) {
        case OutputFormat::Json: out_ << jsonText(resultJson(result)) << "\n"; break;
        case OutputFormat::Csv: out_ << formatCsv(result); break;
        case OutputFormat::Table:
            out_ << formatTable(result);
            if (!result.columns.empty() && result.message.empty())
                out_ << fmt::format("({} row{})\n", result.rows.size(), result.rows.size() == 1 ? "" : "s");
            if (!result.message.empty()) out_ << result.message << "\n";
            break;
    }
    if (timer_) out_ << fmt::format("time: {:.1f} us\n", result.elapsedMicroseconds);
}

bool Session::runStatements(std::string_view text) {
    if (trim(text).empty()) return true;
    try {
        engine_.execute(text, [&](ResultSet&& result) { print(result); });
        return true;
    } catch (const Error& e) {
        if (format_ == OutputFormat::Json) {
            nlohmann::json j = {{"error", {{"kind", toString(e.kind())}, {"message", e.message()}}}};
            if (e.where()) j["error"]["line"] = e.where()->line, j["error"]["column"] = e.where()->column;
            if (!e.hint().empty()) j["error"]["hint"] = e.hint();
            err_ << jsonText(j) << "\n";
        } else {
            err_ << e.render(text) << "\n";
        }
        return false;
    }
}

bool Session::runMeta(std::string_view line) {
    std::string command = trim(line);
    std::string name = command.substr(0, command.find(' '));
    std::string arg = command.size() > name.size() ? trim(command.substr(name.size())) : "";
    try {
        if (name == ".help") {
            out_ << kHelp;
        } else if (name == ".quit" || name == ".exit") {
            quit_ = true;
        } else if (name == ".scenes") {
            return runStatements("SHOW SCENES");
        } else if (name == ".tree") {
            return runStatements(arg.empty() ? "SHOW TREE" : "SHOW TREE " + arg);
        } else if (name == ".format") {
            format_ = parseFormat(arg);
        } else if (name == ".timer") {
            if (arg != "on" && arg != "off")
                throw Error(ErrorKind::Usage, ".timer takes on or off", std::nullopt, ".timer on");
            timer_ = arg == "on";
        } else {
            throw Error(ErrorKind::Usage, fmt::format("unknown command {}", name), std::nullopt,
                        ".help lists the commands");
        }
        return true;
    } catch (const Error& e) {
        err_ << e.render() << "\n";
        return false;
    }
}

}  // namespace smql::shell
