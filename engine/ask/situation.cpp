#include "engine/ask/situation.hpp"

#include <algorithm>
#include <regex>
#include <utility>

#include <fmt/format.h>

#include "engine/ask/wordnet.hpp"
#include "model/category.hpp"
#include "model/error.hpp"

namespace smql::ask {

namespace {

// Words between a thing's name and what says where it is: "the door (that is) on my right".
bool isFiller(const std::string& w) {
    return isOneOf(w, {"is",     "are",     "that",  "which",    "located",   "placed",      "sitting", "standing",
                       "lying",  "hanging", "right", "directly", "just",      "immediately", "close",   "closely",
                       "also",   "being",   "was",   "were",     "somewhere", "slightly",    "a",       "bit",
                       "little", "far",     "all",   "the",      "way",       "both",        "some"});
}

// Words before a thing's name that belong to it: "a couple of", "two black", "some".
bool isLeading(const std::string& w) {
    return isOneOf(
        w, {"the",   "a",     "an",     "some",   "two",    "three",   "four",   "several", "few",  "couple", "my",
            "our",   "this",  "that",   "these",  "those",  "another", "other",  "one",     "its",  "their",  "big",
            "small", "large", "little", "long",   "wooden", "white",   "black",  "brown",   "grey", "gray",   "red",
            "blue",  "green", "yellow", "tall",   "short",  "round",   "square", "pair",    "set",  "bunch",  "row",
            "many",  "more",  "both",   "single", "open",   "closed",  "empty",  "huge",    "tiny"});
}

// A clock position as a side: 12 ahead, 3 right, 6 behind, 9 left (the nearest quarter).
std::optional<int> clockSide(const std::string& w) {
    static constexpr std::string_view names[] = {"twelve", "one",   "two",   "three", "four", "five",
                                                 "six",    "seven", "eight", "nine",  "ten",  "eleven"};
    int hour = -1;
    for (int k = 0; k < 12; ++k)
        if (w == names[k]) hour = k;
    if (hour < 0 && !w.empty() && w.size() <= 2 && std::all_of(w.begin(), w.end(), ::isdigit)) hour = std::stoi(w) % 12;
    if (hour < 0) return std::nullopt;
    return ((hour + 1) / 3) % 4;
}

}  // namespace

// "my 2 o'clock", "my six o'clock direction": the words taken and the side, from w[i] = "my".
std::optional<std::pair<int, std::size_t>> clockAt(const Words& w, std::size_t i) {
    if (i + 3 >= w.size() + 0 || w[i] != "my") return std::nullopt;
    if (i + 3 > w.size()) return std::nullopt;
    auto side = clockSide(w[i + 1]);
    if (!side) return std::nullopt;
    std::size_t k = i + 2;
    if (k < w.size() && w[k] == "o") ++k;
    if (k >= w.size() || (w[k] != "clock" && w[k] != "oclock")) return std::nullopt;
    ++k;
    if (k < w.size() && isOneOf(w[k], {"direction", "position", "side"})) ++k;
    return std::pair{*side, k - i};
}

namespace {

// The side a person's words give after position `i`: "on my left", "to the right", "behind me",
// "in front of me", "at my back", "ahead of me", "on my left side". The side and the words taken.
std::optional<std::pair<int, std::size_t>> sideAt(const Words& w, std::size_t i) {
    auto at = [&](std::size_t k) -> const std::string& {
        static const std::string none;
        return k < w.size() ? w[k] : none;
    };
    std::size_t k = i;
    while (k < w.size() && isFiller(w[k])) ++k;
    auto sideWord = [](const std::string& s) -> std::optional<int> {
        if (s == "left") return Left;
        if (s == "right") return Right;
        return std::nullopt;
    };
    // on my left (side), to my immediate right, on the left hand side, at my left
    if (isOneOf(at(k), {"on", "to", "at", "by"}) && isOneOf(at(k + 1), {"my", "the", "his", "her"})) {
        std::size_t j = k + 2;
        if (isOneOf(at(j), {"immediate", "direct", "near", "far", "own"})) ++j;
        if (auto s = sideWord(at(j))) {
            ++j;
            if (at(j) == "hand") ++j;
            if (at(j) == "side") ++j;
            if (at(j) == "of" && at(j + 1) == "me")
                j += 2;
            else if (at(j) == "of")
                return std::nullopt;  // "on the left of the tv": not mine
            return std::pair{*s, j - i};
        }
        if (isOneOf(at(j), {"back"})) return std::pair{int{Behind}, j + 1 - i};
        if (isOneOf(at(j), {"front"})) return std::pair{int{Ahead}, j + 1 - i};
    }
    // in my two o'clock direction
    if (isOneOf(at(k), {"on", "to", "at", "in", "by"}))
        if (auto clock = clockAt(w, k + 1)) return std::pair{clock->first, k + 1 + clock->second - i};
    // left of me, to the left of me
    if (at(k) == "to" && at(k + 1) == "the" && sideWord(at(k + 2)) && at(k + 3) == "of" && at(k + 4) == "me")
        return std::pair{*sideWord(at(k + 2)), k + 5 - i};
    if (isOneOf(at(k), {"behind", "beside"}) && isOneOf(at(k + 1), {"me", "myself"}))
        return at(k) == "behind" ? std::optional{std::pair{int{Behind}, k + 2 - i}} : std::nullopt;
    if (at(k) == "in" && at(k + 1) == "back" && at(k + 2) == "of" && at(k + 3) == "me")
        return std::pair{int{Behind}, k + 4 - i};
    if (at(k) == "in" && at(k + 1) == "front" && at(k + 2) == "of" && isOneOf(at(k + 3), {"me", "myself"}))
        return std::pair{int{Ahead}, k + 4 - i};
    if (at(k) == "ahead" && at(k + 1) == "of" && at(k + 2) == "me") return std::pair{int{Ahead}, k + 3 - i};
    if (at(k) == "before" && at(k + 1) == "me") return std::pair{int{Ahead}, k + 2 - i};
    return std::nullopt;
}

// The side said before a thing's name: "on my left is the door", "behind me are two chairs",
// "in front of me is a table"; `end` is where the name's leading words begin.
std::optional<int> sideBefore(const Words& w, std::size_t end) {
    std::size_t k = end;
    while (k > 0 && isOneOf(w[k - 1], {"is", "are", "there", "stands", "sits", "lies", "hangs"})) --k;
    for (std::size_t from = k >= 6 ? k - 6 : 0; from < k; ++from)
        if (auto s = sideAt(w, from); s && from + s->second == k) return s->first;
    return std::nullopt;
}

// What a thing's name is: a few words the lexicon finds among the scene's categories (as it is,
// a plural, a synonym, a kind or a broader word; never a guessed spelling).
std::optional<std::size_t> thingAt(const Words& w, std::size_t i, const Lexicon& lexicon) {
    static const std::initializer_list<std::string_view> notThings{
        "left", "right", "front",  "back", "side", "me",   "i",   "way",  "room",  "middle", "center",
        "end",  "top",   "corner", "edge", "part", "area", "one", "hand", "floor", "wall",   "walls"};
    for (std::size_t n = std::min<std::size_t>(3, w.size() - i); n >= 1; --n) {
        if (n == 1 && isOneOf(w[i], notThings)) return std::nullopt;
        WordMatch m = lexicon.lookUp(joined(w, i, i + n));
        if (!m.categories.empty() && m.how != WordMatch::How::Spelling) return n;
    }
    return std::nullopt;
}

struct Mention {
    std::size_t at = 0, words = 0;
    enum Role { Place, Faced, Beside } role = Place;
    int side = Ahead;        // Beside: where the thing is
    bool placeWord = false;  // Place: a preposition or verb of place before it ("on", "at", "using")
};

}  // namespace

std::optional<Situated> splitSituation(const std::string& text) {
    // Sentences end at . ! ? followed by a space (a decimal point is no end).
    std::vector<std::string> sentences;
    std::string current;
    for (std::size_t i = 0; i < text.size(); ++i) {
        current += text[i];
        char c = text[i];
        bool end = (c == '.' || c == '!' || c == '?') &&
                   (i + 1 == text.size() || std::isspace(static_cast<unsigned char>(text[i + 1])));
        if (c == '.' && i > 0 && std::isdigit(static_cast<unsigned char>(text[i - 1])) && i + 1 < text.size() &&
            std::isdigit(static_cast<unsigned char>(text[i + 1])))
            end = false;
        if (end) {
            sentences.push_back(current);
            current.clear();
        }
    }
    if (current.find_first_not_of(" \t\n") != std::string::npos) sentences.push_back(current);
    // One sentence whose opening clause sets the person somewhere: "if I sit on the sofa, what is in front of me?",
    // "standing at the stove, where is the table?". Only a clause of the person's own place (if, when, while or as
    // I ...; sitting, standing, lying or seated at a place; "I'm at the sofa, ..."): "measuring from the closest point
    // of each object, ..." is no situation, and "if I am standing by the stove and facing the sofa, is the tv to my
    // left?" is VSI-Bench's direction question, which its reader takes whole. A clause that faces something sets the
    // person so before a question of what or where ("if I sit on the sofa facing the tv, what is on my left?").
    static const std::regex placeClause(
        R"(^\s*((?:(?:if|when|while|as|once) i(?:'m| am)? [a-z]+(?: down)?|(?:sitting|standing|lying|seated|sat)(?: down)?|i(?:'m| am)(?: (?:sitting|standing|lying|seated))?(?: down)?) (?:on|at|by|in|near|next to|beside|in front of) [^,]+),\s*(\S.*)$)",
        std::regex::icase);
    static const std::regex faces(R"(\b(?:facing|and)\b)", std::regex::icase),
        whQuestion(R"(^(?:what|where|which|how|who)\b)", std::regex::icase);
    if (std::smatch m; sentences.size() == 1 && std::regex_match(sentences.front(), m, placeClause) &&
                       (!std::regex_search(m.str(1), faces) || std::regex_search(m.str(2), whQuestion)))
        sentences = {m.str(1) + ".", m.str(2)};
    if (sentences.size() < 2) return std::nullopt;
    std::string situation;
    for (std::size_t k = 0; k + 1 < sentences.size(); ++k) {
        if (sentences[k].find('?') != std::string::npos) return std::nullopt;  // the question came first
        situation += sentences[k];
    }
    static const std::regex person(R"((^|[^A-Za-z])(i|i'm|my|me|myself)([^A-Za-z]|$))", std::regex::icase);
    static const std::regex gerund(R"(^\s*[A-Za-z]+ing\b)");
    if (!std::regex_search(situation, person) && !std::regex_search(situation, gerund)) return std::nullopt;
    return Situated{situation, sentences.back()};
}

namespace {

// The scene's things a situation names, each with its role: where the person is, what they
// face, what is on one of their sides.
std::vector<Mention> mentionsIn(const Words& w, const Lexicon& lexicon) {
    std::vector<Mention> mentions;
    for (std::size_t i = 0; i < w.size();) {
        auto n = thingAt(w, i, lexicon);
        if (!n) {
            ++i;
            continue;
        }
        Mention m{i, *n};
        // Where the name's leading words begin ("a couple of toolboxes").
        std::size_t lead = i;
        while (lead > 0 && (isLeading(w[lead - 1]) ||
                            (w[lead - 1] == "of" && lead > 1 &&
                             isOneOf(w[lead - 2], {"couple", "pair", "set", "bunch", "row", "few", "lot", "pile"}))))
            --lead;
        const std::string before = lead > 0 ? w[lead - 1] : "";
        const std::string before2 = lead > 1 ? w[lead - 2] + " " + before : before;
        if (auto s = sideAt(w, i + *n)) {
            m.role = Mention::Beside;
            m.side = s->first;
        } else if (auto s = sideBefore(w, lead)) {
            m.role = Mention::Beside;
            m.side = *s;
        } else if (isOneOf(before, {"facing", "face", "faces", "watching", "watch", "towards", "toward"}) ||
                   isOneOf(before2, {"looking at", "look at", "staring at", "front of", "looking out", "out of"}) ||
                   before2 == "looking toward" || before2 == "looking towards") {
            m.role = Mention::Faced;
        } else {
            m.placeWord = isOneOf(before, {"on",   "at",    "by",    "near",    "beside",  "in",   "inside",
                                           "into", "using", "use",   "against", "next",    "to",   "from",
                                           "over", "onto",  "under", "behind",  "between", "with", "across"}) ||
                          (!before.empty() && before.size() > 3 && before.ends_with("ing"));
        }
        mentions.push_back(m);
        i += *n;
    }
    return mentions;
}

}  // namespace

std::optional<Pose> readPose(const std::string& situation, const Lexicon& lexicon, PhraseParser& parser) {
    Words w = words(situation);
    std::vector<Mention> mentions = mentionsIn(w, lexicon);
    if (mentions.empty()) {
        // "I am walking into the room": at the door, facing into the room.
        static const std::regex entering(
            R"(\b(?:walk|walking|walked|enter|entering|entered|come|coming|came|step|stepping|stepped|got|get|getting|just)\s+(?:in|into|inside)\b|\benter(?:ing|ed)?\s+(?:the|this)\s+room\b)");
        if (!std::regex_search(situation, entering) || !thingAt(Words{"door"}, 0, lexicon)) return std::nullopt;
        Words door{"door"};
        std::size_t k = 0;
        Pose pose;
        pose.at = parser.phrase(door, k, false);
        pose.words = "at the door, facing into the room";
        return pose;
    }
    auto phraseOf = [&](const Mention& m) -> std::optional<Phrase> {
        Words span(w.begin() + static_cast<std::ptrdiff_t>(m.at),
                   w.begin() + static_cast<std::ptrdiff_t>(m.at + m.words));
        std::size_t k = 0;
        try {
            Phrase p = parser.phrase(span, k, false);
            if (p.categories.empty() || k != span.size()) return std::nullopt;
            // The pose stands at a thing of the kind named: a shape's filter ("coffee table")
            // could leave none to stand at.
            p.filters.clear();
            p.conditions.clear();
            p.order.reset();
            p.side.clear();
            return p;
        } catch (const Error&) {
            return std::nullopt;
        }
    };
    std::optional<Phrase> place, faced, beside;
    int besideSide = Ahead;
    // The place: a thing after a word of place first, else any thing not faced or on a side.
    for (int pass = 0; pass < 2 && !place; ++pass)
        for (const auto& m : mentions)
            if (m.role == Mention::Place && (pass == 1 || m.placeWord))
                if ((place = phraseOf(m))) break;
    for (const auto& m : mentions)
        if (m.role == Mention::Faced && !faced)
            if (auto p = phraseOf(m); p && (!place || p->categories != place->categories)) faced = p;
    for (const auto& m : mentions)
        if (m.role == Mention::Beside && !beside)
            if (auto p = phraseOf(m); p && (!place || p->categories != place->categories)) {
                beside = p;
                besideSide = m.side;
            }
    // A thing ahead ("with a table in front of me") is a thing faced.
    if (!faced && beside && besideSide == Ahead) faced = std::exchange(beside, std::nullopt);
    Pose pose;
    auto say = [](const Phrase& p) { return "the " + p.words; };
    if (place && faced) {
        pose.at = *place;
        pose.facing = faced;
        pose.words = fmt::format("at {}, facing {}", say(*place), say(*faced));
    } else if (place && beside) {
        // Facing the thing on my side: the view's heading is that side of mine.
        pose.at = *place;
        pose.facing = beside;
        pose.turn = besideSide;
        static constexpr std::string_view sideWords[] = {"ahead", "on your right", "behind you", "on your left"};
        pose.words = fmt::format("at {}, with {} {}", say(*place), say(*beside),
                                 sideWords[static_cast<std::size_t>(besideSide)]);
    } else if (place) {
        // Facing into the room: the view from the place faces the middle of the scene.
        pose.at = *place;
        pose.words = fmt::format("at {}, facing the middle of the room", say(*place));
    } else if (faced && beside) {
        // Beside a thing, facing another: stand by the thing beside.
        pose.at = *beside;
        pose.facing = faced;
        pose.words = fmt::format("by {}, facing {}", say(*beside), say(*faced));
    } else if (faced) {
        // Facing a thing from the room: the view from the thing faces the middle, the person the
        // other way.
        pose.at = *faced;
        pose.turn = Behind;
        pose.words = fmt::format("in front of {}, facing it", say(*faced));
    } else if (beside) {
        // By a thing on one side: the middle of the room lies the other way.
        pose.at = *beside;
        pose.turn = (besideSide + 2) % 4;
        static constexpr std::string_view sideWords[] = {"ahead", "on your right", "behind you", "on your left"};
        pose.words = fmt::format("by {}, {}", say(*beside), sideWords[static_cast<std::size_t>(besideSide)]);
    } else {
        return std::nullopt;
    }
    return pose;
}

std::string viewClause(const Pose& pose) {
    return pose.facing ? fmt::format("VIEW FROM {} FACING {}", reference(pose.at), reference(*pose.facing))
                       : fmt::format("VIEW FROM {}", reference(pose.at));
}

std::string withView(const std::string& smql, const std::string& view) {
    std::string out;
    bool quoted = false;
    auto startsWord = [&](std::size_t i, std::string_view word) {
        return smql.compare(i, word.size(), word) == 0 && (i == 0 || smql[i - 1] == ' ' || smql[i - 1] == '(');
    };
    for (std::size_t i = 0; i < smql.size();) {
        if (!quoted && (startsWord(i, "FIND ") || startsWord(i, "COUNT "))) {
            std::size_t k = smql.find(' ', i) + 1;
            // The target: a name, or a quoted one ('' inside it is a quote).
            if (k < smql.size() && smql[k] == '\'') {
                ++k;
                while (k < smql.size() && !(smql[k] == '\'' && (k + 1 >= smql.size() || smql[k + 1] != '\'')))
                    k += smql[k] == '\'' ? 2 : 1;
                k = std::min(k + 1, smql.size());
            } else {
                while (k < smql.size() && smql[k] != ' ' && smql[k] != ')') ++k;
            }
            out += smql.substr(i, k - i) + " " + view;
            i = k;
            continue;
        }
        if (smql[i] == '\'') quoted = !quoted;
        out += smql[i++];
    }
    if (smql.starts_with("RELATE ")) out += " " + view;
    return out;
}

std::string takeTurn(const std::string& question, Pose& pose) {
    static const std::regex before(
        R"(^\s*(?:(?:if|when|after|once|suppose)\s+(?:i|you)\s+)?(?:turn|turned|rotate|rotated|spin|spun|turning)\s+(?:myself\s+|directly\s+|completely\s+|fully\s+|all\s+the\s+way\s+)?(around|back|backward|backwards|left|right|to\s+the\s+left|to\s+the\s+right|to\s+my\s+left|to\s+my\s+right|180\s+degrees)\b(?:\s+and\s+[^,]*)?,?\s*(?:then\s+)?)",
        std::regex::icase);
    static const std::regex after(
        R"(\s*,?\s*(?:if|when|after|once)\s+(?:i|you)\s+(?:turn|turned|rotate|rotated|turning)\s+(?:myself\s+|directly\s+|completely\s+)?(around|back|left|right|to\s+the\s+left|to\s+the\s+right|to\s+my\s+left|to\s+my\s+right|180\s+degrees)\s*(\??)\s*$)",
        std::regex::icase);
    std::smatch m;
    std::string rest = question, how;
    if (std::regex_search(question, m, before)) {
        how = m.str(1);
        rest = m.suffix().str();
    } else if (std::regex_search(question, m, after)) {
        how = m.str(1);
        rest = m.prefix().str() + "?";
    } else {
        return question;
    }
    std::transform(how.begin(), how.end(), how.begin(), [](unsigned char c) { return std::tolower(c); });
    // The person's heading turns; the view stays: the turn between them changes the other way.
    int by = how.find("left") != std::string::npos ? Left : how.find("right") != std::string::npos ? Right : Behind;
    pose.turn = ((pose.turn - by) % 4 + 4) % 4;
    pose.words += fmt::format(", turned {}", by == Behind ? "around" : by == Left ? "left" : "right");
    return rest;
}

std::optional<Translation> situatedDirection(const std::string& question, const Pose& pose, const Lexicon& lexicon,
                                             PhraseParser& parser, Translation& out) {
    Words w = words(question);
    const std::string text = joined(w, 0, w.size());
    // Which way: "which direction should I go to ...", "which way do I turn to ...", "where should I
    // turn to ...", "should I turn left or right to ...", "is the door on my left or right?",
    // "in which direction is the sink?".
    static const std::regex lead(
        R"(\b(?:in )?(?:which|what) (?:direction|way|side|directions)s?\b(?: (?:should|do|would|can|could|must|will|shall|am|is|are|does) (?:i|we|you))?(?: (?:need to|have to|want to|got to))?(?: (?:turn|go|walk|head|look|face|move|travel|proceed|take|be|turning|going|walking|looking|facing|to go|to turn|to walk|to toss|to look))?|\bwhere (?:should|do|would|can|could|must|will) (?:i|we) (?:need to |have to )?(?:turn|go|walk|head|look|face|move)\b|\bhow (?:do|should|would|can|must) (?:i|we) (?:have to |need to )?(?:turn|move|go|walk|get)\b|\b(?:should|do|would|must|can) (?:i|we) (?:need to |have to )?(?:turn|go|walk|head|look|move) (?:to (?:the|my) )?(?:left|right|back|forward|straight)(?: or (?:to (?:the|my) )?(?:left|right|back|forward|straight|backward|behind))+\b)");
    static const std::regex sideChoice(
        R"(^(?:is|are) (.+?) (?:on|to|at) (?:my|the) (?:left|right|front|back)(?: side)?,? (?:or )?(?:on |to |at )?(?:my |the )?(?:left|right|front|back|behind me|behind)(?: side)?(?:,? or (?:on |to |at )?(?:my |the )?(?:left|right|front|back|behind me|behind))?(?: side)?(?: of me)?$)");
    std::smatch m;
    std::string rest;
    std::vector<std::string> choices;
    if (std::regex_match(text, m, sideChoice)) {
        rest = m.str(1);
        for (const char* s : {"left", "right", "back", "front"})
            if (text.find(s, static_cast<std::size_t>(m.position(1) + m.length(1))) != std::string::npos)
                choices.emplace_back(s);
        if (text.find("behind") != std::string::npos) choices.emplace_back("back");
    } else if (std::regex_search(text, m, lead)) {
        // The thing may be named before the lead ("if I want to leave the room, which way should I go?").
        rest = m.suffix().str() + " " + m.prefix().str();
        choices = {"left", "right", "front", "back"};
        if (std::regex_search(text, std::regex(R"(\bleft or right\b|\bright or left\b)")) &&
            text.find("back") == std::string::npos && text.find("behind") == std::string::npos)
            choices = {"left", "right"};
    } else {
        return std::nullopt;
    }
    // The thing to reach: the first thing named in the rest; else what the verb affords ("to exit"
    // is a door, "to sleep" a bed).
    Words r = words(rest);
    std::optional<Phrase> asked;
    for (std::size_t i = 0; i < r.size() && !asked; ++i) {
        if (isOneOf(r[i], {"me",        "i",         "my",       "way",    "room",  "left",      "right",   "side",
                           "direction", "hands",     "hand",     "want",   "need",  "if",        "should",  "go",
                           "turn",      "front",     "back",     "place",  "thing", "something", "it",      "fire",
                           "time",      "order",     "someone",  "people", "head",  "face",      "walk",    "exit",
                           "use",       "something", "anything", "away",   "trash", "garbage",   "rubbish", "open",
                           "close",     "take",      "get",      "see",    "find",  "reach",     "grab",    "put",
                           "wash",      "leave",     "sit",      "watch",  "look",  "drop",      "pick",    "check",
                           "clean",     "switch",    "plug",     "charge", "store", "hang"}))
            continue;
        WordMatch m1 = lexicon.lookUp(r[i]);
        bool known = !m1.categories.empty() && m1.how != WordMatch::How::Spelling;
        bool absent = m1.how == WordMatch::How::Absent && absentThing(r[i], m1).has_value();
        if (!known && !absent) continue;
        std::size_t k = i;
        try {
            Phrase p = parser.phrase(r, k, false);
            asked = p;
        } catch (const Error&) {
        }
    }
    if (!asked) {
        static const std::pair<std::string_view, std::string_view> verbs[] = {
            {"exit", "door"},        {"leave", "door"},          {"enter", "door"},     {"sleep", "bed"},
            {"nap", "bed"},          {"wash", "sink"},           {"sit", "chair"},      {"cook", "stove"},
            {"shower", "shower"},    {"bathe", "bathtub"},       {"pee", "toilet"},     {"throw", "wastebasket"},
            {"toss", "wastebasket"}, {"discard", "wastebasket"}, {"urinate", "toilet"}, {"work", "desk"},
            {"watch", "tv"},
        };
        for (std::size_t i = 0; i < r.size() && !asked; ++i)
            for (const auto& [verb, thing] : verbs) {
                bool match = r[i] == verb;
                for (const auto& base : wordnet::baseForms(r[i])) match = match || base == verb;
                if (!match) continue;
                Words tw{std::string(thing)};
                std::size_t k = 0;
                try {
                    asked = parser.phrase(tw, k, false);
                } catch (const Error&) {
                }
                if (asked) break;
            }
    }
    if (!asked) return std::nullopt;
    auto names = [](const Phrase& p) {
        return p.categories.empty() ? std::vector<std::string>{model::categoryName(p.noun)} : p.categories;
    };
    out.kind = QuestionKind::Direction;
    out.roles = {names(pose.at), pose.facing ? names(*pose.facing) : std::vector<std::string>{}, names(*asked)};
    out.turn = pose.turn;
    out.choices = choices;
    // The thing as asked ("arm chair"), and its plural for an answer about each ("arm chairs"), also when asked in
    // the plural ("where are the lamps?": its noun is "lamp").
    const std::string noun = model::categoryWords(asked->noun);
    const std::string& said = asked->words;
    const std::size_t lastWord = said.rfind(' ');
    const std::string before = said.ends_with(noun)            ? said.substr(0, said.size() - noun.size())
                               : lastWord == std::string::npos ? std::string()
                                                               : said.substr(0, lastWord + 1);
    out.subject = said.ends_with(noun) ? said : before + noun;
    out.subjectPlural = before + pluralOf(noun);
    out.object = pose.words;
    if (pose.facing) {
        std::vector<std::string> all;
        for (const auto& role : out.roles)
            for (const auto& n : role)
                if (std::find(all.begin(), all.end(), n) == all.end()) all.push_back(n);
        std::string any;
        for (const auto& n : all) any += (any.empty() ? "" : " OR ") + fmt::format("category = {}", smqlString(n));
        out.smql = fmt::format("FIND thing WHERE {} RETURN id, category, box", all.size() > 1 ? "(" + any + ")" : any);
    } else {
        // Facing the middle of the scene: every thing's box, whose mean centre is the middle.
        out.smql = "FIND thing RETURN id, category, box";
    }
    return out;
}

}  // namespace smql::ask
