#include <algorithm>
#include <regex>

#include <fmt/format.h>

#include "engine/ask/phrase.hpp"
#include "engine/ask/readers.hpp"
#include "model/category.hpp"
#include "model/error.hpp"

namespace smql::ask {

// VSI-Bench's route plan: "You are a robot beginning at the bed facing the tv. You want to navigate
// to the toilet. You will perform the following actions (...): 1. Go forward until the tv 2. [please
// fill in] 3. Go forward until the toilet. You have reached the final destination." The things it
// names become the rows (their boxes); the answer fills in each turn (answer.cpp).
std::optional<Translation> routePlan(const Question& question, const Lexicon& lexicon) {
    static const std::regex opening(
        R"(beginning at (?:the )?(.+?),? (?:and )?facing (?:the )?(.+?)\.\s*you want to navigate to (?:the )?(.+?)\.)",
        std::regex::icase);
    std::smatch m;
    if (!std::regex_search(question.text, m, opening)) return std::nullopt;
    const std::string start = m.str(1), facing = m.str(2), goal = m.str(3);
    std::string actions = m.suffix().str();
    if (auto colon = actions.find("):"); colon != std::string::npos) actions.erase(0, colon + 2);
    static const std::regex reached(R"(you have reached.*$)", std::regex::icase);
    actions = std::regex_replace(actions, reached, "");
    static const std::regex item(R"((?:^|\s)\d+\.\s*([\s\S]*?)(?=\s\d+\.\s|$))");
    static const std::regex forward(R"(^\s*go forward until (?:the )?(.+?)[.\s]*$)", std::regex::icase);
    Translation out;
    out.kind = QuestionKind::Route;
    std::vector<std::string> names{start, facing};
    for (auto it = std::sregex_iterator(actions.begin(), actions.end(), item); it != std::sregex_iterator(); ++it) {
        std::string step = (*it)[1].str();
        std::smatch f;
        if (step.find("please fill in") != std::string::npos) {
            out.steps.push_back("turn");
        } else if (std::regex_match(step, f, forward)) {
            out.steps.push_back("forward");
            names.push_back(f.str(1));
        }
    }
    if (out.steps.empty()) return std::nullopt;
    if (names.size() == 2) names.push_back(goal);
    PhraseParser parser(lexicon, out, question.planeCategories, question.scene, question.sceneCount);
    std::vector<std::string> all;
    for (const auto& name : names) {
        Words w = words(name);
        std::size_t i = 0;
        Phrase ph = parser.phrase(w, i, false);
        auto cats = ph.categories.empty() ? std::vector<std::string>{model::categoryName(ph.noun)} : ph.categories;
        out.roles.push_back(cats);
        for (const auto& c : cats)
            if (std::find(all.begin(), all.end(), c) == all.end()) all.push_back(c);
    }
    std::string any;
    for (const auto& n : all) any += (any.empty() ? "" : " OR ") + fmt::format("category = {}", smqlString(n));
    out.smql = fmt::format("FIND thing WHERE {} RETURN id, category, box", all.size() > 1 ? "(" + any + ")" : any);
    out.subject = goal;
    out.object = fmt::format("from the {} facing the {}", start, facing);
    return out;
}

}  // namespace smql::ask
