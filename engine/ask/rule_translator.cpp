// The built-in translator: a recursive-descent reader of English questions. A question is cut into
// words (phrase.hpp), its opening words say which kind of question it is, and each kind reads the
// rest with the phrase grammar:
//   question   := lead* ( room-kind | where-am-i | direction | guidance | distance | size | attribute
//                       | choice | affordance | seating | visibility | changes | count | existence
//                       | relative | locate | relational | yes-no ) unit?
//   room-kind  := "what kind of room is this" | "what room am i in" | "is this" "a"? room
//   where-am-i := "where am i"                      (the thing nearest where the person stands)
//   direction  := "if"? "i am"? "standing" place phrase "and"? "facing" phrase "is" phrase side-choices
//   guidance   := ("how do i get" | "take me" | "what is the way" | "navigate" | "directions")
//                 ("from" phrase | "to" phrase)+
//   distance   := "how far is" phrase (("from" | "to") phrase)? | "how far am i from" phrase
//                 | "is" phrase "far" ("from" phrase)?
//                 | "what is the distance between" phrase "and" phrase      ("me", "here": the person)
//   size       := "how" size-word "is" phrase | "what is the" measure "of" phrase
//   choice     := "which of these" (A, B, ...) "is" order | "which is" order "," A "or" B
//   affordance := (("where" | "what") "can i" | "is there" "anything"? ("i can")? | "anything to"
//                  | ("find" | "show") "me"? "something to" | "show me where") verb
//                 phrase? preposition?
//   seating    := "how many" "people"? "can sit" ("here" | "on" phrase | "at" phrase)?
//   count      := "how many" phrase posts ("do" phrase "have")?
//   ...
// A form is tried when its opening words match; the first form that reads the whole question wins.
#include <algorithm>
#include <array>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <regex>

#include <fmt/format.h>

#include "engine/ask/lexicon.hpp"
#include "engine/ask/phrase.hpp"
#include "engine/ask/readers.hpp"
#include "engine/ask/situation.hpp"
#include "engine/ask/translator.hpp"
#include "engine/ask/units.hpp"
#include "engine/ask/wordnet.hpp"
#include "model/category.hpp"
#include "model/error.hpp"
#include "model/names.hpp"
#include "relations/predicates.hpp"

namespace smql::ask {

namespace {

// The room (or the scene, the house ...) named as a thing: the memory holds its things and walls, not it.
std::string roomNotHeld(const std::string& word) {
    return fmt::format("the {} itself is not a thing the memory holds: its sides and ends are not stored", word);
}

// Why a word the question needs names nothing the memory holds.
std::string unknownWordNote(const std::string& word) {
    // "where is the door from here?": the person, whose sides a situation gives.
    if (word == "here")
        return "'here', where you stand, is no thing the memory holds: ask how far a thing is from you, or say "
               "where you are first ('I am sitting on the bed facing the window. Is the door on my left?')";
    if (namesWholeScene(word))
        return roomNotHeld(word) +
               " (ask by a thing or a wall the room holds, or what is in the middle of the room or in its corners)";
    return fmt::format("I do not know the word '{}'", word);
}

// What a question asks for where it names no thing ("what is on the desk?"): any thing of `kind`.
Phrase anyThing(const char* kind) {
    Phrase thing;
    thing.noun = "thing";
    thing.kind = kind;
    return thing;
}

// Longer questions are refused before the recursive descent: each condition nests a phrase, and a
// question is a sentence, not a document.
constexpr std::size_t kMaxQuestionWords = 60;

// Words without which a question asks no order of first sight (read_appearance.cpp): the rest skip its patterns.
constexpr std::array<std::string_view, 6> kOrderWords{"appear", "seen", "first", "last", "order", "before"};

// What a person can do with things, and the words for the things that afford it: each word goes
// through the Lexicon like a noun of the question ("seat" -> chair, sofa, stool). The verbs' forms
// ("sitting", "sat") reach them through WordNet's base forms.
struct AffordanceRow {
    std::string_view verb;
    std::string_view things;  // words, ' ' between them
    std::string_view how;     // the answer: "You can sit on ..."
};
constexpr AffordanceRow kAffordances[] = {
    {"sit", "seat chair sofa stool bench", "sit on"},
    {"lie", "bed sofa", "lie on"},
    {"sleep", "bed sofa", "sleep on"},
    {"rest", "bed sofa seat", "rest on"},
    {"put", "table desk counter shelf", "put things on"},
    {"place", "table desk counter shelf", "put things on"},
    {"set", "table desk counter shelf", "put things on"},
    {"store", "cabinet shelf drawer box basket wardrobe dresser", "store things in"},
    {"keep", "cabinet shelf drawer box basket wardrobe dresser", "keep things in"},
    {"open", "door window cabinet drawer refrigerator box wardrobe microwave oven", "open"},
    {"work", "desk table", "work at"},
    {"eat", "table counter", "eat at"},
    {"cook", "stove oven microwave", "cook with"},
    {"wash", "sink bathtub shower", "wash at"},
    {"watch", "tv television monitor", "watch"},
    {"read", "book lamp", "read with"},
    {"throw", "wastebasket", "throw things in"},
    {"dispose", "wastebasket", "throw things in"},
    {"charge", "wall-plug socket power-outlet electrical-outlet", "charge things at"},
    {"plug", "wall-plug socket power-outlet electrical-outlet", "plug things into"},
    {"hang", "hook coat-rack coat-hanger hanger wardrobe closet", "hang things on"},
};

const AffordanceRow& affordanceOf(std::string_view verb) {
    return *std::find_if(std::begin(kAffordances), std::end(kAffordances),
                         [verb](const AffordanceRow& r) { return r.verb == verb; });
}

// "the object used for disposing of waste", "a container used to throw away trash": the thing the
// use names (kAffordances), as a noun the phrase grammar reads; the text as it was when the verb
// affords nothing.
std::string thingByUse(const std::string& plain) {
    static const std::regex used(
        R"(\b(?:object|thing|item|container|one|device)s? (?:that (?:is|are) |which (?:is|are) |(is|are) )?used (?:to|for) (\w+)(?: (?:of|away|out|up))?(?: (?:the |some |a |my |your )?(?:waste|trash|garbage|rubbish|litter|paper|things|stuff))?)");
    // "the nearest place to sit", "a spot to sleep near the window": the thing the use names, where more is said of
    // the place than that there is one ("is there a place to sit?" stays a question of where one can).
    static const std::regex nearestPlace(
        R"(\b(closest|nearest|farthest|furthest) (?:place|spot) to (\w+)(?: (?:on|in|at|down))?\b)");
    static const std::regex placeBy(
        R"(\b()(?:place|spot) to (\w+)(?: (?:on|in|at|down))?(?= (?:near|next to|by|beside|close to|in front of|behind)\b))");
    // "how do I get out?", "how can we leave the room?": the way out is the nearest door.
    static const std::regex wayOut(
        R"(^(how (?:do|can|could|should|would|will) (?:i|we|one) )(?:get out|leave|exit|go out)(?: (?:of )?(?:the|this|here) ?(?:room|place|house|apartment|flat|building|office)?)?$)");
    std::smatch m;
    if (std::regex_match(plain, m, wayOut)) return m.str(1) + "get to the nearest door";
    for (const std::regex* place : {&nearestPlace, &placeBy}) {
        if (!std::regex_search(plain, m, *place)) continue;
        for (const auto& base : wordnet::baseForms(m.str(2)))
            for (const auto& row : kAffordances)
                if (row.verb == base)
                    return m.prefix().str() + (m.length(1) ? m.str(1) + " " : "") +
                           std::string(row.things.substr(0, row.things.find(' '))) + m.suffix().str();
    }
    if (!std::regex_search(plain, m, used)) return plain;
    for (const auto& base : wordnet::baseForms(m.str(2)))
        for (const auto& row : kAffordances)
            if (row.verb == base) {
                const std::string thing(row.things.substr(0, row.things.find(' ')));
                // "what color container is used for ...": what color is that thing.
                return m.prefix().str() + thing + (m[1].matched ? " " + m.str(1) : "") + m.suffix().str();
            }
    return plain;
}

// The measure a size question asks for: "how tall" -> height.
struct SizeWord {
    std::string_view word;
    std::string_view measure;
};
constexpr SizeWord kSizeWords[] = {
    {"big", "size"},        {"large", "size"},      {"tall", "height"},    {"high", "height"},
    {"wide", "width"},      {"long", "longest"},    {"deep", "depth"},     {"size", "size"},
    {"height", "height"},   {"width", "width"},     {"length", "longest"}, {"depth", "depth"},
    {"volume", "volume"},   {"dimensions", "size"}, {"dimension", "size"}, {"measurements", "size"},
    {"thickness", "depth"}, {"area", "size"},
};

std::optional<std::string_view> sizeMeasure(const std::string& w) {
    for (const auto& s : kSizeWords)
        if (s.word == w) return s.measure;
    return std::nullopt;
}

// One reading of the words: a cursor with the look-ahead a recursive descent needs.
struct Cursor {
    const Words& w;
    std::size_t i = 0;

    bool done() const { return i >= w.size(); }
    const std::string& peek(std::size_t k = 0) const {
        static const std::string none;
        return i + k < w.size() ? w[i + k] : none;
    }
    // The words of `seq` at the cursor: each position may offer alternatives split by '|'.
    bool accept(std::initializer_list<std::string_view> seq) {
        std::size_t k = i;
        for (std::string_view alternatives : seq) {
            if (k >= w.size()) return false;
            bool any = false;
            for (std::string_view rest = alternatives; !rest.empty() && !any;) {
                std::size_t bar = rest.find('|');
                any = w[k] == rest.substr(0, bar);
                rest = bar == std::string_view::npos ? std::string_view{} : rest.substr(bar + 1);
            }
            if (!any) return false;
            ++k;
        }
        i = k;
        return true;
    }
    // Skips any of these words, but not one that begins a predicate's phrase ("hanging from").
    void skip(std::initializer_list<std::string_view> words) {
        while (!done() && isOneOf(w[i], words) && !PhraseParser::predicateAt(w, i)) ++i;
    }
};

Error cannotTranslate(const std::string& question, const std::string& detail, const std::string& suggestion) {
    return Error(ErrorKind::Binding, fmt::format("cannot translate the question '{}'{}", question, detail),
                 std::nullopt,
                 suggestion.empty() ? "ask as in: where is the mug? what is on the desk? how many chairs are near the "
                                      "table? how far is the sofa from the door? (docs/ask.md)"
                                    : "did you mean: " + suggestion + " (docs/ask.md lists the questions ASK reads)");
}

// Verbs of place and adverbs between a subject and its predicate say no more than it does: "the cabinet is directly
// next to what?", "a kitchen cabinet is installed to the right of what?".
const std::initializer_list<std::string_view> kPlacedBy{
    "located", "placed",   "sitting",    "standing", "hanging", "lying",     "resting",    "kept", "sit",
    "stand",   "hang",     "lie",        "rest",     "attach",  "installed", "mounted",    "set",  "put",
    "found",   "situated", "positioned", "directly", "right",   "just",      "immediately"};

class QuestionReader {
public:
    QuestionReader(const Question& q, const Lexicon& lexicon) : question_(q), lexicon_(lexicon) {}

    Translation read(const std::string& text) {
        words_ = words(text);
        takeUnit();
        takeOnAverage();
        takeHeightAboveFloor();
        takeRoomSides();
        using Form = bool (QuestionReader::*)(Cursor&, PhraseParser&, Translation&);
        static constexpr Form forms[] = {
            &QuestionReader::roomKind,   &QuestionReader::roomPlace,   &QuestionReader::whereAmI,
            &QuestionReader::direction,  &QuestionReader::guidance,    &QuestionReader::roomToWalk,
            &QuestionReader::distance,   &QuestionReader::size,        &QuestionReader::attributeTally,
            &QuestionReader::attribute,  &QuestionReader::affordance,  &QuestionReader::seating,
            &QuestionReader::visibility, &QuestionReader::changes,     &QuestionReader::mostHeld,
            &QuestionReader::mostCommon, &QuestionReader::perRoom,     &QuestionReader::count,
            &QuestionReader::existence,  &QuestionReader::side,        &QuestionReader::eitherSide,
            &QuestionReader::relative,   &QuestionReader::superlative, &QuestionReader::sorted,
            &QuestionReader::reverse,    &QuestionReader::locate,      &QuestionReader::relational,
            &QuestionReader::comparedTo, &QuestionReader::sameAs,      &QuestionReader::comparison,
            &QuestionReader::yesNo,      &QuestionReader::description, &QuestionReader::state,
            &QuestionReader::named,
        };
        // A form whose words fit but whose phrases do not read says why, unless a later form reads
        // the question.
        std::optional<Error> firstError;
        for (Form form : forms) {
            Translation out;
            out.unit = unit_;
            PhraseParser parser(lexicon_, out, question_.planeCategories, question_.scene, question_.sceneCount);
            parser.setSelf(self_);
            Cursor c{words_};
            try {
                if (!(this->*form)(c, parser, out) || !c.done()) continue;
            } catch (const Error& e) {
                // The generic "cannot read a thing" gives way to an error that says more.
                bool generic = e.message().starts_with("cannot read a thing");
                if (!firstError || (!generic && firstError->message().starts_with("cannot read a thing")))
                    firstError = e;
                continue;
            }
            // "how tall are the tables on average?": the mean of a size or a distance; of anything else, each answer.
            if (averageAsked_ && (out.kind == QuestionKind::Size || out.kind == QuestionKind::Distance))
                out.average = true;
            else if (averageAsked_)
                out.notes.push_back("'on average' is left out: ASK averages sizes and distances only");
            if (!parser.unknownWords().empty()) {
                out.kind = QuestionKind::UnknownWord;
                out.runnable = false;
                for (const auto& w : parser.unknownWords()) out.notes.push_back(unknownWordNote(w));
            }
            return out;
        }
        if (firstError) throw *firstError;
        throw unreadable();
    }

    // "which of these objects (sofa, tv, bed) ...": the choices, cut from the text before the words are.
    void setChoices(std::vector<std::string> choices) { choices_ = std::move(choices); }
    // After a situation: "me" and "my left" (situation.hpp).
    void setSelf(std::optional<Self> self) { self_ = std::move(self); }

private:
    // "on the left side of the room", "at the far end of this room": along that wall. The room's sides are its walls,
    // named as the viewpoint sees them (wall.left ... in SMQL; the far end is the back wall).
    void takeRoomSides() {
        Translation scratch;
        std::optional<PhraseParser> places;  // made for the first "the <side> <part> of"
        for (std::size_t k = 0; k + 4 < words_.size(); ++k) {
            if (words_[k] != "the" || !isOneOf(words_[k + 1], {"left", "right", "back", "front", "far", "rear"}) ||
                !isOneOf(words_[k + 2], {"side", "end", "part", "half", "wall"}) || words_[k + 3] != "of")
                continue;
            std::size_t at = k + 4;
            if (isOneOf(words_[at], {"the", "this", "my", "our"})) ++at;
            if (!places)
                places.emplace(lexicon_, scratch, question_.planeCategories, question_.scene, question_.sceneCount);
            const std::size_t place = places->scenePlaceAt(words_, at);
            if (place == 0) continue;
            const std::string side = isOneOf(words_[k + 1], {"far", "rear"}) ? "back" : words_[k + 1];
            // "the left wall of the room" is the left wall; "on the left side of the room" is along it.
            const bool wall = words_[k + 2] == "wall";
            words_.erase(words_.begin() + static_cast<std::ptrdiff_t>(k + 1),
                         words_.begin() + static_cast<std::ptrdiff_t>(at + place));
            words_.insert(words_.begin() + static_cast<std::ptrdiff_t>(k + 1), {side, "wall"});
            if (!wall && k > 0 && isOneOf(words_[k - 1], {"on", "in", "at"})) words_[k - 1] = "near";
        }
    }

    // How high a thing is up, not how tall it is: "at what height is the tv?", "what height is the tv at?", "how high
    // up is the shelf?", "how high is the tv mounted?" read as "how high off the floor is the tv?" (the size form's
    // height above the floor).
    void takeHeightAboveFloor() {
        auto at = [&](std::size_t k, std::initializer_list<std::string_view> options) {
            return k < words_.size() && isOneOf(words_[k], options);
        };
        std::size_t lead = 0;  // the words before "is|are"
        bool trailing = false;
        if (at(0, {"at"}) && at(1, {"what", "which"}) && at(2, {"height"}))
            lead = 3;
        else if (at(0, {"what"}) && at(1, {"height"}) && words_.size() > 3 && words_.back() == "at")
            lead = 2, trailing = true;
        else if (at(0, {"how"}) && at(1, {"high"}) && at(2, {"up"}))
            lead = 3;
        else if (at(0, {"how"}) && at(1, {"high"}) && words_.size() > 3 &&
                 isOneOf(words_.back(), {"hung", "mounted", "placed", "hanging", "installed", "located", "positioned",
                                         "set", "fixed", "attached", "put"}))
            lead = 2, trailing = true;
        if (lead == 0 || !at(lead, {"is", "are"})) return;
        Words rewritten{"how", "high", "off", "the", "floor", words_[lead]};
        rewritten.insert(rewritten.end(), words_.begin() + static_cast<std::ptrdiff_t>(lead + 1),
                         words_.end() - (trailing ? 1 : 0));
        if (rewritten.size() > 6) words_ = std::move(rewritten);
    }

    // "on average", "on the average" anywhere, "the average distance": the mean of what is asked (averageAsked_), not
    // a thing.
    void takeOnAverage() {
        for (std::size_t k = 0; k + 1 < words_.size(); ++k) {
            if (isOneOf(words_[k], {"average", "mean"}) && words_[k + 1] == "distance") {
                words_.erase(words_.begin() + static_cast<std::ptrdiff_t>(k));
                averageAsked_ = true;
                return;
            }
            const std::size_t the = words_[k + 1] == "the" ? 1 : 0;
            if (words_[k] != "on" || k + 1 + the >= words_.size() || words_[k + 1 + the] != "average") continue;
            words_.erase(words_.begin() + static_cast<std::ptrdiff_t>(k),
                         words_.begin() + static_cast<std::ptrdiff_t>(k + 2 + the));
            averageAsked_ = true;
            return;
        }
    }

    // The answer's unit, however the question names it: "(in meters)", "(cm)" (RuleTranslator
    // moves a unit in parentheses to the end), "measured in centimeters", "in feet", "how far in
    // metres is ...", "how many centimeters long is ...", "in square meters". The words go; the
    // unit is the translation's (units.hpp).
    void takeUnit() {
        auto unitAt = [&](std::size_t k) { return k < words_.size() ? lengthUnitNamed(words_[k]) : nullptr; };
        // "in [square] <unit>" anywhere: "how far in metres is the sofa from the door?"
        for (std::size_t k = 0; k + 1 < words_.size(); ++k) {
            if (words_[k] != "in") continue;
            std::size_t u = k + 1;
            bool square = words_[u] == "square" || words_[u] == "sq";
            if (square) ++u;
            if (!unitAt(u) && u + 2 < words_.size() && isOneOf(words_[u], {"units", "unit"}) && words_[u + 1] == "of")
                u += 2;  // "in units of meters"
            if (!unitAt(u)) continue;
            unit_ = square ? "m^2" : std::string(unitAt(u)->symbol);
            std::size_t from = k;
            while (from > 0 && isOneOf(words_[from - 1], {"measured", "given", "expressed", "answered", "answer"}))
                --from;
            words_.erase(words_.begin() + static_cast<std::ptrdiff_t>(from),
                         words_.begin() + static_cast<std::ptrdiff_t>(u + 1));
            break;
        }
        // "how many square meters is the room?": its size.
        if (words_.size() > 4 && words_[0] == "how" && words_[1] == "many" && isOneOf(words_[2], {"square", "sq"}) &&
            unitAt(3)) {
            unit_ = "m^2";
            words_.erase(words_.begin() + 1, words_.begin() + 4);
            words_.insert(words_.begin() + 1, "big");
            if (isOneOf(words_[2], {"does", "do"})) words_.erase(words_.begin() + 2);  // "does the room have"
            if (words_.back() == "have" || words_.back() == "cover") words_.pop_back();
            if (!isOneOf(words_[2], {"is", "are"})) words_.insert(words_.begin() + 2, "is");
        }
        // "how many meters is the sofa from the door?", "how many centimeters tall is the lamp?"
        if (words_.size() > 3 && words_[0] == "how" && words_[1] == "many" && unitAt(2)) {
            unit_ = std::string(unitAt(2)->symbol);
            words_.erase(words_.begin() + 1, words_.begin() + 3);
            if (isOneOf(words_[1], {"away", "apart"}))
                words_[1] = "far";
            else if (!isOneOf(words_[1], {"long", "tall", "wide", "high", "deep", "far", "big", "large"}))
                words_.insert(words_.begin() + 1, "far");
        }
        if (!words_.empty() && words_.back() == "measured") words_.pop_back();
    }

    // ------------------------------------------------------------ forms

    // If I am standing by the bed and facing the tv, is the door to my left or right?
    bool direction(Cursor& c, PhraseParser& p, Translation& out) {
        c.accept({"if|when|suppose|imagine"});
        bool stand = c.accept({"i|you|we", "stand|sit"});
        if (!stand) c.accept({"i|you|we", "am|are|was"});
        if (!stand && !c.accept({"standing|stand|sitting|positioned|beginning"})) return false;
        if (!c.accept({"by|at|near|beside"}) && !c.accept({"next", "to"})) return false;
        Phrase at = p.phrase(c.w, c.i, false);
        c.accept({"and"});
        c.accept({"i|you|we", "am|are"});
        if (!c.accept({"facing|face|looking"})) return false;
        c.accept({"at|toward|towards"});
        Phrase facing = p.phrase(c.w, c.i, false);
        if (!c.accept({"is|are"})) return false;
        auto choice = [](const std::string& w) {
            return isOneOf(w, {"left", "right", "back", "front", "behind", "front-left", "front-right", "back-left",
                               "back-right", "left-hand", "right-hand"});
        };
        // The thing asked about ends where the choices begin ("is the toilet on the left or right?": not "the toilet
        // on the left").
        auto choicesAt = [&](std::size_t k) {  // "to", "on" or "at", maybe "my", "the" or "your", then a side
            if (!isOneOf(c.w[k], {"to", "on", "at"})) return false;
            if (++k < c.w.size() && isOneOf(c.w[k], {"my", "the", "your"})) ++k;
            return k < c.w.size() && choice(c.w[k]);
        };
        std::size_t choices = c.i;
        while (choices < c.w.size() && !choicesAt(choices)) ++choices;
        Phrase asked;
        if (choices < c.w.size()) {
            if (!phraseUpTo(c.w, c.i, choices, p, asked)) return false;
        } else {
            asked = p.phrase(c.w, c.i, false);
        }
        c.accept({"to|on|at"});
        c.accept({"my|the"});
        // "... or the right of me", "on my left or on my right", "on my left-hand side".
        for (; !c.done(); ++c.i) {
            const std::string& w = c.peek();
            if (choice(w))
                out.choices.push_back(w == "behind" ? "back" : w.ends_with("-hand") ? w.substr(0, w.find('-')) : w);
            else if (!isOneOf(w, {"or", "the", "of", "to", "on", "my", "your", "me", "you", "side", "hand", "and"}) &&
                     !(!facing.categories.empty() && isOneOf(w, {facing.noun})))
                break;
        }
        if (!c.done()) {
            // "... to the left or the right of the tv": the thing faced, said again.
            std::size_t save = c.i;
            Phrase again = p.phrase(c.w, c.i, false);
            if (again.categories != facing.categories) c.i = save;
        }
        if (out.choices.empty()) out.choices = {"left", "right"};
        out.kind = QuestionKind::Direction;
        // A thing the scene does not hold keeps its word as its role, which no row then matches: the answer says
        // it is not here, where an empty role would stand for the middle of the scene (situation.cpp).
        auto names = [](const Phrase& ph) {
            return ph.categories.empty() ? std::vector<std::string>{model::categoryName(ph.noun)} : ph.categories;
        };
        out.roles = {names(at), names(facing), names(asked)};
        std::vector<std::string> all;
        for (const auto& role : out.roles)
            for (const auto& n : role)
                if (std::find(all.begin(), all.end(), n) == all.end()) all.push_back(n);
        std::string any;
        for (const auto& n : all) any += (any.empty() ? "" : " OR ") + fmt::format("category = {}", smqlString(n));
        out.smql = fmt::format("FIND thing WHERE {} RETURN id, category, box", all.size() > 1 ? "(" + any + ")" : any);
        out.subject = asked.words;
        out.object = fmt::format("standing by the {} facing the {}", at.words, facing.words);
        return true;
    }

    // How do I get to the sofa from the door? Take me from the door to the chair.
    bool guidance(Cursor& c, PhraseParser& p, Translation& out) {
        bool lead =
            c.accept({"how|where", "do|can|could|would|should|shall", "i|we|you", "get|go|walk|reach|navigate|move"}) ||
            c.accept({"how|where", "do|can|could|would|should|shall", "i|we|you", "find", "my|our", "way"}) ||
            c.accept({"how", "to", "get|go|walk|reach"}) ||
            c.accept({"take|guide|lead|bring|direct|navigate|walk", "me|us"}) ||
            c.accept({"show", "me|us", "the", "way|route|path"}) ||
            c.accept({"what|which", "is", "the", "way|route|path"}) ||
            // "what's the shortest way to the bed?", "the best route from the desk to the sink"
            c.accept({"what|which", "is", "the", "shortest|quickest|fastest|best|easiest", "way|route|path"}) ||
            c.accept({"show", "me|us", "the", "shortest|quickest|fastest|best|easiest", "way|route|path"}) ||
            // "which way to the sofa?", "which way is it to the door?", "which way is the kitchen?"
            (c.peek(2) == "to" && c.accept({"which|what", "way"})) || c.accept({"which|what", "way", "is", "it"}) ||
            c.accept({"which", "way", "is|are"}) || c.accept({"i", "want|need", "to", "go|get|walk"}) ||
            // "can I walk from the bed to the fridge?": the way, if there is one.
            c.accept({"can|could", "i|we|you", "get|go|walk|reach|move"}) ||
            // "navigate to the sink", "go to the bed from the door", "directions to the fridge".
            // Not "go to sleep": the goal is a thing, named with an article or by its kind.
            (isOneOf(c.peek(), {"navigate", "go", "walk", "head", "move"}) && isOneOf(c.peek(1), {"to", "from"}) &&
             (isOneOf(c.peek(2), {"the", "a", "an", "my", "our", "that", "this"}) ||
              !lexicon_.lookUp(c.peek(2)).categories.empty()) &&
             c.accept({"navigate|go|walk|head|move"})) ||
            c.accept({"give|show|get", "me|us", "directions"}) ||
            c.accept({"give|show|get", "me|us", "the", "directions"}) || c.accept({"directions"});
        // "how far do I have to walk from the bed to the fridge?", "what's the walking distance ...?", "how long is
        // the walk ...?": the way, and how long it is.
        if (!lead && (c.accept({"how", "far", "do|would|will|must", "i|we|you", "have|need", "to", "walk|go"}) ||
                      c.accept({"what", "is", "the", "walking", "distance"}) ||
                      c.accept({"how", "long", "is", "the", "walk|route|path|way"})))
            lead = true, out.measure = "length";
        if (!lead) return false;
        c.accept({"the", "way"});
        std::optional<Phrase> from, to;
        while (!c.done()) {
            if (c.accept({"from"}))
                from = p.phrase(c.w, c.i, true);
            else if (c.accept({"to"}) || c.accept({"over", "to"}))
                to = p.phrase(c.w, c.i, true);
            else if (!to)
                to = p.phrase(c.w, c.i, true);
            else
                return false;
        }
        if (!to) return false;
        out.kind = QuestionKind::Guidance;
        std::string goal = reference(*to);
        // Several things of a kind, plainly named: which one the words do not say.
        auto several = [&](const Phrase& ph) {
            return ph.conditions.empty() && ph.filters.empty() && !ph.order && ph.categories.size() == 1 &&
                   ph.side.empty() && repeated(ph.categories.front());
        };
        // Several things of the goal's kind: a person means the nearest one, to where they start or stand, of the
        // colour named ("guide me to the black table").
        if (several(*to)) {
            const std::string kind = smqlName(to->categories.front()) + whereText(*to);
            goal = from ? fmt::format("(FIND {} NEAREST TO {} LIMIT 1)", kind, reference(*from))
                        : fmt::format("(FIND {} ORDER BY distance(HERE) LIMIT 1)", kind);
        }
        // "from the sofa to the door" where two sofas stand: the one nearest the goal's kind.
        std::string start = from ? reference(*from) : "HERE";
        if (from && several(*from)) {
            start = fmt::format("(FIND {}{} NEAREST TO {} LIMIT 1)", smqlName(from->categories.front()),
                                whereText(*from), reference(*to));
            out.notes.push_back(fmt::format("the scene holds several of '{}': the way starts at the one nearest the {}",
                                            from->words, to->words));
        }
        // "which way is the kitchen?": to the nearest of the things that mark it.
        if (to->room && !to->order)
            goal = fmt::format("({}{} LIMIT 1)", findText(*to, false),
                               from ? " NEAREST TO " + reference(*from) : std::string(" ORDER BY distance(HERE)"));
        out.smql = fmt::format("GUIDE FROM {} TO {}", start, goal);
        out.subject = to->words;
        out.object = from ? from->words : "here";
        return true;
    }

    // How far is the sofa from the tv? What is the distance between the bed and the door?
    bool distance(Cursor& c, PhraseParser& p, Translation& out) {
        std::optional<Phrase> a, b;
        bool fromOrder = false;  // b is what a is ordered by the distance to: a keeps its order
        // The thing measured from: "me" or "here" is the person (PhraseParser::person).
        auto from = [&] {
            Phrase person;
            return p.personAt(c.w, c.i, person) ? person : p.phrase(c.w, c.i, true);
        };
        auto pair = [&](std::initializer_list<std::string_view> link) {
            a = p.phrase(c.w, c.i, true);
            c.accept({"away"});
            // "how far away is the door?": from the person; "how far is the nearest chair from the sofa?": from what
            // the thing is nearest to (the phrase took the sofa in as its order).
            if (c.done() && !a->kind) {
                fromOrder = a->order && a->order->measure == "distance" && a->order->to.size() == 1;
                b = fromOrder ? a->order->to.front() : p.person();
                return true;
            }
            if (!c.accept(link)) return false;
            b = from();
            c.accept({"apart"});
            return true;
        };
        if (c.accept({"how", "far|close"})) {
            c.skip({"away", "apart"});
            if (c.accept({"am", "i"})) {
                // "how far am I from the sofa?": the sofa, from the person.
                c.skip({"away"});
                if (!c.accept({"from|to"})) return false;
                a = p.phrase(c.w, c.i, true);
                b = p.person();
            } else if (c.accept({"is|are", "it", "from"})) {
                if (!pair({"to"})) return false;
            } else if (c.accept({"is", "it", "to"})) {
                // "how far is it to the door?": the door, from the person.
                a = p.phrase(c.w, c.i, true);
                b = p.person();
            } else if (c.accept({"is|are"})) {
                if (!pair({"from|to|and"})) return false;
            } else {
                // "(tell me) how far the door is from the window"
                a = p.phrase(c.w, c.i, true);
                if (!c.accept({"is|are"})) return false;
                c.accept({"away"});
                if (!c.accept({"from|to"})) return false;
                b = p.phrase(c.w, c.i, true);
            }
        } else if (const auto far = std::find(c.w.begin(), c.w.end(), "far");
                   far != c.w.end() && c.accept({"is|are"})) {
            // "is the fridge far from me?": how far, which says whether it is.
            Phrase first;
            if (!phraseWithin(c, p, static_cast<std::size_t>(far - c.w.begin()), first)) return false;
            a = first;
            ++c.i;
            c.accept({"away"});
            if (c.done()) {
                b = p.person();
            } else {
                if (!c.accept({"from"})) return false;
                b = from();
            }
        } else if (c.accept({"how", "much", "space|room|distance|gap"})) {
            // "how much space is there between the bed and the desk?": the gap between them.
            c.skip({"is", "there"});
            if (!c.accept({"between"}) || !pair({"and"})) return false;
        } else {
            c.accept({"what|how", "is|far"});
            c.accept({"the"});
            c.skip({"direct", "straight", "straight-line", "euclidean", "shortest", "exact", "line"});
            if (!c.accept({"distance|gap"})) return false;
            if (c.accept({"between"})) {
                if (!pair({"and"})) return false;
            } else if (c.accept({"from|of"})) {
                if (!pair({"to|from"})) return false;
            } else {
                return false;
            }
        }
        // "the distance from the sofa to the nearest table": the table nearest the sofa, which distance(table) measures
        // to (the nearest box of the kind), not the one nearest the viewer.
        if (b->order && b->order->unsaid && !b->order->descending && b->pick == 1 && !a->here)
            b->order.reset(), b->pick = 0;
        out.kind = QuestionKind::Distance;
        Phrase subject = *a;
        if (subject.order && !fromOrder) {
            // "how far is the largest chair from the sofa?": the largest chair, and how far it is.
            out.smql = fmt::format("FIND ({}) ORDER BY distance({})", findText(subject, false), reference(*b));
        } else {
            if (!fromOrder) subject.order = Order{"distance", false, {*b}, ""};
            out.smql = findText(subject, false);
        }
        describeSubject(*a, out);
        out.object = b->words;
        return true;
    }

    // List the furniture from largest to smallest; sort the objects by height. Every thing of the kind in the order
    // asked (a Superlative of them all): the superlative said first ("largest") orders them, as in "the largest
    // table"; "by size" is by the largest first.
    bool sorted(Cursor& c, PhraseParser& p, Translation& out) {
        if (!c.accept({"list|sort|order|rank|show|name|arrange"})) return false;
        c.accept({"me|us"});
        c.accept({"all"});
        c.accept({"the"});
        std::size_t k = c.i;
        while (k < c.w.size() && !isOneOf(c.w[k], {"from", "by"})) ++k;
        if (k == c.i || k == c.w.size()) return false;
        std::string first;
        if (c.w[k] == "from" && k + 4 == c.w.size() && c.w[k + 2] == "to") {
            first = c.w[k + 1];  // "from largest to smallest"
            out.measure = joined(c.w, k, c.w.size());
        } else if (c.w[k] == "by" && k + 2 == c.w.size()) {
            std::string word;
            const auto cmp = comparativeOfSize(adjectiveOfMeasure(c.w[k + 1]), word);
            if (!cmp) return false;
            first = cmp->superlative;  // "by height": the tallest first
            out.measure = "by " + c.w[k + 1] + ", the " + first + " first";
        } else {
            return false;
        }
        Words said{"the", first};
        said.insert(said.end(), c.w.begin() + static_cast<std::ptrdiff_t>(c.i),
                    c.w.begin() + static_cast<std::ptrdiff_t>(k));
        std::size_t at = 0;
        Phrase things = p.phrase(said, at, true);
        if (at != said.size() || !things.order || things.order->measure == "distance") return false;
        things.pick = 0;  // all of them, in order
        c.i = c.w.size();
        out.kind = QuestionKind::Superlative;
        out.top = std::numeric_limits<std::size_t>::max();
        out.smql = findText(things, false);
        describeSubject(things, out);
        return true;
    }

    // Whether the words from `from` to the end only name the scene ("in the room", "in this apartment", "here", or
    // nothing), which a question about all its things may add.
    static bool namesSceneFrom(const Words& w, std::size_t from, PhraseParser& p) {
        if (from == w.size() || (from + 1 == w.size() && w[from] == "here")) return true;
        if (w[from] != "in") return false;
        std::size_t k = from + 1;
        while (k < w.size() && isOneOf(w[k], {"the", "this", "our", "my"})) ++k;
        const std::size_t place = p.scenePlaceAt(w, k);
        return place > 0 && k + place == w.size();
    }

    // "A and B" in the words from the cursor up to `end`, or one kind twice ("the two sofas", "both lamps", "all the
    // beds"): the two sides of a question about a pair.
    static bool twoSides(Cursor& c, PhraseParser& p, std::size_t end, Phrase& a, Phrase& b) {
        const auto last = c.w.begin() + static_cast<std::ptrdiff_t>(end);
        const auto link = std::find(c.w.begin() + static_cast<std::ptrdiff_t>(c.i), last, "and");
        if (link == last) {
            if (!c.accept({"the", "two"}) && !c.accept({"both"}) && !c.accept({"all", "the"})) return false;
            c.accept({"the"});
            if (!phraseWithin(c, p, end, a)) return false;
            b = a;
            return true;
        }
        if (!phraseWithin(c, p, static_cast<std::size_t>(link - c.w.begin()), a)) return false;
        ++c.i;
        return phraseWithin(c, p, end, b);
    }

    // What is the most common object? What kind of furniture is there most of? Which thing appears most often? The
    // things' kinds tallied (Translation::byKind), the most numerous first (measure "most").
    bool mostCommon(Cursor& c, PhraseParser& p, Translation& out) {
        std::size_t end = c.i;  // "... in the room", "... here": the scene, said or not
        while (!namesSceneFrom(c.w, end, p)) ++end;
        std::size_t nounFrom = 0, nounTo = 0;
        if (c.accept({"what|which", "is|are", "the", "most", "common|frequent|numerous"}) ||
            c.accept({"what|which", "is|are", "the", "commonest"})) {
            nounFrom = c.i, nounTo = end;  // "... object (in the room)"
        } else if (c.accept({"what|which"})) {
            c.accept({"kind|type|sort", "of"});  // "what kind of object is there most of?"
            nounFrom = c.i;
            while (c.i < end && !isOneOf(c.w[c.i], {"is", "are", "appears", "appear", "occurs", "occur"})) ++c.i;
            nounTo = c.i;
            const bool thereMost =
                c.accept({"is|are", "there"}) && (c.accept({"the", "most", "of"}) || c.accept({"most", "of"}));
            if (!thereMost && !c.accept({"appears|appear|occurs|occur", "most", "often|frequently"})) return false;
            if (c.i != end) return false;
        } else {
            return false;
        }
        Phrase thing = anyThing("object");
        if (nounTo > nounFrom) {
            std::size_t k = nounFrom;
            if (!phraseUpTo(c.w, k, nounTo, p, thing)) return false;
            // "object", "thing", "item": any thing; a kind named ("piece of furniture"): things of it.
            if (thing.categories.empty() && !thing.kind) return false;
        }
        c.i = c.w.size();
        out.kind = QuestionKind::Locate;
        out.measure = "most";
        out.smql = findText(thing, false);
        describeSubject(thing, out);
        out.byKind = true;  // after describeSubject, which takes it from the words ("what kinds of ...")
        return true;
    }

    // Is there enough room to walk between the bed and the wall? Can I pass between the table and the sofa? The gap
    // between the two (Distance, predicate "walk"), which the answer weighs against the room a person needs.
    bool roomToWalk(Cursor& c, PhraseParser& p, Translation& out) {
        if (c.accept({"is", "there"}) || c.accept({"do", "i", "have"})) {
            c.accept({"enough|sufficient"});
            if (!c.accept({"room|space|clearance"})) return false;
            if (!c.accept({"for", "a", "person"})) c.accept({"for", "me|someone|people"});
            if (!c.accept({"to"})) return false;
        } else if (!c.accept({"can|could", "i|we|someone|one"}) && !c.accept({"can|could", "a", "person"})) {
            return false;
        }
        if (!c.accept({"walk|pass|get|go|fit|squeeze|move"})) return false;
        c.skip({"through", "past", "by"});
        Phrase a, b;
        if (!c.accept({"between"}) || !twoSides(c, p, c.w.size(), a, b)) return false;
        Phrase subject = a;
        subject.order = Order{"distance", false, {b}, ""};
        out.kind = QuestionKind::Distance;
        out.predicate = "walk";
        out.smql = findText(subject, false);
        describeSubject(a, out);
        out.object = b.words;
        return true;
    }

    // How tall is the lamp? What is the length of the longest dimension of the table?
    bool size(Cursor& c, PhraseParser& p, Translation& out) {
        std::string measure;
        bool aboveFloor = false;  // "how high off the ground is the tv?"
        bool saidHigh = false;    // "how high is the sink?"
        if (c.accept({"how", "high|tall", "above|off|over|from", "the", "floor|ground", "is|are"}) ||
            c.accept({"how", "high|tall", "above|off|over|from", "floor|ground", "is|are"})) {
            measure = "height";
            aboveFloor = true;
        } else if (c.accept({"how"}) && sizeMeasure(c.peek()) && isOneOf(c.peek(1), {"is", "are"})) {
            measure = std::string(*sizeMeasure(c.peek()));
            saidHigh = c.peek() == "high";
            c.i += 2;
        } else {
            c.i = 0;
            if (!c.accept({"what"})) return false;
            if (isOneOf(c.peek(), {"size", "height", "width", "length"}) && isOneOf(c.peek(1), {"is", "are"})) {
                // "what size is the table?"
                measure = std::string(*sizeMeasure(c.peek()));
                c.i += 2;
            } else {
                c.accept({"is|are"});
                c.accept({"the"});
                c.accept({"floor|total|overall"});                 // "the floor area of the room"
                out.average = c.accept({"average|mean|typical"});  // "the average height of the tables"
                if (c.accept({"length", "of", "the", "longest|largest", "dimension|side"})) {
                    measure = "longest";
                    // "(length, width, or height)"
                    c.skip({"length", "width", "or", "height", "and"});
                } else if (auto m = sizeMeasure(c.peek()); m && c.peek(1) == "of") {
                    measure = std::string(*m);
                    c.i += 1;
                } else {
                    return false;
                }
                if (!c.accept({"of"})) return false;
            }
        }
        std::size_t save = c.i;
        c.skip({"the", "this", "my"});
        const std::size_t place = p.scenePlaceAt(c.w, c.i);
        if ((place > 0 && c.i + place == c.w.size()) ||
            (c.peek() == "combined" && c.peek(1) == "space" && c.i + 2 == c.w.size())) {
            // The room as a whole: its floor area, from its walls, else its floor, else the figure
            // its layout came with (answer.cpp).
            out.kind = QuestionKind::RoomSize;
            out.measure = "area";
            // The room's own figure where the scene has one (a layout's room node).
            const auto& stored = question_.attributes;
            bool area = std::find(stored.begin(), stored.end(), "area") != stored.end();
            out.smql = fmt::format(
                "FIND node WHERE kind = 'room' OR category = 'wall' OR category = 'floor' RETURN id, category, kind, "
                "box{}",
                area ? ", area" : "");
            out.subject = "room";
            c.i = c.w.size();
            return true;
        }
        c.i = save;
        // "how high is the tv above the floor?", "... off the ground": how far its bottom is from the floor, the
        // thing's place, not its size (the floor is the scene's height 0, with a floor node or without).
        std::size_t end = c.w.size();
        if (!aboveFloor && measure == "height" && end >= c.i + 3 && isOneOf(c.w[end - 1], {"floor", "ground"})) {
            const std::size_t the = c.w[end - 2] == "the" ? 1 : 0;
            aboveFloor = isOneOf(c.w[end - 2 - the], {"above", "off", "from", "over"});
            if (aboveFloor) end -= 2 + the;
        }
        Phrase thing;
        if (!phraseUpTo(c.w, c.i, end, p, thing)) return false;
        c.i = c.w.size();
        out.kind = QuestionKind::Size;
        out.measure = measure;
        out.smql = findText(thing, false) + " RETURN id, category, width, depth, height, volume";
        // "how high is the ceiling?": how far above the floor it is, not how thick its box.
        const bool ceiling = thing.categories == std::vector<std::string>{"ceiling"};
        // "how high is the sink?": how tall, and where its top is when it stands above the floor.
        if (saidHigh && !aboveFloor && !ceiling) out.predicate = "high";
        if (measure == "height" && (aboveFloor || saidHigh || ceiling)) out.smql += ", z";
        describeSubject(thing, out);
        return true;
    }

    // A part of a thing or what covers it, which the memory keeps no colour or shape of apart from the thing.
    static bool isPartOrCover(const std::string& w) {
        return isOneOf(w, {"frame", "fabric", "upholstery", "cover", "lid", "handle", "handles", "legs", "seat", "top",
                           "base", "surface", "trim", "border", "shade", "finish"});
    }

    // What colour is the sofa?
    bool attribute(Cursor& c, PhraseParser& p, Translation& out) {
        std::string measure;
        Phrase thing;
        if (c.accept({"what|which", "color|colour|colors|colours|shape|material|finish|texture|pattern"})) {
            measure = c.w[c.i - 1];
            if (c.accept({"is|are|does|do"})) {
                thing = p.phrase(c.w, c.i, true);
                c.accept({"have|has"});
                c.accept({"made", "of|from"});
            } else if (auto does = std::find_if(c.w.begin() + static_cast<std::ptrdiff_t>(c.i), c.w.end(),
                                                [](const std::string& w) { return w == "does" || w == "do"; });
                       does != c.w.end() && c.w.back() == "have" && does - c.w.begin() == static_cast<long>(c.i) + 1 &&
                       isPartOrCover(c.peek())) {
                // "what color frame does the white board have?": the memory keeps the colour of the
                // whole thing, not of its parts.
                out.notes.push_back(fmt::format("'{}' is read as the thing itself", c.peek()));
                c.i += 2;
                if (!phraseWithin(c, p, c.w.size() - 1, thing)) return false;
                c.i = c.w.size();
            } else {
                // "what color recycling bin sits in the corner?"
                thing = p.phrase(c.w, c.i, false);
                c.skip({"is", "are", "sits", "sit", "stands", "stand", "hangs", "hang", "lies", "lie", "located",
                        "placed"});
                p.posts(c.w, c.i, thing);
            }
        } else if (c.accept(
                       {"what", "is|are", "the", "color|colour|colors|colours|shape|material|finish|texture", "of"})) {
            measure = c.w[c.i - 2];
            thing = p.phrase(c.w, c.i, true);
        } else if (c.accept({"what", "is|are"})) {
            // "what is the chair made of?"
            auto made = std::find(c.w.begin() + static_cast<std::ptrdiff_t>(c.i), c.w.end(), "made");
            if (made == c.w.end() || made + 1 == c.w.end() || !isOneOf(*(made + 1), {"of", "from", "out"}))
                return false;
            if (!phraseWithin(c, p, static_cast<std::size_t>(made - c.w.begin()), thing)) return false;
            c.i = c.w.size();
            measure = "material";
        } else {
            return false;
        }
        if (measure.starts_with("colo")) measure = "color";
        out.kind = QuestionKind::Attribute;
        out.measure = measure;
        const auto& known = question_.attributes;
        bool kept = std::find(known.begin(), known.end(), measure) != known.end();
        // Without colours in the scene the rows still name the things, and the answer says so.
        out.smql = findText(thing, false) + (kept ? " RETURN id, category, " + measure : "");
        describeSubject(thing, out);
        return true;
    }

    // How many colours are there? What materials are there? What is the most common colour? The values of an attribute
    // over the things, tallied (Attribute, byKind).
    bool attributeTally(Cursor& c, PhraseParser& p, Translation& out) {
        std::string measure;
        auto valueWord = [&] {
            if (!c.accept({"color|colour|colors|colours|material|materials"})) return false;
            measure = c.w[c.i - 1].starts_with("colo") ? "color" : "material";
            return true;
        };
        const bool most = c.accept({"what|which", "is", "the", "most", "common|frequent"});
        if (most) {
            if (!valueWord()) return false;
        } else if (c.accept({"how", "many"}) || c.accept({"what|which"})) {
            c.accept({"different|distinct"});
            if (!valueWord() || !c.accept({"are|is", "there"})) return false;
        } else {
            return false;
        }
        if (!namesSceneFrom(c.w, c.i, p)) return false;  // "... in the room"
        c.i = c.w.size();
        out.kind = QuestionKind::Attribute;
        out.measure = measure;
        const auto& known = question_.attributes;
        const bool kept = std::find(known.begin(), known.end(), measure) != known.end();
        out.smql = "FIND object" + (kept ? " RETURN id, category, " + measure : std::string());
        describeSubject(anyThing("object"), out);
        out.byKind = true;
        if (most) out.predicate = "most";
        return true;
    }

    // Where can I sit? What can I sit on? What can I put my cup on? Is there a place to sleep?
    // Is there anything I can sit on? Anything to sit on?
    bool affordance(Cursor& c, PhraseParser& p, Translation& out) {
        // "can I sleep here?", "could we sit somewhere?": where it can be done.
        const bool here = c.w.size() >= 4 && isOneOf(c.w.back(), {"here", "somewhere", "anywhere"}) &&
                          c.accept({"can|could|may", "i|we|one"});
        bool lead = here || c.accept({"where|what", "can|could|should|do|may", "i|we|one|you"}) ||
                    c.accept({"is|are", "there", "somewhere|anywhere|anything|something|a|any"}) ||
                    c.accept({"what", "is", "there", "to"}) ||
                    c.accept({"anything|something|somewhere|anywhere", "to"}) ||
                    // "find me something to sit on", "show us a place to sleep", "show me where to sit".
                    c.accept({"find|show|get|give|bring", "me|us", "somewhere|anywhere|anything|something|a|any"}) ||
                    c.accept({"find|show|get|give|bring", "somewhere|anywhere|anything|something|any"}) ||
                    c.accept({"show|tell", "me|us", "where"}) ||
                    // "I need a place to sit", "we want something to sleep on".
                    c.accept({"i|we", "need|want", "somewhere|anywhere|anything|something|a|some"});
        if (!lead) return false;
        c.accept({"i|we|one|you", "can|could"});
        c.accept({"place|spot|seat|thing", "to"});
        c.accept({"to"});
        if (c.done()) return false;
        const AffordanceRow* row = nullptr;
        for (const auto& base : wordsFor(c.peek()))
            for (const auto& r : kAffordances)
                if (r.verb == base && !row) row = &r;
        if (!row) return false;
        ++c.i;
        static const std::initializer_list<std::string_view> particles{
            "down", "on", "in",   "at", "with", "things", "stuff",  "something", "my",
            "the",  "it", "them", "up", "into", "onto",   "inside", "away"};
        // A preposition the question ends on belongs to the verb ("what can I sit on?"), not to a
        // place still to come, and "here" ends "can I sleep here?": what stands before them is read
        // without them.
        const bool stranded = isOneOf(c.w.back(), {"on", "in", "at", "with", "into", "onto", "inside", "upon"});
        const std::size_t end = c.w.size() - (stranded || here ? 1 : 0);
        const Words rest(c.w.begin() + static_cast<std::ptrdiff_t>(c.i),
                         c.w.begin() + static_cast<std::ptrdiff_t>(end));
        Cursor r{rest};
        r.skip(particles);
        // "what can I sit on in the living room?", "where can I sit near the window?": the things it is afforded by
        // there.
        std::optional<Phrase> there = affordedAt(rest, p, *row);
        if (!r.done() && !there) {
            // "where can I put my cup?": what is put does not change where.
            p.phrase(r.w, r.i, false);
            r.skip(particles);
        }
        c.i = r.done() || there ? c.w.size() : c.i + r.i;
        out.kind = QuestionKind::Affordance;
        out.predicate = std::string(row->how);
        out.smql = there ? findText(*there, false) : "FIND thing WHERE " + affordedBy(*row);
        if (there) describeSubject(*there, out);  // the place's words: "in the living room"
        out.subject = "thing";
        out.subjectPlural = "things";
        return true;
    }

    // The things a use is afforded by in a place the question ends on ("in the living room", "near the window"): those
    // categories with the place's condition; none when the words after the verb name no such place.
    std::optional<Phrase> affordedAt(const Words& rest, PhraseParser& p, const AffordanceRow& row) const {
        const auto at = std::find_if(rest.begin(), rest.end(), [](const std::string& w) {
            return isOneOf(w, {"in", "at", "near", "by", "around", "beside"});
        });
        if (at == rest.end() || at + 1 == rest.end()) return std::nullopt;
        Words placed{"thing"};
        placed.insert(placed.end(), at, rest.end());
        std::size_t k = 0;
        try {
            const Phrase where = p.phrase(placed, k, true);
            if (k != placed.size() || where.conditions.empty()) return std::nullopt;
            Phrase afforded;
            afforded.noun = "thing";
            afforded.categories = categoriesNamed(lexicon_, row.things, WordsAs::Broader);
            afforded.conditions = where.conditions;
            if (afforded.categories.empty()) return std::nullopt;
            return afforded;
        } catch (const Error&) {
            return std::nullopt;
        }
    }

    // The condition on the things a use is afforded by, as this scene names them: "(category = 'chair' OR ...)"; the
    // row's first word when the scene has none of them (the answer is then "nothing").
    std::string affordedBy(const AffordanceRow& row) const {
        const std::vector<std::string> categories = categoriesNamed(lexicon_, row.things, WordsAs::Broader);
        if (categories.empty())
            return fmt::format("category = {}", smqlString(std::string(row.things.substr(0, row.things.find(' ')))));
        std::string any;
        for (const auto& cat : categories)
            any += (any.empty() ? "" : " OR ") + fmt::format("category = {}", smqlString(cat));
        return categories.size() > 1 ? "(" + any + ")" : any;
    }

    // How a holder has the things it is said to have or hold: what a cabinet contains is in it, what a sofa has is on
    // it, and the seats a table has (those "where can I sit?" finds: chairs, stools) stand at it.
    std::string heldAs(const Phrase& thing, bool contains) const {
        if (contains) return "in";
        const std::vector<std::string> seats = categoriesNamed(lexicon_, affordanceOf("sit").things, WordsAs::Broader);
        const bool seat = !thing.categories.empty() &&
                          std::all_of(thing.categories.begin(), thing.categories.end(),
                                      [&](auto& c) { return std::find(seats.begin(), seats.end(), c) != seats.end(); });
        return seat ? "near" : "on";
    }

    // How many people can sit here? How many of us can sit on the sofa? How many people can be seated at the table?
    // The seats (those "where can I sit?" finds) with their lengths; the answer counts their places
    // (model/seating.hpp).
    bool seating(Cursor& c, PhraseParser& p, Translation& out) {
        if (!c.accept({"how", "many"})) return false;
        c.skip({"people", "persons", "guests", "adults", "children", "kids", "visitors", "person"});
        c.accept({"of", "us|you|them"});
        if (!c.accept({"can|could|will|would|may"})) return false;
        if (!c.accept({"sit"}) && !c.accept({"be", "seated"})) return false;
        c.skip({"down", "comfortably", "together"});
        c.accept({"at", "once"});
        const std::string seats = affordedBy(affordanceOf("sit"));
        const std::string columns = " RETURN id, category, width";
        out.kind = QuestionKind::Seating;
        out.subject = "seat";
        out.subjectPlural = "seats";
        // "here", "in the room": every seat.
        std::size_t k = c.i;
        if (k < c.w.size() && isOneOf(c.w[k], {"in", "inside"})) ++k;
        while (k < c.w.size() && isOneOf(c.w[k], {"the", "this", "our", "my"})) ++k;
        if (c.done() || (k < c.w.size() && p.scenePlaceAt(c.w, k) == c.w.size() - k)) {
            c.i = c.w.size();
            out.smql = "FIND thing WHERE " + seats + columns;
            return true;
        }
        if (c.accept({"on|in"})) {
            // "on the sofa": that seat's places.
            const Phrase seat = p.phrase(c.w, c.i, true);
            out.smql = findText(seat, false) + columns;
            out.object = seat.words;
            out.condition = "on";
            return true;
        }
        if (c.accept({"at|around|by"})) {
            // "at the table": the seats beside it.
            const Phrase at = p.phrase(c.w, c.i, true);
            out.smql = fmt::format("FIND thing WHERE {} AND near({}){}", seats, reference(at), columns);
            out.object = at.words;
            out.condition = "at";
            return true;
        }
        return false;
    }

    // Can I see the plant from the door? What can I see from the sofa?
    bool visibility(Cursor& c, PhraseParser& p, Translation& out) {
        bool what = c.accept({"what|which"});
        std::optional<Phrase> thing;
        if (what && !isOneOf(c.peek(), {"can", "could", "do", "is", "are"})) thing = p.phrase(c.w, c.i, false);
        const bool byPerson = c.accept({"can|could|do|would|will", "i|we|one", "see|view|spot|notice"});
        if (!byPerson && !c.accept({"can|could|do|would|will", "you", "see|view|spot|notice"}) &&
            !c.accept({"is|are", "visible"}))
            return false;
        if (!what) thing = p.phrase(c.w, c.i, true);
        Phrase from;
        // "do you see a laptop?" asks the memory whether there is one; "can I see the tv?" asks from where I am.
        if ((c.done() && (byPerson || self_)) || c.accept({"from|at", "where", "i", "am"}) ||
            c.accept({"where", "i", "am"}) || c.accept({"from", "here"})) {
            // From where the person is: the thing a situation put them at, else where the viewer stands (HERE).
            c.skip({"standing", "sitting", "now", "right", "lying"});
            from = p.person();
            from.words = "where you are";
        } else {
            if (!c.accept({"from"})) return false;
            from = p.phrase(c.w, c.i, true);
        }
        Phrase target = thing ? *thing : Phrase{};
        if (!thing) {
            target.kind = "object";
            target.noun = "thing";
        }
        Condition seen;
        seen.predicate = "visible_from";
        seen.args.push_back(from);
        seen.words = from.words == "where you are" ? "visible from where you are" : "visible from the " + from.words;
        target.conditions.push_back(seen);
        out.kind = what ? QuestionKind::Relational : QuestionKind::Existence;
        out.smql = findText(target, false);
        describeSubject(target, out);
        return true;
    }

    // What changed? What is new? Has anything moved?
    bool changes(Cursor& c, PhraseParser&, Translation& out) {
        bool lead = c.accept({"what|has|have|did", "anything|something"}) || c.accept({"what|anything"});
        if (!lead) return false;
        c.accept({"has|have|is|was"});
        if (!c.accept({"changed|moved|new|different|gone|missing|disappeared|appeared|added|removed|change"}))
            return false;
        c.skip({"in", "the", "this", "room", "scene", "since", "recently", "lately", "last", "time", "here"});
        out.kind = QuestionKind::Changes;
        out.smql = "SHOW CHANGES";
        return true;
    }

    // "how many tables and chairs are there?": each kind counted, the rows' categories tallied by the answer.
    // `link` joins the kinds: "and", or "than" when two are compared ("more chairs than tables").
    bool countKinds(Cursor& c, PhraseParser& p, Phrase first, std::initializer_list<std::string_view> filler,
                    Translation& out, std::string_view link = "and") {
        std::vector<Phrase> kinds{std::move(first)};
        while (c.accept({link}) && (link == "and" || kinds.size() == 1)) {
            c.accept({"the|all"});
            kinds.push_back(p.phrase(c.w, c.i, true));
        }
        c.skip(filler);
        c.accept({"do|can|could", "you|i|we", "see|have|find|count"});
        c.skip(filler);
        // "in the room" names the whole scene and adds no condition; a place that does is not read here.
        p.posts(c.w, c.i, kinds.back());
        if (!c.done()) return false;
        std::string where, subject;
        for (std::size_t k = 0; k < kinds.size(); ++k) {
            const Phrase& kind = kinds[k];
            // A kind alone each ("tables and chairs"), not a place or a condition ("chairs near the table").
            if (kind.kind || !kind.id.empty() || !kind.conditions.empty() || kind.noun.empty()) return false;
            // A kind the scene has none of is counted as none ("5 chairs and 0 pianos").
            const std::vector<std::string> categories =
                kind.categories.empty() ? std::vector<std::string>{kind.noun} : kind.categories;
            for (const auto& category : categories)
                where += fmt::format("{}category = {}", where.empty() ? "" : " OR ", smqlString(category));
            subject += (k == 0 ? "" : k + 1 == kinds.size() ? " and " : ", ") + pluralOf(kind.noun);
            out.roles.push_back(categories);
            out.choices.push_back(kind.noun);
        }
        out.kind = QuestionKind::Count;
        out.smql = fmt::format("FIND thing WHERE {} RETURN id, category", where);
        out.subject = out.subjectPlural = subject;
        return true;
    }

    // The things of `thing` that hold its one condition, and every thing of the kind the condition names (`holder`), in
    // one FIND: the answer counts them by holder ("how many pillows are on each bed?", "which bed has the most
    // pillows?"). `measure` is "each", "most" or "fewest".
    static bool countByHolder(const Phrase& thing, const std::string& measure, Translation& out) {
        if (thing.conditions.size() != 1 || !thing.id.empty()) return false;
        const Condition& held = thing.conditions.front();
        if (held.negated || held.args.size() != 1 || held.metres) return false;
        const Phrase& holder = held.args.front();
        if (holder.kind || !holder.id.empty() || holder.order || !holder.conditions.empty() || holder.here)
            return false;
        auto kindsOf = [](const Phrase& ph) {
            const std::vector<std::string> categories =
                ph.categories.empty() ? std::vector<std::string>{hyphenated(ph.noun)} : ph.categories;
            std::string any;
            for (const auto& c : categories)
                any += (any.empty() ? "" : " OR ") + fmt::format("category = {}", smqlString(c));
            return std::pair{categories, categories.size() > 1 ? "(" + any + ")" : any};
        };
        // "things", "objects": any thing but a holder (no kinds of its own).
        const auto [thingKinds, thingClause] =
            thing.kind ? std::pair{std::vector<std::string>{}, fmt::format("kind = {}", smqlString(*thing.kind))}
                       : kindsOf(thing);
        const auto [holderKinds, holderClause] = kindsOf(holder);
        Phrase onHolder = thing;
        onHolder.categories.clear();
        onHolder.kind = "thing";
        out.kind = QuestionKind::Count;
        out.measure = measure;
        out.smql = fmt::format("FIND thing WHERE {} OR ({}{}) RETURN id, category, box", holderClause, thingClause,
                               " AND" + whereText(onHolder).substr(std::string(" WHERE").size()));
        out.roles = {thingKinds, holderKinds};
        out.choices = {thing.noun, holder.noun};
        out.predicate = held.predicate;
        describeSubject(thing, out);
        return true;
    }

    // Which bed has the most pillows (on it)? What table holds more books? The things counted by holder.
    bool mostHeld(Cursor& c, PhraseParser& p, Translation& out) {
        const auto verb = std::find_if(c.w.begin(), c.w.end(), [](const std::string& w) {
            return isOneOf(w, {"has", "have", "holds", "hold", "carries", "contains"});
        });
        const auto most = verb == c.w.end() ? verb : verb + 1 + (verb + 1 != c.w.end() && *(verb + 1) == "the");
        if (most == c.w.end() || !isOneOf(*most, {"most", "more", "fewest", "fewer", "least", "less"}) ||
            !c.accept({"which|what"}))
            return false;
        Phrase holder;
        if (!phraseWithin(c, p, static_cast<std::size_t>(verb - c.w.begin()), holder)) return false;
        const bool contains = *verb == "contains";
        ++c.i;
        c.accept({"the"});
        if (!c.accept({"most|more|fewest|fewer|least|less"})) return false;
        const std::string measure = isOneOf(c.w[c.i - 1], {"most", "more"}) ? "most" : "fewest";
        // "... pillows on it": the holder said again; "... chairs around it": the things near it.
        std::size_t end = c.w.size();
        std::string predicate = contains ? "in" : "on";
        if (end >= c.i + 3 && isOneOf(c.w[end - 1], {"it", "them"})) {
            const bool nextTo = end >= c.i + 4 && c.w[end - 3] == "next" && c.w[end - 2] == "to";
            if (nextTo || isOneOf(c.w[end - 2], {"around", "near", "beside", "by", "at"}))
                predicate = "near";
            else if (isOneOf(c.w[end - 2], {"on", "in"}))
                predicate = c.w[end - 2];
            else
                return false;
            end -= nextTo ? 3 : 2;
        }
        Phrase thing;
        if (!phraseUpTo(c.w, c.i, end, p, thing)) return false;
        c.i = c.w.size();
        // "which table has the most chairs?": as "how many chairs does the table have?".
        if (end == c.w.size()) predicate = heldAs(thing, contains);
        thing.conditions.push_back({predicate, {holder}, std::nullopt, predicate + " the " + holder.words, false});
        return countByHolder(thing, measure, out);
    }

    // How many chairs are near the table? How many cushions do the sofas have?
    bool count(Cursor& c, PhraseParser& p, Translation& out) {
        // "how many more cushions than tables are there?": both kinds counted, the answer says by how many.
        if (c.accept({"how", "many", "more|fewer|less"})) {
            out.measure = c.w[c.i - 1] == "more" ? "how many more" : "how many fewer";
            c.skip({"of", "the"});
            Phrase first = p.phrase(c.w, c.i, true);
            if (c.peek() != "than") return false;
            return countKinds(c, p, std::move(first), {"in", "here", "there", "are", "is"}, out, "than");
        }
        // "are there more chairs than tables?", "are there more books or cushions?": both kinds counted, the
        // answer compares them.
        if (c.accept({"are|is", "there", "more|fewer|less"})) {
            out.measure = c.w[c.i - 1] == "more" ? "more" : "fewer";
            c.skip({"of", "the"});
            Phrase first = p.phrase(c.w, c.i, true);
            const std::string link = c.peek();
            if (link != "than" && link != "or") return false;
            if (link == "or") out.predicate = "or";  // which of the two: the answer names it
            return countKinds(c, p, std::move(first), {"in", "here", "there"}, out, link);
        }
        bool lead = c.accept({"how", "many"}) || c.accept({"count"}) || c.accept({"number", "of"}) ||
                    c.accept({"what", "is", "the", "number", "of"}) || c.accept({"tell", "me", "how", "many"}) ||
                    c.accept({"what", "is", "the", "total", "number|count", "of"}) ||
                    c.accept({"what", "is", "the", "count", "of"});
        if (!lead) return false;
        c.accept({"all|the"});
        c.accept({"the"});
        Phrase thing = p.phrase(c.w, c.i, true);
        static const std::initializer_list<std::string_view> filler{
            "is", "are", "there", "here", "altogether", "total", "exactly", "currently", "right", "now"};
        if (c.peek() == "and") return countKinds(c, p, std::move(thing), filler, out);
        c.skip(filler);
        // "how many chairs are in each room?", "... does each room have?", "... per room": by the kind of room.
        if ((c.accept({"in|for", "each|every", "room"}) || c.accept({"per|by", "room"}) ||
             c.accept({"does|do", "each|every", "room", "have|has|hold|contain"})) &&
            c.done())
            return roomTally(thing, "each", p, out);
        c.accept({"in", "total|all"});  // "how many cushions are there in total on both sofas?"
        c.skip(filler);
        // "how many chairs can I see?" counts from where the person is; "do you see" counts what the memory holds.
        const bool iSee = c.accept({"do|can|could", "i|we", "see"});
        // "how many chairs did I see?": in the capture, what the memory holds.
        const bool see = iSee || c.accept({"do|can|could|did", "you", "see"}) || c.accept({"did", "i|we", "see"});
        if (!see) c.accept({"do|can|could|did", "you|i|we", "have|find|count|spot|notice|detect"});
        c.skip(filler);
        if (see && c.accept({"from"})) {
            // "how many windows can I see from the door?"
            Condition seen;
            seen.predicate = "visible_from";
            Phrase person;
            seen.args.push_back(p.personAt(c.w, c.i, person) ? person : p.phrase(c.w, c.i, true));
            seen.words =
                person.words.empty() ? "visible from the " + seen.args.front().words : "visible from where you are";
            thing.conditions.push_back(seen);
        } else if (iSee && c.done()) {
            Condition seen{"visible_from", {p.person()}, std::nullopt, "visible from where you are", false};
            thing.conditions.push_back(seen);
        }
        p.posts(c.w, c.i, thing);
        // "how many cushions do the sofas have": the holder comes last; "how many chairs does this
        // room (the office) have": the scene holds them all.
        if (std::size_t at = c.i + 1; c.i < c.w.size() && isOneOf(c.w[c.i], {"do", "does"})) {
            while (at < c.w.size() && isOneOf(c.w[at], {"the", "this", "my", "our", "your"})) ++at;
            std::size_t place = p.scenePlaceAt(c.w, at);
            if (place > 0 && at + place < c.w.size() &&
                isOneOf(c.w[at + place], {"have", "hold", "contain", "has", "contains", "holds"})) {
                c.i = at + place + 1;
                c.skip({"in", "it", "altogether", "total"});
            }
        }
        if (c.accept({"do|does"})) {
            auto verb =
                std::find_if(c.w.begin() + static_cast<std::ptrdiff_t>(c.i), c.w.end(), [](const std::string& w) {
                    return isOneOf(w, {"have", "hold", "carry", "contain", "has"});
                });
            Phrase holder;
            if (verb == c.w.end() || !phraseWithin(c, p, static_cast<std::size_t>(verb - c.w.begin()), holder))
                return false;
            const std::string predicate = heldAs(thing, *verb == "contain");
            thing.conditions.push_back({predicate, {holder}, std::nullopt, predicate + " the " + holder.words, false});
            ++c.i;
        }
        c.skip({"is", "are", "there", "altogether", "total", "in", "the", "room"});
        // "how many pillows are on each bed?": counted by bed.
        if (std::any_of(c.w.begin(), c.w.end(),
                        [](const std::string& w) {
                            return isOneOf(w, {"each", "every"});
                        }) &&
            countByHolder(thing, "each", out))
            return true;
        // "how many chairs face the table?" reads in the answer as "facing the table", as a listing does.
        for (auto& cond : thing.conditions) participleFirst(cond);
        out.kind = QuestionKind::Count;
        // "how many kinds of furniture are there?": the things' categories, which the answer tallies.
        out.smql = thing.kinds ? findText(thing, false) + " RETURN id, category" : countText(thing);
        describeSubject(thing, out);
        return true;
    }

    // A predicate's words as said in the words of its first phrase where that is a participle: "what does the sofa
    // face?" reads in the answer as "sofa#7 is facing ...", as "how many chairs face the table?" does.
    static std::string participleSaid(const std::string& predicate, const std::string& said) {
        Condition cond{predicate, {}, std::nullopt, said, false};
        participleFirst(cond);
        return cond.words.substr(0, cond.words.find_last_not_of(' ') + 1);
    }

    // A condition said with a verb ("face the table") in the words of its predicate's first phrase where that is a
    // participle ("facing the table"), so that "1 chair is facing the table" reads.
    static void participleFirst(Condition& cond) {
        const auto* spec = relations::predicateNamed(cond.predicate);
        if (!spec) return;
        const std::string front(relations::englishPhrases(*spec).front());
        const Words said = words(cond.words);
        const auto at = PhraseParser::predicateAt(said, 0);
        if (!at || !words(front).front().ends_with("ing") || said.front() == words(front).front()) return;
        cond.words = front + " " + joined(said, at->second, said.size());
    }

    // "what is to the left of the sofa?": everything on that side of the room holds left_of, and a person means
    // what stands beside it, so the things found come nearest the sofa first.
    static void nearestFirstBeside(Phrase& thing) {
        if (thing.order || thing.conditions.empty()) return;
        // One side, and what rests on or in the thing left out (PhraseParser::leaveOutResting).
        if (std::any_of(thing.conditions.begin() + 1, thing.conditions.end(), [](const Condition& c) {
                return !c.negated || !isOneOf(c.predicate, {"on", "in"});
            }))
            return;
        const Condition& side = thing.conditions.front();
        if (side.negated || side.args.size() != 1 ||
            !isOneOf(side.predicate, {"left_of", "right_of", "in_front_of", "behind"}))
            return;
        thing.order = Order{"distance", false, {side.args.front()}, ""};
    }

    // "is there something red?", "find something red": a thing of the colour that ends the question.
    static void takeTrailingColour(Cursor& c, Phrase& thing) {
        if (thing.kind && !thing.colour && c.i + 1 == c.w.size())
            if (auto colour = colourOf(c.peek())) {
                thing.colour = colour;
                thing.words = c.peek() + " " + thing.words;
                ++c.i;
            }
    }

    // Is there a sofa? Are there any mugs on the table? Does the room have a couch?
    bool existence(Cursor& c, PhraseParser& p, Translation& out) {
        // "does the room have", "does the office have" (when the office is the scene).
        auto sceneHas = [&] {
            if (!c.accept({"does|do", "the|this|my|our|your"})) return false;
            std::size_t place = p.scenePlaceAt(c.w, c.i);
            if (place == 0 || c.i + place >= c.w.size() ||
                !isOneOf(c.w[c.i + place], {"have", "contain", "include", "hold"}))
                return false;
            c.i += place + 1;
            return true;
        };
        bool lead = c.accept({"is|are", "there"}) || c.accept({"do|can|did", "you|i|we", "see|have|own|find|notice"}) ||
                    sceneHas() || (isOneOf(c.peek(), {"any", "anything", "something"}) && c.i == 0) ||
                    // "is anything on the chair?": whether there is.
                    (c.i == 0 && isOneOf(c.peek(1), {"anything", "something"}) && c.accept({"is"}));
        if (!lead) return false;
        Phrase thing = p.phrase(c.w, c.i, true);
        takeTrailingColour(c, thing);
        c.skip({"is", "are", "there", "here"});
        p.posts(c.w, c.i, thing);
        c.skip({"is", "are", "there", "here"});
        out.kind = QuestionKind::Existence;
        out.smql = findText(thing, false);
        describeSubject(thing, out);
        return true;
    }

    // Where is the lamp relative to the window? What is the relation between the mug and the desk?
    bool relative(Cursor& c, PhraseParser& p, Translation& out) {
        Phrase a, b;
        if (c.accept({"where|how", "is|are"}) || c.accept({"how", "does|do"})) {
            // The subject ends where "relative to" (or its like) begins.
            static const std::vector<Words> links{{"relative", "to"},
                                                  {"in", "relation", "to"},
                                                  {"compared", "to"},
                                                  {"with", "respect", "to"},
                                                  {"relate", "to"},
                                                  {"relates", "to"},
                                                  {"from"}};
            std::optional<std::size_t> link, linkWords;
            // "the bin on a desk across from a bed": a predicate's phrase that ends in "from" is no link.
            auto inPredicate = [&](std::size_t k) {
                for (std::size_t b = k > 3 ? k - 3 : 0; b < k; ++b)
                    if (auto pr = PhraseParser::predicateAt(c.w, b); pr && b + pr->second > k) return true;
                return false;
            };
            for (std::size_t k = c.i; k < c.w.size() && !link; ++k)
                for (const auto& l : links)
                    if (k + l.size() <= c.w.size() && std::equal(l.begin(), l.end(), c.w.begin() + k) &&
                        !inPredicate(k)) {
                        link = k;
                        linkWords = l.size();
                        break;
                    }
            if (!link) return placement(c, p, out);
            std::size_t end = *link;
            while (end > c.i && isOneOf(c.w[end - 1], {"placed", "positioned", "located", "oriented", "situated"}))
                --end;
            if (!phraseWithin(c, p, end, a)) return false;
            c.i = *link + *linkWords;
            b = p.phrase(c.w, c.i, true);
        } else if (c.accept({"what|how", "is"}) || c.accept({"describe"})) {
            c.accept({"the"});
            c.accept({"spatial"});
            if (!c.accept({"relation|relationship|position"})) return false;
            if (!c.accept({"between|of"})) return false;
            a = p.phrase(c.w, c.i, true);
            if (!c.accept({"and|to"}) && !c.accept({"relative", "to"})) return false;
            b = p.phrase(c.w, c.i, true);
        } else {
            return false;
        }
        out.kind = QuestionKind::RelativePosition;
        out.smql = fmt::format("RELATE {} TO {}", reference(a), reference(b));
        describeSubject(a, out);
        out.object = b.words;
        return true;
    }

    // "Is the sink to the left or right of the toilet?", "is the lamp in front of or behind the sofa?": RELATE, and the
    // answer says which of the two sides holds (Translation::choices: their predicates), or neither.
    bool eitherSide(Cursor& c, PhraseParser& p, Translation& out) {
        if (!c.accept({"is|are"})) return false;
        const auto orAt = std::find(c.w.begin() + static_cast<std::ptrdiff_t>(c.i), c.w.end(), "or");
        if (orAt == c.w.end()) return false;
        const std::size_t o = static_cast<std::size_t>(orAt - c.w.begin());
        static const std::map<std::string, std::string, std::less<>> sides{
            {"left", "left_of"},  {"right", "right_of"}, {"front", "in_front_of"},
            {"behind", "behind"}, {"above", "above"},    {"below", "below"}};
        // The first side: "left", "in front of" (its "of" before the "or").
        std::size_t first = o - 1;
        if (c.w[first] == "of" && first > c.i && c.w[first - 1] == "front") --first;
        if (first <= c.i || !sides.contains(c.w[first])) return false;
        std::size_t subjectEnd = first;
        while (subjectEnd > c.i && isOneOf(c.w[subjectEnd - 1], {"the", "to", "on", "in", "at", "directly"}))
            --subjectEnd;
        Phrase a;
        if (!phraseWithin(c, p, subjectEnd, a)) return false;
        std::size_t k = o + 1;
        while (k < c.w.size() && isOneOf(c.w[k], {"the", "to", "on", "in", "at", "directly"})) ++k;
        if (k >= c.w.size() || !sides.contains(c.w[k])) return false;
        const std::string second = c.w[k++];
        while (k < c.w.size() && isOneOf(c.w[k], {"side", "hand", "of"})) ++k;
        if (k >= c.w.size()) return false;
        c.i = k;
        Phrase b = p.phrase(c.w, c.i, true);
        out.kind = QuestionKind::RelativePosition;
        out.smql = fmt::format("RELATE {} TO {}", reference(a), reference(b));
        out.choices = {sides.find(c.w[first])->second, sides.find(second)->second};
        describeSubject(a, out);
        out.object = b.words;
        return true;
    }

    // How is the sink located? How is the towel placed on the wall? (read_placement.cpp)
    bool placement(Cursor& c, PhraseParser& p, Translation& out) { return readPlacement(c.w, c.i, p, out); }

    // A phrase that must take exactly the words up to `end` (where a verb or link word follows).
    static bool phraseWithin(Cursor& c, PhraseParser& p, std::size_t end, Phrase& out) {
        return phraseUpTo(c.w, c.i, end, p, out);
    }

    // On what side of the bed is the lamp? What side of the desk are the chairs on?
    bool side(Cursor& c, PhraseParser& p, Translation& out) {
        // "the table is to what side of the bed?": the same question, its subject first.
        if (auto what = std::find(c.w.begin(), c.w.end(), "what"); what != c.w.end() && what - c.w.begin() >= 3 &&
                                                                   isOneOf(*(what - 1), {"on", "to", "at"}) &&
                                                                   isOneOf(*(what - 2), {"is", "are"})) {
            const std::size_t whatAt = static_cast<std::size_t>(what - c.w.begin());
            Phrase a;
            if (!phraseWithin(c, p, whatAt - 2, a)) return false;
            c.i = whatAt + 1;
            if (!c.accept({"side|part|end"})) return false;
            if (!c.accept({"of"})) return false;
            Phrase b = p.phrase(c.w, c.i, true);
            out.kind = QuestionKind::RelativePosition;
            out.smql = fmt::format("RELATE {} TO {}", reference(a), reference(b));
            describeSubject(a, out);
            out.object = b.words;
            return true;
        }
        c.accept({"on|to|at|in"});
        if (!c.accept({"what|which", "side|part|corner|end|area"})) return false;
        c.accept({"of"});
        c.skip({"the", "this", "a"});
        if (isOneOf(c.peek(), {"room", "scene", "house", "space"})) return false;  // where in the room: locate
        Phrase b = p.phrase(c.w, c.i, true);
        if (!c.accept({"is|are|does|do"})) return false;
        std::size_t end = c.w.size();
        while (end > c.i && isOneOf(c.w[end - 1], {"located", "placed", "on", "sit", "stand", "hang", "found", "kept"}))
            --end;
        Phrase a;
        if (!phraseWithin(c, p, end, a)) return false;
        c.i = c.w.size();
        out.kind = QuestionKind::RelativePosition;
        out.smql = fmt::format("RELATE {} TO {}", reference(a), reference(b));
        describeSubject(a, out);
        out.object = b.words;
        return true;
    }

    // What is the lamp on? What is the cabinet next to? The desk is to the right of what? To the
    // right of what is the black cabinet? What bed are the pillows on?
    bool reverse(Cursor& c, PhraseParser& p, Translation& out) {
        std::optional<Phrase> answerKind, subject;
        std::optional<std::pair<std::string, std::size_t>> pred;
        std::size_t predAt = 0;
        auto predicateEnding = [&](std::size_t from, std::size_t to) {
            // The predicate phrase that ends exactly at `to`.
            for (std::size_t k = from; k < to; ++k)
                if (auto found = PhraseParser::predicateAt(c.w, k); found && k + found->second == to) {
                    pred = found;
                    predAt = k;
                    return true;
                }
            return false;
        };
        const auto& verbs = kPlacedBy;
        // "what is the piano on next to the bed?", "the armchair is next to what to the left of the
        // bed?": the thing asked for, placed by the conditions after it (from `from`, to the end).
        std::optional<Phrase> placed;
        auto placedFrom = [&](std::size_t from) {
            Phrase thing = answerKind ? *answerKind : anyThing("thing");
            std::size_t k = from;
            try {
                p.posts(c.w, k, thing);
            } catch (const Error&) {
                return false;
            }
            if (k != c.w.size() || (thing.conditions.empty() && thing.excluded.empty())) return false;
            thing.words = (answerKind ? answerKind->words + " " : std::string()) + joined(c.w, from, k);
            placed = std::move(thing);
            return true;
        };
        if (c.accept({"what|which"})) {
            // what is the lamp on? / what bed are the pillows on?
            if (!isOneOf(c.peek(), {"is", "are", "does", "do"})) answerKind = p.phrase(c.w, c.i, false);
            // "what position is the door in?": a position is no thing the door is in.
            if (answerKind && answerKind->categories.empty() && !answerKind->kind && answerKind->id.empty() &&
                !absentThing(answerKind->noun, lexicon_.lookUp(answerKind->noun)))
                return false;
            if (!c.accept({"is|are|does|do"})) return false;
            bool ends = predicateEnding(c.i, c.w.size());
            for (std::size_t k = c.w.size() - 1; !ends && k > c.i + 1; --k)
                ends = PhraseParser::predicateAt(c.w, k) && predicateEnding(c.i, k) && placedFrom(k);
            if (!ends) return false;
            std::size_t end = predAt;
            while (end > c.i && (isOneOf(c.w[end - 1], verbs) || isVerbOfPlace(c.w[end - 1]))) --end;
            Phrase s;
            if (!phraseWithin(c, p, end, s)) return false;
            subject = s;
            c.i = c.w.size();
        } else if (auto found = PhraseParser::predicateAt(c.w, 0)) {
            std::size_t k = found->second;
            if (k < c.w.size() && c.w[k] == "what") {
                // to the right of what is the black cabinet? on what wall is the tv located?
                pred = found;
                c.i = k + 1;
                // "in what part of the room": where it is (locate); "on what side of": side.
                if (isOneOf(c.peek(), {"part", "side", "corner", "end", "area"})) return false;
                if (!isOneOf(c.peek(), {"is", "are"})) answerKind = p.phrase(c.w, c.i, false);
                if (!c.accept({"is|are"})) return false;
                subject = p.phrase(c.w, c.i, true);
                c.skip({"located", "placed"});
            } else {
                // to the left of the sink is what?
                Phrase thing = anyThing("object");
                p.posts(c.w, c.i, thing);
                if (!c.accept({"is|are", "what"}) && !c.accept({"what", "is|are"})) return false;
                nearestFirstBeside(thing);
                out.kind = QuestionKind::Relational;
                out.smql = findText(thing, false);
                describeSubject(thing, out);
                return true;
            }
        } else if (auto what = std::find_if(c.w.begin(), c.w.end(),
                                            [](const std::string& w) { return w == "what" || w == "which"; });
                   c.w.size() >= 2 && what != c.w.end() && what != c.w.begin()) {
            // the desk is to the right of what? the trash can is sitting against what wall? the guitar
            // case is to the right of which door?
            const std::size_t whatAt = static_cast<std::size_t>(what - c.w.begin());
            if (whatAt + 1 < c.w.size() &&
                (PhraseParser::predicateAt(c.w, whatAt + 1) || c.w[whatAt + 1] == "besides")) {
                if (!placedFrom(whatAt + 1)) return false;
            } else if (whatAt + 1 < c.w.size()) {
                std::size_t k = whatAt + 1;
                answerKind = p.phrase(c.w, k, false);
                if (k != c.w.size()) return false;
            }
            if (!predicateEnding(0, whatAt)) return false;
            std::size_t end = predAt;
            while (end > 0 && (isOneOf(c.w[end - 1], verbs) || isVerbOfPlace(c.w[end - 1]))) --end;
            Phrase s;
            if (end > 0 && isOneOf(c.w[end - 1], {"is", "are"})) {
                if (!phraseWithin(c, p, end - 1, s)) return false;
            } else {
                // "the picture is hanging on the wall above what?": where the subject is says which one.
                auto verb = std::find_if(c.w.begin(), c.w.begin() + static_cast<std::ptrdiff_t>(end),
                                         [](const std::string& w) { return w == "is" || w == "are"; });
                std::size_t k = static_cast<std::size_t>(verb - c.w.begin());
                if (k == 0 || k >= end || !phraseWithin(c, p, k, s)) return false;
                ++k;
                while (k < end && (isOneOf(c.w[k], verbs) || isVerbOfPlace(c.w[k])) &&
                       !PhraseParser::predicateAt(c.w, k))
                    ++k;
                Words head(c.w.begin(), c.w.begin() + static_cast<std::ptrdiff_t>(end));
                const std::size_t before = s.conditions.size();
                p.posts(head, k, s);
                // "the brown chair is in front of a door and beside what?": the conditions say which one.
                if (k + 1 == end && c.w[k] == "and") ++k;
                if (k != end || s.conditions.size() == before) return false;
            }
            subject = s;
            c.i = c.w.size();
        } else {
            return false;
        }
        if (!pred || !subject) return false;
        // What the subject is on or by may be an anchor too (a wall, the floor).
        Phrase other = placed ? *placed : answerKind ? *answerKind : anyThing("thing");
        relateBack(*subject, other, answerKind, pred->first, out);
        out.condition = participleSaid(pred->first, joined(c.w, predAt, predAt + pred->second));
        return true;
    }

    // The RELATE a reverse question asks: the subject to what it is asked of (`other`), by the predicate said.
    void relateBack(const Phrase& subject, const Phrase& other, const std::optional<Phrase>& answerKind,
                    std::string predicate, Translation& out) {
        // "what wall is the tv on": on a wall is hanging there.
        if (predicate == "on" && answerKind &&
            std::all_of(answerKind->categories.begin(), answerKind->categories.end(),
                        [&](const std::string& cat) {
                            return std::find(question_.planeCategories.begin(), question_.planeCategories.end(), cat) !=
                                   question_.planeCategories.end();
                        }) &&
            !answerKind->categories.empty())
            predicate = "attached";
        out.kind = QuestionKind::Reverse;
        out.predicate = predicate;
        out.background = question_.anchorCategories;
        out.smql = fmt::format("RELATE {} TO {}", reference(subject), reference(other));
        describeSubject(subject, out);
        out.object = other.kind ? "thing" : other.words;
    }

    // Which is the largest object? Which cushion is closest to the window? Which of these objects
    // (sofa, tv, bed) is the closest to the door? What is the second largest table?
    bool superlative(Cursor& c, PhraseParser& p, Translation& out) {
        if (!c.accept({"which|what"}) && !c.accept({"find|name"})) return false;
        std::optional<Phrase> subject;
        if (c.accept({"of", "these|those|the"})) {
            c.skip({"objects", "things", "items", "ones", "following", "choices"});
            if (choices_.empty()) return false;
            Phrase any;
            any.noun = "thing";
            for (const auto& choice : choices_) {  // "sofa", "tv", "bed"
                Words cw = words(choice);
                std::size_t k = 0;
                Phrase one = p.phrase(cw, k, false);
                for (const auto& cat : one.categories.empty() ? std::vector<std::string>{one.noun} : one.categories)
                    if (std::find(any.categories.begin(), any.categories.end(), cat) == any.categories.end())
                        any.categories.push_back(cat);
            }
            subject = any;
        } else if (!isOneOf(c.peek(), {"is", "are"})) {
            subject = p.phrase(c.w, c.i, true);
        }
        if (c.accept({"is|are"})) {
            c.accept({"the"});
            if (!subject) subject = anyThing("object");
            if (c.done()) return false;
            // "closest to the window" orders the subject; "the largest (one)" may name it again.
            std::string first = c.peek();
            if (isOneOf(first, {"closest", "nearest", "farthest", "furthest"}) &&
                isOneOf(c.peek(1), {"to", "from", "away"})) {
                p.posts(c.w, c.i, *subject);
            } else {
                Phrase tail = p.phrase(c.w, c.i, true);
                if (!tail.order) return false;
                if (tail.kind == std::optional<std::string>("object")) {
                    subject->order = tail.order;
                    subject->pick = tail.pick;
                    subject->top = tail.top;
                    for (auto& cond : tail.conditions) subject->conditions.push_back(std::move(cond));
                    for (auto& filter : tail.filters) subject->filters.push_back(std::move(filter));
                } else {
                    subject = std::move(tail);
                }
            }
        }
        if (!subject || !subject->order) return false;
        out.kind = QuestionKind::Superlative;
        out.pick = std::max<std::size_t>(subject->pick, 1);
        out.top = subject->top;
        out.smql = findText(*subject, false);
        out.measure = subject->order->words;
        describeSubject(*subject, out);
        return true;
    }

    // Where is the red mug? Find the bottle.
    bool locate(Cursor& c, PhraseParser& p, Translation& out) {
        // "what is the window above the table?", "in what part of the room is the sofa?"
        if (c.accept({"in|on", "what|which", "part|side|corner|area", "of", "the", "room|scene"}) ||
            c.accept({"in|on", "what|which", "part|side|corner|area"})) {
            if (!c.accept({"is|are|does|do"})) return false;
            Phrase thing;
            std::size_t end = c.w.size();
            while (end > c.i && isOneOf(c.w[end - 1], {"located", "placed", "kept", "sit", "stand", "hang", "go"}))
                --end;
            if (!phraseWithin(c, p, end, thing)) return false;
            c.i = c.w.size();
            return locateAnswer(thing, out);
        }
        if (c.accept({"what|which", "is|are", "the|a|an"})) {
            c.i -= 1;
            // "what is the only window in the room?": which one it is, and where.
            const bool only = c.peek(1) == "only";
            Phrase thing = p.phrase(c.w, c.i, true);
            c.skip({"located", "placed"});
            if ((thing.conditions.empty() && !(only && !thing.kind)) || !c.done()) return false;
            return locateAnswer(thing, out);
        }
        bool where = c.accept({"where"});
        if (where) {
            c.accept({"exactly"});
            if (c.accept({"does|do"})) {
                // "where does the shower curtain hang?"
                auto verb =
                    std::find_if(c.w.begin() + static_cast<std::ptrdiff_t>(c.i), c.w.end(), [](const std::string& w) {
                        return isOneOf(w, {"hang", "sit", "stand", "lie", "go", "belong", "rest", "stay", "run"});
                    });
                if (verb == c.w.end()) return false;
                Phrase thing;
                if (!phraseWithin(c, p, static_cast<std::size_t>(verb - c.w.begin()), thing)) return false;
                c.i = c.w.size();
                return locateAnswer(thing, out);
            }
            bool verb = c.accept({"is|are|was|were|would|do|did|can|could"});
            c.accept({"i|we|one|you", "find|leave|put|see|keep|left|get"});
            if (!verb) {
                // "where the lamp is"
                Phrase thing = p.phrase(c.w, c.i, true);
                if (!c.accept({"is|are|was|were"})) return false;
                c.skip({"located", "kept"});
                return locateAnswer(thing, out);
            }
        } else if (c.accept({"find|locate|show|point|get|fetch|bring|grab"}) ||
                   // "I am looking for the basket", "I need a chair", "help me find the remote",
                   // "could you find the lamp?": a request to find it.
                   c.accept({"i", "am|was", "looking|searching", "for"}) || c.accept({"looking|searching", "for"}) ||
                   c.accept({"i", "need|want"}) || c.accept({"help", "me", "find|locate"}) ||
                   c.accept({"can|could|would", "you", "find|locate|show"})) {
            c.accept({"me"});
            c.accept({"to"});
        } else {
            return false;
        }
        Phrase thing = p.phrase(c.w, c.i, true);
        takeTrailingColour(c, thing);
        if (where && c.accept({"and"})) {
            // "where are the black magazine rack and the silver magazine rack located?": each of them.
            Phrase other = p.phrase(c.w, c.i, true);
            c.skip({"located", "kept", "placed", "positioned", "situated"});
            if (!c.done()) return false;
            out.kind = QuestionKind::Locate;
            out.smql = fmt::format("FIND thing WHERE {} OR {} PATH", matchText(thing), matchText(other));
            out.subject = thing.words + " or " + other.words;
            out.subjectPlural = "things";
            return true;
        }
        c.skip({"located", "kept", "placed", "be", "attached", "mounted", "positioned", "situated", "installed",
                "stored", "hung", "hanging", "lying", "sitting", "standing", "resting", "set"});
        // "where is the radiator affixed?", "where is the curtain hanged?": how it is placed is where.
        if (where && c.i + 1 == c.w.size() && isVerbOfPlace(c.peek())) ++c.i;
        if (!where && !thing.order && !thing.conditions.empty()) return false;  // "show me everything on ..."
        return locateAnswer(thing, out);
    }

    // The verb of place between a subject and its predicate, which says no more than the predicate: "what is located
    // on ...", "what is stacked up on ...", "what is leaning against ...", "what is set above ...", "what is thrown
    // over ..." (an irregular form is one WordNet takes back to another base: thrown, built).
    static void skipVerbOfPlace(Cursor& c) {
        const std::size_t verbAt = c.i;
        c.skip({"present", "seen", "found", "hanged", "hung", "directly", "just", "located", "placed", "sitting",
                "lying", "standing", "kept", "hanging", "positioned", "situated"});
        auto verbForm = [](const std::string& w) {
            if (w.ends_with("ing") || w.ends_with("ed") || isOneOf(w, {"set", "put"})) return true;
            const auto bases = wordnet::baseForms(w);
            return std::any_of(bases.begin(), bases.end(), [&](const std::string& b) { return b != w; });
        };
        if (c.i == verbAt && !c.done() && verbForm(c.peek()) && !PhraseParser::predicateAt(c.w, c.i)) {
            std::size_t k = c.i + 1;
            if (k < c.w.size() && isOneOf(c.w[k], {"up", "down", "out", "around", "sideways", "together"}) &&
                !PhraseParser::predicateAt(c.w, k))
                ++k;
            if (PhraseParser::predicateAt(c.w, k)) c.i = k;
        }
    }

    // What is on the desk near the left wall? Which chairs are near the table? Show me everything
    // on the counter.
    bool relational(Cursor& c, PhraseParser& p, Translation& out) {
        Phrase thing;
        if (c.accept({"what|which"})) {
            c.accept({"else"});  // "what else is on the bed besides the pillows?"
            std::size_t at = c.i;
            static const std::initializer_list<std::string_view> verbs{"is",    "are",    "sits",   "sit",   "lies",
                                                                       "lie",   "stands", "stand",  "rests", "rest",
                                                                       "hangs", "hang",   "hanged", "hung"};
            // "what faces the sofa?", "what surrounds the table?": a verb that is a predicate, of any thing.
            const bool verbFirst =
                c.peek().ends_with('s') && !isOneOf(c.peek(), verbs) && PhraseParser::predicateAt(c.w, c.i).has_value();
            if (verbFirst || isOneOf(c.peek(), verbs) || isOneOf(c.peek(), {"do", "can", "could", "will", "would"})) {
                thing.kind = "object";
                thing.noun = "thing";
            } else {
                thing = p.phrase(c.w, c.i, false);
                if (c.i == at) return false;
                // "what type of table in the room is ...": the room is the scene.
                if (std::size_t k = c.i + 1; c.peek() == "in") {
                    while (k < c.w.size() && isOneOf(c.w[k], {"the", "this", "a"})) ++k;
                    if (std::size_t place = p.scenePlaceAt(c.w, k); place > 0) c.i = k + place;
                }
            }
            // "which chairs face the table?": the predicate is the verb.
            bool verbIsPredicate = PhraseParser::predicateAt(c.w, c.i).has_value() && (c.i > at || verbFirst);
            if (!verbIsPredicate &&
                !c.accept({"is|are|sits|sit|lies|lie|stands|stand|rests|rest|hangs|hang|hanged|hung"}) &&
                !c.accept({"do|can|will|would", "you|i", "see|find|have"}) && !c.accept({"is|are", "there"}) &&
                !c.accept({"can|could", "be", "seen|found"}))
                return false;
            c.accept({"there|here"});
            // "what is there?", "what objects are there?", "what is here?": where nothing follows, the
            // scene's things, all of them.
            const bool thereAlone = c.done() && isOneOf(c.w[c.i - 1], {"there", "here"});
            // "what is orange behind me on the floor?", "which objects are black?": a thing of that colour.
            bool colourAlone = false;
            if (auto colour = colourOf(c.peek());
                colour && !thing.colour && (PhraseParser::predicateAt(c.w, c.i + 1) || c.i + 1 == c.w.size())) {
                thing.colour = colour;
                colourAlone = c.i + 1 == c.w.size();
                ++c.i;
            } else if (c.i + 3 == c.w.size() && !thing.colour && thing.kind == "object" && c.peek() == "the" &&
                       isOneOf(c.w[c.i + 2],
                               {"thing", "things", "object", "objects", "one", "ones", "item", "items"})) {
                // "what is the red thing?", "what are the black objects?": the things of that colour.
                if (auto colour = colourOf(c.w[c.i + 1])) {
                    thing.colour = colour;
                    colourAlone = true;
                    c.i += 3;
                }
            }
            // "what doors are open to the right of the bunk beds?": the memory keeps no such state.
            if (isOneOf(c.peek(), {"open", "opened", "closed", "shut", "empty", "full", "lit"}) &&
                PhraseParser::predicateAt(c.w, c.i + 1)) {
                out.notes.push_back(fmt::format("'{}' is left out: the memory keeps no such state", c.peek()));
                ++c.i;
            }
            std::size_t verbAt = c.i;
            skipVerbOfPlace(c);
            std::size_t before = thing.conditions.size();
            const std::size_t postsAt = c.i, filtersBefore = thing.filters.size();
            p.posts(c.w, c.i, thing);
            // "what is in the room?", "what objects are in here?", "what is in the kitchen?" (the scene a
            // kitchen): the whole scene, read without a condition (not "in the corner", a part of the room the
            // memory keeps nothing of).
            const bool wholeScene =
                thereAlone || colourAlone || (c.done() && postsAt < c.w.size() && namesSceneFrom(c.w, postsAt, p));
            // "what is taller than 1 m?": a measure of its own is a condition too.
            if (thing.conditions.size() == before && thing.filters.size() == filtersBefore && thing.excluded.empty() &&
                !wholeScene)
                return false;
            if (verbIsPredicate && thing.conditions.size() > before) {
                // "face the table" reads in the answer as "facing the table": the table's first phrase.
                auto& cond = thing.conditions[before];
                std::size_t took = PhraseParser::predicateAt(c.w, verbAt)->second;
                const auto* spec = relations::predicateNamed(cond.predicate);
                std::size_t words = 1 + static_cast<std::size_t>(std::count(cond.words.begin(), cond.words.end(), ' '));
                if (spec)
                    cond.words = std::string(relations::englishPhrases(*spec).front()) + " " +
                                 joined(c.w, verbAt + took, verbAt + words);
            }
        } else if (c.accept({"show|list|give|tell|name|find|locate|get|fetch|bring"})) {
            c.accept({"me|us"});
            c.accept({"a|the", "list|rundown|inventory", "of"});  // "give me a list of all the chairs"
            // "tell me about the desk" asks for all the memory holds of it (readDescription).
            if (c.peek() == "about" || c.accept({"more", "about"})) return false;
            c.accept({"all|every"});
            c.accept({"of"});
            thing = p.phrase(c.w, c.i, true);
            if (!thing.kind && thing.conditions.empty()) return locateAnswer(thing, out);
            // "list all objects", "name the things in the room": a kind word alone lists them all.
            if (thing.conditions.empty() && thing.excluded.empty() && thing.kind != "object" && thing.kind != "thing")
                return false;
        } else {
            return false;
        }
        nearestFirstBeside(thing);
        out.kind = QuestionKind::Relational;
        out.smql = findText(thing, false);
        describeSubject(thing, out);
        return true;
    }

    // Is the sofa longer than the bed? Is the chair closer to the door than the bed? Are the
    // cushions smaller than the lamp?
    bool comparison(Cursor& c, PhraseParser& p, Translation& out) {
        // "how much taller is the lamp than the table?": by how much.
        const bool byHowMuch = c.accept({"how", "much"});
        std::optional<Comparative> cmp;
        std::string word;
        Phrase a;
        if (byHowMuch) {
            cmp = comparativeOf(c.peek());
            if (!cmp || cmp->measure == "distance") return false;
            word = c.peek();
            ++c.i;
            if (!c.accept({"is|are|was|were"})) return false;
            a = p.phrase(c.w, c.i, true);
        } else {
            if (!c.accept({"is|are|was|were"})) return false;
            a = p.phrase(c.w, c.i, true);
            c.accept({"any|much|a|lot|bit|little|even|still"});
            c.accept({"lot|bit|little"});
            cmp = comparativeOf(c.peek());
            if (!cmp) return false;
            word = c.peek();
            ++c.i;
        }
        // "longer or shorter than": the first is asked, the answer says which.
        if (c.peek() == "or" && comparativeOf(c.peek(1))) c.i += 2;
        std::optional<Phrase> to;
        std::string toWords;
        if (cmp->measure == "distance") {
            std::size_t at = c.i;
            c.accept({"away"});
            if (!c.accept({"to|from"})) return false;
            to = p.phrase(c.w, c.i, false);
            toWords = joined(c.w, at, c.i);
        }
        if (!c.accept({"than"})) return false;
        Phrase b = p.phrase(c.w, c.i, true);
        c.accept({"is|are|does|do"});
        c.accept({"to|from", "it|them"});
        compared(a, b, *cmp, toWords.empty() ? word : word + " " + toWords, to, out);
        out.byHowMuch = byHowMuch;
        return true;
    }

    // How tall is the lamp compared to the nightstand? How big is the bed in comparison with the sofa? By how much,
    // whichever way it goes (Translation::eitherWay): the comparative of the size asked ("taller") orders the rows.
    bool comparedTo(Cursor& c, PhraseParser& p, Translation& out) {
        if (!c.accept({"how"}) || c.peek().empty()) return false;
        std::string word;
        const std::optional<Comparative> cmp = comparativeOfSize(c.peek(), word);
        if (!cmp) return false;
        ++c.i;
        if (!c.accept({"is|are|was|were"})) return false;
        std::size_t said = c.i;
        while (said < c.w.size() && !isOneOf(c.w[said], {"compared", "relative", "against", "versus", "vs"}) &&
               !(c.w[said] == "in" && said + 1 < c.w.size() && c.w[said + 1] == "comparison"))
            ++said;
        Phrase a;
        if (said == c.w.size() || !phraseWithin(c, p, said, a)) return false;
        if (!c.accept({"compared|relative", "to|with"}) && !c.accept({"in", "comparison", "to|with"}) &&
            !c.accept({"against|versus|vs"}))
            return false;
        const Phrase b = p.phrase(c.w, c.i, true);
        compared(a, b, *cmp, word, std::nullopt, out);
        out.byHowMuch = out.eitherWay = true;
        return true;
    }

    // The adjective of a size named by its noun ("height": "tall"), or "" for a noun that names none.
    static std::string adjectiveOfMeasure(const std::string& noun) {
        static const std::map<std::string, std::string> adjectives{
            {"size", "large"}, {"volume", "large"}, {"height", "tall"}, {"width", "wide"}, {"length", "long"}};
        const auto at = adjectives.find(noun);
        return at == adjectives.end() ? std::string() : at->second;
    }

    // The comparative of a size's adjective ("tall": "taller", "big": "bigger"), its word in `word`; none for a
    // distance or a word that is no size.
    static std::optional<Comparative> comparativeOfSize(const std::string& adjective, std::string& word) {
        if (adjective.empty()) return std::nullopt;
        for (const std::string& more : {adjective + "er", adjective + "r", adjective + adjective.back() + "er"})
            if (auto cmp = comparativeOf(more); cmp && cmp->measure != "distance") {
                word = more;
                return cmp;
            }
        return std::nullopt;
    }

    // Are the two nightstands the same height? Is the sofa the same size as the bed? Is the lamp as tall as the
    // table? By how much, either way (comparedTo), and whether they are alike (predicate "the same").
    bool sameAs(Cursor& c, PhraseParser& p, Translation& out) {
        if (!c.accept({"is|are"})) return false;
        const Words& w = c.w;
        std::size_t k = c.i;
        while (k + 2 < w.size() && !(w[k] == "the" && w[k + 1] == "same") && !(w[k] == "as" && w[k + 2] == "as")) ++k;
        if (k + 2 >= w.size()) return false;
        std::string word;
        const auto cmp = comparativeOfSize(w[k] == "the" ? adjectiveOfMeasure(w[k + 2]) : w[k + 1], word);
        if (!cmp) return false;
        const bool same = w[k] == "the";
        Phrase a, b;
        if (same && k + 3 == w.size()) {
            // "are the sofa and the bed the same size?", "are the two nightstands the same height?"
            if (!twoSides(c, p, k, a, b)) return false;
            c.i = w.size();
        } else {
            // "is the sofa the same size as the bed?", "is the lamp as tall as the table?"
            const std::size_t other = same ? k + 4 : k + 3;
            if (other > w.size() || w[other - 1] != "as" || !phraseWithin(c, p, k, a)) return false;
            c.i = other;
            b = p.phrase(w, c.i, true);
        }
        compared(a, b, *cmp, word, std::nullopt, out);
        out.byHowMuch = out.eitherWay = true;
        out.predicate = "the same";
        return true;
    }

    // The two sides of a comparison and the measure the comparative orders them by (or the distance to `to`).
    static void compared(const Phrase& a, const Phrase& b, const Comparative& cmp, const std::string& predicate,
                         const std::optional<Phrase>& to, Translation& out) {
        auto side = [](const Phrase& ph) {
            if (!ph.id.empty()) return std::vector<std::string>{ph.id.substr(ph.id.find('#'))};
            return ph.categories.empty() ? std::vector<std::string>{ph.noun} : ph.categories;
        };
        out.kind = QuestionKind::Comparison;
        out.roles = {side(a), side(b)};
        out.measure = cmp.measure;
        out.greater = cmp.descending;
        out.predicate = predicate;
        std::string order = cmp.measure == "distance" ? "distance(" + reference(*to) + ")" : cmp.measure;
        std::string columns = cmp.measure == "distance" ? "id, category, distance" : "id, category, " + cmp.measure;
        const std::string both = matchText(a) == matchText(b) ? matchText(a) : matchText(a) + " OR " + matchText(b);
        out.smql = fmt::format("FIND thing WHERE {} ORDER BY {}{} RETURN {}", both, order,
                               cmp.descending ? " DESC" : "", columns);
        describeSubject(a, out);
        out.object = b.words;
        out.condition =
            cmp.measure == "distance" ? (to->words.empty() ? "away" : "from the " + to->words) : cmp.adjective;
    }

    // "vase?", "cushions on the sofa", "red mug": a thing named alone, as a search is typed, asks where it is. Only
    // words that name the scene's kinds (an unknown word stays a question nothing reads).
    bool named(Cursor& c, PhraseParser& p, Translation& out) {
        Phrase thing = p.phrase(c.w, c.i, true);
        if (!c.done() || thing.categories.empty() || !p.unknownWords().empty()) return false;
        return locateAnswer(thing, out);
    }

    // Is the door open? Is the lamp on? Are the windows closed? The memory keeps no state of a
    // thing: the question is refused saying so, not answered by a guess.
    bool state(Cursor& c, PhraseParser& p, Translation&) {
        if (!c.accept({"is|are"}) || c.w.size() < c.i + 2) return false;
        const std::string& word = c.w.back();
        if (!isOneOf(word, {"open", "opened", "closed", "shut", "on", "off", "lit", "empty", "full", "locked",
                            "unlocked", "broken", "clean", "dirty", "running", "working"}))
            return false;
        // "is the monitor turned on?", "are the lights switched off?": the state, said with its verb.
        std::size_t end = c.w.size() - 1;
        const bool turned = end > c.i + 1 && isOneOf(c.w[end - 1], {"turned", "switched", "left", "kept", "still"});
        if (turned) --end;
        Phrase thing;
        if (!phraseWithin(c, p, end, thing)) return false;
        const std::string& verb = c.w.front();  // is | are, as the question has it
        throw Error(ErrorKind::Binding,
                    fmt::format("the memory keeps no state of the {}: not whether {} {} {}{}", thing.words,
                                verb == "are" ? "they" : "it", verb, turned ? c.w[end] + " " : "", word),
                    std::nullopt,
                    fmt::format("it keeps where things are, their size, colour and kind: ask as in: where {} the {}? "
                                "what is near the {}?",
                                verb, thing.words, thing.words));
    }

    // Is the lamp left of the window? Does the lamp stand on the desk? Is the mug red?
    bool yesNo(Cursor& c, PhraseParser& p, Translation& out) {
        bool does = false;
        if (!c.accept({"is|are"})) {
            if (!c.accept({"does|do"})) return false;
            does = true;
        }
        Phrase subject;
        if (does) {
            // "does the lamp stand on the desk": the subject ends at the verb.
            auto verb =
                std::find_if(c.w.begin() + static_cast<std::ptrdiff_t>(c.i), c.w.end(), [](const std::string& w) {
                    return isOneOf(
                        w, {"stand", "stands", "sit", "sits", "lie", "lies", "hang", "hangs", "rest", "rests", "be"});
                });
            if (verb == c.w.end()) return false;
            std::size_t end = static_cast<std::size_t>(verb - c.w.begin());
            if (!phraseWithin(c, p, end, subject)) return false;
            ++c.i;
        } else {
            subject = p.phrase(c.w, c.i, false);
        }
        const std::size_t subjectEnd = c.i;
        // "is the table on my left black?": whether there is such a thing where it is said to be.
        if (!does && c.i + 1 < c.w.size() && !subject.colour && colourOf(c.w.back())) {
            Words head(c.w.begin(), c.w.end() - 1);
            std::size_t k = c.i;
            Phrase placed = subject;
            try {
                p.posts(head, k, placed);
            } catch (const Error&) {
                k = c.i;
            }
            if (k == head.size() && !placed.conditions.empty()) {
                placed.colour = colourOf(c.w.back());
                c.i = c.w.size();
                out.kind = QuestionKind::Existence;
                out.smql = findText(placed, false);
                describeSubject(placed, out);
                return true;
            }
        }
        // "is the mug red?": whether there is such a thing.
        if (c.i + 1 == c.w.size() && !subject.colour && colourOf(c.peek())) {
            subject.colour = colourOf(c.peek());
            ++c.i;
            out.kind = QuestionKind::Existence;
            out.smql = findText(subject, false);
            describeSubject(subject, out);
            return true;
        }
        Phrase checked;
        checked.noun = subject.noun;
        const std::size_t place = c.i;
        p.posts(c.w, c.i, checked);
        // "is the fridge in the room?", "... in the kitchen" of a scene that is one: the place is the whole scene (no
        // condition), which holds such a thing or not; "is the sofa longer than 2 m?": whether there is one that is.
        if (checked.conditions.empty() && c.i > place && c.done()) {
            subject.filters.insert(subject.filters.end(), checked.filters.begin(), checked.filters.end());
            subject.measured = checked.measured;
            out.kind = QuestionKind::Existence;
            out.smql = findText(subject, false);
            describeSubject(subject, out);
            return true;
        }
        if (checked.conditions.size() != 1) return false;
        const Condition& cond = checked.conditions.front();
        describeSubject(subject, out);
        out.kind = QuestionKind::YesNo;
        out.predicate = cond.predicate;
        out.condition = cond.words;
        const auto* spec = relations::predicateNamed(cond.predicate);
        if (cond.predicate == "between" || cond.metres || cond.negated || (spec && spec->relateRank == 0) ||
            cond.args.front().here) {
            // RELATE compares two things: "between" takes three, a distance is a question of its own,
            // what RELATE leaves out (visible_from) and the person where the viewer stands (HERE, no node) are asked
            // as a FIND.
            subject.conditions.push_back(cond);
            out.smql = findText(subject, false);
            out.kind = QuestionKind::Existence;
            return true;
        }
        out.object = cond.args.front().words;
        // "are all the cushions on the sofa?", "is every cushion on a sofa?": of every one of them, so the ones it does
        // not hold of answer (none: yes). Without "all", one that holds says yes ("are the cushions on the sofa?").
        const bool every =
            !does && subject.id.empty() && !subject.pick &&
            std::any_of(c.w.begin(), c.w.begin() + static_cast<std::ptrdiff_t>(subjectEnd), [](const std::string& w) {
                return isOneOf(w, {"all", "every", "each"});
            });
        if (every) {
            Condition notHeld = cond;
            notHeld.negated = true;
            subject.conditions.push_back(notHeld);
            out.measure = "every";
            out.smql = findText(subject, false);
            return true;
        }
        out.smql = fmt::format("RELATE {} TO {}", reference(subject), reference(cond.args.front()));
        return true;
    }

    // What does the urinal look like? What does the cabinet near the copier say? (read_description.cpp)
    bool description(Cursor& c, PhraseParser& p, Translation& out) {
        return readDescription(c.w, c.i, p, question_.sceneRoot, out);
    }

    // Where am I? Where the person stands (the scene's viewpoint, or the thing a situation put them at), said by the
    // thing nearest it.
    bool whereAmI(Cursor& c, PhraseParser& p, Translation& out) {
        if (!c.accept({"where", "am|are", "i|we"})) return false;
        c.skip({"now", "right", "standing", "exactly"});
        if (!c.done()) return false;
        Phrase nearest = anyThing("object");
        nearest.order = Order{"distance", false, {p.person()}, "nearest to you"};
        nearest.pick = 1;
        out.kind = QuestionKind::Superlative;
        out.smql = findText(nearest, true);
        out.measure = nearest.order->words;
        describeSubject(nearest, out);
        out.notes.push_back(self_ ? "you stand where the situation put you; the thing nearest you says where that is"
                                  : "you stand at the scene's viewpoint (SHOW SCENES shows it); the thing nearest it "
                                    "says where that is");
        return true;
    }

    // Which room is the chair in? In what room is the toilet? For each thing of the kind, the kind of room whose marks
    // (kRoomMarks) stand nearest it within a room's area (kRoomAreaReach): the things and the marks with their boxes,
    // which the answer measures between.
    bool roomOf(Cursor& c, PhraseParser& p, Translation& out) {
        std::size_t end = c.w.size();
        if (c.accept({"which|what", "room|part", "is|are"}) ||
            c.accept({"which|what", "part", "of", "the", "house|home|flat|apartment", "is|are"})) {
            if (end == 0 || c.w[end - 1] != "in") return false;  // "which room is the largest?" is not asked here
            --end;
        } else if (c.accept({"which|what", "room", "has|holds|contains|houses"})) {
            // "which room has the toilet?": the room is the one its thing is in; "which room has the most chairs?": the
            // rooms by how many they hold.
            if (c.accept({"the", "most|fewest"}) || c.accept({"most|fewest"})) out.measure = c.w[c.i - 1];
        } else if (!c.accept({"in", "which|what", "room|part", "is|are"})) {
            return false;
        }
        if (isOneOf(c.peek(), {"this", "it", "here", "i", "we"})) return false;
        Phrase thing;
        if (!phraseUpTo(c.w, c.i, end, p, thing)) return false;
        c.i = c.w.size();
        return roomTally(thing, out.measure, p, out);
    }

    // How many chairs per room? How many things are there by room? Counted by the kind of room (roomTally).
    bool perRoom(Cursor& c, PhraseParser& p, Translation& out) {
        if (c.w.size() < 5 || c.w.back() != "room" || !isOneOf(c.w[c.w.size() - 2], {"per", "by"}) ||
            !c.accept({"how", "many"}))
            return false;
        const Words head(c.w.begin(), c.w.end() - 2);
        const Phrase thing = p.phrase(head, c.i, true);
        while (c.i < head.size() && isOneOf(head[c.i], {"is", "are", "there", "here", "in", "the", "house", "home"}))
            ++c.i;
        if (c.i != head.size()) return false;
        c.i = c.w.size();
        return roomTally(thing, "each", p, out);
    }

    // The things of a kind (or every thing: "which room has the most things?") and every mark of a kind of room
    // (kRoomMarks), with their boxes: the answer puts each thing in the kind of room whose mark stands nearest it
    // (answer.cpp, roomOf). `measure` is "" (which room is each in), "each" (how many in each), "most" or "fewest".
    static bool roomTally(const Phrase& thing, const std::string& measure, PhraseParser& p, Translation& out) {
        // A kind of thing, as it is named: the answer measures each of them.
        const bool everyThing = thing.categories.empty() && (thing.kind == "object" || thing.kind == "thing");
        if (!thing.id.empty() || (thing.kind && !everyThing) || !thing.side.empty() || thing.colour ||
            !thing.conditions.empty() || !thing.filters.empty() || !thing.excluded.empty() || thing.order)
            return false;
        // Every thing: an empty list of kinds asked (answer.cpp).
        std::vector<std::string> asked = everyThing                 ? std::vector<std::string>{}
                                         : thing.categories.empty() ? std::vector<std::string>{hyphenated(thing.noun)}
                                                                    : thing.categories;
        // The things asked about and every mark, one query: FIND's category alternatives (conditionsOf).
        Phrase both;
        both.noun = "thing";
        both.categories = asked;
        for (const auto& m : p.roomMarks())
            for (const auto& category : m)
                if (std::find(both.categories.begin(), both.categories.end(), category) == both.categories.end())
                    both.categories.push_back(category);
        out.kind = QuestionKind::RoomOf;
        out.measure = measure;
        out.smql = (everyThing ? std::string("FIND object") : findText(both, false)) + " RETURN id, category, box";
        for (const auto& row : kRoomMarks) out.choices.emplace_back(row.room);
        out.roles = p.roomMarks();
        out.roles.push_back(asked);  // after the rooms' marks: the things asked about
        describeSubject(thing, out);
        return true;
    }

    // What is in the middle of the room? What stands in the corners? The things by where they stand in the room's
    // outline (answer.cpp: roomPlace measures it from the floor, else from the things' boxes), so every thing's box.
    // "Is the table in the middle of the room?", "are the chairs in the corners?": the things of the kind asked about
    // (Translation::roles), each in it or not.
    bool roomPlace(Cursor& c, PhraseParser& p, Translation& out) {
        std::optional<Phrase> asked;
        if (c.accept({"is|are"})) {
            c.accept({"there"});  // "is there a chair in the corner?"
            const std::size_t at = c.i;
            asked = p.phrase(c.w, c.i, false);
            if (c.i == at || !asked->conditions.empty() || asked->colour || !asked->filters.empty() ||
                !asked->excluded.empty())
                return false;
        } else {
            if (!c.accept({"what|which"})) return false;
            c.accept({"things|objects|furniture|thing|object|item|items"});
            if (!c.accept({"is|are|stands|stand|sits|sit|lies|lie"})) return false;
            c.accept({"there"});
        }
        c.skip(kPlacedBy);
        if (!c.accept({"in|at|near|around|by"})) return false;
        c.accept({"the|a|one"});
        if (c.accept({"middle|centre|center|midst"}))
            out.measure = "middle";
        else if (c.accept({"corner|corners"}))
            out.measure = "corner";
        else
            return false;
        // "... of the room", "... of this office", "... here", or nothing.
        if (c.accept({"of"})) {
            c.accept({"the|this|my|our"});
            const std::size_t place = p.scenePlaceAt(c.w, c.i);
            if (place == 0) return false;
            c.i += place;
        }
        c.accept({"here"});
        if (!c.done()) return false;
        out.kind = QuestionKind::RoomPlace;
        out.smql = "FIND thing RETURN id, category, kind, box";
        out.subject = "thing";
        out.subjectPlural = "things";
        // "Is there anything in the middle of the room?": what is there, listed.
        if (asked && asked->kind) asked.reset();
        if (asked) {
            // A kind the scene holds none of keeps its word, which no row matches: the answer says it is not here.
            out.roles = {asked->categories.empty() ? std::vector<std::string>{model::categoryName(asked->noun)}
                                                   : asked->categories};
            describeSubject(*asked, out);
        }
        return true;
    }

    // What kind of room is this? What room am I in? Is this a kitchen? The scene's things, and which of them mark a
    // kind of room (kRoomMarks): the answer names the kinds they mark.
    bool roomKind(Cursor& c, PhraseParser& p, Translation& out) {
        if (roomOf(c, p, out)) return true;
        c.i = 0;
        std::string asked;
        // "in here", "in this apartment": the whole scene, said or not.
        auto here = [&] {
            return c.done() || c.accept({"here"}) || c.accept({"in", "here"}) ||
                   c.accept({"in", "this|the", "place|space|home|house|flat|apartment|scene"});
        };
        // "how many rooms are there?", "how many rooms does this place have?": the kinds of room its things mark.
        // "how many bedrooms are there?": a kind of room, which things mark (not a thing called so).
        auto roomsNamed = [&]() -> const RoomMarks* {
            for (const auto& marks : kRoomMarks) {
                const Words plural = words(pluralOf(std::string(marks.room)));
                if (c.i + plural.size() <= c.w.size() &&
                    std::equal(plural.begin(), plural.end(), c.w.begin() + static_cast<std::ptrdiff_t>(c.i))) {
                    c.i += plural.size();
                    return &marks;
                }
            }
            return nullptr;
        };
        bool count = c.accept({"how", "many", "rooms"});
        const RoomMarks* kindCounted = nullptr;
        if (!count && c.accept({"how", "many"})) {
            kindCounted = roomsNamed();
            count = kindCounted != nullptr;
            if (!count) c.i = 0;
        }
        if (count) {
            if (!c.done() && !c.accept({"are", "there"}) &&
                !c.accept({"does|do", "it|this|the", "place|space|home|house|flat|apartment|scene", "have"}) &&
                !c.accept({"does|do", "it", "have"}))
                return false;
            here();
            if (kindCounted) asked = std::string(kindCounted->room);
        } else if (c.accept({"what|which", "kind|type|sort", "of", "room|place|space"}) ||
                   c.accept({"what|which", "room|place|space"}) ||
                   c.accept({"what", "is", "this", "room", "used", "for"}) ||
                   c.accept({"what", "is", "this", "room", "for"})) {
            // "... is this?", "... am I in?", "... is it?"
            if (!c.done() && !c.accept({"is", "this|it|here"}) && !c.accept({"am", "i", "in"}) &&
                !c.accept({"are", "we", "in"}))
                return false;
        } else if (c.accept({"is", "this|it|here"}) || c.accept({"am", "i", "in"}) || c.accept({"are", "we", "in"})) {
            // "is this a kitchen?", "am I in the bathroom?"
            c.accept({"a|an|the|my|our"});
            const RoomMarks* known = roomNamedAt(c.w, c.i);
            if (!known || c.i + words(std::string(known->room)).size() != c.w.size()) return false;
            asked = std::string(known->room);
            c.i = c.w.size();
        } else if (c.accept({"is", "there", "a|an"})) {
            // "is there a kitchen here?": a kind of room, which things mark, not a thing named so ("is there a
            // kitchen cabinet?" is a thing).
            const RoomMarks* known = roomNamedAt(c.w, c.i);
            if (!known) return false;
            c.i += words(std::string(known->room)).size();
            if (!here()) return false;
            asked = std::string(known->room);
        } else {
            return false;
        }
        if (!c.done()) return false;
        out.kind = QuestionKind::RoomKind;
        out.smql = "FIND object RETURN id, category";
        out.predicate = asked;
        if (count) out.measure = "count";
        for (const auto& marks : kRoomMarks) out.choices.emplace_back(marks.room);
        out.roles = p.roomMarks();
        out.subject = "room";
        out.subjectPlural = "rooms";
        return true;
    }

    // ------------------------------------------------------------ helpers

    bool repeated(const std::string& category) const {
        return std::find(question_.repeatedCategories.begin(), question_.repeatedCategories.end(), category) !=
               question_.repeatedCategories.end();
    }

    static std::vector<std::string> wordsFor(const std::string& verb);

    // Says which words were not read and offers the nearest question that can be.
    Error unreadable() const;

    const Question& question_;
    const Lexicon& lexicon_;
    Words words_;
    std::string unit_ = "m";
    bool averageAsked_ = false;
    std::vector<std::string> choices_;
    std::optional<Self> self_;
};

std::vector<std::string> QuestionReader::wordsFor(const std::string& verb) {
    std::vector<std::string> out{verb};
    for (const auto& base : wordnet::baseForms(verb)) out.push_back(base);
    return out;
}

// The questions ASK reads, one per form, for the did-you-mean of a question it cannot.
struct Example {
    std::string_view text;
    std::string_view shape;  // with X and Y for the question's own nouns
};
constexpr Example kExamples[] = {
    {"where is the mug", "where is the X?"},
    {"what is on the desk", "what is on the X?"},
    {"how many chairs are there", "how many Xs are there?"},
    {"is there a sofa", "is there a X?"},
    {"is the lamp left of the window", "is the X left of the Y?"},
    {"how far is the sofa from the door", "how far is the X from the Y?"},
    {"which did I see first, the bed or the sofa", "which did I see first, the X or the Y?"},
    {"how big is the table", "how big is the X?"},
    {"which is the largest object", "which is the largest X?"},
    {"which chair is closest to the window", "which X is closest to the Y?"},
    {"how do i get to the bed from the door", "how do I get to the X from the Y?"},
    {"can i see the plant from the door", "can I see the X from the Y?"},
    {"where can i sit", "where can I sit?"},
    {"what color is the sofa", "what color is the X?"},
    {"where is the lamp relative to the window", "where is the X relative to the Y?"},
    {"what changed", "what changed?"},
};

Error QuestionReader::unreadable() const {
    // The words that name things here, and the ones nothing reads.
    std::vector<std::string> nouns, unread;
    static const std::initializer_list<std::string_view> grammar{
        "what", "where", "which", "how",  "is",   "are",  "the",  "a",    "an",   "there", "many",
        "much", "can",   "i",     "you",  "do",   "does", "of",   "to",   "from", "in",    "on",
        "and",  "or",    "me",    "my",   "it",   "this", "that", "be",   "get",  "far",   "big",
        "see",  "find",  "any",   "some", "most", "than", "more", "with", "for",  "at",    "by"};
    for (std::size_t k = 0; k < words_.size(); ++k) {
        const std::string& w = words_[k];
        if (isOneOf(w, grammar) || PhraseParser::predicateAt(words_, k)) continue;
        WordMatch m = lexicon_.lookUp(w);
        if (!m.categories.empty() && m.how != WordMatch::How::Spelling)
            nouns.push_back(m.categories.front());
        else if (m.how == WordMatch::How::Unknown || m.how == WordMatch::How::Spelling)
            unread.push_back(w);
    }
    // The form whose words the question shares most of.
    const Example* best = nullptr;
    std::size_t bestShared = 0;
    for (const auto& e : kExamples) {
        Words ew = words(std::string(e.text));
        std::size_t shared = 0;
        for (const auto& w : ew)
            if (std::find(words_.begin(), words_.end(), w) != words_.end()) ++shared;
        if (shared > bestShared) {
            bestShared = shared;
            best = &e;
        }
    }
    std::string suggestion;
    if (best && bestShared >= 2) {
        suggestion = std::string(best->shape);
        auto put = [&](std::string_view slot, const std::string& noun) {
            if (auto at = suggestion.find(slot); at != std::string::npos) suggestion.replace(at, slot.size(), noun);
        };
        put("X", !nouns.empty() ? nouns[0] : "mug");
        put("Y", nouns.size() > 1 ? nouns[1] : "door");
    }
    std::string detail;
    if (!unread.empty()) {
        std::string list;
        for (std::size_t k = 0; k < unread.size() && k < 6; ++k) list += (k ? "', '" : "") + unread[k];
        detail = fmt::format(": not understood: '{}'", list);
    }
    return cannotTranslate(question_.text, detail, suggestion);
}

class RuleTranslator final : public Translator {
public:
    std::string name() const override { return "the built-in reader"; }

private:
    // ScanQA's ways of asking, each as a form the reader reads (the first that fits).
    static std::string readScanQaForm(std::string plain) {
        // ScanQA's ways of asking: "what surrounds the sink?" (what is around it), "what does the
        // cabinet have?" (what is on it), "a copier sits on the floor to the left of what?" (the
        // copier is to the left of what), "where does the trash can set?".
        static const std::pair<std::regex, std::string> scanQa[] = {
            {std::regex(R"(^what (?:surrounds|borders|flanks|encircles|lines)\b)"), "what is around"},
            {std::regex(R"(^what (?:does|do) (.+?) (?:have|hold|contain|carry|support)(?: on (?:it|top))?$)"),
             "what is on $1"},
            // "what does the chair have at the foot of the bed?": what is on the chair there.
            {std::regex(
                 R"(^what (?:does|do) (.+?) (?:have|hold|carry|support) ((?:at|by|near|next to|beside|in|on|under|above|behind|in front of|to the (?:left|right) of) .+)$)"),
             "what is on $1 $2"},
            // "the table is surrounded by what?", "what is the sink surrounded by?": what is around it.
            {std::regex(R"(^(?:the |a |an )?(.+?) (?:is|are) (?:surrounded|encircled|flanked|bordered) by what$)"),
             "what is around the $1"},
            {std::regex(R"(^what (?:is|are) (.+?) (?:surrounded|encircled|flanked|bordered) by$)"),
             "what is around $1"},
            // "what is the table covered in?", "the desk is cluttered with what?": what is on it.
            {std::regex(R"(^what (?:is|are) (.+?) (?:covered|topped|cluttered|piled|strewn) (?:in|with|by)$)"),
             "what is on $1"},
            {std::regex(
                 R"(^(?:the |a |an )?(.+?) (?:is|are) (?:covered|topped|cluttered|piled|strewn) (?:in|with|by) what$)"),
             "what is on the $1"},
            // "to the left of the open door is what color armchair?": what color the armchair there is.
            {std::regex(
                 R"(^((?:to the (?:left|right) of|in front of|behind|next to|beside|across from|above|below|under|near|on top of) .+?) (?:is|are) what (colou?r|shape|material) (.+)$)"),
             "what $2 is the $3 $1"},
            // "the towel is olive green and what shape?": the shape of the olive green towel.
            {std::regex(
                 R"(^(?:the |a |an )?(.+?) (?:is|are) ((?:dark |light |olive |bright |pale )?(?:red|green|blue|white|black|gray|grey|brown|yellow|orange|pink|purple|beige|silver|gold)) and what (colou?r|shape|material)$)"),
             "what $3 is the $2 $1"},
            // "which way is the sofa facing?", "which direction does the chair face?": what it faces.
            {std::regex(R"(^(?:which|what) (?:way|direction) (?:is|are) (.+?) (?:facing|turned|pointing|pointed)$)"),
             "what is $1 facing"},
            {std::regex(R"(^(?:which|what) (?:way|direction) (?:does|do) (.+?) (?:face|point)$)"), "what does $1 face"},
            // "the door is left of a row of what?": what the door is left of.
            {std::regex(R"(^(.+ )(?:a|an|the) (?:row|group|line|pile|stack|set|collection|cluster) of what$)"),
             "$1what"},
            // "the door is to the left of the dresser and what other object?": what else it is left of.
            {std::regex(
                 R"(^(.+ (?:of|to|from|by|near|beside|behind|above|below|under|against)) (?:the |a |an )?(.+?) and what (?:other|else)(?: object| thing| item| furniture)?s?$)"),
             "$1 what besides the $2"},
            // "the tv is on the same wall as what?": what else is by that wall.
            {std::regex(
                 R"(^(?:the |a |an )?(.+?) (?:is|are) (?:located |placed |hanging |mounted )?(on|against) the same wall as what$)"),
             "what is $2 the same wall as the $1"},
            // "what type of wood is the door?": what it is made of.
            {std::regex(
                 R"(^what (?:type|kind|sort) of (?:wood|metal|material|fabric|stone) (?:is|are) (.+?)(?: made of)?$)"),
             "what material is $1"},
            // "what is the water fountain closest to?": as "the water fountain is closest to what?".
            {std::regex(R"(^what (?:is|are) (?:the |a |an )?(.+?) (closest|nearest) to$)"),
             "what is $2 to the $1 besides the $1"},
            // "what type of toilet is it?", "what type of door is there?" (read as "which ..."): the
            // thing itself, where it is. "what kind of room is this?" asks what the things make of it (roomKind), and
            // "what kinds of things are there?" the kinds of the scene's things (Translation::byKind).
            {std::regex(
                 R"(^what (?:type|kind|sort|types|kinds) of (?!(?:room|place|space|things?|objects?|items?|furniture|stuff) )(.+?) (?:is|are) (?:it|this|that|there|they|these|those)$)"),
             "where is the $1"},
            // "what is the location of the piano in relation to the desk?": where it is relative to it.
            {std::regex(
                 R"(^what (?:is|are) the (?:location|position|placement|orientation) of (.+?) (relative to|in relation to|with respect to|compared to) (.+)$)"),
             "where is $1 $2 $3"},
            {std::regex(R"(^what (?:is|are) the (?:location|position|placement) of (.+)$)"), "where is $1"},
            {std::regex(
                 R"(^(?:a|an|the) (.+?) (?:sits|stands|lies|hangs|rests|is placed|is located|is sitting|is standing|is hanging|is positioned)( .+ what(?: \w+)?)$)"),
             "the $1 is$2"},
            {std::regex(R"(^where does (.+?) (?:set|sit|stand|lie|rest)$)"), "where is $1"},
            {std::regex(R"(^where (?:is|are) (.+?) set$)"), "where is $1"},
            // "where is the tv hanging from?": what it hangs from.
            {std::regex(R"(^where (?:is|are) (.+?) (hanging|hung|attached|mounted) (from|on|to)$)"),
             "what is $1 $2 $3"},
            {std::regex(R"(^how many (.+?) (?:surround|border|flank|encircle)s? (.+)$)"), "how many $1 are around $2"},
            // "how many chairs is the tv above?": the chairs below the tv (the predicate turned round).
            {std::regex(R"(^how many (.+?) (?:is|are) (.+?) (?:located |placed |hanging |sitting |standing )?above$)"),
             "how many $1 are below $2"},
            {std::regex(
                 R"(^how many (.+?) (?:is|are) (.+?) (?:located |placed |hanging |sitting |standing )?(?:below|under|underneath|beneath)$)"),
             "how many $1 are above $2"},
            {std::regex(
                 R"(^how many (.+?) (?:is|are) (.+?) (?:located |placed |sitting |standing )?(?:near|next to|beside|close to)$)"),
             "how many $1 are near $2"},
            // "the armchair is closest to what?": distance is the same both ways, so it is what else
            // is closest to the armchair (the armchair is at no distance from itself).
            {std::regex(
                 R"(^(?:the |a |an )?(.+?) (?:is|are) (?:the )?(closest|nearest)(?: object| thing| one| item)? to what(?: in the room)?$)"),
             "what is $2 to the $1 besides the $1"},
        };
        for (const auto& [from, to] : scanQa)
            if (std::regex_search(plain, from)) {
                plain = std::regex_replace(plain, from, to);
                break;
            }
        return plain;
    }

    // Questions that ask what another question asks, read as that one, one table of them in the order they apply.
    static std::string readAsAnother(std::string plain) {
        static const std::pair<std::regex, std::string> others[] = {
            // "what is closest to the centre of the room?": what stands in its middle, nearest the centre first.
            {std::regex(
                 R"(^(?:what|which)(?: object| thing| item)? is (?:the )?(?:(?:object|thing|item|one) )?(?:closest|nearest) to the (?:center|centre|middle) of (?:the|this) room$)"),
             "what is in the middle of the room"},
            // "are the cushions all on the sofa?": as "are all the cushions on the sofa?".
            {std::regex(R"(^(are|were) the ([a-z ]+?) all (.+)$)"), "$1 all the $2 $3"},
            // "what is the room's floor area?" (the words' "'s" is " is"): the floor area of the room.
            {std::regex(
                 R"(^what is (?:the|this) room is ((?:total |overall )?(?:floor area|floor space|area|size|dimensions))$)"),
             "what is the $1 of the room"},
            // "how far is the farthest object from the door?": the farthest thing, which the answer says how far away
            // is (a kind named, "the farthest chair", reads as it is).
            {std::regex(R"(^how far (?:away )?is the (farthest|furthest) ((?:object|thing|item) from .+)$)"),
             "what is the $1 $2"},
            // "which two chairs are closest together?": how far apart they are, the closest two first.
            {std::regex(
                 R"(^(?:which|what) (?:two |2 )?([a-z ]+?) (?:are|stand|sit) (?:the )?(?:closest|nearest) (?:together|to each other|to one another)$)"),
             "how far apart are the $1"},
            // "how many plants are there and where are they?": where they are, which names each and so counts them.
            {std::regex(
                 R"(^how many (.+?) (?:are|is)(?: there| here)?(?: in (?:the|this) room)?,? and where (?:are|is) (?:they|it)$)"),
             "where are the $1"},
        };
        for (const auto& [asked, as] : others) plain = std::regex_replace(plain, asked, as);
        return plain;
    }

    // SQA3D's ways of asking what the memory answers another way: "is the number of chairs odd or
    // even?" (a count), "is the door open or closed?" (the door; `stateWords` say what is left
    // out), "is the table small or large?" (its size), "what can I use in front of me to ...?"
    // (what is there), "is the shape of the table round or square?" (its shape).
    // ScanQA's too (readScanQaForm).
    static std::string readAsAsked(std::string plain, std::optional<std::string>& stateWords) {
        plain = readScanQaForm(std::move(plain));
        // "the lamp nearest the sofa": nearest as a preposition is nearest to.
        static const std::regex nearestAsPreposition(R"(\b(nearest|closest)(?= (?:the|a|an|this|that|my|your|our)\b))");
        plain = std::regex_replace(plain, nearestAsPreposition, "$1 to");
        plain = readAsAnother(std::move(plain));
        // "how many cushions are there in total?": a count is of all of them anyway.
        static const std::regex inTotal(R"(^(how many .+?) (?:in total|in all|altogether|overall)$)");
        plain = std::regex_replace(plain, inTotal, "$1");
        // "is the number of chairs odd or even?", "can the number of chairs be divided by three?":
        // the count answers it.
        static const std::pair<std::regex, std::string> counts[] = {
            {std::regex(
                 R"(^(?:is|are) (?:the )?(?:total )?(?:number|amount|count|quantity) of (.+?) (?:an? )?(?:odd|even)(?: or (?:odd|even))?(?: number)?$)"),
             "how many $1"},
            {std::regex(R"(^(?:is|are) there an? (?:odd|even)(?: or (?:odd|even))? (?:number|amount) of (.+)$)"),
             "how many $1"},
            {std::regex(
                 R"(^(?:can|could|is) (?:the )?(?:total )?(?:number|amount|count) of (.+?) (?:be )?(?:divided|divisible|dividable) by \w+$)"),
             "how many $1"},
            {std::regex(R"(^(?:are )?(?:the )?(.+?) (?:are )?(?:odd|even) or (?:odd|even)(?: in number)?$)"),
             "how many $1"},
        };
        // "is the monitor on the desk or on the chair?": what it is on answers which.
        static const std::regex onWhich(
            R"(^(?:is|are) ((?:the |a |an )?[a-z][a-z ]*?) (on|in|inside|under|below|above|attached to) (?:the |a |an )?(?!(?:my|your|me|front|left|right|back|top|bottom|or)\b)[a-z][a-z ]*? or (?:\2 )?(?:the |a |an )?(?!(?:my|your|me|front|left|right|back|behind|off)\b)[a-z][a-z ]*$)");
        plain = std::regex_replace(plain, onWhich, "what is $1 $2");
        static const std::pair<std::regex, std::string> more[] = {
            {std::regex(R"(^(?:are|is) there (?:more|less|fewer) than (?:one|two|three|four|five|\d+) (.+)$)"),
             "how many $1"},
            {std::regex(R"(^is (?:that|this|it) the only (.+)$)"), "how many $1"},
            {std::regex(
                 R"(^(?:are|is) (?:all )?(?:the )?(.+?) (?:all )?(?:of )?(?:the )?same (color|colour|shape|material)$)"),
             "what $2 are the $1"},
        };
        for (const auto& [from, to] : more)
            if (std::regex_match(plain, from)) {
                plain = std::regex_replace(plain, from, to);
                break;
            }
        for (const auto& [from, to] : counts)
            if (std::regex_match(plain, from)) {
                plain = std::regex_replace(plain, from, to);
                break;
            }
        // "is the door open or closed?", "is the bed messy or tidy?": the memory keeps no such state;
        // the thing is looked for, and the answer says so.
        static const std::string states =
            "open|opened|closed|shut|on|off|messy|tidy|clean|dirty|neat|empty|full|made|unmade|lit|locked|unlocked|"
            "occupied|vacant|parted|drawn|up|down|folded|unfolded|plugged in|unplugged|covered|uncovered|well made";
        static const std::regex state("^(?:is|are) (.+?) (?:(?:switched|turned|fully|completely|all) )?(" + states +
                                      ") or (?:(?:switched|turned|fully|completely) )?(?:" + states + "|not)( .+)?$");
        static const std::regex stateAfter("^(?:the )?(.+?) (?:is|are) (?:(?:switched|turned|fully) )?(" + states +
                                           ") or (?:" + states + ")$");
        static const std::regex sizeChoice(
            "^(?:is|are) (.+?) (small|large|big|tall|short|little|long|wide|narrow|high|low) or "
            "(?:small|large|big|tall|short|little|long|wide|narrow|high|low)( .+)?$");
        if (std::smatch sm; std::regex_match(plain, sm, state)) {
            stateWords = sm.str(2) + " or ...";
            plain = "is there " + sm.str(1) + sm.str(3);
        } else if (std::regex_match(plain, sm, stateAfter)) {
            stateWords = sm.str(2) + " or ...";
            plain = "is there " + sm.str(1);
        } else if (std::regex_match(plain, sm, sizeChoice)) {
            // "is the table small or large?": its size answers it.
            const std::string measure =
                sm.str(2) == "tall" || sm.str(2) == "short" || sm.str(2) == "high" || sm.str(2) == "low" ? "tall"
                : sm.str(2) == "long"                                                                    ? "long"
                : sm.str(2) == "wide" || sm.str(2) == "narrow"                                           ? "wide"
                                                                                                         : "big";
            plain = "how " + measure + " is " + sm.str(1) + sm.str(3);
        }
        // "what can I use in front of me to make copies?", "what is the name of the thing on my left?":
        // what is there. A question that ends on its preposition ("what can I put my cup on?") asks
        // what affords it, and is read as it is, as is one whose use is said before a place ("what can I sit on
        // in the kitchen?": the seats there).
        static const std::regex useFor(
            R"(^(?!.* (?:on|in|at|into|onto|upon|with)$)(?:what|which)( object| thing| item)? (?:can|could|should|would|do|will) i (?:use|be using|put|place|open|take|grab|reach|touch|(?:write on|be writing on|sit on|lean on|lie on)(?! (?:in|near|at|by|around|beside|next to|close to) )) (.+?)(?: to .*| if .*| for .*)?$)");
        static const std::regex nameOf(R"(^what is the name of (.+)$)");
        plain = std::regex_replace(plain, useFor, "what$1 is $2");
        plain = std::regex_replace(plain, nameOf, "which is $1");
        // "what did you see?", "what have you found in the video?": what the memory holds, the room's things.
        static const std::regex seen(
            R"(^(?:what|which things|what things|what objects) (?:did|do|have|can) you (?:see|seen|find|found|spot|spotted|capture|captured|record|recorded|remember)(?: here| in (?:the|this) (?:room|scene|video|capture|place))?$)");
        plain = std::regex_replace(plain, seen, "what is in the room");
        // "how far apart, on average, are the lamps?": "on average" last, where the reader takes it from
        // (takeOnAverage), so that the forms below read the question as they read it without.
        static const std::regex onAverage(R"(^(.+?),? on (?:the )?average,?( .+)$)");
        plain = std::regex_replace(plain, onAverage, "$1$2 on average");
        // "the distance between the two chairs", "how far apart are both lamps?": between one of
        // them and the other.
        static const std::regex bothOf(
            R"(^(.*\b(?:distance between|apart are|apart is)) (?:the )?(?:two|2|both)(?: of the)? ([a-z]+)( on average)?$)");
        plain = std::regex_replace(plain, bothOf, "$1 the $2 and the $2$3");
        // "the distance between the sofas", "how far apart are the sofas?": the same, of a kind named in the plural.
        static const std::regex amongThem(R"(^(.*\b(?:distance between|apart are)) the ([a-z]+s)( on average)?$)");
        plain = std::regex_replace(plain, amongThem, "$1 the $2 and the $2$3");
        // "which chair is bigger?", "which lamp is closer to the door?": of them, the one that is most so.
        static const std::regex compared(R"(^(which|what) ([a-z][a-z ]*?) (is|are) ([a-z]+er)( (?:to|from) .+)?$)");
        if (std::smatch m; std::regex_match(plain, m, compared) && plain.find(" than ") == std::string::npos)
            if (const auto most = comparativeOf(m.str(4)))
                plain = m.str(1) + " " + m.str(2) + " " + m.str(3) + " the " + most->superlative + m.str(5);

        // "is the shape of the table round or square?": what shape it is.
        static const std::regex shapeChoice(
            R"(^is the (shape|color|colour|material) of (.+?)(?: (?:round|square|rectangular|circular|oval|triangular|rectangle|circle|cylindrical|wood|wooden|metal|plastic|glass|fabric|leather|white|black|brown|gray|grey|red|blue|green|yellow|or))+$)");
        plain = std::regex_replace(plain, shapeChoice, "what $1 is $2");
        return plain;
    }

    static std::string lowered(std::string w) {
        std::transform(w.begin(), w.end(), w.begin(), [](unsigned char ch) { return std::tolower(ch); });
        return w;
    }

    // "which is bigger between A and B?", "is A or B closer to me?", "is A or B closer to C?", "is C closer
    // to A or to B?", "which is closer to me, A or B?", "which one is bigger the door or the bed?": the forms
    // the choosing below reads.
    static std::string eitherAsChoice(std::string text) {
        static const std::regex between(
            R"(^\s*(?:which|what)(?: one)? is ([A-Za-z]+) between (?:the )?(.+?) and (?:the )?([^?]+)\??\s*$)",
            std::regex::icase);
        if (std::smatch b; std::regex_match(text, b, between) && comparativeOf(lowered(b.str(1))))
            text = "which of " + b.str(2) + " and " + b.str(3) + " is " + b.str(1) + "?";
        {
            const auto byDistance = [](const std::string& word) {
                return isOneOf(lowered(word), {"closer", "nearer", "farther", "further"});
            };
            static const std::regex eitherCloser(
                R"(^\s*(?:is|are) (?:the )?(.+?) or (?:the )?(.+?) ([A-Za-z]+)( (?:to|from) [^?]+?)\??\s*$)",
                std::regex::icase);
            // "is the lamp closer to the sofa or to the table?": a distance is the same both ways, so this is
            // which of the two is closer to the lamp.
            static const std::regex closerToEither(
                R"(^\s*(?:is|are) (?:the )?(.+?) ([A-Za-z]+) (to|from) (?:the )?(.+?),? or (?:(?:to|from) )?(?:the )?([^?]+?)\??\s*$)",
                std::regex::icase);
            static const std::regex toMe(
                R"(^\s*(?:which|what)(?: one)? is ([A-Za-z]+)( (?:to|from) (?:me|my position|where i am)),? *(?:between )?(?:the )?(.+?) (?:or|and) (?:the )?([^?]+?)\??\s*$)",
                std::regex::icase);
            // "which is closer, the tv or the trash can?"; not "which is closer to the door: the sofa or the
            // table?", which the choosing below reads as it is.
            static const std::regex noComma(
                R"(^\s*(?:which|what)(?: one)? is ([A-Za-z]+)[,:]? (?:between )?(?:the )?([^,:]+?) or (?:the )?([^?,:]+?)\??\s*$)",
                std::regex::icase);
            std::smatch e;
            if (std::regex_match(text, e, eitherCloser) && byDistance(e.str(3)))
                text = fmt::format("which is {}{}, {} or {}?", e.str(3), e.str(4), e.str(1), e.str(2));
            else if (std::regex_match(text, e, closerToEither) && byDistance(e.str(2)))
                text =
                    fmt::format("which is {} {} the {}, {} or {}?", e.str(2), e.str(3), e.str(1), e.str(4), e.str(5));
            else if (std::regex_match(text, e, toMe))
                text = fmt::format("which is {}{}, {} or {}?", e.str(1) == "close" ? "closer" : e.str(1), e.str(2),
                                   e.str(3), e.str(4));
            else if (std::regex_match(text, e, noComma))
                // "which is closer, the tv or the trash can?": to the person who asks.
                text = fmt::format("which is {}{}, {} or {}?", e.str(1),
                                   isOneOf(e.str(1), {"closer", "nearer", "farther", "further"}) ? " to me" : "",
                                   e.str(2), e.str(3));
        }
        return text;
    }

    // "wher is the cabinet?", "wha is on the dresser?": a first word nobody knows, one letter from a
    // question word, is that word (the nouns have the lexicon's did-you-mean; this is the grammar's).
    static std::string questionWordRespelt(const std::string& plain, const Lexicon& lexicon) {
        const std::size_t space = plain.find(' ');
        if (space == std::string::npos) return plain;
        static constexpr std::array<std::string_view, 8> kAsks{"what", "where", "which", "how",
                                                               "who",  "when",  "is",    "are"};
        const std::string first = plain.substr(0, space);
        // A question word as written is looked up no further: "which" is no noun in WordNet, and the
        // look-up would try each word one letter away from it (40 ms).
        if (first.size() < 3 || std::find(kAsks.begin(), kAsks.end(), first) != kAsks.end() ||
            lexicon.lookUp(first).how != WordMatch::How::Unknown)
            return plain;
        for (std::string_view asks : kAsks)
            if (model::editDistance(first, asks) == 1) return std::string(asks) + plain.substr(space);
        return plain;
    }

    // "When entering the kitchen, what is the first cabinet on the right?", "where is the office chair
    // when you walk in the door?": the person stands where one comes in, as SQA3D's "I am entering
    // the room." says (situation.cpp reads it: by the door).
    static std::string enteringAsSituation(const std::string& text) {
        static const std::string entering =
            R"((?:when|as|once|upon|after) (?:you |i |one |we )?(?:first )?(?:entering|enters|enter|walking|walks|walk|coming|comes|come|stepping|steps|step)\b(?: in| into| through)?(?: (?:the|a|this) (?:\w+ )?(?:room|door|doorway|entrance|entry|kitchen|bathroom|bedroom|office|area|space))?)";
        static const std::regex before(R"(^\s*)" + entering + R"(\s*,?\s*(.+)$)", std::regex::icase);
        static const std::regex after(R"(^\s*(.+?),?\s+)" + entering + R"(\s*\??\s*$)", std::regex::icase);
        std::smatch m;
        if (std::regex_match(text, m, before) || std::regex_match(text, m, after)) {
            std::string question = m.str(1);
            if (question.find('?') == std::string::npos) question += "?";
            return "I am entering the room. " + question;
        }
        return text;
    }

    // "the vase, where is it?", "the cushions: how many are there?": the thing said first is the pronoun's, or the
    // noun the question leaves out.
    static std::string topicAsSubject(const std::string& text) {
        static const std::regex topic(R"(^\s*((?:the|my|a|an) [^,:?]+)\s*[,:]\s*(.+?)\b(it|they|them)\b(.*)$)",
                                      std::regex::icase);
        static const std::regex countFirst(
            R"(^\s*((?:the|my) [^,:?]+)\s*[,:]\s*how many( are there| do you see)?\s*\??\s*$)", std::regex::icase);
        std::smatch m;
        if (std::regex_match(text, m, topic)) return m.str(2) + m.str(1) + m.str(4);
        if (std::regex_match(text, m, countFirst)) return "how many " + m.str(1).substr(m.str(1).find(' ') + 1) + "?";
        return text;
    }

    // The pose a situation before the question says; `text` becomes the question alone.
    static std::optional<Pose> situationOf(const Question& question, const Lexicon& lexicon, std::string& text,
                                           std::vector<std::string>& notes) {
        auto situated = splitSituation(text);
        if (!situated) return std::nullopt;
        Translation scratch;
        PhraseParser parser(lexicon, scratch, question.planeCategories, question.scene, question.sceneCount);
        std::optional<Pose> pose = readPose(situated->situation, lexicon, parser);
        text = situated->question;
        if (pose) {
            text = takeTurn(text, *pose);
            notes.push_back(fmt::format("the situation places you {}: {}", pose->words, viewClause(*pose)));
        } else {
            notes.push_back("the situation names none of the scene's things; it is left out");
        }
        return pose;
    }

    // The question as read; where it cannot be, the question without a few words that describe a
    // part or a look the memory keeps nothing of ("the table with black legs", "the sink that
    // appears to be ..."), the fewest words from the first such word that make it readable, with
    // a note of what is left out.
    static Translation readLeavingOut(QuestionReader& reader, const std::string& plain) {
        try {
            return reader.read(plain);
        } catch (const Error& first) {
            Words w = words(plain);
            for (std::size_t at = 1; at < w.size(); ++at) {
                if (!isOneOf(w[at], {"with", "that", "which", "who", "having", "made", "appear", "appears", "looks",
                                     "look", "shaped"}))
                    continue;
                // "the object that covers an opening": the words say which thing; without them it is any.
                if (isOneOf(w[at - 1], {"object", "objects", "thing", "things", "item", "items", "one", "ones",
                                        "something", "anything", "stuff"}))
                    continue;
                for (std::size_t n = 2; n <= 7 && at + n <= w.size(); ++n) {
                    // The words left out end where the question goes on: at its end, a verb of
                    // place or a predicate ("the bed with a blue mattress located": not "bed blue
                    // mattress").
                    const std::size_t next = at + n;
                    if (next < w.size() && !PhraseParser::predicateAt(w, next) &&
                        !isOneOf(w[next], {"located", "placed", "sitting", "standing", "hanging", "kept", "is", "are",
                                           "found", "positioned", "have", "has"}))
                        continue;
                    Words kept(w.begin(), w.begin() + static_cast<std::ptrdiff_t>(at));
                    kept.insert(kept.end(), w.begin() + static_cast<std::ptrdiff_t>(at + n), w.end());
                    try {
                        Translation out = reader.read(joined(kept, 0, kept.size()));
                        out.notes.push_back(
                            fmt::format("'{}' is left out: the memory keeps nothing of it", joined(w, at, at + n)));
                        return out;
                    } catch (const Error&) {
                    }
                }
            }
            throw first;
        }
    }

public:
    Translation translate(const Question& question) const override {
        if (question.text.find("[please fill in]") != std::string::npos) {
            Lexicon lexicon(question.categories);
            if (auto route = routePlan(question, lexicon)) return *route;
        }
        if (std::any_of(kOrderWords.begin(), kOrderWords.end(),
                        [&](std::string_view word) { return question.text.find(word) != std::string::npos; })) {
            Lexicon lexicon(question.categories);
            if (auto order = appearanceOrder(question, lexicon)) return *order;
        }
        // A situation before the question ("I am sitting on the bed facing the window. What is to my
        // left?"): the pose it says, against which "my left" and "which way" are read. "When you
        // enter the room, what is on the right?" says one too, as "I am entering the room" does.
        std::string text = topicAsSubject(enteringAsSituation(question.text));
        Lexicon lexicon(question.categories);
        std::vector<std::string> situationNotes;
        std::optional<Pose> pose = situationOf(question, lexicon, text, situationNotes);
        // One question: a second sentence explains the first ("The directions refer to ...").
        if (auto mark = text.find('?'); mark != std::string::npos) text.erase(mark + 1);
        // "which of these objects (sofa, tv, bed) is ...": the choices keep their commas.
        std::vector<std::string> choices;
        static const std::regex listed(R"(\(([^()]*,[^()]*)\))");
        std::smatch m;
        if (std::regex_search(text, m, listed)) {
            std::string inner = m.str(1);
            for (std::size_t at = 0; at <= inner.size();) {
                std::size_t comma = inner.find(',', at);
                std::string item = inner.substr(at, comma - at);
                static const std::regex joiner(R"(^\s*(or|and)\s+|^\s+|\s+$)");
                item = std::regex_replace(item, joiner, "");
                if (!item.empty()) choices.push_back(item);
                if (comma == std::string::npos) break;
                at = comma + 1;
            }
            text = m.prefix().str() + " " + m.suffix().str();
        }
        // A unit in parentheses ("the door (cm)", "(in meters)", "(square meters)") is the answer's
        // unit, however placed: said at the end, where QuestionReader::takeUnit reads it.
        static const std::regex unitGroup(R"(\(\s*((?:in\s+|unit:?\s*)?(?:square\s+)?)([A-Za-z]+)\s*\))");
        for (std::smatch u; std::regex_search(text, u, unitGroup);) {
            const std::string word = lowered(u.str(2));
            if (!lengthUnitNamed(word)) break;
            bool square = u.str(1).find("square") != std::string::npos;
            text = u.prefix().str() + " " + u.suffix().str() + (square ? " in square " : " in ") + word;
        }
        // "which is closer to the tv, the sofa or the stove?", "which is bigger: the table or the bed?",
        // "which of the table and the bed is longer?": the same as choosing among them by the
        // comparative's superlative (kSuperlatives in phrase.cpp).
        static const std::regex chooseAfter(
            R"(^\s*(?:which|what)(?: one| thing| object)? is ([A-Za-z]+)(?: away)?((?: (?:to|from) [^,:]+)?)\s*[,:](.+)\bor\b([^?]+)\??\s*$)",
            std::regex::icase);
        static const std::regex chooseBefore(
            R"(^\s*(?:which|what)(?: one)? of (.+?)\band\b(.+?)\bis (?:the )?([A-Za-z]+)((?: (?:to|from) [^?]+)?)\??\s*$)",
            std::regex::icase);
        text = eitherAsChoice(std::move(text));
        std::optional<Comparative> chosen;
        std::string chosenTo, chosenA, chosenB;
        if (choices.empty() && std::regex_search(text, m, chooseAfter) && comparativeOf(lowered(m.str(1)))) {
            chosen = comparativeOf(lowered(m.str(1)));
            chosenTo = m.str(2), chosenA = m.str(3), chosenB = m.str(4);
        } else if (choices.empty() && std::regex_search(text, m, chooseBefore) && comparativeOf(lowered(m.str(3)))) {
            chosen = comparativeOf(lowered(m.str(3)));
            chosenTo = m.str(4), chosenA = m.str(1), chosenB = m.str(2);
        }
        if (chosen && (chosen->measure == "distance") == !chosenTo.empty()) {
            for (std::string item : {chosenA, chosenB}) {
                static const std::regex edges(R"(^[\s,]+|[\s,]+$)");
                item = std::regex_replace(item, edges, "");
                if (!item.empty()) choices.push_back(item);
            }
            static const std::regex toFrom(R"(^\s*(?:to|from)\s+)");
            std::string to = std::regex_replace(chosenTo, toFrom, "");
            text = chosen->measure == "distance" ? fmt::format("which of these is the {} {} {}?", chosen->superlative,
                                                               chosen->descending ? "from" : "to", to)
                                                 : fmt::format("which of these is the {}?", chosen->superlative);
        }
        // "besides the pillows, what is on the bed?": the exclusion said first is the same as last.
        static const std::regex leading(
            R"(^\s*(besides|apart from|aside from|other than|except for|excluding)\s+([^,]+),\s*(.+?)\??\s*$)",
            std::regex::icase);
        if (std::regex_search(text, m, leading)) text = m.str(3) + " " + m.str(1) + " " + m.str(2) + "?";
        Words all = words(text);
        if (all.size() > kMaxQuestionWords)
            throw Error(ErrorKind::Binding,
                        fmt::format("the question has {} words; ASK reads at most {}", all.size(), kMaxQuestionWords),
                        std::nullopt, "ask one short question at a time");
        // Politeness and framing at the start: "please", "can you tell me", "measuring from the
        // closest point of each object" (how smql measures distances anyway); not "tell me about",
        // which asks for a description.
        static const std::regex lead(
            "^(?:please |hey |ok |okay |so |now |and |excuse me |(?:can|could|would) you (?:please )?(?:tell me "
            "(?!(?:more )?about )|say |show me (?=where|what|which|how))?|tell me (?!(?:more )?about )|i want to know "
            "|i wonder |i would like to know |measuring "
            "from the closest point of each object |these are frames of a video )+");
        std::string plain = std::regex_replace(joined(all, 0, all.size()), lead, "");
        plain = questionWordRespelt(plain, lexicon);
        plain = thingByUse(plain);
        std::optional<std::string> stateWords;
        plain = readAsAsked(plain, stateWords);
        // "what type of chair ..." asks which chair; "what kinds of things ..." their kinds (Translation::byKind).
        static const std::regex kindOf(
            "^what (?:type|kind|sort|types|kinds) of (?!(?:things?|objects?|items?|furniture|stuff) )"),
            please(" please$"), myClock(R"(\bmy (?:\w+ )?o clock\b)");
        plain = std::regex_replace(plain, kindOf, "which ");
        plain = std::regex_replace(plain, please, "");
        if (plain.empty()) throw cannotTranslate(question.text, "", "");
        if (!pose && std::regex_search(plain, myClock))
            throw Error(ErrorKind::Binding, "'o'clock' needs where you are and which way you face", std::nullopt,
                        "say it first, as in: I am sitting on the bed facing the window. What is at my 3 o'clock?");
        QuestionReader reader(question, lexicon);
        reader.setChoices(std::move(choices));
        if (stateWords)
            situationNotes.push_back(fmt::format("'{}' is left out: the memory keeps no such state", *stateWords));
        if (!pose) {
            Translation out = unsituated(reader, plain);
            for (const auto& note : situationNotes) out.notes.push_back(note);
            return out;
        }
        return situated(question, lexicon, *pose, plain, reader, situationNotes);
    }

private:
    // A question with no situation; "me" is the person where the viewer stands (PhraseParser::person, HERE), whose
    // sides ("what is to my left?") are read again as the phrase grammar reads them when the words as said fail.
    static Translation unsituated(QuestionReader& reader, const std::string& plain) {
        try {
            return readLeavingOut(reader, plain);
        } catch (const Error&) {
            // "is the door on my left or right?": which side needs which way the person faces, which a situation
            // says ("is the door on my left?" alone is read from where the viewer stands).
            static const std::regex eitherSide(
                R"(\b(?:on|to|at) my (?:left|right|front|back)\b.* or (?:on |to |at )?(?:my |the )?(?:left|right|front|back|behind)\b|\b(?:in front of|behind) me,? or (?:in front of|behind)\b)");
            if (std::regex_search(plain, eitherSide))
                throw Error(ErrorKind::Binding, "which side a thing is on needs where you are and which way you face",
                            std::nullopt,
                            "say it first, as in: I am sitting on the bed facing the window. Is the door on my left or "
                            "right?");
            // "which side of the room is the door on?": the room's sides are not stored, its walls are.
            static const std::regex sideOfRoom(
                R"(^(?:which|what) (?:side|part|end|corner|half) of the (room|scene|house|apartment|space) )");
            if (std::smatch room; std::regex_search(plain, room, sideOfRoom))
                throw Error(ErrorKind::Binding, roomNotHeld(room.str(1)), std::nullopt,
                            "ask by a wall or a thing the room holds, as in: which wall is the door on?");
            const std::string sided = withPersonSides(plain);
            if (sided == plain) throw;
            return readLeavingOut(reader, sided);
        }
    }

    // The person's own sides as the phrase grammar reads them: "to my left" is "to the left of me", "in back of me"
    // "behind me", "ahead of me" "in front of me". A situation's reading adds more (situated).
    static std::string withPersonSides(std::string plain) {
        static const std::pair<std::regex, std::string> sides[] = {
            {std::regex(
                 R"(\b(?:to|on|at|by) (?:my|your) (?:immediate |direct |very |own |far )?(left|right)(?: hand| foot| feet)?(?: side)?(?: of me)?\b)"),
             "to the $1 of me"},
            {std::regex(R"(\b(?:right |directly |just |immediately )?(?:behind|in back of) (?:me|myself|us)\b)"),
             "behind me"},
            {std::regex(R"(\b(?:right |directly |just |straight )?(?:in front of|ahead of|before) (?:me|myself|us)\b)"),
             "in front of me"},
        };
        for (const auto& [from, to] : sides) plain = std::regex_replace(plain, from, to);
        return plain;
    }

    // A question read against a situation's pose: which way a thing is, or any question whose "me"
    // and "my left" are the pose's, with the pose's VIEW FROM.
    static Translation situated(const Question& question, const Lexicon& lexicon, const Pose& pose, std::string plain,
                                QuestionReader& reader, const std::vector<std::string>& notes) {
        Translation out;
        PhraseParser parser(lexicon, out, question.planeCategories, question.scene, question.sceneCount);
        // "what am I sitting on?": the thing the situation places the person at.
        static const std::regex self(
            R"(^(?:what|which) (?:object |thing |furniture |item )?am i (?:sitting|standing|lying|leaning|resting|laying|using|holding|touching) ?(?:on|at|in|by|against|next to|near|beside)?$)");
        static const std::regex faced(
            R"(^(?:what|which) (?:object |thing |furniture |item )?am i (?:facing|looking at|standing in front of|sitting in front of|in front of|watching)$)");
        const bool aboutPose = std::regex_match(plain, self) || std::regex_match(plain, faced);
        if (std::regex_match(plain, self)) plain = "where is the " + pose.at.words;
        if (std::regex_match(plain, faced))
            plain = "where is the " + (pose.facing && pose.turn == 0 ? pose.facing->words : pose.at.words);
        // "where is the rug relative to me?": which way it is.
        static const std::regex whereToMe(
            R"(^where (?:is|are) (.+?) (?:located |positioned |placed )?(?:according to|relative to|with respect to|compared to|in relation to|from|to) me$)");
        plain = std::regex_replace(plain, whereToMe, "is $1 on my left or right or behind me");
        // "where is the lamp?" of one placed by a situation: which way each lamp is and how far, nearest first.
        static const std::regex whereThing(
            R"(^where (?:is|are) (?:the |a |an |my )?([a-z]+(?: [a-z]+)?)(?: (?:located|placed|positioned|kept))?$)");
        std::smatch thing;
        const bool located = !aboutPose && std::regex_match(plain, thing, whereThing) &&
                             situatedDirection("in which direction is the " + thing.str(1), pose, lexicon, parser, out);
        out.everyAsked = located;
        if (!located && !situatedDirection(plain, pose, lexicon, parser, out)) {
            // The person's sides said as the phrase grammar reads them: "to the left of me", and more of them a
            // situation gives ("to the left", "where I am").
            static const std::pair<std::regex, std::string> sides[] = {
                {std::regex(
                     R"(\b(?:to|on|at) the (left|right)(?: hand)?(?: side)?\b(?! of\b)(?! side\b)(?! hand\b)(?! end\b)(?! corner\b))"),
                 "to the $1 of me"},
                {std::regex(
                     R"(\bmy (?:current |present |own )?(?:position|location|spot|place|seat)(?: on the \w+)?\b|\bwhere i (?:am(?: (?:standing|sitting|now|lying|seated|sat))?|stand|sit)\b)"),
                 "me"},
                {std::regex(R"(\b(?:across from|opposite|facing) me\b)"), "in front of me"},
                {std::regex(R"(\b(?:that |which )?i am (?:facing|looking at|in front of)\b)"), "in front of me"},
                {std::regex(R"(\b(?:that |which )?i am (?:sitting|standing|lying|leaning) (?:on|at|in|by|against)\b)"),
                 "near me"},
                {std::regex(
                     R"(^can i (?:reach|touch|grab|get to) (.+?)(?: from where i am(?: standing| sitting| now)?| from me| without moving| from here)?$)"),
                 "is $1 near me"},

                {std::regex(R"(\bat my back\b)"), "behind me"},
                {std::regex(R"(\bbehind$)"), "behind me"},
                {std::regex(R"(\b(?:straight |directly |right )?ahead\b(?! of))"), "in front of me"},
                {std::regex(R"(\b(?:directly |right )?in front\b(?! of))"), "in front of me"},
                {std::regex(R"(^how (?:may|many) (?:total |in total )?)"), "how many "},
            };
            // "on the 3 o'clock of the sofa": a side of the sofa, as the person sees it.
            static const std::pair<std::regex, std::string> clockOf[] = {
                {std::regex(R"(\b(?:on|at|to|in) the (?:12|twelve|11|eleven|1|one) o clock (?:direction |side )?of\b)"),
                 "behind"},
                {std::regex(R"(\b(?:on|at|to|in) the (?:2|two|3|three|4|four) o clock (?:direction |side )?of\b)"),
                 "to the right of"},
                {std::regex(R"(\b(?:on|at|to|in) the (?:5|five|6|six|7|seven) o clock (?:direction |side )?of\b)"),
                 "in front of"},
                {std::regex(R"(\b(?:on|at|to|in) the (?:8|eight|9|nine|10|ten) o clock (?:direction |side )?of\b)"),
                 "to the left of"},
            };
            for (const auto& [from, to] : clockOf) plain = std::regex_replace(plain, from, to);
            // "on my 5 o'clock": the nearest side.
            Words pw = words(plain);
            for (std::size_t k = 0; k + 1 < pw.size(); ++k)
                if (isOneOf(pw[k], {"on", "to", "at", "in", "by"}))
                    if (auto clock = clockAt(pw, k + 1)) {
                        static constexpr std::string_view said[] = {"in front of me", "to the right of me", "behind me",
                                                                    "to the left of me"};
                        pw.erase(pw.begin() + static_cast<std::ptrdiff_t>(k),
                                 pw.begin() + static_cast<std::ptrdiff_t>(k + 1 + clock->second));
                        Words side = words(std::string(said[static_cast<std::size_t>(clock->first)]));
                        pw.insert(pw.begin() + static_cast<std::ptrdiff_t>(k), side.begin(), side.end());
                    }
            plain = withPersonSides(joined(pw, 0, pw.size()));
            for (const auto& [from, to] : sides) plain = std::regex_replace(plain, from, to);
            reader.setSelf(Self{pose.at, pose.turn});
            try {
                out = reader.read(plain);
            } catch (const Error&) {
                // "what is to my left that keeps food cold?": what the clause says of the thing is
                // beyond the memory; the thing and its place are read.
                static const std::regex clause(
                    R"(\s(?:that|which|who)\s(?!is\s|are\s).*$|\s(?:that|which)\s(?:is|are)\s(?:used|made|shaped|meant|for)\b.*$|\s(?:while|when|as|if|without|so|because)\s.*$|\s(?:has|have|with)\s(?:a|an|the|some|its|their|any)\s.*$|\s(?:could|can|should|do|does|would|will|must)\s(?:i|you|we|be)\b.*$)");
                std::string shorter = std::regex_replace(plain, clause, "");
                if (shorter == plain) throw;
                out = reader.read(shorter);
                out.notes.push_back(fmt::format("'{}' is left out", plain.substr(shorter.size() + 1)));
            }
            // The view matters to the sides (and to what is in sight, facing the way the person does).
            static const std::regex viewed(R"(\b(left_of|right_of|in_front_of|behind)\(|\.(left|right|front|back)\b)");
            bool sight = out.smql.find("visible_from(") != std::string::npos && pose.turn == 0;
            if (out.runnable && (std::regex_search(out.smql, viewed) || sight))
                out.smql = withView(out.smql, viewClause(pose));
        }
        for (const auto& note : notes) out.notes.push_back(note);
        return out;
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
        case QuestionKind::Distance:
            return "distance";
        case QuestionKind::Size:
            return "size";
        case QuestionKind::Superlative:
            return "superlative";
        case QuestionKind::Direction:
            return "direction";
        case QuestionKind::Affordance:
            return "affordance";
        case QuestionKind::Seating:
            return "seating";
        case QuestionKind::Attribute:
            return "attribute";
        case QuestionKind::Changes:
            return "changes";
        case QuestionKind::Reverse:
            return "reverse";
        case QuestionKind::Comparison:
            return "comparison";
        case QuestionKind::RoomSize:
            return "room size";
        case QuestionKind::RoomKind:
            return "room kind";
        case QuestionKind::RoomOf:
            return "room of a thing";
        case QuestionKind::RoomPlace:
            return "place in the room";
        case QuestionKind::Statement:
            return "statement";
        case QuestionKind::Route:
            return "route plan";
        case QuestionKind::Appearance:
            return "appearance order";
        case QuestionKind::UnknownWord:
            return "unknown word";
    }
    return {};
}

}  // namespace smql::ask
