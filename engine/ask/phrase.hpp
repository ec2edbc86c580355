// The noun phrases of a question and the SMQL they become. A question is first cut into words
// (`words()`: lower case, contractions expanded, "chair(s)" read as "chairs"), then read by a small
// recursive descent:
//   phrase    := determiner* ordinal? superlative? (colour | side | adjective)* noun+ post*
//   post      := condition | order | exclusion | "that is" condition
//   condition := predicate-phrase phrase ["and" phrase]       ("between the sofa and the lamp")
//   order     := ("closest" | "nearest" | "farthest") ("to" | "from") phrase
//   exclusion := ("besides" | "other than" | "except") phrase
// so "the lamp on the table near the window" is a lamp with a condition whose table has one of its
// own. The predicate phrases come from the predicate table (relations::englishPhrases); nouns go
// through the Lexicon (scene categories, WordNet, did-you-mean).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/ask/lexicon.hpp"
#include "engine/ask/translator.hpp"
#include "model/error.hpp"

namespace smql::ask {

using Words = std::vector<std::string>;

// The question's words: lower case, contractions expanded ("what's" -> what is), punctuation out,
// decimal numbers kept ("1.5"), "tv(s)" read as "tvs".
Words words(const std::string& text);
std::string joined(const Words& w, std::size_t from, std::size_t to);

bool isOneOf(const std::string& word, std::initializer_list<std::string_view> words);
// A verb that says how a thing is placed or what it does there, not what it is: one WordNet knows as
// a verb and not as a noun ("sits", "hanged", "affixed", "pushed", "up" as in "up against").
bool isVerbOfPlace(const std::string& w);
// A comparative ("longer", "closer") and what it compares: the measure (an attribute, or "distance"
// to a thing that follows), whether more wins, its superlative ("longest") and how the answer says
// the measure ("long"). kSuperlatives in phrase.cpp is the one table of both.
struct Comparative {
    std::string measure;
    bool descending = false;
    std::string superlative;
    std::string adjective;
};
std::optional<Comparative> comparativeOf(const std::string& word);

// A colour word as the memory names it ("grey" is gray), or nothing.
std::optional<std::string> colourOf(const std::string& word);

struct Phrase;

struct Condition {
    std::string predicate;
    std::vector<Phrase> args;
    std::optional<double> metres;  // "within 1 m of the door"
    std::string words;             // "on the desk near the left wall"
    bool negated = false;          // "not on the table": NOT on(table)
};

// ORDER BY: "the largest table" (volume, descending), "the cushion closest to the window".
struct Order {
    std::string measure;  // an attribute (volume, height, z, width), or "distance" to `to`
    bool descending = false;
    std::vector<Phrase> to;  // distance's reference (one phrase)
    std::string words;       // "largest", "closest to the window"
    bool unsaid = false;     // "the nearest chair": from the person, though no reference was said
};

struct Phrase {
    std::string words;                // as the answer says it: "red mug", "desk near the left wall"
    std::string noun;                 // singular: "mug"
    std::optional<std::string> kind;  // object / anchor: every node of that kind
    std::string side;                 // wall.left: the side
    std::string id;                   // a node named by its id: "sofa#50", "#50", "src#93"
    std::vector<std::string> categories;
    std::optional<std::string> colour;
    std::vector<Condition> conditions;
    std::vector<std::string> filters;  // comparisons the noun itself implies: "coffee table" is height < 0.55 m
    std::string measured;              // a comparison of its own size, as said: "taller than 1 m" (in `filters`)
    std::vector<Phrase> excluded;      // things left out: "besides the cushions"
    std::optional<Order> order;
    std::size_t pick = 0;  // an ordinal or a superlative: the pick-th in `order` (1 = first)
    std::size_t top = 1;   // "the two largest": how many of `order` answer
    bool self = false;     // "me": the thing the person stands at (PhraseParser::setSelf)
    bool here = false;     // "me", "here" with no situation: where the viewer stands, HERE in SMQL (distances only)
    bool room = false;     // a kind of room read as the things that mark it ("the kitchen": its fridge and oven)
    bool kinds = false;    // "what kinds of things are there?": the kinds of the things asked for, not each thing
};

// The person who asks, where a situation placed them (situation.hpp): "me" is the thing they stand
// at (the view's place), and "on my left" is a side of the view turned by `turn` quarter turns
// (clockwise, from the person's heading to the view's).
struct Self {
    Phrase at;
    int turn = 0;
};

// What marks a kind of room: the things a person names it by ("a bed: a bedroom"). Sinks, tables and chairs stand in
// many kinds of room and mark none.
struct RoomMarks {
    std::string_view room;
    std::string_view things;  // words, ' ' between them
};
// Each word names a category as it is or as a plural (categoriesNamed, WordsAs::Names): the names data sets give a
// kind (a fridge, ScanNet's refrigerator) are listed, as WordNet's senses mark rooms that are not so (a "closet" is
// also a water closet, a "stool" a toilet).
inline constexpr RoomMarks kRoomMarks[] = {
    {"bedroom", "bed bunk-bed nightstand wardrobe dresser"},
    {"living room", "sofa couch tv television armchair fireplace"},
    {"kitchen", "fridge refrigerator oven stove microwave dishwasher toaster"},
    {"bathroom", "toilet bathtub shower"},
    {"office", "desk monitor keyboard printer"},
};
// Kinds of room marked in one scene from which it is one space of several rooms rather than one room (a studio
// apartment's kitchen, bed and bathroom; an office with a sofa is an office).
inline constexpr std::size_t kSeveralRooms = 3;
// In a scene of several rooms, "in the kitchen" is the area within this of the kitchen's marks (metres).
inline constexpr double kRoomAreaReach = 1.5;

// The scene's categories the words name: each word as a category or a plural (Names), also as a kind of it (Kinds:
// "bed" names a bunk-bed), also as a broader word (Broader: "seat" names chairs and sofas); never as a synonym of
// another sense or a spelling.
enum class WordsAs { Names, Kinds, Broader };
std::vector<std::string> categoriesNamed(const Lexicon& lexicon, std::string_view words, WordsAs as);

// The kind of room (a row of kRoomMarks) whose words begin at w[at] ("living room"); none.
const RoomMarks* roomNamedAt(const Words& w, std::size_t at);

class PhraseParser {
public:
    // `scene` and `sceneCount`: the current scene's name and how many the database holds, which say
    // whether "the office" is the scene (scenePlaceAt).
    PhraseParser(const Lexicon& lexicon, Translation& out, std::vector<std::string> planeCategories,
                 std::string scene = {}, std::size_t sceneCount = 1)
        : lexicon_(lexicon),
          out_(out),
          planes_(std::move(planeCategories)),
          scene_(std::move(scene)),
          sceneCount_(sceneCount) {}

    // How many words from w[i] name the scene itself as a place, 0 when they do not: "here",
    // "room", "scene", "house" ...; a kind of room ("office", "living room") that no category of
    // the scene is called, where the database holds one scene or the scene's name says that kind
    // ("replica-office0"). Determiners before it are the caller's.
    std::size_t scenePlaceAt(const Words& w, std::size_t i) const;

    // The predicate whose phrase starts at w[i] and how many words it takes.
    static std::optional<std::pair<std::string, std::size_t>> predicateAt(const Words& w, std::size_t i);

    // A phrase from w[i]; `withPosts`: also its conditions, orders and exclusions.
    Phrase phrase(const Words& w, std::size_t& i, bool withPosts);
    // condition | order | exclusion, joined by "and", from w[i], onto `p`.
    void posts(const Words& w, std::size_t& i, Phrase& p);
    // "the nearest lamp to the sofa", "the farthest chair from the door": `p` ordered by its distance from the
    // thing after "to" or "from" at w[i]; from the person (person()) after "to me" or with no "to"; `word` is the
    // superlative said.
    void orderByDistanceFrom(const Words& w, std::size_t& i, Phrase& p, bool farthest, const std::string& word);
    // A word before a phrase's noun that counts, picks or orders it ("three", "the second", "the largest", "the
    // nearest ... to"): read onto `p` (Read), read and the phrase ended ("the second closest to the door":
    // EndsPhrase), or no such word (None).
    enum class Quantifier { None, Read, EndsPhrase };
    Quantifier quantifierAt(const Words& w, std::size_t& i, Phrase& p, std::optional<bool>& pendingDistance,
                            std::string& pendingWord);
    // Parts of posts, each true when it read w[at...] (i moved past it): "out of the three chairs" (one of
    // them, which the phrase names already); "on the same wall as the bed" (by the wall nearest the bed, the bed
    // left out); "on the right under the table" (a side of no one category before a predicate, left out: a side
    // names one node of one category, the left wall).
    bool amongThem(const Words& w, std::size_t at, std::size_t& i, Phrase& p);
    bool onSameWallAs(const Words& w, std::size_t at, std::size_t& i, Phrase& p);
    bool sideLeftOut(const Words& w, std::size_t at, std::size_t& i, const Phrase& p);
    // "taller than 1 m", "more than 2 metres long", "under 50 cm wide": a comparison of the thing's own size.
    static bool measuredAt(const Words& w, std::size_t at, std::size_t& i, Phrase& p);
    // "near the sofa but not on it": a predicate at w[at] whose argument is "it" or "them", the thing of the
    // condition before it, as a condition of `p`.
    bool onThatThing(const Words& w, std::size_t at, std::size_t& i, const std::pair<std::string, std::size_t>& pred,
                     Phrase& p);
    void leaveOutResting(Phrase& p) const;
    void leaveOutRestingOn(Phrase& p, const Phrase& thing) const;
    static std::size_t pastVerbOfPlace(const Words& w, std::size_t at);
    bool roomPlaceLeftOut(const Words& w, std::size_t at, std::size_t& i,
                          const std::pair<std::string, std::size_t>& pred);
    // The scene's categories that mark each kind of room, row by row of kRoomMarks (categoriesNamed, by name only:
    // a chair is no armchair), worked out once a parser.
    const std::vector<std::vector<std::string>>& roomMarks() const;
    // "in the kitchen" where the scene holds the things of several kinds of room: the kitchen's area (kRoomMarks,
    // kRoomAreaReach), a condition of the phrase. roomAreaAt: the kind of room named at w[at...] whose area it is;
    // none where the scene holds the things of fewer kinds of room than kSeveralRooms, or none of this one's.
    const RoomMarks* roomAreaAt(const Words& w, std::size_t at) const;
    bool roomArea(const Words& w, std::size_t at, std::size_t& i, const std::pair<std::string, std::size_t>& pred,
                  Phrase& p);
    // An ordinal with no measure: "the first cabinet from the door" is the nearest to it; "the first cabinet on
    // the right" after a situation, the nearest to the person.
    void orderByNearness(const Words& w, std::size_t& i, Phrase& p);

    // "me", "my left": the person a situation placed (none: "me" names nothing).
    void setSelf(std::optional<Self> self) { self_ = std::move(self); }
    // What a distance is measured from when the person asks from where they are: "me", "myself", "here" or "you"
    // at w[i] (true, `i` past it, `out` the person). The person: the thing a situation placed them at, else where
    // the viewer stands (Phrase::here).
    bool personAt(const Words& w, std::size_t& i, Phrase& out) const;
    Phrase person() const;

    Error notUnderstood(const Words& w, std::size_t at) const;
    // Words neither the scene nor WordNet knows: the answer names them and nothing runs.
    const std::vector<std::string>& unknownWords() const { return unknownWords_; }

private:
    Condition condition(const Words& w, std::size_t& i, const std::pair<std::string, std::size_t>& pred);
    // A node named by its id at w[i] ("sofa#50"), with its posts: true, and `i` past it.
    bool idPhrase(const Words& w, std::size_t& i, bool withPosts, Phrase& p);
    // "me" after a situation, with its posts: true, and `i` past it; without one, an error.
    bool selfPhrase(const Words& w, std::size_t& i, bool withPosts, Phrase& p);
    // A noun of more words than a name takes loses its first ones, with a note; far more is an error.
    void shortenNoun(std::vector<std::string>& nounWords, const Words& w, std::size_t start);
    void resolveNoun(Phrase& p, const std::vector<std::string>& nounWords);
    // A word at w[i] that describes the noun rather than naming it, or a part of it ("the back of"):
    // true, with `i` past what it took (notes say what is left out).
    bool describing(const Words& w, std::size_t& i, std::vector<std::string>& nounWords, std::string& side,
                    std::size_t wordsStart);
    // "located on the left" after a noun of one category: its side; true, with `i` past it.
    bool sideAfterVerb(const Words& w, std::size_t at, std::size_t& i, Phrase& p) const;
    bool isPlane(const Phrase& p) const;

    const Lexicon& lexicon_;
    Translation& out_;
    std::vector<std::string> planes_;
    std::string scene_;
    std::size_t sceneCount_ = 1;
    std::vector<std::string> unknownWords_;
    std::optional<Self> self_;
    int nested_ = 0;  // inside a condition's phrase: an exclusion belongs to the outer one
    mutable std::optional<std::vector<std::vector<std::string>>> roomMarks_;  // roomMarks(), once asked
};

// ------------------------------------------------------------------ SMQL

// A name as SMQL writes it: bare when the grammar reads it back as the same name, else quoted.
std::string smqlName(const std::string& name);
std::string smqlString(const std::string& text);
// A number of metres as SMQL writes it: fixed decimals, trailing zeros dropped ("1.5", "100").
std::string smqlMetres(double metres);

// The phrase as a reference: `sofa`, `wall.left`, `(FIND desk WHERE near(window))`.
std::string reference(const Phrase& p);
// The phrase as one condition on a node: its category (or id), then its own conditions, as in
// `(category = 'lamp' AND on(table))`; for an OR of several phrases.
std::string matchText(const Phrase& p);
// The phrase's WHERE conditions, " WHERE a AND b" or empty.
std::string whereText(const Phrase& p);
// FIND <phrase> [ORDER BY ..] [LIMIT ..] [PATH]; `view` is a VIEW FROM clause or empty.
std::string findText(const Phrase& p, bool path, const std::string& view = {});
std::string countText(const Phrase& p, const std::string& view = {});

// A phrase that takes exactly the words w[i..end) (a verb or a link word follows): true, with `i` at
// `end`; false when the phrase ends elsewhere.
bool phraseUpTo(const Words& w, std::size_t& i, std::size_t end, PhraseParser& p, Phrase& out);

// The words the answer says the thing asked about in: "red mug", "red mugs", and its conditions
// ("on the desk besides the cushions").
void describeSubject(const Phrase& p, Translation& out);

// Where the thing is: FIND ... PATH (the nearest, largest ... of an order).
bool locateAnswer(const Phrase& thing, Translation& out);

// The view-relative predicate that holds for a thing on `side` of a person whose view is turned by
// `turn` quarter turns clockwise from their heading, with the view's place as the reference: side
// 0 ahead, 1 right, 2 behind, 3 left. Ahead of the view's place is `behind` in SMQL's terms
// (farther from the viewer), behind it `in_front_of`.
std::string selfSidePredicate(int side, int turn);

}  // namespace smql::ask
