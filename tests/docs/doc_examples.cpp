// Runs every SMQL example of the documentation against the database its page names, so a
// page cannot show a statement that does not work. The convention is in docs/contributing.md
// ("Examples that run").
//
// Usage: smql_doc_examples SMQL_BINARY SHARED_DATA_DIR PAGE.md...
// Each database is built once with the commands a reader would type; every ```smql block then
// runs in a fresh read-only session on it.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "engine/engine.hpp"
#include "model/error.hpp"

namespace fs = std::filesystem;

namespace {

struct Statement {
    int line = 0;  // in the page
    std::string text;
    // In a transcript, what the shell prints for it (the error, for a `smql error` block).
    std::optional<std::vector<std::string>> expectedOutput;
};

struct Block {
    int line = 0;  // of the opening fence
    std::string database;
    bool expectError = false;
    std::vector<Statement> statements;
    std::string problem;  // a block the convention does not allow
};

std::string trim(const std::string& s) {
    auto b = s.find_first_not_of(" \t\r\n");
    if (b == std::string::npos) return {};
    return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

std::vector<std::string> splitLines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    return lines;
}

// Splits a script at the `;` that end statements, skipping those in strings ('..', "..", with
// doubled quotes inside) and comments (`--` to the end of the line). Pieces that hold only
// spaces and comments are dropped.
std::vector<Statement> splitStatements(const std::vector<std::string>& lines, int firstLine) {
    std::vector<Statement> out;
    Statement current;
    char quote = 0;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const std::string& l = lines[i];
        for (std::size_t c = 0; c < l.size(); ++c) {
            char ch = l[c];
            if (quote) {
                if (ch == quote && c + 1 < l.size() && l[c + 1] == quote)
                    current.text += ch, ++c;
                else if (ch == quote)
                    quote = 0;
                current.text += ch;
                continue;
            }
            if (ch == '-' && c + 1 < l.size() && l[c + 1] == '-') break;
            if (ch == ';') {
                if (!trim(current.text).empty()) out.push_back({current.line, trim(current.text), std::nullopt});
                current = {};
                continue;
            }
            if (ch == '\'' || ch == '"') quote = ch;
            if (current.text.empty() && (ch == ' ' || ch == '\t')) continue;
            if (current.text.empty()) current.line = firstLine + static_cast<int>(i);
            current.text += ch;
        }
        if (!current.text.empty()) current.text += '\n';
    }
    if (!trim(current.text).empty()) out.push_back({current.line, trim(current.text), std::nullopt});
    return out;
}

// A transcript: `smql> ` starts a statement, `...> ` continues it, other lines are its output.
std::vector<Statement> readTranscript(const std::vector<std::string>& lines, int firstLine) {
    std::vector<Statement> out;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const std::string& l = lines[i];
        if (l.rfind("smql> ", 0) == 0) {
            out.push_back({firstLine + static_cast<int>(i), l.substr(6), std::vector<std::string>{}});
        } else if (l.rfind("...> ", 0) == 0 && !out.empty() && out.back().expectedOutput->empty()) {
            out.back().text += "\n" + l.substr(5);
        } else if (!out.empty()) {
            out.back().expectedOutput->push_back(l);
        }
    }
    for (auto& s : out)
        while (!s.expectedOutput->empty() && trim(s.expectedOutput->back()).empty()) s.expectedOutput->pop_back();
    return out;
}

std::vector<Block> readPage(const std::string& path) {
    static const std::regex marker(R"(^\s*<!--\s*smql-db:\s*(\S+)\s*-->\s*$)");
    static const std::regex fence(R"(^ {0,3}(```+)\s*(.*)$)");
    std::ifstream in(path);
    std::vector<Block> blocks;
    std::string database, line, closing;
    std::vector<std::string> body;
    Block* open = nullptr;
    bool inFence = false;
    for (int number = 1; std::getline(in, line); ++number) {
        std::smatch m;
        if (inFence) {
            if (std::regex_match(line, m, fence) && m[1].length() >= static_cast<long>(closing.size()) &&
                trim(m[2]).empty()) {
                inFence = false;
                if (!open) continue;
                bool transcript = false;
                for (const auto& l : body) transcript |= l.rfind("smql> ", 0) == 0;
                if (transcript && !open->expectError)
                    open->problem = "a transcript (smql> prompts) belongs in a `smql error` block";
                open->statements =
                    transcript ? readTranscript(body, open->line + 1) : splitStatements(body, open->line + 1);
                if (open->statements.empty()) open->problem = "the block holds no statement";
                open = nullptr;
            } else if (open) {
                body.push_back(line);
            }
            continue;
        }
        if (std::regex_match(line, m, marker)) {
            database = m[1];
        } else if (std::regex_match(line, m, fence)) {
            inFence = true;
            closing = m[1];
            std::istringstream info(m[2].str());
            std::vector<std::string> words;
            for (std::string w; info >> w;) words.push_back(w);
            if (words.empty() || words[0] != "smql") continue;
            blocks.push_back({number, database, false, {}, {}});
            open = &blocks.back();
            body.clear();
            for (std::size_t i = 1; i < words.size(); ++i) {
                if (words[i] == "error")
                    open->expectError = true;
                else
                    open->problem = "unknown word '" + words[i] + "' after ```smql (only `error` is known)";
            }
            if (database.empty()) open->problem = "no database named before this block (<!-- smql-db: NAME -->)";
        }
    }
    if (inFence && open) open->problem = "the block is never closed";
    return blocks;
}

std::string quote(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

class Databases {
public:
    Databases(std::string smql, std::string sharedData) : smql_(std::move(smql)), data_(std::move(sharedData)) {
        std::string pattern = (fs::temp_directory_path() / "smql-doc-examples-XXXXXX").string();
        if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a folder under /tmp");
        work_ = pattern;
    }
    ~Databases() { fs::remove_all(work_); }

    // The directory of the database `name`, built on first use; nullopt (with `problem` set)
    // when the name is unknown or building it failed.
    std::optional<std::string> get(const std::string& name, std::string& problem) {
        if (auto it = built_.find(name); it != built_.end()) {
            if (!it->second.second.empty()) problem = "the database '" + name + "' could not be built (see above)";
            return it->second.second.empty() ? std::optional(it->second.first) : std::nullopt;
        }
        fs::create_directories(work_ / name);
        std::string db = (work_ / name / "db").string();
        std::string smql = quote(smql_);
        std::vector<std::string> commands;
        static const std::regex synth(R"(synth-(\d+))"), changed(R"(synth-(\d+)-changed)");
        std::smatch m;
        if (name == "replica-room0") {
            commands.push_back(smql + " import replica " + quote(data_ + "/replica-room0/info_semantic.json") +
                               " --db " + quote(db));
        } else if (std::regex_match(name, m, synth)) {
            std::string capture = (work_ / name / "capture").string();
            commands.push_back(smql + " synth --seed " + m[1].str() + " --frames 1 --out " + quote(capture));
            commands.push_back(smql + " import json " + quote(capture + "/truth.json") + " --db " + quote(db));
        } else if (std::regex_match(name, m, changed)) {
            // The room, then the same room after --changes as its next version.
            std::string before = (work_ / name / "before").string(), after = (work_ / name / "after").string();
            commands.push_back(smql + " synth --seed " + m[1].str() + " --frames 1 --out " + quote(before));
            commands.push_back(smql + " synth --seed " + m[1].str() + " --frames 1 --changes --out " + quote(after));
            commands.push_back(smql + " import json " + quote(before + "/truth.json") + " --db " + quote(db));
            commands.push_back(smql + " import json " + quote(after + "/truth.json") + " --db " + quote(db) +
                               " --update synth-" + m[1].str());
        } else {
            problem = "unknown database '" + name + "' (known: replica-room0, synth-N, synth-N-changed)";
        }
        for (const auto& command : commands) {
            std::string log = (work_ / name / "log.txt").string();
            if (problem.empty() && std::system((command + " >" + quote(log) + " 2>&1").c_str()) != 0) {
                std::ifstream in(log);
                problem = "building it failed: " + command + "\n" + std::string(std::istreambuf_iterator<char>(in), {});
            }
        }
        built_[name] = {db, problem};
        return problem.empty() ? std::optional(db) : std::nullopt;
    }

private:
    std::string smql_, data_;
    fs::path work_;
    std::map<std::string, std::pair<std::string, std::string>> built_;
};

std::string indent(const std::string& text) {
    std::string out;
    for (const auto& l : splitLines(text)) out += "    " + l + "\n";
    return out;
}

// Runs one statement; returns an empty string when it did what the block says, else what went wrong.
std::string check(smql::Engine& engine, const Block& block, const Statement& statement) {
    try {
        engine.execute(statement.text);
    } catch (const smql::Error& e) {
        std::string rendered = e.render(statement.text);
        if (!block.expectError) return "failed:\n" + indent(rendered);
        if (statement.expectedOutput && *statement.expectedOutput != splitLines(rendered)) {
            std::string expected;
            for (const auto& l : *statement.expectedOutput) expected += l + "\n";
            return "the page shows the error as\n" + indent(expected) + "  but it is\n" + indent(rendered);
        }
        return "";
    }
    return block.expectError ? "succeeded, but the block expects an error" : "";
}

int run(int argc, char** argv) {
    Databases databases(argv[1], argv[2]);
    int total = 0, failed = 0;
    for (int i = 3; i < argc; ++i) {
        std::string page = argv[i];
        int pageRun = 0, pageFailed = 0;
        for (const auto& block : readPage(page)) {
            std::string problem = block.problem;
            std::optional<std::string> dir;
            if (problem.empty()) dir = databases.get(block.database, problem);
            if (!problem.empty()) {
                ++pageFailed;
                std::cout << "FAIL " << page << ":" << block.line << ": " << problem << "\n";
                continue;
            }
            auto engine = smql::Engine::open(*dir, /*readOnly=*/true);
            for (const auto& statement : block.statements) {
                ++pageRun;
                std::string what = check(*engine, block, statement);
                if (what.empty()) continue;
                ++pageFailed;
                std::cout << "FAIL " << page << ":" << statement.line << " (" << block.database
                          << "): " << statement.text << "\n  " << what << "\n";
            }
        }
        if (pageRun || pageFailed) std::cout << page << ": " << pageRun << " statements, " << pageFailed << " failed\n";
        total += pageRun, failed += pageFailed;
    }
    std::cout << total << " statements, " << failed << " failed\n";
    if (total == 0) std::cout << "FAIL: no ```smql example found\n";
    return failed == 0 && total > 0 ? 0 : 1;
}
}  // namespace

int main(int argc, char** argv) {
    if (argc < 4) {
        std::cerr << "usage: smql_doc_examples SMQL_BINARY SHARED_DATA_DIR PAGE.md...\n";
        return 2;
    }
    try {
        return run(argc, argv);
    } catch (const smql::Error& e) {
        std::cout << "FAIL: " << e.render() << "\n";
    } catch (const std::exception& e) {
        std::cout << "FAIL: " << e.what() << "\n";
    }
    return 1;
}
