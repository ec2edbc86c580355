#include "shell/repl.hpp"

#include <sys/select.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <fstream>
#include <iostream>

#include <readline/history.h>
#include <readline/readline.h>

#include <fmt/format.h>

#include "relations/predicates.hpp"
#include "relations/thresholds.hpp"
#include "shell/interrupt.hpp"

namespace smql::shell {

namespace {

constexpr const char* kPrompt = "smql> ";
constexpr const char* kContinuationPrompt = "   ...> ";
constexpr std::size_t kHistoryKept = 1000;

// ---------------------------------------------------------------- completion

// Readline's callbacks are plain C functions: they reach the session and the candidates from here.
Session* completingSession = nullptr;
std::vector<std::string> candidates;

std::vector<std::string> metaCommandNames() {
    std::vector<std::string> names;
    for (const auto& command : Session::metaCommands())
        for (const auto& name : command.names) names.emplace_back(name);
    return names;
}

const Session::MetaCommand* metaCommandNamed(const std::string& name) {
    for (const auto& command : Session::metaCommands())
        if (std::find(command.names.begin(), command.names.end(), name) != command.names.end()) return &command;
    return nullptr;
}

std::string upper(std::string word) {
    for (char& c : word) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return word;
}

// The word before the one being completed, upper-cased ("" at the start of the line).
std::string previousWord(int start) {
    std::string before(rl_line_buffer, static_cast<std::size_t>(start));
    auto end = before.find_last_not_of(" \t'\"");
    if (end == std::string::npos) return {};
    auto begin = before.find_last_of(" \t(,", end);
    return upper(before.substr(begin == std::string::npos ? 0 : begin + 1,
                               end - (begin == std::string::npos ? 0 : begin + 1) + 1));
}

std::vector<std::string> sceneNames(Engine& engine) {
    std::vector<std::string> names;
    for (const ResultSet& result : engine.execute("SHOW SCENES")) {
        int column = result.columnIndex("name");
        if (column < 0) continue;
        for (const auto& row : result.rows)
            if (typeOf(row[column]) == ValueType::Text) names.push_back(std::get<std::string>(row[column]));
    }
    return names;
}

// What may stand where the cursor is: meta commands at the start of a line, their arguments after
// them, sides after `name.`, settings after SET, scenes after USE SCENE, else keywords, predicates
// and the database's categories.
std::vector<std::string> candidatesFor(const std::string& text, int start) {
    std::string line(rl_line_buffer);
    bool lineStart = line.find_first_not_of(" \t") >= static_cast<std::size_t>(start);
    if (lineStart && text.rfind('.', 0) == 0) return metaCommandNames();
    if (line.rfind('.', 0) == 0) {
        const Session::MetaCommand* command = metaCommandNamed(line.substr(0, line.find_first_of(" \t")));
        if (command && command->argument == Session::MetaArgument::Mode) {
            auto modes = outputModeNames();
            modes.emplace_back(Session::kAskMode);
            return modes;
        }
        if (command && command->argument == Session::MetaArgument::OnOff) return {"on", "off"};
        return {};
    }
    if (auto dot = text.find('.'); dot != std::string::npos) {
        std::vector<std::string> out;
        for (const auto& side : referenceSides()) out.push_back(text.substr(0, dot + 1) + side);
        return out;
    }
    Engine& engine = completingSession->engine();
    std::string previous = previousWord(start);
    if (previous == "SET") {
        std::vector<std::string> out;
        for (const auto& setting : relations::settingsCatalogue()) out.push_back(setting.name);
        return out;
    }
    if (previous == "SCENE") return sceneNames(engine);
    std::vector<std::string> out = languageKeywords();
    for (auto& word : relations::predicateWords()) out.push_back(std::move(word));
    for (auto& category : engine.knownCategories()) out.push_back(std::move(category));
    return out;
}

char* nextCandidate(const char* text, int state) {
    static std::size_t index;
    if (state == 0) index = 0;
    std::size_t length = std::strlen(text);
    bool lowerTyped = length > 0 && std::islower(static_cast<unsigned char>(text[0]));
    while (index < candidates.size()) {
        const std::string& word = candidates[index++];
        if (strncasecmp(word.c_str(), text, length) != 0) continue;
        // Keywords complete in the case the user started typing in.
        std::string out = word;
        if (lowerTyped)
            std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return std::tolower(c); });
        return strdup(out.c_str());
    }
    return nullptr;
}

char** complete(const char* text, int start, int) {
    std::string line(rl_line_buffer);
    // File names after the meta commands that take a file or a folder: readline's own completion.
    const Session::MetaCommand* command =
        line.rfind('.', 0) == 0 ? metaCommandNamed(line.substr(0, line.find_first_of(" \t"))) : nullptr;
    bool takesPath = command && command->argument == Session::MetaArgument::Path && start > 0;
    rl_attempted_completion_over = !takesPath;
    if (takesPath) return nullptr;
    try {
        candidates = candidatesFor(text, start);
    } catch (const std::exception&) {
        candidates.clear();  // a database that cannot answer offers nothing to complete
    }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    return rl_completion_matches(text, nextCandidate);
}

// ---------------------------------------------------------------- history

// One entry per line, so a statement typed over several lines comes back whole: `\n` and `\\` are
// escaped (readline's own file would split it into one entry per line).
std::string historyPath() {
    const char* home = std::getenv("HOME");
    return home ? std::string(home) + "/.smql_history" : std::string();
}

std::string escapeEntry(const std::string& entry) {
    std::string out;
    for (char c : entry) out += c == '\\' ? std::string("\\\\") : c == '\n' ? std::string("\\n") : std::string(1, c);
    return out;
}

std::string unescapeEntry(const std::string& line) {
    std::string out;
    for (std::size_t i = 0; i < line.size(); ++i) {
        if (line[i] == '\\' && i + 1 < line.size() && (line[i + 1] == 'n' || line[i + 1] == '\\'))
            out += line[++i] == 'n' ? '\n' : '\\';
        else
            out += line[i];
    }
    return out;
}

void loadHistory(const std::string& path) {
    std::ifstream in(path);
    std::deque<std::string> entries;
    for (std::string line; std::getline(in, line);) {
        if (line.empty()) continue;
        entries.push_back(line);
        if (entries.size() > kHistoryKept) entries.pop_front();
    }
    for (const auto& e : entries) add_history(unescapeEntry(e).c_str());
    // Rewritten at the cap, so the file does not grow without end.
    if (in.eof() && entries.size() == kHistoryKept) {
        std::ofstream out(path, std::ios::trunc);
        for (const auto& e : entries) out << e << "\n";
    }
}

// Saved at once, so a shell that is killed keeps what was typed.
void remember(const std::string& entry, const std::string& path) {
    add_history(entry.c_str());
    if (path.empty()) return;
    std::ofstream out(path, std::ios::app);
    out << escapeEntry(entry) << "\n";
}

// ---------------------------------------------------------------- the loop

struct Loop {
    Session& session;
    std::string historyFile;
    std::string typed;  // the statement so far, over its lines
    bool ended = false;
    int status = 0;
};
Loop* loop = nullptr;

void onLine(char* raw) {
    if (!raw) {  // Ctrl-D
        loop->ended = true;
        return;
    }
    std::string line(raw);
    std::free(raw);
    Session::Step step = loop->session.feedLine(line);
    if (line.find_first_not_of(" \t") != std::string::npos) loop->typed += loop->typed.empty() ? line : "\n" + line;
    if (step != Session::Step::More) {
        loop->session.finishOutput();
        if (!loop->typed.empty()) remember(loop->typed, loop->historyFile);
        loop->typed.clear();
        if (step == Session::Step::Failed && loop->session.options().bail) loop->status = 1, loop->ended = true;
    }
    if (loop->session.quitRequested()) loop->ended = true;
    if (loop->ended) {
        rl_callback_handler_remove();  // no prompt after the last line
        return;
    }
    rl_set_prompt(step == Session::Step::More ? kContinuationPrompt : kPrompt);
}

// Ctrl-C at the prompt: the line and the statement being typed are dropped; a fresh prompt follows.
void cancelLine() {
    interrupt::clear();
    loop->session.discardPending();
    loop->typed.clear();
    // ^C after what was typed, as a terminal shows it, then an empty line under the first prompt.
    rl_point = rl_end;
    rl_redisplay();
    std::fputs("^C", rl_outstream);
    rl_crlf();
    rl_free_line_state();
    rl_callback_sigcleanup();
    rl_replace_line("", 1);
    rl_set_prompt(kPrompt);
    rl_on_new_line();
    rl_redisplay();
}

}  // namespace

int runRepl(Session& session, const std::string& databaseDir) {
    completingSession = &session;
    rl_readline_name = "smql";
    rl_attempted_completion_function = complete;
    rl_basic_word_break_characters = const_cast<char*>(" \t\n(),;=<>!");
    rl_completer_quote_characters = const_cast<char*>("'\"");
    // Ctrl-C is ours (shell/interrupt.cpp): readline must not install its own handler over it.
    rl_catch_signals = 0;
    Loop state{.session = session, .historyFile = historyPath(), .typed = {}};
    loop = &state;
    if (!state.historyFile.empty()) loadHistory(state.historyFile);

    std::cout << fmt::format("smql {} on {} (scene '{}'). .help for help, .quit to leave.\n", "0.1", databaseDir,
                             session.engine().currentScene());
    rl_callback_handler_install(kPrompt, onLine);
    const int wake = interrupt::wakeFd();
    while (!state.ended) {
        fd_set input;
        FD_ZERO(&input);
        FD_SET(STDIN_FILENO, &input);
        if (wake >= 0) FD_SET(wake, &input);
        if (select(std::max(STDIN_FILENO, wake) + 1, &input, nullptr, nullptr, nullptr) < 0) {
            if (errno != EINTR) break;
            continue;  // the wake-up descriptor says whether it was Ctrl-C
        }
        if (wake >= 0 && FD_ISSET(wake, &input)) {
            interrupt::drainWakeFd();
            // Still set: pressed at the prompt. Cleared: a statement already took it.
            if (interrupt::requested()) cancelLine();
            continue;
        }
        rl_callback_read_char();
    }
    rl_callback_handler_remove();
    if (!session.quitRequested()) std::cout << "\n";  // after Ctrl-D, whose prompt line is still open
    return state.status;
}

}  // namespace smql::shell
