#include <algorithm>

#include <fmt/format.h>

#include "engine/ask/readers.hpp"

namespace smql::ask {

// What a thing looks like or says is what the memory holds of it: DESCRIBE gives its category, box,
// attributes and text.
bool readDescription(const Words& w, std::size_t& i, PhraseParser& parser, Translation& out) {
    if (i + 2 > w.size() || !isOneOf(w[i], {"what", "how"}) || !isOneOf(w[i + 1], {"does", "do"})) return false;
    i += 2;
    auto verb = std::find_if(w.begin() + static_cast<std::ptrdiff_t>(i), w.end(), [](const std::string& word) {
        return isOneOf(word, {"look", "appear", "say", "read", "resemble", "show", "display"});
    });
    if (verb == w.end()) return false;
    const std::size_t verbAt = static_cast<std::size_t>(verb - w.begin());
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
