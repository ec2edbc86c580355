// English questions -> SMQL. A Translator turns a Question (its text and the categories of the
// scene it is asked about) into a Translation: one SMQL statement, the kind of question (which
// decides how the answer is worded), the words it mapped to categories and notes. The built-in
// translator is rule-based, deterministic and local (rule_translator.cpp, WordNet for the
// vocabulary). Engine::setAskTranslator plugs in another one, such as a client of a language
// model's endpoint; the engine runs whatever SMQL it returns through the parser, binder, planner
// and executor like any statement (docs/ask.md).
#pragma once

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/types.hpp"

namespace smql::ask {

enum class QuestionKind {
    Locate,            // where is the red mug?                     FIND mug WHERE color = 'red' PATH
    Relational,        // what is on the desk near the left wall?   FIND object WHERE on((FIND desk ...))
    YesNo,             // is the lamp left of the window?           RELATE lamp TO window
    Existence,         // is there a sofa?                          FIND sofa
    Count,             // how many chairs are near the table?       COUNT chair WHERE near(table)
    RelativePosition,  // where is the lamp relative to the window? RELATE lamp TO window
    Guidance,          // how do I get to the fridge from the door? GUIDE FROM door TO fridge
    Distance,          // how far is the sofa from the tv?          FIND sofa ORDER BY distance(tv)
    Size,              // how tall is the lamp?                     FIND lamp RETURN id, category, width, ...
    Superlative,       // which is the largest table?               FIND table ORDER BY volume DESC LIMIT 1
    Direction,         // standing by the bed facing the tv, is the door to my left or right?
    Affordance,        // where can I sit?                          FIND node WHERE category = 'chair' OR ...
    Seating,           // how many people can sit here?             FIND thing WHERE ... RETURN id, category, width
    Attribute,         // what colour is the sofa?                  FIND sofa RETURN id, category, color
    Changes,           // what changed?                             SHOW CHANGES
    Reverse,           // what is the lamp on?                      RELATE lamp TO object (the "on" rows)
    RoomSize,          // what is the size of this room?            FIND node WHERE kind = 'room' OR ...
    RoomKind,          // what kind of room is this? is this a kitchen? FIND object RETURN id, category
    RoomOf,            // which room is the chair in?               FIND thing WHERE <marks> ORDER BY distance(chair)
    RoomPlace,         // what is in the middle of the room?         FIND thing RETURN id, category, kind, box
    Route,             // VSI-Bench's route plan: "you are a robot beginning at the bed ... [please fill in]"
    Appearance,        // in what order were the chair, the sofa and the tv first seen? ORDER BY first_seen
    Statement,         // a plugged-in translator's SMQL: the answer says what its rows hold
    Comparison,        // is the sofa longer than the bed?          FIND thing WHERE ... ORDER BY width DESC
    UnknownWord,       // a word neither the scene nor WordNet knows: nothing runs, the answer names it
};

struct Question {
    std::string text;
    std::string scene;                    // the current scene's name
    std::vector<std::string> categories;  // the current scene's categories
    // The categories whose nodes are all walls, doors or windows (vertical planes) or ceilings: things are on
    // them by hanging ("the picture on the wall" is attached to it, "the light on the ceiling" hangs from it).
    std::vector<std::string> planeCategories;
    // The categories of which the scene holds more than one node ("take me to the chair": the nearest).
    std::vector<std::string> repeatedCategories;
    // The attributes some node of the scene carries (color, material ...).
    std::vector<std::string> attributes;
    // The categories of the scene's anchors (walls, floor, doors): what a thing is "on" only when
    // it rests on nothing else.
    std::vector<std::string> anchorCategories{};
    // How many scenes the database holds: where it holds one, "the office" or "the kitchen" is that
    // scene, whatever it is called.
    std::size_t sceneCount = 1;
    // The current scene's own node, which DESCRIBE sums up ("describe the room"); none across all scenes.
    model::NodeId sceneRoot = model::kNoNode;
    // SMQL in brief, for a translator that is a language model: its statements, the predicates (the
    // predicate table's usage lines) and the attributes (the attribute table's); bind_ask.cpp.
    std::string grammar{};
};

// One word of the question and the categories it was taken to mean ("couch" -> sofa).
struct WordMapping {
    std::string word;
    std::vector<std::string> categories;  // empty: the scene has none of it
    std::string how;                      // plural, synonym, kinds of it, spelling, not in this scene
};

struct Translation {
    QuestionKind kind = QuestionKind::Locate;
    std::string smql;      // one SMQL statement
    bool runnable = true;  // false: nothing runs (a word the scene does not know)
    std::vector<WordMapping> mappings;
    std::vector<std::string> notes;  // words left out, why nothing runs

    // How the answer speaks of the question's parts.
    std::string subject;        // singular: "red mug", "thing"
    std::string subjectPlural;  // "red mugs", "things"
    std::string condition;      // "on the sofa", empty without one
    std::string predicate;      // YesNo: the relation the answer checks ("left_of"); Count of two kinds: "or" when
                                // the question asks which has more ("are there more books or cushions?");
                                // Attribute tallied (byKind): "most" when the most common value is asked;
                                // Distance: "walk" when it asks whether a person can walk between the two
    std::string object;         // YesNo: what it is checked against ("the window")

    // Size: the measure asked ("height", "longest", "size"); Attribute: the attribute ("color"); Count of two
    // kinds compared: "more" or "fewer".
    std::string measure;
    std::string unit = "m";  // the unit the question asks the answer in: m, cm
    std::size_t pick = 1;    // Superlative: the row that answers ("the second largest": 2)
    // Direction: the categories of the thing stood by, the thing faced and the thing asked about,
    // and the answer's choices ("left", "right", "back"; or the four quadrants). Count of several kinds
    // ("tables and chairs"): each kind's categories, and its noun as asked.
    std::vector<std::vector<std::string>> roles;
    std::vector<std::string> choices;
    // Direction after a situation (situation.hpp): quarter turns clockwise from the person's heading
    // to the way from the thing stood by to the thing faced; no thing faced (empty roles[1]): to
    // the middle of the scene, the mean centre of the rows.
    int turn = 0;
    // Direction: answer for every thing of the kind asked about, nearest the thing stood by first (a situated
    // "where is the lamp?"), instead of the first.
    bool everyAsked = false;
    // Reverse: the anchor categories, named only when nothing else holds ("on the rug", not "on
    // the floor and the rug").
    std::vector<std::string> background;
    std::size_t top = 1;  // Superlative: how many rows answer ("the two largest": 2)
    // Comparison: whether the comparative asks for more ("longer") or less ("shorter", "closer");
    // `measure` is the attribute compared (or "distance"), `predicate` the comparative, `roles` the
    // two sides (categories, or "#id" for a node named by id), `condition` how a value is said
    // ("long", "from the door").
    bool greater = true;
    bool byHowMuch = false;  // Comparison: "how much taller is the lamp than the table?": the difference
    bool eitherWay = false;  // ... and "how tall is the lamp compared to the table?": more or less, whichever holds;
                             // with `predicate` "the same", whether they are alike ("are the two beds the same size?")
    bool average = false;    // Size: the mean of the measure over the things found ("the average height of the tables")
    // Route: the steps in order, "forward" (to the next of `roles` after the start and the thing
    // faced) or "turn" (a turn to fill in).
    std::vector<std::string> steps;
    // The scene holds things the ingest could not name (model::kUnnamedCategory): a kind it has none of may be
    // one of them. Set by the binder from the scene, whichever translator read the question.
    bool unnamedThings = false;
    // Locate, Relational, Count: the question asks for the kinds of the things found ("what kinds of things are
    // there?", "how many types of furniture are in the room?"), which the rows' categories tally; Attribute: the
    // values of the attribute ("what colours are there?"), which the rows' values tally.
    bool byKind = false;
};

// A translator that cannot answer now (an endpoint absent, failing, or replying with no
// statement): the built-in reader answers instead, with a note.
struct Unavailable : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class Translator {
public:
    virtual ~Translator() = default;
    // Throws smql::Error (kind Binding) for a question it cannot translate, with a hint, or
    // Unavailable when it cannot answer at all.
    virtual Translation translate(const Question& question) const = 0;
    // Another translation after `failed` could not be bound or run (`error` says why); nothing
    // when the translator does not repair. Asked once per question.
    virtual std::optional<Translation> repair(const Question&, const Translation& /*failed*/,
                                              const std::string& /*error*/) const {
        return std::nullopt;
    }
    // How notes name it: "the built-in reader", the endpoint's URL.
    virtual std::string name() const { return "a plugged-in translator"; }
};

// The built-in rule-based translator (shared, stateless).
const Translator& ruleTranslator();

std::string_view toString(QuestionKind kind);

}  // namespace smql::ask
