// Words of a question -> the categories of the scene. A word names a category as it is
// ("sofa"), as a plural ("mugs"), as a synonym ("couch" -> sofa), as a more general word that
// covers several ("seat" -> chair, sofa, bench; "furniture" -> every furniture category), as a
// narrower word for one ("pillow" -> cushion), or misspelt ("cushon" -> cushion). WordNet (wordnet.hpp) gives the
// plurals, synonyms and hypernyms; the engine's did-you-mean gives the spelling.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace smql::ask {

struct WordMatch {
    enum class How { Category, Plural, Synonym, Kind, Broader, Spelling, Absent, Unknown };
    How how = How::Unknown;
    std::vector<std::string> categories;  // scene categories the word stands for (Category ... Spelling)
    std::string lemma;                    // the base form ("pianos" -> piano), for answers
};

// Words for the whole scene as a place: "in the room", "in this scene", "in here". They name no category of
// things ("the left side of the room" is no side of a closet, which WordNet has as a kind of room).
bool namesWholeScene(const std::string& word);

class Lexicon {
public:
    explicit Lexicon(std::vector<std::string> sceneCategories);

    // `words` is one or more words of a noun phrase ("couch", "coffee table"). Absent: an English
    // noun the scene has no category for ("piano", or a word for the whole scene: namesWholeScene); Unknown: a
    // word neither the scene nor WordNet knows, and that spells no category.
    WordMatch lookUp(const std::string& words) const;

    const std::vector<std::string>& categories() const { return categories_; }

private:
    // The synsets above each sense of a category (its first senses: the ones people mean).
    const std::set<long>& ancestors(const std::string& category) const;
    WordMatch fromNounSenses(const std::vector<std::string>& bases, WordMatch match) const;

    std::vector<std::string> categories_;
    mutable std::map<std::string, std::set<long>> ancestors_;
};

// A noun for a physical thing (some sense of it is a physical object in WordNet: a piano, not an
// idea) that none of the scene's categories stands for, not as a synonym, a broader or a narrower
// word either: its base form ("pianos" -> piano). `match` is `name` looked up in the scene's Lexicon.
// Naming such a thing is an empty answer; any other unknown name is an error with hints.
std::optional<std::string> absentThing(const std::string& name, const WordMatch& match);

// The English plural of a singular noun, for answers: "couch" -> couches, "shelf" -> shelves (WordNet's
// exceptions), "furniture" -> pieces of furniture.
std::string pluralOf(const std::string& noun);

// Words joined by hyphens, as WordNet and the categories of imports spell compounds: "coffee-table".
std::string hyphenated(std::string words);

// "How" as the answer shows it: "couch -> sofa (synonym)".
std::string describe(WordMatch::How how);

}  // namespace smql::ask
