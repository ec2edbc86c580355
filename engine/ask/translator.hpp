// English questions -> SMQL. A Translator turns a Question (its text and the categories of the
// scene it is asked about) into a Translation: one SMQL statement, the kind of question (which
// decides how the answer is worded), the words it mapped to categories and notes. The built-in
// translator is rule-based, deterministic and local (rule_translator.cpp, WordNet for the
// vocabulary). Engine::setAskTranslator plugs in another one, such as a client of a language
// model's endpoint; the engine runs whatever SMQL it returns through the parser, binder, planner
// and executor like any statement (docs/ask.md).
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace smql::ask {

enum class QuestionKind {
    Locate,            // where is the red mug?                     FIND mug WHERE color = 'red' PATH
    Relational,        // what is on the desk near the left wall?   FIND object WHERE on((FIND desk ...))
    YesNo,             // is the lamp left of the window?           RELATE lamp TO window
    Existence,         // is there a sofa?                          FIND sofa
    Count,             // how many chairs are near the table?       COUNT chair WHERE near(table)
    RelativePosition,  // where is the lamp relative to the window? RELATE lamp TO window
    Guidance,          // how do I get to the fridge from the door? GUIDE FROM door TO fridge
    UnknownWord,       // a word neither the scene nor WordNet knows: nothing runs, the answer names it
};

struct Question {
    std::string text;
    std::string scene;                    // the current scene's name
    std::vector<std::string> categories;  // the current scene's categories
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
    std::string predicate;      // YesNo: the relation the answer checks ("left_of")
    std::string object;         // YesNo: what it is checked against ("the window")
};

class Translator {
public:
    virtual ~Translator() = default;
    // Throws smql::Error (kind Binding) for a question it cannot translate, with a hint.
    virtual Translation translate(const Question& question) const = 0;
};

// The built-in rule-based translator (shared, stateless).
const Translator& ruleTranslator();

std::string_view toString(QuestionKind kind);

}  // namespace smql::ask
