#include "engine/ask/phrase.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <regex>
#include <sstream>

#include <fmt/format.h>

#include "engine/ask/units.hpp"
#include "engine/ask/wordnet.hpp"
#include "model/category.hpp"
#include "model/error.hpp"
#include "model/names.hpp"
#include "relations/predicates.hpp"

namespace smql::ask {

namespace {

constexpr std::size_t kMaxNounWords = 4;
// m: "near me", with no thing a situation put the person at, is within this of where they stand: near.distance's
// default, the largest gap near allows between two things (docs/relations.md).
constexpr double kNearYou = 1.0;

bool isDeterminer(const std::string& w) {
    return isOneOf(w, {"the",   "a",     "an",    "any",  "some", "all", "my",    "our", "your", "this",    "that",
                       "these", "those", "every", "each", "of",   "its", "their", "his", "her",  "another", "both"});
}

bool isSideWord(const std::string& w) { return isOneOf(w, {"left", "right", "front", "back"}); }

// A word that counts or sorts the things named after "of": "pieces of furniture", "a pair of shoes", "kinds of things".
bool isMeasureWord(const std::string& w) {
    return isOneOf(w, {"piece", "pieces", "pair", "pairs", "set", "sets", "kind", "kinds", "type", "types", "sort",
                       "sorts", "bunch", "stack", "pile", "group", "groups", "cluster"});
}
// "kinds of things" asks for their kinds ("different kinds" too: an adjective before one asks nothing of its own).
bool isKindWord(const std::string& w) { return isOneOf(w, {"kind", "kinds", "type", "types", "sort", "sorts"}); }

// Adjectives the memory has no attribute for: left out of the query, and said so.
bool isIgnoredAdjective(const std::string& w) {
    return isOneOf(w, {"big",   "small",  "large", "little", "tall", "short", "long", "old",  "new",   "wooden",
                       "round", "square", "other", "single", "only", "nice",  "tiny", "huge", "whole", "same"});
}

// Words after a noun phrase that end it without being part of a post.
bool endsPhrase(const std::string& w) {
    return isOneOf(w,
                   {"is",        "are",     "was",        "were",       "and",       "or",      "that",     "which",
                    "who",       "there",   "located",    "placed",     "sitting",   "lying",   "standing", "resting",
                    "kept",      "do",      "does",       "can",        "could",     "you",     "i",        "we",
                    "see",       "have",    "has",        "relative",   "compared",  "with",    "from",     "to",
                    "currently", "right",   "now",        "altogether", "total",     "exactly", "than",     "if",
                    "when",      "as",      "while",      "away",       "measured",  "in",      "hanging",  "hung",
                    "attached",  "mounted", "positioned", "situated",   "installed", "stored",  "supported"});
}

// Words for "anything" and kinds of node.
std::optional<std::string> kindTarget(const std::string& w) {
    if (isOneOf(w, {"object", "objects", "thing", "things", "one", "ones", "anything", "everything", "something",
                    "stuff", "item", "items", "furnishing", "furnishings"}))
        return "object";
    if (isOneOf(w, {"anchor", "anchors"})) return "anchor";
    return std::nullopt;
}

// Parts of a thing: "the corner of the room", "the top of the stove", "the foot of the bed", "the lid
// of the bin". The memory keeps boxes, not parts: "what is on the back of the chair?" is about the chair.
bool isPartWord(const std::string& w) {
    return isOneOf(w, {"corner",   "top",      "bottom", "side",    "end",     "middle",  "center",   "centre",
                       "edge",     "part",     "area",   "back",    "front",   "foot",    "head",     "surface",
                       "rest",     "lid",      "seat",   "portion", "half",    "outside", "inside",   "exterior",
                       "interior", "backside", "frame",  "handle",  "handles", "legs",    "leg",      "base",
                       "opening",  "backrest", "sides",  "corners", "ends",    "edges",   "surfaces", "section"});
}

// Parts that are things of their own elsewhere: "the door of the refrigerator", "a drawer of the
// dresser" (but "the door of the room" is a door).
bool isPartOfThing(const std::string& w) {
    return isOneOf(
        w, {"door", "doors", "drawer", "drawers", "shelf", "shelves", "panel", "panels", "knob", "knobs", "floor"});
}

// Words that place a part on a thing: "the upper portion of", "the bottom left corner of", "the far end of".
bool isPartPlaceWord(const std::string& w) {
    return isSideWord(w) || isOneOf(w, {"upper", "lower", "top", "bottom", "far", "near", "outer", "inner", "middle",
                                        "center", "immediate", "very", "hand", "rear"});
}

// Kinds of room: "in the office" is the scene when the scene is one (PhraseParser::scenePlaceAt).
constexpr std::string_view kRoomKinds[] = {
    "office",      "bedroom",         "kitchen",      "bathroom",    "living room",  "dining room",  "lounge",
    "study",       "hallway",         "hall",         "den",         "nursery",      "guest room",   "laundry room",
    "classroom",   "conference room", "workshop",     "restroom",    "lobby",        "studio",       "playroom",
    "family room", "kids room",       "meeting room", "toilet room", "utility room", "storage room", "entryway",
    "corridor",    "basement",        "attic",        "garage",
};

// Superlatives and comparatives and the measure they order by: "the largest table" is FIND table
// ORDER BY volume DESC LIMIT 1; "is the sofa larger than the bed?" compares their volumes. A measure
// "distance" orders by the distance to a thing that follows ("closest to the door").
struct Superlative {
    std::string_view word;
    std::string_view comparative;  // empty: none ("topmost")
    std::string_view measure;
    bool descending;
    std::string_view adjective;  // how the answer says the measure: "2.1 m long"
};
constexpr std::array<Superlative, 18> kSuperlatives{{
    {"largest", "larger", "volume", true, "in volume"},
    {"biggest", "bigger", "volume", true, "in volume"},
    {"smallest", "smaller", "volume", false, "in volume"},
    {"tiniest", "tinier", "volume", false, "in volume"},
    {"littlest", "littler", "volume", false, "in volume"},
    {"tallest", "taller", "height", true, "tall"},
    {"shortest", "shorter", "height", false, "tall"},
    {"highest", "higher", "z", true, "high"},
    {"topmost", "", "z", true, "high"},
    {"lowest", "lower", "z", false, "high"},
    {"longest", "longer", "width", true, "long"},
    {"widest", "wider", "width", true, "wide"},
    {"narrowest", "narrower", "width", false, "wide"},
    {"thinnest", "thinner", "width", false, "wide"},
    {"closest", "closer", "distance", false, "away"},
    {"nearest", "nearer", "distance", false, "away"},
    {"farthest", "farther", "distance", true, "away"},
    {"furthest", "further", "distance", true, "away"},
}};

const Superlative* superlativeOf(const std::string& w) {
    for (const auto& s : kSuperlatives)
        if (s.word == w && s.measure != "distance") return &s;
    return nullptr;
}

// "closest to", "nearest", "farthest from": an order by distance to a phrase that follows.
std::optional<bool> distanceOrderWord(const std::string& w) {
    for (const auto& s : kSuperlatives)
        if (s.word == w && s.measure == "distance") return s.descending;
    return std::nullopt;
}

std::optional<std::size_t> ordinalOf(const std::string& w) {
    static const std::array<std::string_view, 10> words{"first", "second",  "third",  "fourth", "fifth",
                                                        "sixth", "seventh", "eighth", "ninth",  "tenth"};
    static const std::array<std::string_view, 10> short_{"1st", "2nd", "3rd", "4th", "5th",
                                                         "6th", "7th", "8th", "9th", "10th"};
    for (std::size_t k = 0; k < words.size(); ++k)
        if (w == words[k] || w == short_[k]) return k + 1;
    return std::nullopt;
}

std::optional<std::size_t> cardinalOf(const std::string& w) {
    static const std::array<std::string_view, 10> words{"one", "two",   "three", "four", "five",
                                                        "six", "seven", "eight", "nine", "ten"};
    for (std::size_t k = 0; k < words.size(); ++k)
        if (w == words[k]) return k + 1;
    if (w.size() <= 2 &&
        std::all_of(w.begin(), w.end(), [](char ch) { return std::isdigit(static_cast<unsigned char>(ch)); }))
        return static_cast<std::size_t>(std::stoi(w));
    return std::nullopt;
}

// "besides", "other than", "except (for)", "apart from": the words it takes, 0 when none.
std::size_t exclusionAt(const Words& w, std::size_t i) {
    if (i >= w.size()) return 0;
    if (isOneOf(w[i], {"besides", "excluding"})) return 1;
    if (i + 1 < w.size() && ((w[i] == "other" && w[i + 1] == "than") || (w[i] == "apart" && w[i + 1] == "from") ||
                             (w[i] == "aside" && w[i + 1] == "from") || (w[i] == "except" && w[i + 1] == "for") ||
                             (w[i] == "but" && w[i + 1] == "not") || (w[i] == "save" && w[i + 1] == "for")))
        return 2;
    if (i + 1 < w.size() && w[i] == "not" && isOneOf(w[i + 1], {"counting", "including"})) return 2;
    return w[i] == "except" ? 1 : 0;
}

// Kinds told apart by their shape: a phrase whose words name a category by a shape the memory keeps
// ("coffee table": a low table). Each is the category and a condition on the box.
struct ShapedKind {
    std::string_view words;
    std::string_view category;
    std::string_view condition;  // SMQL
    std::string_view meaning;    // for the answer's Words line
};
constexpr std::array<ShapedKind, 7> kShapedKinds{{
    {"coffee table", "table", "height < 0.55 m", "a low table"},
    {"cocktail table", "table", "height < 0.55 m", "a low table"},
    {"side table", "table", "width < 0.8 m", "a small table"},
    {"end table", "table", "width < 0.8 m", "a small table"},
    {"bedside table", "table", "width < 0.8 m", "a small table"},
    {"dining table", "table", "height >= 0.6 m AND width >= 0.9 m", "a table to eat at"},
    {"kitchen table", "table", "height >= 0.6 m AND width >= 0.9 m", "a table to eat at"},
}};

// A node named by its id as SMQL writes one: `#50`, `sofa#50` (a category and an id), `src#93` (the
// id it had in its file). The category part is folded as a stored category is.
std::optional<std::string> idReference(const std::string& word) {
    static const std::regex id(R"(^(src#|([a-z_][a-z0-9_-]*)?#)([0-9]+)$)");
    std::smatch m;
    if (!std::regex_match(word, m, id)) return std::nullopt;
    if (m.str(1) == "src#" || m.str(2).empty()) return word;
    return model::categoryName(m.str(2)) + "#" + m.str(3);
}

// "the wall on the left", "the window on the right side", "the lamp on the left hand side": the
// side, with `i` past its words; empty (and `i` as it was) when none follows.
std::string sideAfter(const Words& w, std::size_t& i) {
    if (i + 2 >= w.size() || w[i] != "on" || w[i + 1] != "the" || !isSideWord(w[i + 2])) return {};
    std::size_t k = i + 3;
    if (k + 1 < w.size() && w[k] == "hand" && w[k + 1] == "side")
        k += 2;
    else if (k < w.size() && w[k] == "side")
        k += 1;
    if (k < w.size() && w[k] == "of") return {};
    std::string side = w[i + 2];
    i = k;
    return side;
}

struct PredicatePhrase {
    Words words;
    std::string predicate;
};

// Every predicate's English phrases (the predicate table's), longest first at each start, so "on
// the left of" wins over "on".
const std::vector<PredicatePhrase>& predicatePhrases() {
    static const std::vector<PredicatePhrase> table = [] {
        std::vector<PredicatePhrase> t;
        for (const auto& spec : relations::predicates())
            for (std::string_view phrase : relations::englishPhrases(spec)) {
                PredicatePhrase row;
                row.predicate = std::string(spec.name());
                std::istringstream in{std::string(phrase)};
                for (std::string w; in >> w;) row.words.push_back(w);
                t.push_back(std::move(row));
            }
        std::stable_sort(t.begin(), t.end(),
                         [](const auto& a, const auto& b) { return a.words.size() > b.words.size(); });
        return t;
    }();
    return table;
}

std::string conditionText(const Condition& c) {
    // In a kind of room's area: the things that mark it, and what lies within its reach of them.
    if (c.predicate == "within" && c.args.size() == 1 && c.metres) {
        std::string marks;
        for (const auto& category : c.args.front().categories)
            marks += fmt::format("category = {} OR ", smqlString(category));
        return fmt::format("{}({}distance({}) < {} m)", c.negated ? "NOT " : "", marks, reference(c.args.front()),
                           smqlMetres(*c.metres));
    }
    // Near the person: within a distance of where the viewer stands.
    if (c.predicate == "near" && c.args.size() == 1 && c.args.front().here)
        return fmt::format("{}distance(HERE) < {} m", c.negated ? "NOT " : "", smqlMetres(c.metres.value_or(kNearYou)));
    std::string args;
    for (const auto& a : c.args) args += (args.empty() ? "" : ", ") + reference(a);
    if (c.metres) args += ", " + smqlMetres(*c.metres) + " m";
    return fmt::format("{}{}({})", c.negated ? "NOT " : "", c.predicate, args);
}

std::string targetOf(const Phrase& p) {
    if (!p.id.empty()) return p.id;
    if (p.kind) return *p.kind;
    if (!p.side.empty()) return smqlName(p.categories.front()) + "." + p.side;
    if (p.categories.size() == 1) return smqlName(p.categories.front());
    return "thing";
}

std::vector<std::string> conditionsOf(const Phrase& p) {
    std::vector<std::string> where;
    if (p.id.empty() && !p.kind && p.side.empty() && p.categories.size() != 1) {
        // Several categories, or none (an English noun the scene lacks: the answer is "none").
        const std::vector<std::string> names =
            p.categories.empty() ? std::vector<std::string>{hyphenated(p.noun)} : p.categories;
        std::string any;
        for (const auto& c : names) any += (any.empty() ? "" : " OR ") + fmt::format("category = {}", smqlString(c));
        where.push_back(names.size() > 1 ? "(" + any + ")" : any);
    }
    for (const auto& e : p.excluded) {
        // "besides the coffee table": not that kind of thing, with its own conditions.
        std::vector<std::string> what = conditionsOf(e);
        if (!e.kind && e.side.empty() && e.categories.size() == 1)
            what.insert(what.begin(), fmt::format("category = {}", smqlString(e.categories.front())));
        if (what.empty()) continue;
        std::string all;
        for (const auto& w : what) all += (all.empty() ? "" : " AND ") + w;
        where.push_back(what.size() == 1 ? "NOT " + all : "NOT (" + all + ")");
    }
    if (p.colour) where.push_back(fmt::format("color = {}", smqlString(*p.colour)));
    where.insert(where.end(), p.filters.begin(), p.filters.end());
    // A condition said twice ("near the sofa but not on it", where "near" leaves out what is on it) is one.
    for (const auto& c : p.conditions)
        if (std::string text = conditionText(c); std::find(where.begin(), where.end(), text) == where.end())
            where.push_back(std::move(text));
    return where;
}

std::string orderText(const Phrase& p) {
    if (!p.order) return {};
    std::string measure =
        p.order->measure == "distance" ? "distance(" + reference(p.order->to.front()) + ")" : p.order->measure;
    return fmt::format(" ORDER BY {}{}", measure, p.order->descending ? " DESC" : "");
}

}  // namespace

std::optional<Comparative> comparativeOf(const std::string& word) {
    for (const auto& s : kSuperlatives)
        if (!s.comparative.empty() && s.comparative == word)
            return Comparative{std::string(s.measure), s.descending, std::string(s.word), std::string(s.adjective)};
    return std::nullopt;
}

bool isOneOf(const std::string& word, std::initializer_list<std::string_view> words) {
    return std::find(words.begin(), words.end(), word) != words.end();
}

bool isVerbOfPlace(const std::string& w) {
    return !isOneOf(w, {"is", "are", "was", "were", "be", "been", "being", "not", "do", "does", "have", "has"}) &&
           wordnet::isVerbNotNoun(w);
}

std::optional<std::string> colourOf(const std::string& word) {
    if (word == "grey") return "gray";
    if (isOneOf(word, {"red", "green", "blue", "white", "black", "gray", "brown", "yellow", "orange", "pink", "purple",
                       "beige", "silver", "gold", "golden"}))
        return word;
    return std::nullopt;
}

Words words(const std::string& text) {
    // "chair(s)", "tv(s)", "box(es)": the benchmark's way of asking for a plural.
    static const std::regex pluralAsked(R"(\((e?s)\))"), apostrophe("\xE2\x80\x99");  // the typographic one
    std::string plain = std::regex_replace(text, pluralAsked, "$1");
    plain = std::regex_replace(plain, apostrophe, "'");
    std::string s;
    for (std::size_t i = 0; i < plain.size(); ++i) {
        unsigned char c = static_cast<unsigned char>(plain[i]);
        if (std::isalnum(c))
            s += static_cast<char>(std::tolower(c));
        else if (c == '\'' || c == '-')
            s += static_cast<char>(c);
        else if (c == '#' && i + 1 < plain.size() && std::isdigit(static_cast<unsigned char>(plain[i + 1])))
            s += '#';  // a node's id: "sofa#50", "#50", "src#93"
        else if (c == '.' && i + 1 < plain.size() && std::isdigit(static_cast<unsigned char>(plain[i + 1])) &&
                 !s.empty() && std::isdigit(static_cast<unsigned char>(s.back())))
            s += '.';
        else if (c >= 0x80)
            s += static_cast<char>(c);  // letters outside ASCII stay, to be named as unknown
        else
            s += ' ';
    }
    static const std::array<std::pair<std::string_view, std::string_view>, 12> contractions{{
        {"can't", "can not"},
        {"'s", " is"},
        {"'re", " are"},
        {"n't", " not"},
        {"'m", " am"},
        {"'ll", " will"},
        {"'ve", " have"},
        {"'d", " would"},
        {"'", " "},
        {"--", " "},
        {"infront", "in front"},  // a common way to write it
        {"oclock", "o clock"},    // "my 8 oclock", as "my 8 o'clock"
    }};
    for (const auto& [from, to] : contractions)
        for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
            s.replace(at, from.size(), to);
    // Contractions typed without their apostrophe, as chat writes them ("whats on the table",
    // "wheres the lamp"); not "its", "ill" or "were", which are words of their own. And chat's letters for
    // words ("how many chairs r there", "can u see a lamp"), which name no thing; the question's own small words as
    // they are often mistyped ("is ther a vase", "wat is on the desk"), which the spelling of things does not mend.
    static const std::array<std::pair<std::string_view, std::string_view>, 27> bare{{
        {"r", "are"},           {"u", "you"},        {"whats", "what is"}, {"wheres", "where is"},
        {"hows", "how is"},     {"whos", "who is"},  {"thats", "that is"}, {"theres", "there is"},
        {"heres", "here is"},   {"isnt", "is not"},  {"arent", "are not"}, {"dont", "do not"},
        {"doesnt", "does not"}, {"cant", "can not"}, {"wont", "will not"}, {"im", "i am"},
        {"ive", "i have"},      {"ther", "there"},   {"wher", "where"},    {"whre", "where"},
        {"wat", "what"},        {"wht", "what"},     {"waht", "what"},     {"whcih", "which"},
        {"teh", "the"},         {"hte", "the"},      {"hw", "how"},
    }};
    Words out;
    std::istringstream in(s);
    for (std::string w; in >> w;) {
        while (!w.empty() && w.front() == '-') w.erase(w.begin());
        while (!w.empty() && w.back() == '-') w.pop_back();
        if (w.empty()) continue;
        const auto* expansion = std::find_if(bare.begin(), bare.end(), [&](const auto& row) { return row.first == w; });
        if (expansion == bare.end()) {
            out.push_back(w);
            continue;
        }
        std::istringstream parts{std::string(expansion->second)};
        for (std::string part; parts >> part;) out.push_back(part);
    }
    return out;
}

std::string joined(const Words& w, std::size_t from, std::size_t to) {
    std::string out;
    for (std::size_t i = from; i < to && i < w.size(); ++i) out += (out.empty() ? "" : " ") + w[i];
    return out;
}

namespace {

// A length written at w[k] and its unit at w[k + 1] ("1.5 m", "30 cm", "one metre"), in metres.
std::optional<double> lengthAt(const Words& w, std::size_t k) {
    static const std::regex number("[0-9]+(\\.[0-9]+)?");
    if (k + 1 >= w.size() || !lengthUnitNamed(w[k + 1])) return std::nullopt;
    const std::optional<double> value = std::regex_match(w[k], number) ? std::optional<double>(std::stod(w[k]))
                                        : cardinalOf(w[k])             ? std::optional<double>(*cardinalOf(w[k]))
                                                                       : std::nullopt;
    if (!value) return std::nullopt;
    return *value * lengthUnitNamed(w[k + 1])->metres;
}

}  // namespace

std::optional<std::pair<std::string, std::size_t>> PhraseParser::predicateAt(const Words& w, std::size_t i) {
    // within 1.5 m of x / within 30 cm of x
    if (i + 3 < w.size() && w[i] == "within" && lengthAt(w, i + 1) && w[i + 3] == "of")
        return std::pair{std::string("near"), std::size_t{4}};
    for (const auto& row : predicatePhrases()) {
        if (i + row.words.size() > w.size()) continue;
        bool match = true;
        for (std::size_t k = 0; k < row.words.size() && match; ++k) match = w[i + k] == row.words[k];
        if (match) return std::pair{row.predicate, row.words.size()};
    }
    return std::nullopt;
}

void PhraseParser::shortenNoun(std::vector<std::string>& nounWords, const Words& w, std::size_t start) {
    // A name of a thing is a few words ("kitchen cabinet door"); more is a sentence read wrongly,
    // unless a few more describe it ("the large larder style stainless steel fridge freezer": its
    // last words name it).
    if (nounWords.size() > 2 * kMaxNounWords) throw notUnderstood(w, start);
    if (nounWords.size() <= kMaxNounWords) return;
    const auto cut = nounWords.begin() + static_cast<std::ptrdiff_t>(nounWords.size() - kMaxNounWords);
    out_.notes.push_back(fmt::format("'{}' is left out", joined(Words(nounWords.begin(), cut), 0, nounWords.size())));
    nounWords.erase(nounWords.begin(), cut);
}

bool PhraseParser::selfPhrase(const Words& w, std::size_t& i, bool withPosts, Phrase& p) {
    if (i >= w.size() || !isOneOf(w[i], {"me", "myself", "us"})) return false;
    if (!self_) {
        if (w[i] == "us") return false;
        throw Error(ErrorKind::Binding, fmt::format("'{}' needs where you are", w[i]), std::nullopt,
                    "say it first, as in: I am sitting on the bed facing the window. What is on my left?");
    }
    // "near me", "left of me": the thing the person stands at.
    p = self_->at;
    p.self = true;
    ++i;
    if (withPosts) posts(w, i, p);
    p.words = "you";
    return true;
}

bool PhraseParser::idPhrase(const Words& w, std::size_t& i, bool withPosts, Phrase& p) {
    if (i >= w.size()) return false;
    auto id = idReference(w[i]);
    if (!id) return false;
    // "sofa#50", "#50", "src#93": the node of that id (the binder checks its category).
    p.id = *id;
    p.noun = id->substr(0, id->find('#'));
    if (p.noun.empty() || p.noun == "src") p.noun = "thing";
    ++i;
    if (withPosts) posts(w, i, p);
    return true;
}

bool PhraseParser::describing(const Words& w, std::size_t& i, std::vector<std::string>& nounWords, std::string& side,
                              std::size_t wordsStart) {
    const std::string& word = w[i];
    // "the hanging towel", "the standing lamp": before the noun, a verb of place describes it
    // (the memory keeps no such state); after it, it ends the phrase ("the towel hanging on ...").
    if (nounWords.empty() && word.ends_with("ing") && endsPhrase(word) && i + 1 < w.size() && !predicateAt(w, i + 1) &&
        !endsPhrase(w[i + 1])) {
        out_.notes.push_back(fmt::format("'{}' is left out: the memory keeps no such state", word));
        return true;
    }
    // "dark green", "light brown": the memory keeps the colour, not its shade.
    if (nounWords.empty() && isOneOf(word, {"dark", "light", "bright", "pale", "deep", "olive"}) && i + 1 < w.size() &&
        colourOf(w[i + 1]))
        return true;
    if (word != "of") return false;
    // "the left wall of the room", "the wall of the house": of the scene, which it is in anyway.
    if (!nounWords.empty() && !isPartWord(nounWords.back()) && i + 1 < w.size()) {
        std::size_t k = i + 1;
        while (k < w.size() && isDeterminer(w[k])) ++k;
        if (std::size_t place = scenePlaceAt(w, k); place > 0) {
            i = k + place - 1;
            return true;
        }
    }
    // "the corner of the room", "the top of the stove", "the back of the chair", "the upper
    // portion of the bed": the part is read as the thing itself.
    if ((!nounWords.empty() || !side.empty()) &&
        (nounWords.empty() || isPartWord(nounWords.back()) || isPartOfThing(nounWords.back())) &&
        std::all_of(nounWords.begin(), nounWords.end(),
                    [](const std::string& n) { return isPartWord(n) || isPartPlaceWord(n) || isPartOfThing(n); })) {
        out_.notes.push_back(fmt::format("'{}' is read as the thing itself", joined(w, wordsStart, i + 1)));
        nounWords.clear();
        side.clear();
        while (i + 1 < w.size() && isDeterminer(w[i + 1])) ++i;
        return true;
    }
    return false;
}

PhraseParser::Quantifier PhraseParser::quantifierAt(const Words& w, std::size_t& i, Phrase& p,
                                                    std::optional<bool>& pendingDistance, std::string& pendingWord) {
    const std::string& word = w[i];
    if (auto n = cardinalOf(word); n && *n > 1) {
        p.top = *n;
        return Quantifier::Read;
    }
    // "one door of the wardrobe": "one" before a noun is an article.
    if (word == "one" && i + 1 < w.size() && !endsPhrase(w[i + 1]) && !predicateAt(w, i + 1) &&
        !isDeterminer(w[i + 1]) && !exclusionAt(w, i + 1) && w[i + 1] != "not")
        return Quantifier::Read;
    if (auto k = ordinalOf(word)) {
        p.pick = *k;
        return Quantifier::Read;
    }
    if (const auto* s = superlativeOf(word)) {
        p.order = Order{std::string(s->measure), s->descending, {}, std::string(s->word)};
        p.pick = std::max<std::size_t>(p.pick, 1);
        return Quantifier::Read;
    }
    // "which is the bigger bed?": of two, the comparative is the superlative.
    if (auto more = comparativeOf(word); more && more->measure != "distance" && i > 0 && w[i - 1] == "the" &&
                                         i + 1 < w.size() && w[i + 1] != "than" && !predicateAt(w, i + 1)) {
        p.order = Order{more->measure, more->descending, {}, more->superlative};
        p.pick = std::max<std::size_t>(p.pick, 1);
        return Quantifier::Read;
    }
    if (auto far = distanceOrderWord(word); far && i + 1 < w.size() && !isOneOf(w[i + 1], {"to", "from"})) {
        pendingDistance = *far;
        pendingWord = word;
        p.pick = std::max<std::size_t>(p.pick, 1);
        return Quantifier::Read;
    }
    // "the second closest to the door": a thing, by its distance to the door.
    if (auto far = distanceOrderWord(word); far && p.pick > 0 && i + 2 < w.size()) {
        std::size_t k = i + 2;
        Phrase to = phrase(w, k, false);
        p.order = Order{"distance", *far, {std::move(to)}, joined(w, i, k)};
        i = k;
        return Quantifier::EndsPhrase;
    }
    return Quantifier::None;
}

Phrase PhraseParser::phrase(const Words& w, std::size_t& i, bool withPosts) {
    Phrase p;
    std::size_t start = i;
    while (i < w.size() && isDeterminer(w[i])) ++i;
    // The answer reads "no desk near the left wall", without the question's article.
    const std::size_t wordsStart = i;
    std::string side;
    std::vector<std::string> nounWords;
    std::optional<bool> pendingDistance;  // "the nearest lamp to the sofa": the reference follows
    std::string pendingWord;
    if (idPhrase(w, i, withPosts, p)) {
        p.words = joined(w, wordsStart, i);
        return p;
    }
    if (selfPhrase(w, i, withPosts, p)) return p;
    for (; i < w.size(); ++i) {
        const std::string& word = w[i];
        if (nounWords.empty()) {
            const Quantifier q = quantifierAt(w, i, p, pendingDistance, pendingWord);
            if (q == Quantifier::Read) continue;
            if (q == Quantifier::EndsPhrase) break;
        }
        if (predicateAt(w, i) && !(isSideWord(word) && nounWords.empty() && i + 1 < w.size() && w[i + 1] != "of"))
            break;
        if (exclusionAt(w, i) || (distanceOrderWord(word) && !nounWords.empty())) break;
        // "the black chair out of the three chairs", "the chairs present in the room": the noun ends there.
        if (!nounWords.empty() && word == "out" && i + 1 < w.size() && w[i + 1] == "of") break;
        if (!nounWords.empty() && word == "present" && (i + 1 == w.size() || predicateAt(w, i + 1))) break;
        // "the biggest thing here": here is the scene, which the thing is in anyway.
        if (!nounWords.empty() && word == "here") {
            ++i;
            break;
        }
        // "the chairs not near the window", "the sofa longer than the bed", "anything more than 2 m long": the noun
        // ends there.
        if (!nounWords.empty() && (word == "not" || comparativeOf(word) ||
                                   (isOneOf(word, {"more", "less"}) && i + 1 < w.size() && w[i + 1] == "than")))
            break;
        // "can" ends a phrase as a verb ("what can I see"), but a trash can is a thing.
        if (word == "can" && !nounWords.empty() &&
            (i + 1 == w.size() || !isOneOf(w[i + 1], {"i", "you", "we", "one", "be", "see", "find"}))) {
            nounWords.push_back(word);
            continue;
        }
        if (describing(w, i, nounWords, side, wordsStart)) continue;
        if (endsPhrase(word) && !(word == "right" && nounWords.empty())) break;
        // "pieces of furniture": the thing is what follows "of"; "kinds of things" asks for their kinds.
        if (word == "of" && nounWords.size() == 1 && isMeasureWord(nounWords.front())) {
            p.kinds = isKindWord(nounWords.front());
            nounWords.clear();
            continue;
        }
        // "a long row of cabinets", "a line of chairs": the things in it (but "how many rows of
        // drawers" counts rows, which the memory keeps none of).
        if (word == "of" && nounWords.size() == 1 && isOneOf(nounWords.front(), {"row", "line"}) && wordsStart > 0 &&
            isOneOf(w[wordsStart - 1], {"a", "an"})) {
            nounWords.clear();
            continue;
        }
        // An article inside the nouns starts another phrase ("the lamp the sofa" is two).
        if (!nounWords.empty() && isDeterminer(word)) break;
        if (isOneOf(word, {"will", "would", "should", "shall", "must", "might", "be", "been", "being", "had"})) break;
        if (auto colour = colourOf(word)) {
            if (!nounWords.empty() && i + 1 == w.size()) break;  // "is the mug red?"
            if (nounWords.empty()) {
                p.colour = colour;
                continue;
            }
        }
        if (isSideWord(word) && nounWords.empty()) {
            side = word;
            if (i + 1 < w.size() && w[i + 1] == "side") ++i;  // "the right side"
            continue;
        }
        // "what color wall is the board on?": the wall, whose colour is asked, not a "color wall".
        if (nounWords.empty() && isOneOf(word, {"color", "colour", "shape", "material"}) && i + 1 < w.size() &&
            !endsPhrase(w[i + 1]) && !predicateAt(w, i + 1) && w[i + 1] != "of" && !isDeterminer(w[i + 1])) {
            out_.notes.push_back(
                fmt::format("'{}' asks of the {}: the memory keeps it where recorded", word, w[i + 1]));
            continue;
        }
        if (nounWords.empty() && (isIgnoredAdjective(word) || wordnet::isAdjectiveOnly(word))) {
            if (i + 1 == w.size() || !isKindWord(w[i + 1]))  // "different kinds": no attribute asked
                out_.notes.push_back(fmt::format("'{}' is left out: the memory keeps no such attribute", word));
            continue;
        }
        // "the towel hanged on the door", "the monitor sits on the desk", "the radiator affixed": a
        // word WordNet knows as a verb and not as a noun says what the thing does, and ends its name,
        // where no noun follows it ("an open fronted cabinet" is a cabinet).
        if (!nounWords.empty() && isVerbOfPlace(word)) {
            const std::size_t next = i + 1;
            if (next == w.size() || predicateAt(w, next) || endsPhrase(w[next]) || isDeterminer(w[next]) ||
                distanceOrderWord(w[next]) || isVerbOfPlace(w[next]) ||
                isOneOf(w[next], {"up", "down", "out", "around", "together", "by", "directly"}))
                break;
        }
        nounWords.push_back(word);
    }
    if (side.empty()) side = sideAfter(w, i);
    if (nounWords.empty()) {
        // "the red one", "the largest" are any such thing; a side alone ("the left") names nothing.
        if (!(p.colour || p.order || pendingDistance) || !side.empty()) throw notUnderstood(w, start);
        nounWords.push_back("object");
    }
    // A name of a thing is a few words ("kitchen cabinet door"); more is a sentence read wrongly.
    shortenNoun(nounWords, w, start);
    resolveNoun(p, nounWords);
    if (!side.empty()) {
        // A side names one node of one category (wall.left); of anything else it is left out.
        if (p.kind || p.categories.size() != 1)
            out_.notes.push_back(fmt::format("'{}' is left out: sides are of one category (the left wall)", side));
        else
            p.side = side;
    }
    if (pendingDistance) orderByDistanceFrom(w, i, p, *pendingDistance, pendingWord);
    if (withPosts) posts(w, i, p);
    if (p.pick > 0 && !p.order) orderByNearness(w, i, p);
    p.words = joined(w, wordsStart, i);
    return p;
}

namespace {

// "closest to you", "farthest from you": how the answer says an order by the distance from the person.
std::string youWords(const std::string& superlative, bool farthest) {
    return superlative + (farthest ? " from you" : " to you");
}

}  // namespace

Phrase PhraseParser::person() const {
    Phrase at;
    if (self_) {
        at = self_->at;
        at.self = true;
    } else {
        at.here = true;
    }
    at.words = "you";
    return at;
}

bool PhraseParser::personAt(const Words& w, std::size_t& i, Phrase& out) const {
    if (i >= w.size() || !isOneOf(w[i], {"me", "myself", "here", "you"})) return false;
    out = person();
    ++i;
    return true;
}

void PhraseParser::orderByDistanceFrom(const Words& w, std::size_t& i, Phrase& p, bool farthest,
                                       const std::string& word) {
    const bool linked = i < w.size() && isOneOf(w[i], {"to", "from"});
    std::size_t k = linked ? i + 1 : i;
    // "the nearest chair to me", and "the nearest chair" with no "to" after it: from where the person is.
    if (Phrase to; !linked || personAt(w, k, to)) {
        p.order = Order{"distance", farthest, {linked ? std::move(to) : person()}, youWords(word, farthest), !linked};
        i = k;
        return;
    }
    const std::size_t toAt = i++;
    Phrase to = phrase(w, i, false);
    // "the closest thing to the bed" is beside it, not a pillow on it.
    if (!farthest) leaveOutRestingOn(p, to);
    p.order = Order{"distance", farthest, {std::move(to)}, word + " " + joined(w, toAt, i)};
}

void PhraseParser::orderByNearness(const Words& w, std::size_t& i, Phrase& p) {
    if (i + 1 < w.size() && w[i] == "from") {
        std::size_t k = i + 1;
        Phrase to = phrase(w, k, false);
        const std::string said = "closest to the " + to.words;
        p.order = Order{"distance", false, {std::move(to)}, said};
        i = k;
    } else if (self_) {
        Phrase to = self_->at;
        to.self = true;
        p.order = Order{"distance", false, {std::move(to)}, "closest to you"};
    }
}

namespace {

// "beyond and to the right of the lamp": two predicates of the same things. The first one, with `at`
// and `pred` moved to the second; nothing when w[at] begins one predicate only (or "between").
std::optional<std::pair<std::string, std::size_t>> firstOfTwo(
    const Words& w, std::size_t& at, std::optional<std::pair<std::string, std::size_t>>& pred) {
    const std::size_t andAt = at + pred->second;
    if (pred->first == "between" || andAt + 1 >= w.size() || w[andAt] != "and") return std::nullopt;
    auto second = PhraseParser::predicateAt(w, andAt + 1);
    if (!second || second->first == "between") return std::nullopt;
    auto first = pred;
    at = andAt + 1;
    pred = second;
    return first;
}

}  // namespace

bool PhraseParser::sideAfterVerb(const Words& w, std::size_t at, std::size_t& i, Phrase& p) const {
    // "the armchair located on the left": the one on that side, as "the armchair on the left".
    if (!p.side.empty() || p.kind || p.categories.size() != 1 || !p.id.empty()) return false;
    std::string side = sideAfter(w, at);
    if (side.empty()) return false;
    p.side = side;
    i = at;
    return true;
}

// A verb of place before a predicate says no more than it: "sits on the desk", "hanged on the door", "pushed up
// against the wall", "pushed closest to the wall". Where the predicate begins, else `at`.
std::size_t PhraseParser::pastVerbOfPlace(const Words& w, std::size_t at) {
    if (at >= w.size() || !isVerbOfPlace(w[at]) || predicateAt(w, at)) return at;
    std::size_t k = at + 1;
    while (k < w.size() && isOneOf(w[k], {"up", "down", "out", "around", "together", "directly", "right"}) &&
           !predicateAt(w, k))
        ++k;
    return k < w.size() && (predicateAt(w, k) || distanceOrderWord(w[k])) ? k : at;
}

bool PhraseParser::amongThem(const Words& w, std::size_t at, std::size_t& i, Phrase& p) {
    if (!(at + 2 < w.size() && w[at] == "out" && w[at + 1] == "of" && (!p.categories.empty() || p.kind))) return false;
    std::size_t k = at + 2;
    ++nested_;
    Phrase among = phrase(w, k, false);
    --nested_;
    if (p.kind == std::optional<std::string>("object") && p.categories.empty() && !among.kind) {
        // "the second closest to the door out of the trash cans": one of them.
        p.kind.reset();
        p.categories = among.categories;
        p.noun = among.noun;
        i = k;
        return true;
    }
    if (!p.categories.empty() && among.categories == p.categories) {
        k = std::min(k + (k < w.size() && w[k] == "present" ? 1 : 0), w.size());
        out_.notes.push_back(
            fmt::format("'{}' says no more than '{}'", joined(w, at, k), p.words.empty() ? p.noun : p.words));
        i = k;
        return true;
    }
    return false;
}

bool PhraseParser::onSameWallAs(const Words& w, std::size_t at, std::size_t& i, Phrase& p) {
    if (!(at + 5 < w.size() && isOneOf(w[at], {"on", "against", "along", "by"}) && w[at + 1] == "the" &&
          w[at + 2] == "same" && w[at + 3] == "wall" && w[at + 4] == "as"))
        return false;
    std::size_t k = at + 5;
    ++nested_;
    Phrase as = phrase(w, k, false);
    --nested_;
    Phrase wall;
    resolveNoun(wall, {"wall"});
    wall.order = Order{"distance", false, {as}, "closest to the " + as.words};
    wall.pick = 1;
    Condition c;
    c.predicate = "near";
    c.args.push_back(std::move(wall));
    c.words = joined(w, at, k);
    p.conditions.push_back(std::move(c));
    if (!p.categories.empty() || p.kind) p.excluded.push_back(std::move(as));
    i = k;
    return true;
}

// What rests on or in the thing a listing is near (or to the left of, right of, in front of or behind, or the
// thing closest to) is on or in it, not beside it: a person asked what is next to the sofa names the side table and the
// lamp, not the cushions on it (those are "on the sofa", as RELATE names the most specific relation), so the condition
// on a list of things of any kind comes with NOT on and NOT in of the same thing, as far as that kind carries things on
// or holds them (docs/ask.md, "Near and next to"). What the thing itself stands on is under it, not beside it either:
// for a kind put on tops (a monitor, a mug: relations::usualSupport), NOT below the thing too, so that "what is next
// to the monitor?" does not name the desk it stands on. A written distance ("within 1 m of the sofa") is a distance and
// keeps everything within it; a named kind ("the chairs near the table") is left as asked, and nothing rests on the
// room's walls, floor or ceiling in this sense.
void PhraseParser::leaveOutResting(Phrase& p) const {
    const Condition& near = p.conditions.back();
    if (!isOneOf(near.predicate, {"near", "left_of", "right_of", "in_front_of", "behind"}) || near.metres ||
        near.args.size() != 1)
        return;
    leaveOutRestingOn(p, near.args.front());
}

void PhraseParser::leaveOutRestingOn(Phrase& p, const Phrase& thing) const {
    // Next to a kind of room read as its things ("what is near the kitchen?"): what stands by them, not they.
    if (p.kind && thing.room) {
        Phrase own = thing;
        own.words = fmt::format("{}'s things", thing.noun);
        p.excluded.push_back(std::move(own));
        return;
    }
    if (!p.kind || thing.here || thing.self || thing.categories.size() != 1 || isPlane(thing) ||
        isOneOf(thing.categories.front(), {"floor", "ceiling"}))
        return;
    const relations::Affordance affords = relations::affordanceOf(thing.categories.front());
    for (const char* predicate : {"on", "in"}) {
        const bool possible =
            predicate == std::string_view("on")
                ? affords != relations::Affordance::Holder && affords != relations::Affordance::Nothing
                : affords != relations::Affordance::Surface && affords != relations::Affordance::Nothing;
        if (!possible) continue;
        Condition c;
        c.predicate = predicate;
        c.args = {thing};
        c.negated = true;
        p.conditions.push_back(std::move(c));
    }
    if (relations::usualSupport(thing.categories.front()) == relations::Support::Surface) {
        Condition carrier;
        carrier.predicate = "below";
        carrier.args = {thing};
        carrier.negated = true;
        p.conditions.push_back(std::move(carrier));
    }
}

bool PhraseParser::sideLeftOut(const Words& w, std::size_t at, std::size_t& i, const Phrase& p) {
    if (!((p.kind || p.categories.size() != 1) && p.id.empty())) return false;
    std::size_t k = at;
    const std::string side = sideAfter(w, k);
    if (side.empty() || k >= w.size() || !predicateAt(w, k)) return false;
    out_.notes.push_back(fmt::format("'{}' is left out: sides are of one category (the left wall)", joined(w, at, k)));
    i = k;
    return true;
}

// The room or a place in it after a predicate at w[at]: "in the room", "in here", "in the office" (when the office is
// this scene) are the whole scene; a corner, the middle or a part of the room, which the memory keeps none of, is
// left out with a note. True when it read them (i past them).
bool PhraseParser::roomPlaceLeftOut(const Words& w, std::size_t at, std::size_t& i,
                                    const std::pair<std::string, std::size_t>& pred) {
    // "in the room": the whole scene.
    std::size_t after = at + pred.second;
    while (after < w.size() && isDeterminer(w[after])) ++after;
    // "in the corner of the room" is in the room; "on the far end of the room", "at the back of
    // the room" too: the memory keeps no parts of a room.
    std::size_t part = after;
    while (part < w.size() && (isPartPlaceWord(w[part]) || isPartWord(w[part]))) ++part;
    const bool ofPart = part > after && part + 1 < w.size() && isPartWord(w[part - 1]) && w[part] == "of";
    if (ofPart) {
        after = part + 1;
        while (after < w.size() && isDeterminer(w[after])) ++after;
    }
    // "the rug in the corner", "the door in the right corner", "the counter in the middle": a corner
    // or the middle of the room, which the memory keeps none of (as "in the corner of the room").
    if (part > after && isOneOf(w[part - 1], {"corner", "corners", "middle", "center", "centre"}) &&
        (part == w.size() || w[part] != "of") && isOneOf(pred.first, {"in", "at", "on", "near"}) &&
        !std::any_of(lexicon_.categories().begin(), lexicon_.categories().end(),
                     [&](const std::string& c) { return c == w[part - 1]; })) {
        out_.notes.push_back(
            fmt::format("'{}' is left out: the memory keeps no corners or middle of the room", joined(w, at, part)));
        i = part;
        return true;
    }
    if ((pred.first == "in" || (ofPart && isOneOf(pred.first, {"on", "near"}))) && after < w.size()) {
        // "in here", "in the room", "in the office" (when the office is this scene), "in a
        // cluttered room" (a look the memory keeps nothing of).
        std::size_t placeAt = after;
        while (placeAt < w.size() && (isIgnoredAdjective(w[placeAt]) || wordnet::isAdjectiveOnly(w[placeAt])))
            ++placeAt;
        std::size_t place = scenePlaceAt(w, placeAt);
        if (place > 0 && (ofPart || placeAt + place == w.size() || !predicateAt(w, placeAt + place))) {
            if (placeAt > after)
                out_.notes.push_back(
                    fmt::format("'{}' is left out: the memory keeps no such attribute", joined(w, after, placeAt)));
            i = placeAt + place;
            return true;
        }
    }
    return false;
}

const std::vector<std::vector<std::string>>& PhraseParser::roomMarks() const {
    if (!roomMarks_) {
        roomMarks_.emplace();
        for (const auto& row : kRoomMarks) roomMarks_->push_back(categoriesNamed(lexicon_, row.things, WordsAs::Names));
    }
    return *roomMarks_;
}

// Words after a kind of room that name the same place: "the kitchen area".
const std::initializer_list<std::string_view> kAreaWords{"area", "part", "section", "space", "side"};

const RoomMarks* PhraseParser::roomAreaAt(const Words& w, std::size_t at) const {
    const RoomMarks* asked = roomNamedAt(w, at);
    if (!asked) return nullptr;
    const auto& marks = roomMarks();
    const auto kinds = std::count_if(marks.begin(), marks.end(), [](const auto& m) { return !m.empty(); });
    // A scene of one room (an office with a sofa too) is that room: "in the office" is the whole scene (scenePlaceAt).
    return !marks[static_cast<std::size_t>(asked - kRoomMarks)].empty() &&
                   static_cast<std::size_t>(kinds) >= kSeveralRooms
               ? asked
               : nullptr;
}

bool PhraseParser::roomArea(const Words& w, std::size_t at, std::size_t& i,
                            const std::pair<std::string, std::size_t>& pred, Phrase& p) {
    if (pred.first != "in") return false;
    std::size_t after = at + pred.second;
    while (after < w.size() && isDeterminer(w[after])) ++after;
    const RoomMarks* asked = roomAreaAt(w, after);
    if (!asked) return false;
    std::vector<std::string> marks = roomMarks()[static_cast<std::size_t>(asked - kRoomMarks)];
    out_.notes.push_back(
        fmt::format("'the {}' is the area within {} m of its things ({}): the scene holds the things "
                    "of several kinds of room",
                    asked->room, smqlMetres(kRoomAreaReach), model::joinAlternatives(marks)));
    Phrase area;
    area.noun = "thing";
    area.categories = std::move(marks);
    area.words = fmt::format("the {}'s things", asked->room);
    p.conditions.push_back({"within", {std::move(area)}, kRoomAreaReach, fmt::format("in the {}", asked->room)});
    i = after + words(std::string(asked->room)).size();
    // "in the kitchen area", "in the bedroom part": the same area.
    if (i < w.size() && isOneOf(w[i], kAreaWords)) ++i;
    return true;
}

void PhraseParser::posts(const Words& w, std::size_t& i, Phrase& p) {
    while (i < w.size()) {
        std::size_t at = i;
        bool joinedByAnd = false;
        if (isOneOf(w[i], {"that", "which", "who"}) && i + 1 < w.size() && isOneOf(w[i + 1], {"is", "are"}))
            at += 2;
        else if ((w[i] == "and" && (!p.conditions.empty() || p.order || !p.excluded.empty())) ||
                 (w[i] == "but" && !p.conditions.empty() && i + 2 < w.size() && w[i + 1] == "not" &&
                  predicateAt(w, i + 2))) {
            // "near the sofa but not on it": "but" joins the negated condition as "and" does.
            at += 1;
            joinedByAnd = true;
        }
        if (at < w.size() && isOneOf(w[at], {"is", "are"}) && joinedByAnd) ++at;
        while (at < w.size() &&
               isOneOf(w[at], {"located", "placed", "sitting", "lying", "standing", "resting", "kept", "hanging",
                               "hung", "found", "situated", "the", "right", "directly", "just", "immediately"}) &&
               !predicateAt(w, at))
            ++at;
        at = pastVerbOfPlace(w, at);
        // besides the cushions / other than the lamps
        if (std::size_t n = exclusionAt(w, at); n && nested_ == 0) {
            i = at + n;
            ++nested_;
            p.excluded.push_back(phrase(w, i, false));
            --nested_;
            continue;
        }
        // closest to the window / farthest from the door
        if (at < w.size()) {
            if (auto far = distanceOrderWord(w[at])) {
                std::size_t k = at + 1;
                if (k < w.size() && isOneOf(w[k], {"to", "from"}))
                    ++k;
                else if (k + 1 < w.size() && w[k] == "away" && w[k + 1] == "from")
                    k += 2;
                i = k;
                Phrase to;
                const bool fromPerson = personAt(w, i, to);
                if (!fromPerson) to = phrase(w, i, false);
                p.order = Order{"distance", *far, {to}, fromPerson ? youWords(w[at], *far) : joined(w, at, i)};
                p.pick = std::max<std::size_t>(p.pick, 1);
                continue;
            }
        }
        // not on the table / not near the window: the condition negated.
        bool negated = false;
        if (at + 1 < w.size() && (w[at] == "not" || (w[at] == "nowhere" && w[at + 1] == "near"))) {
            std::size_t k = at + 1;
            while (k < w.size() &&
                   isOneOf(w[k], {"located", "placed", "sitting", "lying", "standing", "resting", "kept", "hanging",
                                  "hung", "found", "situated", "directly"}) &&
                   !predicateAt(w, k))
                ++k;
            if (!predicateAt(w, k) || exclusionAt(w, k)) return;
            negated = true;
            at = k;
        }
        if (!negated && measuredAt(w, at, i, p)) continue;
        if (sideAfterVerb(w, at, i, p)) continue;
        if (amongThem(w, at, i, p)) continue;
        if (onSameWallAs(w, at, i, p)) continue;
        if (sideLeftOut(w, at, i, p)) continue;
        auto pred = predicateAt(w, at);
        if (!pred) return;
        const std::size_t bothAt = at;
        auto also = firstOfTwo(w, at, pred);
        i = at;
        if (roomArea(w, at, i, *pred, p)) continue;
        if (roomPlaceLeftOut(w, at, i, *pred)) continue;
        if (also || !onThatThing(w, at, i, *pred, p)) p.conditions.push_back(condition(w, i, *pred));
        // What is near the person comes nearest first.
        if (const auto& args = p.conditions.back().args; !p.order && args.size() == 1 && args.front().here)
            p.order = Order{"distance", false, {args.front()}, "nearest to you"};
        if (also) {
            // The answer says "beyond and to the right of the lamp" once.
            p.conditions.back().words = joined(w, bothAt, i);
            Condition first = p.conditions.back();
            first.predicate = also->first;
            first.words.clear();
            p.conditions.push_back(std::move(first));
        }
        if (negated) {
            p.conditions.back().negated = true;
            p.conditions.back().words = "not " + p.conditions.back().words;
        } else if (!also) {
            leaveOutResting(p);
        }
        // "near the curtain and the door": the same relation to each.
        while (i + 1 < w.size() && w[i] == "and" && !predicateAt(w, i + 1) && !exclusionAt(w, i + 1) &&
               !isOneOf(w[i + 1], {"is", "are", "that", "which", "not"})) {
            std::size_t k = i + 1;
            Condition again = p.conditions.back();
            ++nested_;
            try {
                again.args = {phrase(w, k, false)};
            } catch (const Error&) {
                --nested_;
                break;
            }
            --nested_;
            if (again.predicate == "between") break;
            // The answer says "near the door and the window" once.
            p.conditions.back().words += " " + joined(w, i, k);
            again.words.clear();
            p.conditions.push_back(std::move(again));
            i = k;
        }
    }
}

bool PhraseParser::measuredAt(const Words& w, std::size_t at, std::size_t& i, Phrase& p) {
    // The size a word says, as a comparative ("taller") or the adjective after a length ("2 m long"): kSuperlatives'
    // rows of a box's own sides (not a distance, a volume or a height over the floor).
    auto sized = [](const std::string& word) -> std::optional<std::string_view> {
        for (const auto& s : kSuperlatives)
            if ((s.comparative == word || s.adjective == word) && (s.measure == "height" || s.measure == "width"))
                return s.measure;
        return std::nullopt;
    };
    std::optional<std::string_view> measure;
    std::optional<double> metres;
    bool greater = true;
    std::size_t end = at;
    if (at + 3 < w.size() && w[at + 1] == "than" && comparativeOf(w[at])) {
        // "taller than 1 m", "shorter than 50 cm"
        measure = sized(w[at]);
        metres = lengthAt(w, at + 2);
        greater = comparativeOf(w[at])->descending;
        end = at + 4;
    } else if (at + 3 < w.size() && (isOneOf(w[at], {"over", "under", "above", "below"}) ||
                                     (isOneOf(w[at], {"more", "less"}) && w[at + 1] == "than"))) {
        // "more than 2 m long", "under 50 cm wide"
        const std::size_t k = isOneOf(w[at], {"more", "less"}) ? at + 2 : at + 1;
        metres = lengthAt(w, k);
        measure = k + 2 < w.size() ? sized(w[k + 2]) : std::nullopt;
        greater = isOneOf(w[at], {"over", "above", "more"});
        end = k + 3;
    }
    if (!measure || !metres) return false;
    p.filters.push_back(fmt::format("{} {} {} m", *measure, greater ? ">" : "<", smqlMetres(*metres)));
    p.measured += (p.measured.empty() ? "" : " and ") + joined(w, at, end);
    i = end;
    return true;
}

bool PhraseParser::onThatThing(const Words& w, std::size_t at, std::size_t& i,
                               const std::pair<std::string, std::size_t>& pred, Phrase& p) {
    const std::size_t pronoun = at + pred.second;
    if (pronoun >= w.size() || !isOneOf(w[pronoun], {"it", "them"}) || p.conditions.empty() ||
        p.conditions.back().args.size() != 1 || pred.first == "within" || pred.first == "between")
        return false;
    const Phrase& thing = p.conditions.back().args.front();
    p.conditions.push_back({pred.first, {thing}, std::nullopt, joined(w, at, pronoun) + " the " + thing.words, false});
    i = pronoun + 1;
    return true;
}

Condition PhraseParser::condition(const Words& w, std::size_t& i, const std::pair<std::string, std::size_t>& pred) {
    Condition c;
    c.predicate = pred.first;
    std::size_t start = i;
    if (w[i] == "within" && pred.second == 4) c.metres = lengthAt(w, i + 1);
    i += pred.second;
    if (c.predicate == "between") {
        ++nested_;
        c.args.push_back(phrase(w, i, false));
        --nested_;
        if (i >= w.size() || w[i] != "and") {
            // "between the two cabinets": between two things of one kind.
            bool plural = i > 0 && w[i - 1] != c.args.front().noun && w[i - 1].ends_with("s");
            if (!plural)
                throw Error(ErrorKind::Binding, "'between' needs two things: between the sofa and the lamp",
                            std::nullopt, "ask as in: what is between the sofa and the lamp?");
            c.args.push_back(c.args.front());
            c.words = joined(w, start, i);
            return c;
        }
        ++i;
    }
    // "me" with no situation: the person standing where the viewer stands (HERE). Near them is within a distance of
    // that place (distance(HERE)); their sides are the viewpoint's: "in front of me" lies beyond them as the view
    // sees it (SMQL's behind), "behind me" nearer (in_front_of).
    if (Phrase person; !self_ && isOneOf(c.predicate, {"near", "left_of", "right_of", "in_front_of", "behind"}) &&
                       personAt(w, i, person)) {
        c.args.push_back(std::move(person));
        if (c.predicate == "near") {
            c.metres = c.metres.value_or(kNearYou);
            c.words = fmt::format("within {} m of you", smqlMetres(*c.metres));
            return c;
        }
        c.words = joined(w, start, i - 1) + " you";
        if (c.predicate == "in_front_of")
            c.predicate = "behind";
        else if (c.predicate == "behind")
            c.predicate = "in_front_of";
        return c;
    }
    ++nested_;
    c.args.push_back(phrase(w, i, true));
    --nested_;
    // Things are on a wall by hanging there: "the picture on the wall" is attached to it.
    if (c.predicate == "on" && isPlane(c.args.front())) c.predicate = "attached";
    c.words = joined(w, start, i);
    if (self_) {
        // After a situation the sides are the person's, whose heading is the view's turned back by
        // `turn`: "left of me", "behind me" (ahead of me is farther ahead, `behind` in SMQL's
        // terms); "right of the sofa" (the person's right). Of another thing, in front of it is
        // nearer the person (SMQL's in_front_of).
        static constexpr std::array<std::string_view, 4> sides{"behind", "right_of", "in_front_of", "left_of"};
        const bool self = c.args.front().self;
        const std::string asked = !self                          ? c.predicate
                                  : c.predicate == "in_front_of" ? "behind"
                                  : c.predicate == "behind"      ? "in_front_of"
                                                                 : c.predicate;
        for (int side = 0; side < 4; ++side)
            if (sides[static_cast<std::size_t>(side)] == asked) {
                c.predicate = selfSidePredicate(side, self_->turn);
                break;
            }
        static const std::regex me("\\bme\\b"), my("\\bmy\\b");
        c.words = std::regex_replace(std::regex_replace(c.words, me, "you"), my, "your");
    }
    return c;
}

std::string selfSidePredicate(int side, int turn) {
    static constexpr std::array<std::string_view, 4> viewSides{"behind", "right_of", "in_front_of", "left_of"};
    return std::string(viewSides[static_cast<std::size_t>(((side - turn) % 4 + 4) % 4)]);
}

bool PhraseParser::isPlane(const Phrase& p) const {
    if (p.kind || p.categories.empty()) return false;
    return std::all_of(p.categories.begin(), p.categories.end(), [&](const std::string& c) {
        return std::find(planes_.begin(), planes_.end(), c) != planes_.end();
    });
}

Error PhraseParser::notUnderstood(const Words& w, std::size_t at) const {
    return Error(ErrorKind::Binding, fmt::format("cannot read a thing to look for in '{}'", joined(w, at, w.size())),
                 std::nullopt, "name something the scene holds, as in: what is on the sofa?");
}

std::size_t PhraseParser::scenePlaceAt(const Words& w, std::size_t i) const {
    if (i >= w.size()) return 0;
    if (namesWholeScene(w[i])) return 1;  // "in the room", "in here": the whole scene, no condition
    if (roomAreaAt(w, i)) return 0;       // a part of the scene (roomArea)
    for (std::string_view kind : kRoomKinds) {
        Words parts = words(std::string(kind));
        if (i + parts.size() > w.size() || !std::equal(parts.begin(), parts.end(), w.begin() + i)) continue;
        // A room kind the scene has as a thing ("closet", "study") is that thing; not a thing WordNet gives as one of
        // its senses (a bathroom's "toilet"), in a scene of that room.
        const WordMatch match = lexicon_.lookUp(joined(w, i, i + parts.size()));
        if (match.how == WordMatch::How::Category || match.how == WordMatch::How::Plural) return 0;
        const std::string name = model::categoryName(scene_), word = model::categoryName(kind);
        // A scene of one room whose things mark the kind asked (a sofa: a living room) is that room too, of several
        // scenes whose names say nothing (VSI-Bench's "41069025").
        const RoomMarks* marked = roomNamedAt(w, i);
        bool fits = sceneCount_ <= 1 || name.find(word) != std::string::npos ||
                    name.find(std::string(kind.substr(0, kind.find(' ')))) != std::string::npos ||
                    (marked && !roomMarks()[static_cast<std::size_t>(marked - kRoomMarks)].empty());
        if (!fits) return 0;
        out_.notes.push_back(fmt::format("'{}' is the scene '{}'", kind, scene_));
        const std::size_t end = i + parts.size();
        return parts.size() + (end < w.size() && isOneOf(w[end], kAreaWords) ? 1 : 0);
    }
    return 0;
}

void PhraseParser::resolveNoun(Phrase& p, const std::vector<std::string>& nounWords) {
    std::string all = joined(nounWords, 0, nounWords.size());
    // A pronoun stands for a thing said before, and ASK reads each question on its own: "where is it?" names
    // nothing to look for (not a thing called "it", which no scene holds).
    if (nounWords.size() == 1 && isOneOf(nounWords[0], {"it", "they", "them", "this", "that", "these", "those"}))
        throw Error(ErrorKind::Binding,
                    fmt::format("'{}' stands for no thing here: each question is read on its own", nounWords[0]),
                    std::nullopt, "name the thing, as in: where is the lamp?");
    // A kind of room named as a thing, where the scene holds the things of several ("how far is the bathroom from the
    // kitchen?", "what is near the kitchen?"): the things that mark it, whose area "in the kitchen" is (roomArea).
    if (const RoomMarks* room = roomAreaAt(nounWords, 0); room && words(std::string(room->room)) == nounWords) {
        p.noun = std::string(room->room);
        p.room = true;
        p.categories = roomMarks()[static_cast<std::size_t>(room - kRoomMarks)];
        out_.notes.push_back(
            fmt::format("'the {}' is its things ({}): the scene holds the things of several kinds of "
                        "room",
                        room->room, model::joinAlternatives(p.categories)));
        return;
    }
    if (nounWords.size() == 1) {
        if (auto kind = kindTarget(nounWords[0])) {
            p.kind = *kind;
            p.noun = "thing";
            return;
        }
    }
    auto said = [&](const std::string& word) {
        return std::any_of(out_.mappings.begin(), out_.mappings.end(), [&](const auto& m) { return m.word == word; });
    };
    // A kind told by its shape ("coffee table"), where the scene has the category but not the name.
    for (const auto& shaped : kShapedKinds) {
        if (shaped.words != all) continue;
        WordMatch whole = lexicon_.lookUp(all);
        if (whole.how == WordMatch::How::Category || whole.how == WordMatch::How::Plural ||
            whole.how == WordMatch::How::Synonym)
            break;  // a name of a kind the scene holds ("bedside table": its nightstands) wins over the shape
        const auto& cats = lexicon_.categories();
        if (std::find(cats.begin(), cats.end(), std::string(shaped.category)) == cats.end()) break;
        p.noun = all;
        p.categories = {std::string(shaped.category)};
        p.filters.emplace_back(shaped.condition);
        if (!said(all))
            out_.mappings.push_back(
                WordMapping{all, p.categories, fmt::format("{}: {}", shaped.meaning, std::string(shaped.condition))});
        return;
    }
    // The whole phrase first ("coffee table", "wall plug"), then its last word ("table").
    WordMatch match = lexicon_.lookUp(all);
    std::string word = all;
    auto isNamed = [](const WordMatch& m) {
        return m.how == WordMatch::How::Category || m.how == WordMatch::How::Plural || m.how == WordMatch::How::Synonym;
    };
    // A phrase that names nothing here as a whole ("coffee mug") is read by its last word, unless
    // WordNet knows the whole or maps it to kinds the scene has.
    // A whole that WordNet knows ("trash can": a kind of bin) is not read by its head ("can").
    // A whole WordNet knows as no physical thing ("open door": a policy) is read by its head too.
    bool wholeKnown = (match.how == WordMatch::How::Absent &&
                       (absentThing(all, match) || wordnet::nounSenses(match.lemma).empty())) ||
                      match.how == WordMatch::How::Broader;
    if (nounWords.size() > 1 && !isNamed(match) && match.how != WordMatch::How::Kind && !wholeKnown) {
        WordMatch head = lexicon_.lookUp(nounWords.back());
        // A compound category of another kind is not the thing asked for: a "tv stand" is no
        // plant-stand. The modifier must be a noun for that ("potted plant" is an indoor-plant).
        const std::string& modifier = nounWords[nounWords.size() - 2];
        bool nounModifier = !wordnet::nounSenses(modifier).empty() ||
                            std::find(lexicon_.categories().begin(), lexicon_.categories().end(), modifier) !=
                                lexicon_.categories().end();
        if (nounModifier) {
            std::erase_if(head.categories, [&](const std::string& c) {
                return c.find('-') != std::string::npos && !c.starts_with(modifier + "-");
            });
            if (head.categories.empty() && head.how != WordMatch::How::Unknown) head.how = WordMatch::How::Absent;
        }
        if (head.how == WordMatch::How::Absent && nounModifier) {
            // Neither the whole nor its head is here: the answer speaks of the whole ("no tv stand"),
            // its head in its base form as WordNet spells it ("kitchen cabinets": no kitchen cabinet;
            // "water fointain": no water fountain).
            if (!head.lemma.empty() && head.lemma != nounWords.back())
                all = joined(std::vector<std::string>(nounWords.begin(), nounWords.end() - 1), 0, nounWords.size()) +
                      " " + head.lemma;
            p.noun = all;
            if (!said(all)) out_.mappings.push_back(WordMapping{all, {}, describe(WordMatch::How::Absent)});
            return;
        }
        out_.notes.push_back(fmt::format("'{}' is read as '{}'", all, nounWords.back()));
        match = head;
        word = nounWords.back();
    }
    p.noun = match.lemma;
    // The room itself is no thing to place others by: its sides and ends are not stored (its middle and corners are
    // read whole: QuestionReader::roomPlace).
    if (match.how == WordMatch::How::Unknown || namesWholeScene(match.lemma)) {
        unknownWords_.push_back(word);
        return;
    }

    p.categories = match.categories;
    if (match.how != WordMatch::How::Category && !said(word))
        out_.mappings.push_back(WordMapping{word, match.categories, describe(match.how)});
}

// ------------------------------------------------------------------ SMQL

std::string smqlName(const std::string& name) {
    static const std::regex bare("[a-z_][a-z0-9_]*(-[a-z0-9_]+)*");
    bool reserved = isOneOf(name, {"and", "or", "not", "like"});
    if (std::regex_match(name, bare) && !reserved) return name;
    return smqlString(name);
}

std::string smqlString(const std::string& text) { return model::quoted(text); }

std::string smqlMetres(double metres) {
    std::string out = fmt::format("{:.3f}", metres);
    out.erase(out.find_last_not_of('0') + 1);
    if (out.back() == '.') out.pop_back();
    return out;
}

std::string matchText(const Phrase& p) {
    std::vector<std::string> all;
    if (!p.id.empty()) {
        const auto hash = p.id.find('#');
        all.push_back(p.id.starts_with("src#") ? "source_id = " + p.id.substr(hash + 1)
                                               : "id = " + p.id.substr(hash + 1));
    } else if (!p.kind && p.side.empty() && p.categories.size() == 1) {
        all.push_back(fmt::format("category = {}", smqlString(p.categories.front())));
    } else if (p.kind && *p.kind == "anchor") {
        all.push_back("kind = 'anchor'");
    }
    for (auto& c : conditionsOf(p)) all.push_back(std::move(c));
    if (all.empty()) return "kind = 'object'";
    std::string out;
    for (const auto& w : all) out += (out.empty() ? "" : " AND ") + w;
    return all.size() > 1 ? "(" + out + ")" : out;
}

std::string whereText(const Phrase& p) {
    std::string out;
    for (const auto& w : conditionsOf(p)) out += (out.empty() ? " WHERE " : " AND ") + w;
    return out;
}

std::vector<std::string> categoriesNamed(const Lexicon& lexicon, std::string_view words, WordsAs as) {
    std::vector<std::string> categories;
    const std::string things{words};
    for (std::size_t at = 0; at < things.size();) {
        const std::size_t space = things.find(' ', at);
        const WordMatch m = lexicon.lookUp(things.substr(at, space - at));
        const bool named = m.how == WordMatch::How::Category || m.how == WordMatch::How::Plural ||
                           (as != WordsAs::Names && m.how == WordMatch::How::Kind) ||
                           (as == WordsAs::Broader && m.how == WordMatch::How::Broader);
        if (named)
            for (const auto& cat : m.categories)
                if (std::find(categories.begin(), categories.end(), cat) == categories.end()) categories.push_back(cat);
        at = space == std::string::npos ? things.size() : space + 1;
    }
    return categories;
}

const RoomMarks* roomNamedAt(const Words& w, std::size_t at) {
    for (const auto& row : kRoomMarks) {
        const Words room = words(std::string(row.room));
        if (at + room.size() <= w.size() && std::equal(room.begin(), room.end(), w.begin() + at)) return &row;
    }
    return nullptr;
}

std::string reference(const Phrase& p) {
    if (p.here) return "HERE";
    std::string where = whereText(p), order = orderText(p);
    if (where.empty() && order.empty()) return targetOf(p);
    // A reference names the pick-th thing of its order: "the lamp on the largest table".
    std::string limit = p.order ? fmt::format(" LIMIT {}", std::max<std::size_t>(p.pick, 1)) : "";
    return "(FIND " + targetOf(p) + where + order + limit + ")";
}

std::string findText(const Phrase& p, bool path, const std::string& view) {
    std::string limit = p.order && p.pick ? fmt::format(" LIMIT {}", std::max(p.pick, p.top)) : "";
    return "FIND " + targetOf(p) + (view.empty() ? "" : " " + view) + whereText(p) + orderText(p) + limit +
           (path ? " PATH" : "");
}

std::string countText(const Phrase& p, const std::string& view) {
    return "COUNT " + targetOf(p) + (view.empty() ? "" : " " + view) + whereText(p);
}

bool phraseUpTo(const Words& w, std::size_t& i, std::size_t end, PhraseParser& p, Phrase& out) {
    Words head(w.begin(), w.begin() + static_cast<std::ptrdiff_t>(end));
    std::size_t k = i;
    out = p.phrase(head, k, true);
    if (k != end) return false;
    i = end;
    return true;
}

void describeSubject(const Phrase& p, Translation& out) {
    std::string adjectives = p.colour ? *p.colour + " " : "";
    // "trash-bin" is a trash bin in words.
    const std::string noun = model::categoryWords(!p.side.empty() ? p.side + " " + p.noun : p.noun);
    out.subject = adjectives + noun;
    out.subjectPlural = adjectives + pluralOf(noun);
    // A kind of room read as its things (resolveNoun): several of them are the room's things, not several rooms.
    if (p.room) out.subjectPlural = "things of the " + noun;
    std::string condition = p.measured;
    for (const auto& c : p.conditions)
        if (!c.words.empty()) condition += (condition.empty() ? "" : " and ") + c.words;
    // "on the bed besides the pillows"
    for (const auto& e : p.excluded) condition += std::string(condition.empty() ? "" : " ") + "besides the " + e.words;
    if (out.condition.empty()) out.condition = condition;
    out.byKind = p.kinds;
}

bool locateAnswer(const Phrase& thing, Translation& out) {
    out.kind = thing.order ? QuestionKind::Superlative : QuestionKind::Locate;
    out.pick = std::max<std::size_t>(thing.pick, 1);
    if (thing.order) out.measure = thing.order->words;
    out.smql = findText(thing, true);
    describeSubject(thing, out);
    return true;
}

}  // namespace smql::ask
