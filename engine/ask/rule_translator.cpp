// The built-in translator: a question is normalised (lower case, contractions expanded,
// punctuation dropped), its form is recognised by a short list of patterns (one per way of
// asking), and its noun phrases are parsed by a small recursive descent:
//   phrase    := determiner* modifier* noun+ condition*
//   condition := predicate-words phrase [and phrase]          ("between the sofa and the lamp")
// so "the desk near the left wall" is a desk with a condition of its own. Nouns go through the
// Lexicon (scene categories, WordNet, did-you-mean).
#include <algorithm>
#include <array>
#include <cctype>
#include <optional>
#include <regex>
#include <sstream>

#include <fmt/format.h>

#include "engine/ask/lexicon.hpp"
#include "engine/ask/translator.hpp"
#include "model/error.hpp"

namespace smql::ask {

namespace {

// Longer questions are refused before the recursive descent: each condition nests a phrase, and a
// question is a sentence, not a document.
constexpr std::size_t kMaxQuestionWords = 60;

using Tokens = std::vector<std::string>;

// ------------------------------------------------------------------ words

struct PredicateWords {
    std::vector<std::string_view> words;
    std::string_view predicate;
};

// Longest first at each start, so "on the left of" wins over "on".
const std::vector<PredicateWords>& predicateWords() {
    static const std::vector<PredicateWords> table = [] {
        std::vector<PredicateWords> t{
            {{"to", "the", "left", "of"}, "left_of"},
            {{"on", "the", "left", "of"}, "left_of"},
            {{"on", "the", "left", "side", "of"}, "left_of"},
            {{"left", "of"}, "left_of"},
            {{"to", "the", "right", "of"}, "right_of"},
            {{"on", "the", "right", "of"}, "right_of"},
            {{"on", "the", "right", "side", "of"}, "right_of"},
            {{"right", "of"}, "right_of"},
            {{"in", "front", "of"}, "in_front_of"},
            {{"in", "back", "of"}, "behind"},
            {{"behind"}, "behind"},
            {{"on", "top", "of"}, "on"},
            {{"on"}, "on"},
            {{"onto"}, "on"},
            {{"upon"}, "on"},
            {{"inside", "of"}, "in"},
            {{"inside"}, "in"},
            {{"in"}, "in"},
            {{"within"}, "in"},
            {{"above"}, "above"},
            {{"over"}, "above"},
            {{"below"}, "below"},
            {{"under"}, "below"},
            {{"underneath"}, "below"},
            {{"beneath"}, "below"},
            {{"near", "to"}, "near"},
            {{"near"}, "near"},
            {{"nearby"}, "near"},
            {{"close", "to"}, "near"},
            {{"next", "to"}, "near"},
            {{"beside"}, "near"},
            {{"besides"}, "near"},
            {{"by"}, "near"},
            {{"around"}, "near"},
            {{"adjacent", "to"}, "near"},
            {{"attached", "to"}, "attached"},
            {{"fixed", "to"}, "attached"},
            {{"mounted", "on"}, "attached"},
            {{"hanging", "on"}, "attached"},
            {{"between"}, "between"},
        };
        std::stable_sort(t.begin(), t.end(),
                         [](const auto& a, const auto& b) { return a.words.size() > b.words.size(); });
        return t;
    }();
    return table;
}

bool isOneOf(const std::string& word, std::initializer_list<std::string_view> words) {
    return std::find(words.begin(), words.end(), word) != words.end();
}

bool isDeterminer(const std::string& w) {
    return isOneOf(w, {"the", "a", "an", "any", "some", "all", "my", "our", "your", "this", "that", "these", "those",
                       "every", "each", "of"});
}

bool isColour(const std::string& w) {
    return isOneOf(w, {"red", "green", "blue", "white", "black", "gray", "grey", "brown", "yellow", "orange", "pink",
                       "purple", "beige", "silver", "gold", "golden"});
}

bool isSideWord(const std::string& w) { return isOneOf(w, {"left", "right", "front", "back"}); }

// Adjectives the memory has no attribute for: left out of the query, and said so.
bool isIgnoredAdjective(const std::string& w) {
    return isOneOf(w, {"big", "small", "large", "little", "tall", "short", "long", "old", "new", "wooden", "round",
                       "square", "other", "single", "only", "nice", "tiny", "huge"});
}

// Words after a noun phrase that end it without being part of a condition.
bool endsPhrase(const std::string& w) {
    return isOneOf(
        w, {"is",      "are",    "was",     "were",      "and",      "that",    "which",      "who",      "there",
            "located", "placed", "sitting", "lying",     "standing", "resting", "kept",       "do",       "does",
            "can",     "could",  "you",     "i",         "we",       "see",     "have",       "relative", "compared",
            "with",    "from",   "to",      "currently", "right",    "now",     "altogether", "total",    "exactly"});
}

// Words for "anything" and kinds of node.
std::optional<std::string> kindTarget(const std::string& w) {
    if (isOneOf(w, {"object", "objects", "thing", "things", "one", "ones", "anything", "everything", "something",
                    "stuff", "item", "items"}))
        return "object";
    if (isOneOf(w, {"anchor", "anchors"})) return "anchor";
    return std::nullopt;
}

// "in the room", "in this scene": the whole scene, no condition.
bool isWholeScene(const std::string& w) {
    return isOneOf(w, {"room", "scene", "house", "place", "space", "home", "apartment"});
}

// Lower case, "what's" -> "what is", punctuation out, numbers kept ("1.5").
Tokens normalise(const std::string& text) {
    std::string s;
    for (std::size_t i = 0; i < text.size(); ++i) {
        unsigned char c = static_cast<unsigned char>(text[i]);
        if (std::isalnum(c))
            s += static_cast<char>(std::tolower(c));
        else if (c == '\'' || c == '-')
            s += static_cast<char>(c);
        else if (c == '.' && i + 1 < text.size() && std::isdigit(static_cast<unsigned char>(text[i + 1])) &&
                 !s.empty() && std::isdigit(static_cast<unsigned char>(s.back())))
            s += '.';
        else if (c >= 0x80)
            s += static_cast<char>(c);  // letters outside ASCII stay, to be named as unknown
        else
            s += ' ';
    }
    static const std::array<std::pair<std::string_view, std::string_view>, 9> contractions{{
        {"'s", " is"},
        {"'re", " are"},
        {"n't", " not"},
        {"'m", " am"},
        {"'ll", " will"},
        {"'ve", " have"},
        {"'d", " would"},
        {"'", " "},
        {"--", " "},
    }};
    for (const auto& [from, to] : contractions)
        for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
            s.replace(at, from.size(), to);
    Tokens out;
    std::istringstream words(s);
    for (std::string w; words >> w;) {
        while (!w.empty() && w.front() == '-') w.erase(w.begin());
        while (!w.empty() && w.back() == '-') w.pop_back();
        if (!w.empty()) out.push_back(w);
    }
    return out;
}

std::string joined(const Tokens& t, std::size_t from, std::size_t to) {
    std::string out;
    for (std::size_t i = from; i < to && i < t.size(); ++i) out += (out.empty() ? "" : " ") + t[i];
    return out;
}

// A name as SMQL writes it: bare when the grammar reads it back as the same name, else quoted.
std::string smqlName(const std::string& name) {
    static const std::regex bare("[a-z_][a-z0-9_]*(-[a-z0-9_]+)*");
    bool reserved = isOneOf(name, {"and", "or", "not", "like"});
    if (std::regex_match(name, bare) && !reserved) return name;
    std::string quoted = "'";
    for (char c : name) quoted += c == '\'' ? std::string("''") : std::string(1, c);
    return quoted + "'";
}

std::string smqlString(const std::string& text) { return "'" + std::regex_replace(text, std::regex("'"), "''") + "'"; }

// ------------------------------------------------------------------ phrases

struct Phrase;

struct Condition {
    std::string predicate;
    std::vector<Phrase> args;
    std::optional<double> metres;  // "within 1 m of the door"
    std::string words;             // "on the desk near the left wall"
};

struct Phrase {
    std::string words;                // as the answer says it: "red mug", "desk near the left wall"
    std::string noun;                 // singular: "mug"
    std::optional<std::string> kind;  // object / anchor: every node of that kind
    std::string side;                 // wall.left: the side
    std::vector<std::string> categories;
    std::optional<std::string> colour;
    std::vector<Condition> conditions;
};

class Parser {
public:
    Parser(const Lexicon& lexicon, Translation& out) : lexicon_(lexicon), out_(out) {}

    // The predicate whose words start at t[i], and how many words they take.
    static std::optional<std::pair<std::string, std::size_t>> predicateAt(const Tokens& t, std::size_t i) {
        // within 1.5 m of x / within 30 cm of x
        if (i + 3 < t.size() && t[i] == "within" && std::regex_match(t[i + 1], std::regex("[0-9]+(\\.[0-9]+)?")) &&
            isOneOf(t[i + 2], {"m", "metre", "metres", "meter", "meters", "cm", "centimetres", "centimeters"}) &&
            t[i + 3] == "of")
            return std::pair{std::string("near"), std::size_t{4}};
        for (const auto& row : predicateWords()) {
            if (i + row.words.size() > t.size()) continue;
            bool match = true;
            for (std::size_t k = 0; k < row.words.size() && match; ++k) match = t[i + k] == row.words[k];
            if (match) return std::pair{std::string(row.predicate), row.words.size()};
        }
        return std::nullopt;
    }

    Phrase phrase(const Tokens& t, std::size_t& i, bool withConditions) {
        Phrase p;
        std::size_t start = i;
        while (i < t.size() && isDeterminer(t[i])) ++i;
        // The answer reads "no desk near the left wall", without the question's article.
        const std::size_t wordsStart = i;
        std::string side;
        std::vector<std::string> nounWords;
        for (; i < t.size(); ++i) {
            const std::string& w = t[i];
            if (predicateAt(t, i) && !(isSideWord(w) && nounWords.empty() && i + 1 < t.size() && t[i + 1] != "of"))
                break;
            if (endsPhrase(w) && !(w == "right" && nounWords.empty())) break;
            if (isColour(w) && !nounWords.empty() && i + 1 == t.size()) break;  // "is the mug red?"
            if (isColour(w) && nounWords.empty()) {
                p.colour = w == "grey" ? "gray" : w;
                continue;
            }
            if (isSideWord(w) && nounWords.empty()) {
                side = w;
                continue;
            }
            if (isIgnoredAdjective(w) && nounWords.empty()) {
                out_.notes.push_back(fmt::format("'{}' is left out: the memory keeps no such attribute", w));
                continue;
            }
            nounWords.push_back(w);
        }
        // "the wall on the left"
        if (side.empty() && i + 2 < t.size() && t[i] == "on" && t[i + 1] == "the" && isSideWord(t[i + 2]) &&
            (i + 3 >= t.size() || (t[i + 3] != "of" && t[i + 3] != "side"))) {
            side = t[i + 2];
            i += 3;
        }
        if (nounWords.empty()) {
            // "the red one" is any red thing; a side alone ("the left") names nothing.
            if (!p.colour || !side.empty()) throw notUnderstood(t, start);
            nounWords.push_back("object");
        }
        resolveNoun(p, nounWords);
        if (!side.empty()) {
            if (p.kind || p.categories.size() != 1)
                throw Error(
                    ErrorKind::Binding,
                    fmt::format("'{} {}' names no side of the room", side, joined(nounWords, 0, nounWords.size())),
                    std::nullopt, "sides are of one category: the left wall, the window on the right");
            p.side = side;
        }
        if (withConditions) conditions(t, i, p);
        p.words = joined(t, wordsStart, i);
        return p;
    }

    // condition (and condition)*, each starting with predicate words.
    void conditions(const Tokens& t, std::size_t& i, Phrase& p) {
        while (i < t.size()) {
            std::size_t at = i;
            if (isOneOf(t[i], {"that", "which"}) && i + 1 < t.size() && isOneOf(t[i + 1], {"is", "are"}))
                at += 2;
            else if (t[i] == "and" && !p.conditions.empty())
                at += 1;
            while (at < t.size() &&
                   isOneOf(t[at], {"located", "placed", "sitting", "lying", "standing", "resting", "kept"}))
                ++at;
            auto pred = predicateAt(t, at);
            if (!pred) return;
            i = at;
            // "in the room": the whole scene.
            std::size_t after = i + pred->second;
            while (after < t.size() && isDeterminer(t[after])) ++after;
            if (pred->first == "in" && after < t.size() && isWholeScene(t[after]) &&
                (after + 1 == t.size() || !predicateAt(t, after + 1))) {
                i = after + 1;
                continue;
            }
            p.conditions.push_back(condition(t, i, *pred));
        }
    }

    Condition condition(const Tokens& t, std::size_t& i, const std::pair<std::string, std::size_t>& pred) {
        Condition c;
        c.predicate = pred.first;
        std::size_t start = i;
        if (t[i] == "within" && pred.second == 4) {
            double value = std::stod(t[i + 1]);
            c.metres = t[i + 2].starts_with("c") ? value / 100.0 : value;
        }
        i += pred.second;
        if (c.predicate == "between") {
            c.args.push_back(phrase(t, i, false));
            if (i >= t.size() || t[i] != "and")
                throw Error(ErrorKind::Binding, "'between' needs two things: between the sofa and the lamp",
                            std::nullopt, "ask as in: what is between the sofa and the lamp?");
            ++i;
        }
        c.args.push_back(phrase(t, i, true));
        c.words = joined(t, start, i);
        return c;
    }

    Error notUnderstood(const Tokens& t, std::size_t at) const {
        return Error(ErrorKind::Binding,
                     fmt::format("cannot read a thing to look for in '{}'", joined(t, at, t.size())), std::nullopt,
                     "name something the scene holds, as in: what is on the sofa?");
    }

private:
    void resolveNoun(Phrase& p, const std::vector<std::string>& nounWords) {
        std::string all = joined(nounWords, 0, nounWords.size());
        if (nounWords.size() == 1) {
            if (auto kind = kindTarget(nounWords[0])) {
                p.kind = *kind;
                p.noun = "thing";
                return;
            }
        }
        // The whole phrase first ("coffee table", "wall plug"), then its last word ("table").
        WordMatch match = lexicon_.lookUp(all);
        std::string word = all;
        // A phrase that names nothing here as a whole ("coffee mug", "ceiling fan") is read by its
        // last word, unless WordNet maps the whole to kinds the scene has.
        if (nounWords.size() > 1 && !isNamed(match) && match.how != WordMatch::How::Kind) {
            WordMatch head = lexicon_.lookUp(nounWords.back());
            out_.notes.push_back(fmt::format("'{}' is read as '{}'", all, nounWords.back()));
            match = head;
            word = nounWords.back();
        }
        p.noun = match.lemma;
        if (match.how == WordMatch::How::Unknown) {
            unknownWords_.push_back(word);
            return;
        }
        p.categories = match.categories;
        bool said =
            std::any_of(out_.mappings.begin(), out_.mappings.end(), [&](const auto& m) { return m.word == word; });
        if (match.how != WordMatch::How::Category && !said)
            out_.mappings.push_back(WordMapping{word, match.categories, describe(match.how)});
    }

    static bool isNamed(const WordMatch& m) {
        return m.how == WordMatch::How::Category || m.how == WordMatch::How::Plural || m.how == WordMatch::How::Synonym;
    }

    const Lexicon& lexicon_;
    Translation& out_;
    std::vector<std::string> unknownWords_;

public:
    // Words neither the scene nor WordNet knows: the answer names them and nothing runs.
    const std::vector<std::string>& unknownWords() const { return unknownWords_; }
};

// ------------------------------------------------------------------ SMQL

struct Smql {
    std::string target;
    std::vector<std::string> where;
};

std::string reference(const Phrase& p);

std::string conditionText(const Condition& c) {
    std::string args;
    for (const auto& a : c.args) args += (args.empty() ? "" : ", ") + reference(a);
    if (c.metres) {
        // SMQL numbers have no exponent: fixed decimals, trailing zeros dropped ("1.5", "100").
        std::string metres = fmt::format("{:.3f}", *c.metres);
        metres.erase(metres.find_last_not_of('0') + 1);
        if (metres.back() == '.') metres.pop_back();
        args += ", " + metres + " m";
    }
    return fmt::format("{}({})", c.predicate, args);
}

Smql targetOf(const Phrase& p) {
    Smql s;
    if (p.kind) {
        s.target = *p.kind;
    } else if (!p.side.empty()) {
        s.target = smqlName(p.categories.front()) + "." + p.side;
    } else if (p.categories.size() == 1) {
        s.target = smqlName(p.categories.front());
    } else {
        // Several categories, or none (an English noun the scene lacks: the answer is "none").
        s.target = "node";
        std::string any;
        const std::vector<std::string> names = p.categories.empty() ? std::vector<std::string>{p.noun} : p.categories;
        for (const auto& c : names) any += (any.empty() ? "" : " OR ") + fmt::format("category = {}", smqlString(c));
        s.where.push_back(names.size() > 1 ? "(" + any + ")" : any);
    }
    if (p.colour) s.where.push_back(fmt::format("color = {}", smqlString(*p.colour)));
    for (const auto& c : p.conditions) s.where.push_back(conditionText(c));
    return s;
}

std::string whereText(const std::vector<std::string>& where) {
    std::string out;
    for (const auto& w : where) out += (out.empty() ? " WHERE " : " AND ") + w;
    return out;
}

std::string reference(const Phrase& p) {
    Smql s = targetOf(p);
    if (s.where.empty()) return s.target;
    return "(FIND " + s.target + whereText(s.where) + ")";
}

std::string findText(const Phrase& p, bool path) {
    Smql s = targetOf(p);
    return "FIND " + s.target + whereText(s.where) + (path ? " PATH" : "");
}

std::string countText(const Phrase& p) {
    Smql s = targetOf(p);
    return "COUNT " + s.target + whereText(s.where);
}

// ------------------------------------------------------------------ question forms

struct Form {
    QuestionKind kind;
    std::regex pattern;  // over the normalised question; groups are the phrases
};

const std::vector<Form>& forms() {
    using K = QuestionKind;
    auto re = [](const char* p) { return std::regex(p, std::regex::optimize); };
    static const std::vector<Form> table{
        {K::Guidance, re("^(?:how|where) (?:do|can|could|would|should|shall) (?:i|we|you) (?:get|go|walk|reach|find my "
                         "way)(?: to)? (.+?) from (.+)$")},
        {K::Guidance, re("^(?:how|where) (?:do|can|could|would|should|shall) (?:i|we|you) (?:get|go|walk|find my way) "
                         "from (.+?) to (.+)$")},
        {K::Guidance, re("^(?:please )?(?:take|guide|lead|bring|show) (?:me|us) (?:the way )?from (.+?) to (.+)$")},
        {K::Guidance, re("^(?:please )?(?:take|guide|lead|bring|show) (?:me|us) (?:the way )?to (.+?) from (.+)$")},
        {K::Guidance, re("^what is the (?:way|route|path) from (.+?) to (.+)$")},
        {K::RelativePosition,
         re("^where (?:is|are) (.+?) (?:relative to|in relation to|compared to|with respect to|from) (.+)$")},
        {K::RelativePosition, re("^how (?:is|are) (.+?) (?:placed |positioned |located |oriented )?(?:relative to|in "
                                 "relation to|with respect to) (.+)$")},
        {K::RelativePosition, re("^(?:what is|how is|describe) the (?:relation|relationship|spatial relation|position) "
                                 "(?:between|of) (.+?) (?:and|to|relative to) (.+)$")},
        {K::RelativePosition, re("^how (?:does|do) (.+?) relate to (.+)$")},
        {K::Count, re("^(?:how many|count|count the|count all|count all the|number of|what is the number of|tell me "
                      "how many) (.+)$")},
        {K::Existence, re("^(?:is|are) there (.+)$")},
        {K::Existence, re("^(?:do|can|did) (?:you|i|we) (?:see|have|own|find|notice) (.+)$")},
        {K::Existence, re("^(?:does|do) (?:the|this|my|our) (?:room|scene|place|house|home|apartment) "
                          "(?:have|contain|include|hold) (.+)$")},
        {K::Existence, re("^((?:any|anything|something) .+)$")},
        {K::Locate, re("^where (?:exactly )?(?:is|are|was|were|would|do|did|can|could) (?:i find |i leave |i put |i "
                       "see |we find |one find )?(.+?)(?: located| kept| placed| be)?$")},
        {K::Locate, re("^where (.+?) (?:is|are|was|were)(?: located| kept)?$")},
        {K::Locate, re("^(?:find|locate|where) (.+)$")},
        {K::Relational, re("^(?:what|which) ?(.*?) (?:is|are|sits|sit|lies|lie|stands|stand|rests|rest|hangs|hang|do "
                           "you see|can you see|can i find|do i have|is there|are there)(?: located| placed| lying| "
                           "sitting| standing| resting| kept)? (.+)$")},
        {K::Relational, re("^(?:show|list|give|tell)(?: me)?(?: about)?(?: all)?(?: of)? (.+)$")},
        {K::YesNo, re("^(?:is|are) (.+)$")},
        {K::YesNo, re("^(?:does|do) (.+?) (?:stand|stands|sit|sits|lie|lies|hang|hangs|rest|rests|be)( .+)$")},
    };
    return table;
}

Error cannotTranslate(const std::string& question) {
    return Error(ErrorKind::Binding, fmt::format("cannot translate the question '{}'", question), std::nullopt,
                 "ask as in: where is the mug? what is on the desk? is there a sofa? how many chairs are near the "
                 "table? is the lamp left of the window? (docs/ask.md)");
}

class RuleTranslator final : public Translator {
public:
    Translation translate(const Question& question) const override {
        Tokens tokens = normalise(question.text);
        if (tokens.size() > kMaxQuestionWords)
            throw Error(
                ErrorKind::Binding,
                fmt::format("the question has {} words; ASK reads at most {}", tokens.size(), kMaxQuestionWords),
                std::nullopt, "ask one short question at a time");
        // Politeness and filler at the start: "please", "can you tell me", "could you show me".
        static const std::regex lead(
            "^(?:please |hey |ok |so |now |and |excuse me |(?:can|could|would) you (?:please )?(?:tell me |say )?|tell "
            "me |i want to know |i wonder )+");
        std::string text = std::regex_replace(joined(tokens, 0, tokens.size()), lead, "");
        text = std::regex_replace(text, std::regex(" please$"), "");
        if (text.empty()) throw cannotTranslate(question.text);
        Lexicon lexicon(question.categories);
        for (const auto& form : forms()) {
            std::smatch m;
            if (!std::regex_match(text, m, form.pattern)) continue;
            Translation out;
            out.kind = form.kind;
            Parser parser(lexicon, out);
            if (!build(form.kind, m, parser, out)) continue;
            if (!parser.unknownWords().empty()) {
                out.kind = QuestionKind::UnknownWord;
                out.runnable = false;
                for (const auto& w : parser.unknownWords())
                    out.notes.push_back(fmt::format("I do not know the word '{}'", w));
            }
            return out;
        }
        throw cannotTranslate(question.text);
    }

private:
    // Fills `out` from the pattern's groups; false when the groups do not read as that form (the
    // next form is tried).
    static bool build(QuestionKind kind, const std::smatch& m, Parser& parser, Translation& out) {
        switch (kind) {
            case QuestionKind::Guidance: {
                bool fromFirst = m.str(0).find(" from ") < m.str(0).find(" to ");
                Phrase destination = whole(parser, fromFirst ? m.str(2) : m.str(1));
                Phrase start = whole(parser, fromFirst ? m.str(1) : m.str(2));
                out.smql = fmt::format("GUIDE FROM {} TO {}", reference(start), reference(destination));
                out.subject = destination.words;
                out.object = start.words;
                return true;
            }
            case QuestionKind::RelativePosition: {
                Phrase a = whole(parser, m.str(1)), b = whole(parser, m.str(2));
                out.smql = fmt::format("RELATE {} TO {}", reference(a), reference(b));
                describeSubject(a, out);
                out.object = b.words;
                return true;
            }
            case QuestionKind::Count: {
                Phrase p = subjectWithConditions(parser, m.str(1));
                out.smql = countText(p);
                describeSubject(p, out);
                return true;
            }
            case QuestionKind::Existence: {
                Phrase p = subjectWithConditions(parser, m.str(1));
                out.smql = findText(p, false);
                describeSubject(p, out);
                return true;
            }
            case QuestionKind::Locate: {
                Tokens t = normalise(m.str(1));
                std::size_t i = 0;
                Phrase p = parser.phrase(t, i, true);
                if (i != t.size()) return false;
                out.smql = findText(p, true);
                describeSubject(p, out);
                return true;
            }
            case QuestionKind::Relational: {
                Tokens t = normalise(m.str(m.size() - 1));
                Phrase p;
                std::size_t i = 0;
                if (m.size() == 3) {
                    // what [objects] are <conditions>
                    std::string what = m.str(1);
                    if (!Parser::predicateAt(t, 0)) return false;
                    Tokens w = normalise(what.empty() ? "object" : what);
                    std::size_t k = 0;
                    p = parser.phrase(w, k, false);
                    if (k != w.size()) return false;
                    parser.conditions(t, i, p);
                } else {
                    // show me <phrase with conditions>
                    p = parser.phrase(t, i, true);
                    if (!p.kind && p.conditions.empty()) {
                        out.kind = QuestionKind::Locate;
                        if (i != t.size()) return false;
                        out.smql = findText(p, true);
                        describeSubject(p, out);
                        return true;
                    }
                }
                if (i != t.size() || p.conditions.empty()) return false;
                out.smql = findText(p, false);
                describeSubject(p, out);
                return true;
            }
            case QuestionKind::YesNo: {
                Tokens t = normalise(m.str(1) + (m.size() > 2 ? m.str(2) : ""));
                std::size_t i = 0;
                Phrase subject = parser.phrase(t, i, false);
                // "is the mug red?": whether there is such a thing.
                if (i + 1 == t.size() && isColour(t[i]) && !subject.colour) {
                    subject.colour = t[i] == "grey" ? "gray" : t[i];
                    out.kind = QuestionKind::Existence;
                    out.smql = findText(subject, false);
                    describeSubject(subject, out);
                    return true;
                }
                Phrase checked;
                checked.noun = subject.noun;
                parser.conditions(t, i, checked);
                if (i != t.size() || checked.conditions.size() != 1) return false;
                const Condition& c = checked.conditions.front();
                describeSubject(subject, out);
                out.predicate = c.predicate;
                out.condition = c.words;
                if (c.predicate == "between" || c.metres) {
                    // RELATE compares two things; "between" takes three, a distance is a question of its own.
                    subject.conditions.push_back(c);
                    out.smql = findText(subject, false);
                    out.kind = QuestionKind::Existence;
                    return true;
                }
                out.object = c.args.front().words;
                out.smql = fmt::format("RELATE {} TO {}", reference(subject), reference(c.args.front()));
                return true;
            }
            case QuestionKind::UnknownWord:
                return false;
        }
        return false;
    }

    static Phrase whole(Parser& parser, const std::string& text) {
        Tokens t = normalise(text);
        std::size_t i = 0;
        Phrase p = parser.phrase(t, i, true);
        if (i != t.size()) throw parser.notUnderstood(t, i);
        return p;
    }

    // "chairs are near the table", "chairs near the table", "pianos", "mugs do you see on the desk"
    static Phrase subjectWithConditions(Parser& parser, const std::string& text) {
        Tokens t = normalise(text);
        std::size_t i = 0;
        Phrase p = parser.phrase(t, i, true);
        while (i < t.size() && endsPhrase(t[i]) && t[i] != "and") ++i;
        parser.conditions(t, i, p);
        while (i < t.size() && endsPhrase(t[i]) && t[i] != "and") ++i;
        if (i != t.size()) throw parser.notUnderstood(t, i);
        return p;
    }

    static void describeSubject(const Phrase& p, Translation& out) {
        std::string adjectives = p.colour ? *p.colour + " " : "";
        std::string noun = !p.side.empty() ? p.side + " " + p.noun : p.noun;
        out.subject = adjectives + noun;
        out.subjectPlural = adjectives + pluralOf(noun);
        std::string condition;
        for (const auto& c : p.conditions) condition += (condition.empty() ? "" : " and ") + c.words;
        if (out.condition.empty()) out.condition = condition;
    }
};

}  // namespace

const Translator& ruleTranslator() {
    static const RuleTranslator translator;
    return translator;
}

std::string_view toString(QuestionKind kind) {
    switch (kind) {
        case QuestionKind::Locate:
            return "locate";
        case QuestionKind::Relational:
            return "relational";
        case QuestionKind::YesNo:
            return "yes/no";
        case QuestionKind::Existence:
            return "existence";
        case QuestionKind::Count:
            return "count";
        case QuestionKind::RelativePosition:
            return "relative position";
        case QuestionKind::Guidance:
            return "guidance";
        case QuestionKind::UnknownWord:
            return "unknown word";
    }
    return {};
}

}  // namespace smql::ask
