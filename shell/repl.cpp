#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>

#include <readline/history.h>
#include <readline/readline.h>

#include <fmt/format.h>

#include "engine/parser/parser.hpp"
#include "shell/session.hpp"

namespace smql::shell {

namespace {

// Readline's completion callbacks are plain C functions: they read the word list from here.
std::vector<std::string> completionWords;

char* completionGenerator(const char* text, int state) {
    static std::size_t index;
    static std::size_t length;
    if (state == 0) index = 0, length = std::strlen(text);
    while (index < completionWords.size()) {
        const std::string& word = completionWords[index++];
        if (strncasecmp(word.c_str(), text, length) == 0) {
            // Keywords complete in the case the user started typing in.
            std::string out = word;
            bool lowerTyped = length > 0 && std::islower(static_cast<unsigned char>(text[0]));
            if (lowerTyped)
                for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
            return strdup(out.c_str());
        }
    }
    return nullptr;
}

char** complete(const char* text, int, int) {
    rl_attempted_completion_over = 1;  // no file-name completion
    return rl_completion_matches(text, completionGenerator);
}

std::string historyPath() {
    const char* home = std::getenv("HOME");
    return home ? std::string(home) + "/.smql_history" : std::string();
}

}  // namespace

int runRepl(Engine& engine, const std::string& databaseDir, OutputFormat format) {
    completionWords = parser::keywords();
    for (const auto& c : engine.knownCategories()) completionWords.push_back(c);
    for (const char* meta : {".help", ".scenes", ".tree", ".format", ".timer", ".quit"}) completionWords.push_back(meta);
    rl_attempted_completion_function = complete;
    rl_basic_word_break_characters = const_cast<char*>(" \t\n(),;=<>!");
    std::string history = historyPath();
    if (!history.empty()) read_history(history.c_str());

    std::cout << fmt::format("smql {} on {} (scene '{}'). .help for help, .quit to leave.\n", "0.1", databaseDir,
                             engine.currentScene());
    Session session(engine, std::cout, std::cerr, format);
    std::string pending;
    while (!session.quitRequested()) {
        char* raw = readline(pending.empty() ? "smql> " : "   ...> ");
        if (!raw) break;  // Ctrl-D
        std::string line(raw);
        std::free(raw);
        if (pending.empty() && line.find_first_not_of(" \t") == std::string::npos) continue;
        if (pending.empty() && line.find_first_not_of(" \t") != std::string::npos &&
            line[line.find_first_not_of(" \t")] == '.') {
            add_history(line.c_str());
            session.runMeta(line);
            continue;
        }
        pending += pending.empty() ? line : "\n" + line;
        if (parser::isIncomplete(pending)) continue;
        add_history(pending.c_str());
        session.runStatements(pending);  // errors are printed; the session goes on
        pending.clear();
    }
    if (!history.empty()) write_history(history.c_str());
    std::cout << "\n";
    return 0;
}

}  // namespace smql::shell
