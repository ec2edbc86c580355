#include "engine/ask/lexicon.hpp"

#include <algorithm>
#include <optional>
#include <set>

#include "engine/ask/wordnet.hpp"
#include "model/category.hpp"
#include "model/names.hpp"

namespace smql::ask {

namespace {

// A category's senses beyond these are rare meanings ("table" as a data table) that would make a
// general word match it by accident.
constexpr std::size_t kCategorySenses = 2;

bool contains(const std::vector<std::string>& v, const std::string& s) {
    return std::find(v.begin(), v.end(), s) != v.end();
}

void addUnique(std::vector<std::string>& v, const std::string& s) {
    if (!contains(v, s)) v.push_back(s);
}

// Names for one kind of thing that WordNet 3.0 does not join (it has no nightstand; a wastebasket
// and a trash can are different synsets there), in canonical form (model/category.hpp). A word of
// a row names the categories of the row's other words, either way round, as a synonym does.
constexpr std::string_view kEquivalents[][9] = {
    {"nightstand", "night-table", "bedside-table", "bedside-cabinet", "night-stand"},
    {"wastebasket", "trash-can", "trash-bin", "garbage-can", "waste-bin", "wastebin", "dustbin", "bin",
     "wastepaper-basket"},
    {"tv", "television", "television-set", "tv-screen", "tv-monitor"},
    {"refrigerator", "fridge"},
    {"sofa", "couch"},
    {"cabinet", "cupboard"},
    {"mug", "cup"},
    {"lamp", "light"},
    {"trash-bag", "garbage-bag", "bin-bag"},
    {"whiteboard", "white-board", "dry-erase-board", "marker-board"},
    {"door", "exit", "entrance", "way-out"},
    {"wall-plug", "power-outlet", "power-socket", "electrical-outlet", "electric-outlet", "wall-socket", "socket"},
};

// The other names of `name`'s rows in kEquivalents.
std::vector<std::string_view> equivalents(const std::string& name) {
    std::vector<std::string_view> out;
    for (const auto& row : kEquivalents)
        if (std::find(std::begin(row), std::end(row), name) != std::end(row))
            for (std::string_view other : row)
                if (!other.empty() && other != name) out.push_back(other);
    return out;
}

// English plurals WordNet may not list for a category it does not know ("wall-plugs").
std::vector<std::string> singulars(const std::string& word) {
    std::vector<std::string> out;
    if (word.size() > 3 && word.ends_with("ies")) out.push_back(word.substr(0, word.size() - 3) + "y");
    if (word.size() > 2 && word.ends_with("es")) out.push_back(word.substr(0, word.size() - 2));
    if (word.size() > 1 && word.ends_with("s") && !word.ends_with("ss")) out.push_back(word.substr(0, word.size() - 1));
    return out;
}

// Whether some sense of a noun is a physical object in WordNet (a piano, a path; not a unicorn or
// an idea): the things a scene could hold.
bool physicalThing(const std::string& noun) {
    static const std::optional<long> physicalObject = []() -> std::optional<long> {
        for (const auto& sense : wordnet::nounSenses("object"))
            if (std::find(sense.words.begin(), sense.words.end(), "physical-object") != sense.words.end())
                return sense.offset;
        return std::nullopt;
    }();
    if (!physicalObject) return false;
    for (const auto& sense : wordnet::nounSenses(noun))
        if (wordnet::hypernymClosure(sense.offset).count(*physicalObject)) return true;
    return false;
}

// The nouns WordNet knows one edit away from `word` (a letter left out, added, changed, or two
// swapped), for a word of five letters or more that WordNet does not know at all.
std::set<std::string> misspeltNouns(const std::string& word) {
    if (word.size() < 5 || word.find_first_not_of("abcdefghijklmnopqrstuvwxyz") != std::string::npos ||
        wordnet::isKnown(word))
        return {};
    std::set<std::string> candidates;
    for (std::size_t k = 0; k < word.size(); ++k) {
        candidates.insert(word.substr(0, k) + word.substr(k + 1));
        if (k + 1 < word.size()) {
            std::string swapped = word;
            std::swap(swapped[k], swapped[k + 1]);
            candidates.insert(swapped);
        }
    }
    for (std::size_t k = 0; k <= word.size(); ++k)
        for (char ch = 'a'; ch <= 'z'; ++ch) {
            candidates.insert(word.substr(0, k) + ch + word.substr(k));
            if (k < word.size() && word[k] != ch) {
                std::string changed = word;
                changed[k] = ch;
                candidates.insert(changed);
            }
        }
    std::set<std::string> nouns;
    for (const auto& c : candidates)
        if (c != word) {
            auto bases = wordnet::nounBaseForms(c);
            if (!bases.empty()) nouns.insert(bases.front());
        }
    return nouns;
}

}  // namespace

bool namesWholeScene(const std::string& word) {
    static const std::set<std::string> kWholeScene{"room", "scene",     "house", "place", "space",
                                                   "home", "apartment", "area",  "here",  "flat"};
    return kWholeScene.count(word) > 0;
}

Lexicon::Lexicon(std::vector<std::string> sceneCategories) : categories_(std::move(sceneCategories)) {
    std::sort(categories_.begin(), categories_.end());
}

const std::set<long>& Lexicon::ancestors(const std::string& category) const {
    auto it = ancestors_.find(category);
    if (it != ancestors_.end()) return it->second;
    std::set<long> all;
    auto senses = wordnet::nounSenses(category);
    for (std::size_t i = 0; i < senses.size() && i < kCategorySenses; ++i)
        all.merge(wordnet::hypernymClosure(senses[i].offset));
    return ancestors_.emplace(category, std::move(all)).first->second;
}

// A noun WordNet knows whose base forms name no category here: a category in one of its synsets, every category
// below one of its senses, a compound category ending in it, or the category its first sense is a kind of (docs/ask.md,
// "Words", 3-5).
WordMatch Lexicon::fromNounSenses(const std::vector<std::string>& bases, WordMatch match) const {
    match.lemma = bases.front();
    // Synonyms: a category in one of the word's synsets ("couch" and sofa share one).
    std::vector<wordnet::Sense> senses;
    for (const auto& base : bases)
        for (auto& sense : wordnet::nounSenses(base)) senses.push_back(std::move(sense));
    for (const auto& sense : senses)
        for (const auto& w : sense.words)
            if (const std::string name = model::categoryName(w); contains(categories_, name))
                addUnique(match.categories, name);
    if (!match.categories.empty()) {
        match.how = WordMatch::How::Synonym;
        return match;
    }
    // A more general word: every category with one of the word's senses above it.
    for (const auto& category : categories_) {
        const auto& above = ancestors(category);
        for (const auto& sense : senses)
            if (sense.common && above.count(sense.offset)) {
                addUnique(match.categories, category);
                break;
            }
    }
    // A compound category whose last part is the word ("plant" -> indoor-plant): WordNet knows
    // few of the hyphenated names imports use.
    if (match.categories.empty())
        for (const auto& category : categories_)
            for (const auto& base : bases)
                if (category.ends_with("-" + base)) addUnique(match.categories, category);
    if (!match.categories.empty()) {
        match.how = WordMatch::How::Kind;
        return match;
    }
    // A narrower word for a category ("pillow" -> cushion): the category is the word's first
    // sense's direct hypernym.
    if (!senses.empty())
        for (const auto& parent : wordnet::hypernyms(senses.front().offset))
            for (const auto& w : parent.words)
                if (contains(categories_, w)) addUnique(match.categories, w);
    match.how = match.categories.empty() ? WordMatch::How::Absent : WordMatch::How::Broader;
    return match;
}

WordMatch Lexicon::lookUp(const std::string& words) const {
    const std::string word = hyphenated(words);
    WordMatch match;
    match.lemma = word;
    // The category's one name (model/category.hpp): "trash cans", "Trash_Can" are trash-can.
    if (const std::string name = model::categoryName(words); contains(categories_, name)) {
        match.how = name == word ? WordMatch::How::Category : WordMatch::How::Plural;
        match.categories = {name};
        match.lemma = name;
        return match;
    }
    // Names WordNet does not join (kEquivalents), either way round.
    for (std::string_view other : equivalents(model::categoryName(words)))
        if (contains(categories_, std::string(other))) addUnique(match.categories, std::string(other));
    if (!match.categories.empty()) {
        match.how = WordMatch::How::Synonym;
        match.lemma = model::categoryName(words);
        return match;
    }
    // A name of the table WordNet lacks ("whiteboard"), for a thing the scene does not hold.
    if (!equivalents(model::categoryName(words)).empty() && wordnet::nounBaseForms(word).empty()) {
        match.how = WordMatch::How::Absent;
        match.lemma = model::categoryName(words);
        return match;
    }
    if (namesWholeScene(word)) {
        match.how = WordMatch::How::Absent;
        return match;
    }
    for (const auto& singular : singulars(word)) {
        if (contains(categories_, singular)) {
            match.how = WordMatch::How::Plural;
            match.categories = {singular};
            match.lemma = singular;
            return match;
        }
    }
    auto bases = wordnet::nounBaseForms(word);
    for (const auto& base : bases) {
        if (contains(categories_, base)) {
            match.how = base == word ? WordMatch::How::Category : WordMatch::How::Plural;
            match.categories = {base};
            match.lemma = base;
            return match;
        }
    }
    if (!bases.empty()) return fromNounSenses(bases, std::move(match));
    // One word for a name WordNet writes as two ("trashcan", "trashcans": trash can).
    if (word.find('-') == std::string::npos)
        for (std::size_t cut = 3; cut + 3 <= word.size(); ++cut) {
            std::string spaced = word;
            spaced.insert(cut, 1, ' ');
            if (!wordnet::nounBaseForms(hyphenated(spaced)).empty()) return lookUp(spaced);
        }
    // Not an English noun: a misspelt category, or the plural of one ("chiars")?
    auto close = model::nearestNames(word, categories_, 1);
    for (const auto& singular : singulars(word))
        if (close.empty()) close = model::nearestNames(singular, categories_, 1);
    if (!close.empty()) {
        match.how = WordMatch::How::Spelling;
        match.categories = close;
        match.lemma = close.front();
        return match;
    }
    // A misspelt English noun ("wordrobe", "courch", "fointain"): the one noun WordNet knows a letter
    // away, where WordNet knows the word as written in no part of speech ("hanged" is a verb).
    // Of several ("courch": couch, church), the one that names a category here.
    {
        const std::set<std::string> respelt = misspeltNouns(word);
        std::vector<WordMatch> naming;
        for (const auto& noun : respelt)
            if (WordMatch m = lookUp(noun); m.how == WordMatch::How::Category || m.how == WordMatch::How::Plural ||
                                            m.how == WordMatch::How::Synonym)
                naming.push_back(std::move(m));
        if (naming.size() == 1 || (naming.empty() && respelt.size() == 1)) {
            WordMatch m = naming.empty() ? lookUp(*respelt.begin()) : naming.front();
            m.how = m.categories.empty() ? WordMatch::How::Absent : WordMatch::How::Spelling;
            return m;
        }
    }
    // Two nouns written as one that WordNet does not know together ("rackstand": a rack stand), for
    // a thing the scene does not hold.
    if (word.find('-') == std::string::npos && word.size() >= 7 && !wordnet::isKnown(word)) {
        std::vector<std::string> splits;
        for (std::size_t cut = 3; cut + 3 <= word.size(); ++cut)
            if (!wordnet::nounBaseForms(word.substr(0, cut)).empty() &&
                !wordnet::nounBaseForms(word.substr(cut)).empty())
                splits.push_back(word.substr(0, cut) + "-" + word.substr(cut));
        if (splits.size() == 1) {
            match.how = WordMatch::How::Absent;
            match.lemma = splits.front();
            return match;
        }
    }
    // A plural of a word that is no noun in WordNet stays the word as written.
    match.how = WordMatch::How::Unknown;
    return match;
}

std::optional<std::string> absentThing(const std::string& name, const WordMatch& match) {
    if (match.how != WordMatch::How::Absent) return std::nullopt;
    std::string noun = match.lemma.empty() ? name : match.lemma;  // "pianos" -> piano
    if (namesWholeScene(noun) || (!physicalThing(noun) && equivalents(noun).empty())) return std::nullopt;
    return noun;
}

std::string hyphenated(std::string words) {
    std::replace(words.begin(), words.end(), ' ', '-');
    return words;
}

std::string pluralOf(const std::string& noun) {
    if (noun.empty()) return noun;
    // "a desk lamp" -> "desk lamps": the last word counts.
    if (const auto space = noun.rfind(' '); space != std::string::npos)
        return noun.substr(0, space + 1) + pluralOf(noun.substr(space + 1));
    // Nouns with no plural are counted in pieces: "11 pieces of furniture", not "11 furnitures".
    static const std::set<std::string, std::less<>> kMass{"furniture", "equipment", "luggage",   "clothing",
                                                          "cutlery",   "jewelry",   "jewellery", "stuff"};
    if (kMass.count(noun)) return "pieces of " + noun;
    // An irregular plural is one WordNet's exception list takes back to the noun ("shelves" -> shelf,
    // "knives" -> knife); its rules for endings take no "ves" back, so a made-up form never passes.
    for (const std::size_t drop : {std::size_t{1}, std::size_t{2}})
        if (noun.size() > drop + 1 && (drop == 1 ? noun.ends_with("f") : noun.ends_with("fe"))) {
            const std::string ves = noun.substr(0, noun.size() - drop) + "ves";
            const auto bases = wordnet::nounBaseForms(ves);
            if (std::find(bases.begin(), bases.end(), noun) != bases.end()) return ves;
        }
    if (noun.ends_with("s") || noun.ends_with("x") || noun.ends_with("ch") || noun.ends_with("sh")) return noun + "es";
    bool consonantY = noun.size() > 1 && noun.ends_with("y") &&
                      std::string_view("aeiou").find(noun[noun.size() - 2]) == std::string_view::npos;
    return consonantY ? noun.substr(0, noun.size() - 1) + "ies" : noun + "s";
}

std::string describe(WordMatch::How how) {
    switch (how) {
        case WordMatch::How::Category:
            return "category";
        case WordMatch::How::Plural:
            return "plural";
        case WordMatch::How::Synonym:
            return "synonym";
        case WordMatch::How::Kind:
            return "kinds of it";
        case WordMatch::How::Broader:
            return "the kind it is";
        case WordMatch::How::Spelling:
            return "spelling";
        case WordMatch::How::Absent:
            return "not in this scene";
        case WordMatch::How::Unknown:
            return "unknown word";
    }
    return {};
}

}  // namespace smql::ask
