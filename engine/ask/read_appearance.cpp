#include <algorithm>
#include <regex>

#include <fmt/format.h>

#include "engine/ask/phrase.hpp"
#include "engine/ask/readers.hpp"
#include "model/category.hpp"
#include "model/error.hpp"

namespace smql::ask {

namespace {

// The list of things a question asks the order of first sight of, whether it asks if the first came before the
// second, and whether it asks from the end (which came last). VSI-Bench's form: "What will be the first-time appearance
// order of the following categories in the video: chair, sofa, tv, table?"; a person's: "which did I see first, the
// bed or the sofa?", "what came first: ...", "which of the bed and the sofa did I see first?", "in what order did I see
// the bed, the sofa and the fridge?", "what order did the bed and the sofa appear in?", "when did I first see the
// fridge?" (a list of one), "did I see the bed before the sofa?", "was the bed seen before the sofa?" (`before`);
// "which did I see last, ...?" (`last`: the one first seen latest), "when did I last see the mug?" (`last` of one: the
// frame that last saw it).
struct AskedOrder {
    std::string list;
    bool before = false;
    bool last = false;
};

std::optional<AskedOrder> askedOrder(const std::string& text) {
    // "did I see", "did we notice": the person's sight, said as such.
    static const std::string saw = R"(did (?:i|we) (?:see|notice|spot|come across|pass))";
    static const std::string came = "(?:" + saw + "|came|appeared|showed up|was seen) (?:first|last)";
    auto pattern = [](const std::string& source) { return std::regex(source, std::regex::icase); };
    static const std::regex vsiBench = pattern(
        R"((?:appearance order|order of (?:first )?appearance|order (?:were|are|did) .*?(?:first )?(?:seen|appear))[^:]*:\s*([^?]+))");
    static const std::regex whichFirst = pattern(R"(^\s*(?:which|what)(?: one| thing)? )" + came +
                                                 R"(\s*[,:]?\s*(?:of\s+|between\s+)?([^?]+?)\s*\??\s*$)");
    static const std::regex whichOfFirst = pattern(R"(^\s*which of\s+([^?]+?)\s+)" + came + R"(\s*\??\s*$)");
    static const std::regex inWhatOrder =
        pattern(R"(^\s*(?:in )?(?:what|which) order (?:)" + saw +
                R"(|were|did|do)\s+([^?]+?)(?:\s+(?:seen|appear|show up|come up))?(?:\s+in)?\s*\??\s*$)");
    static const std::regex when =
        pattern(R"(^\s*when did (?:i|we) (?:first|last) (?:see|notice|spot|come across|pass)\s+([^?]+?)\s*\??\s*$)");
    static const std::regex before = pattern(R"(^\s*)" + saw + R"(\s+([^?]+?)\s+before\s+([^?]+?)\s*\??\s*$)");
    static const std::regex seenBefore =
        pattern(R"(^\s*(?:was|were)\s+([^?]+?)\s+(?:seen|spotted|noticed)\s+before\s+([^?]+?)\s*\??\s*$)");
    static const std::regex lastWord = pattern(R"(\blast\b)");
    std::smatch m;
    if (std::regex_search(text, m, vsiBench) || std::regex_search(text, m, whichFirst) ||
        std::regex_search(text, m, whichOfFirst) || std::regex_search(text, m, inWhatOrder) ||
        std::regex_search(text, m, when)) {
        const std::string said = m.str(0);
        return AskedOrder{m.str(1), false, std::regex_search(said.substr(0, said.size() - m.str(1).size()), lastWord)};
    }
    if (std::regex_search(text, m, before) || std::regex_search(text, m, seenBefore))
        return AskedOrder{m.str(1) + ", " + m.str(2), true};
    return std::nullopt;
}

// "what did I see first?", "what was the last thing I saw?": the thing first seen earliest, or latest (true).
std::optional<bool> askedFirstThing(const std::string& text) {
    static const std::regex seenFirst(
        R"(^\s*what(?:'s| is| was)? (?:did (?:i|we) (?:see|notice|spot) (first|last)|the (first|last) (?:thing|object) (?:(?:that )?(?:i|we) (?:saw|noticed|spotted|came across)|seen))\s*\??\s*$)",
        std::regex::icase);
    std::smatch m;
    if (!std::regex_match(text, m, seenFirst)) return std::nullopt;
    return (m.str(1) + m.str(2)) == "last";
}

void needsFirstSeen(const Question& question) {
    const auto& stored = question.attributes;
    if (std::find(stored.begin(), stored.end(), "first_seen") == stored.end())
        throw Error(ErrorKind::Binding,
                    fmt::format("scene '{}' keeps no frame that first saw each thing (a layout, not a capture)",
                                question.scene),
                    std::nullopt, "ask it of a scene made by smql ingest from a capture's frames");
}

}  // namespace

// The nodes of the kinds asked ordered by the frame that first saw each (ingest's `first_seen`); the answer lists
// the kinds in that order, or says whether the first came before the second.
std::optional<Translation> appearanceOrder(const Question& question, const Lexicon& lexicon) {
    if (const std::optional<bool> last = askedFirstThing(question.text)) {
        needsFirstSeen(question);
        Translation out;
        out.kind = QuestionKind::Appearance;
        out.measure = *last ? "last" : "first";
        out.smql = fmt::format(
            "FIND object WHERE first_seen IS NOT NULL ORDER BY first_seen{} RETURN id, category, "
            "first_seen",
            *last ? " DESC" : "");
        out.subject = "thing";
        out.subjectPlural = "things";
        return out;
    }
    const std::optional<AskedOrder> asked = askedOrder(question.text);
    if (!asked) return std::nullopt;
    std::string list = std::regex_replace(asked->list, std::regex(R"(\s+(?:and|or)\s+)", std::regex::icase), ", ");
    Translation out;
    out.kind = QuestionKind::Appearance;
    if (asked->before) out.predicate = "before";
    if (asked->last) out.measure = "last";
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
    needsFirstSeen(question);
    std::string any;
    for (const auto& n : all) any += (any.empty() ? "" : " OR ") + fmt::format("category = {}", smqlString(n));
    out.smql = fmt::format("FIND thing WHERE {} ORDER BY first_seen RETURN id, category, first_seen{}",
                           all.size() > 1 ? "(" + any + ")" : any,
                           asked->last && out.choices.size() == 1 ? ", last_seen" : "");
    out.subject = "thing";
    out.subjectPlural = "things";
    return out;
}

}  // namespace smql::ask
