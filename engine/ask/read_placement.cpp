#include <algorithm>

#include <fmt/format.h>

#include "engine/ask/readers.hpp"

namespace smql::ask {

// How a thing stands is where it is, or how it stands to the thing named after the verb.
bool readPlacement(const Words& w, std::size_t& i, PhraseParser& parser, Translation& out) {
    if (w.empty() || w.front() != "how") return false;
    auto verb = std::find_if(w.begin() + static_cast<std::ptrdiff_t>(i), w.end(), [](const std::string& word) {
        return isOneOf(word, {"located",   "placed",   "positioned", "situated", "set",  "laid",    "mounted",
                              "installed", "arranged", "oriented",   "attached", "hung", "hanging", "sitting",
                              "standing",  "lying",    "sit",        "stand",    "lie",  "hang",    "rest",
                              "resting",   "kept",     "put",        "stored"});
    });
    if (verb == w.end()) return false;
    const std::size_t verbAt = static_cast<std::size_t>(verb - w.begin());
    Phrase thing;
    if (!phraseUpTo(w, i, verbAt, parser, thing)) return false;
    // The verb may begin the predicate's phrase ("attached to", "mounted on", "hanging on").
    std::size_t predAt = verbAt;
    auto pred = PhraseParser::predicateAt(w, predAt);
    if (!pred && verbAt + 1 < w.size()) pred = PhraseParser::predicateAt(w, predAt = verbAt + 1);
    if (!pred) {
        i = verbAt + 1;
        return i >= w.size() && locateAnswer(thing, out);
    }
    i = predAt + pred->second;
    Phrase other = parser.phrase(w, i, true);
    out.kind = QuestionKind::RelativePosition;
    out.smql = fmt::format("RELATE {} TO {}", reference(thing), reference(other));
    describeSubject(thing, out);
    out.object = other.words;
    return true;
}

}  // namespace smql::ask
