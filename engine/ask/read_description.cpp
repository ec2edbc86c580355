#include <algorithm>

#include <fmt/format.h>

#include "engine/ask/readers.hpp"

namespace smql::ask {

namespace {

// Whether w[from..] is the whole scene alone ("the room", "this place", "the office" where the scene is one):
// DESCRIBE of the scene's node sums it up.
bool describesScene(const Words& w, std::size_t from, std::size_t to, PhraseParser& parser, model::NodeId sceneRoot,
                    Translation& out) {
    while (from < to && isOneOf(w[from], {"the", "this", "my", "our", "your"})) ++from;
    const std::size_t place = parser.scenePlaceAt(w, from);
    if (sceneRoot == model::kNoNode || place == 0 || from + place != to) return false;
    out.kind = QuestionKind::Statement;
    out.smql = fmt::format("DESCRIBE #{}", sceneRoot);
    out.subject = out.subjectPlural = "room";
    return true;
}

}  // namespace

// What a thing looks like or says is what the memory holds of it: DESCRIBE gives its category, box,
// attributes and text.
bool readDescription(const Words& w, std::size_t& i, PhraseParser& parser, model::NodeId sceneRoot, Translation& out) {
    // "describe the desk", "tell me about the monitor", "what do you know about the chair?": all the
    // memory holds of it.
    static const std::vector<Words> asks{words("describe"),
                                         words("tell me about"),
                                         words("tell me more about"),
                                         words("what do you know about"),
                                         words("what can you tell me about"),
                                         words("give me a description of")};
    for (const Words& lead : asks) {
        if (i + lead.size() >= w.size() ||
            !std::equal(lead.begin(), lead.end(), w.begin() + static_cast<std::ptrdiff_t>(i)))
            continue;
        i += lead.size();
        if (describesScene(w, i, w.size(), parser, sceneRoot, out)) {
            i = w.size();
            return true;
        }
        Phrase thing = parser.phrase(w, i, true);
        if (i < w.size()) return false;
        out.kind = QuestionKind::Statement;
        out.smql = "DESCRIBE " + reference(thing);
        describeSubject(thing, out);
        return true;
    }
    // "what is the room like?", "what's this place like?", before a thing is looked for in "the room like"
    if (i + 3 < w.size() && w[i] == "what" && isOneOf(w[i + 1], {"is", "'s"}) && w.back() == "like" &&
        describesScene(w, i + 2, w.size() - 1, parser, sceneRoot, out)) {
        i = w.size();
        return true;
    }
    // "what is object#7?" (an `object` its models could not name among them), "what is the black table?", "what are
    // the boxes?": a thing named by its id, or by its kind and nothing more than its colour, is asked for all the
    // memory holds of it. Every other "what is ...?" form was tried before this one.
    if (i + 2 < w.size() && w[i] == "what" && isOneOf(w[i + 1], {"is", "'s", "are"})) {
        std::size_t k = i + 2;
        Phrase thing = parser.phrase(w, k, true);
        const bool named = !thing.id.empty() || (!thing.categories.empty() && !thing.kind && thing.conditions.empty() &&
                                                 !thing.order && thing.excluded.empty() && thing.filters.empty() &&
                                                 !thing.room && !thing.self && !thing.here);
        if (k == w.size() && named) {
            i = k;
            out.kind = QuestionKind::Statement;
            out.smql = "DESCRIBE " + reference(thing);
            describeSubject(thing, out);
            return true;
        }
    }
    if (i + 2 > w.size() || !isOneOf(w[i], {"what", "how"}) || !isOneOf(w[i + 1], {"does", "do"})) return false;
    i += 2;
    auto verb = std::find_if(w.begin() + static_cast<std::ptrdiff_t>(i), w.end(), [](const std::string& word) {
        return isOneOf(word, {"look", "appear", "say", "read", "resemble", "show", "display"});
    });
    if (verb == w.end()) return false;
    const std::size_t verbAt = static_cast<std::size_t>(verb - w.begin());
    // "what does the room look like?"
    if (*verb == "look" && verbAt + 2 == w.size() && w.back() == "like" &&
        describesScene(w, i, verbAt, parser, sceneRoot, out)) {
        i = w.size();
        return true;
    }
    Phrase thing;
    if (!phraseUpTo(w, i, verbAt, parser, thing)) return false;
    i = verbAt + 1;
    if (*verb == "look") {
        if (i >= w.size() || w[i] != "like") return false;
        ++i;
    } else if (*verb == "appear") {
        if (i + 2 > w.size() || w[i] != "to" || w[i + 1] != "be") return false;
        i += 2;
        // "what does the trash can appear to be full of?": how full is beyond the memory.
        if (i < w.size()) out.notes.push_back(fmt::format("'{}' is left out", joined(w, i, w.size())));
        i = w.size();
    }
    if (i < w.size()) return false;
    out.kind = QuestionKind::Statement;
    out.smql = "DESCRIBE " + reference(thing);
    describeSubject(thing, out);
    return true;
}

}  // namespace smql::ask
