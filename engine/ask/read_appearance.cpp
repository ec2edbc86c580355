#include <algorithm>
#include <regex>

#include <fmt/format.h>

#include "engine/ask/phrase.hpp"
#include "engine/ask/readers.hpp"
#include "model/category.hpp"
#include "model/error.hpp"

namespace smql::ask {

// VSI-Bench's appearance order: "What will be the first-time appearance order of the following
// categories in the video: chair, sofa, tv, table?" The nodes of those categories ordered by the
// frame that first saw each (ingest's `first_seen`); the answer lists the categories in that order.
std::optional<Translation> appearanceOrder(const Question& question, const Lexicon& lexicon) {
    static const std::regex asked(
        R"((?:appearance order|order of (?:first )?appearance|order (?:were|are|did) .*?(?:first )?(?:seen|appear))[^:]*:\s*([^?]+))",
        std::regex::icase);
    std::smatch m;
    if (!std::regex_search(question.text, m, asked)) return std::nullopt;
    std::string list = std::regex_replace(m.str(1), std::regex(R"(\s+and\s+)"), ", ");
    Translation out;
    out.kind = QuestionKind::Appearance;
    PhraseParser parser(lexicon, out, question.planeCategories, question.scene, question.sceneCount);
    std::vector<std::string> all;
    for (std::size_t at = 0; at <= list.size();) {
        std::size_t comma = list.find(',', at);
        Words w = words(list.substr(at, comma == std::string::npos ? std::string::npos : comma - at));
        at = comma == std::string::npos ? list.size() + 1 : comma + 1;
        if (w.empty()) continue;
        std::size_t i = 0;
        Phrase ph = parser.phrase(w, i, false);
        auto cats = ph.categories.empty() ? std::vector<std::string>{model::categoryName(ph.noun)} : ph.categories;
        out.roles.push_back(cats);
        out.choices.push_back(joined(w, 0, w.size()));
        for (const auto& c : cats)
            if (std::find(all.begin(), all.end(), c) == all.end()) all.push_back(c);
    }
    if (all.empty()) return std::nullopt;
    const auto& stored = question.attributes;
    if (std::find(stored.begin(), stored.end(), "first_seen") == stored.end())
        throw Error(ErrorKind::Binding,
                    fmt::format("scene '{}' keeps no frame that first saw each thing (a layout, not a capture)",
                                question.scene),
                    std::nullopt, "ask it of a scene made by smql ingest from a capture's frames");
    std::string any;
    for (const auto& n : all) any += (any.empty() ? "" : " OR ") + fmt::format("category = {}", smqlString(n));
    out.smql = fmt::format("FIND thing WHERE {} ORDER BY first_seen RETURN id, category, first_seen",
                           all.size() > 1 ? "(" + any + ")" : any);
    out.subject = "thing";
    out.subjectPlural = "things";
    return out;
}

}  // namespace smql::ask
