#include "engine/ask/wordnet.hpp"

#include <algorithm>
#include <array>
#include <fstream>
#include <map>
#include <mutex>
#include <string_view>
#include <unordered_set>
#include <utility>
#include <vector>

#include <wn.h>

namespace smql::ask::wordnet {

namespace {

// One lock for the whole library: its searches share static buffers and file positions.
std::mutex& lock() {
    static std::mutex m;
    return m;
}

// Called with the lock held.
bool open() {
    static const bool opened = wninit() == 0;
    return opened;
}

std::string categorySpelling(const char* word) {
    std::string out(word);
    for (char& c : out) c = c == '_' || c == ' ' ? '-' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

std::string wordNetSpelling(const std::string& word) {
    std::string out = word;
    std::replace(out.begin(), out.end(), '-', '_');
    return out;
}

}  // namespace

bool available() {
    std::lock_guard guard(lock());
    return open();
}

std::vector<std::string> nounBaseForms(const std::string& word) {
    std::lock_guard guard(lock());
    // Each word of a question is looked up with every question (at most the vocabulary asked).
    static std::map<std::string, std::vector<std::string>> known;
    if (auto it = known.find(word); it != known.end()) return it->second;
    std::vector<std::string> out;
    if (!open() || word.empty()) return out;
    std::string key = wordNetSpelling(word);
    // morphstr returns the first base form, then the next ones for a null argument. Its forms
    // come first: "seats" is also a noun of its own in WordNet, but people mean seat.
    for (char* form = morphstr(key.data(), NOUN); form; form = morphstr(nullptr, NOUN)) {
        std::string base = categorySpelling(form);
        if (std::find(out.begin(), out.end(), base) == out.end()) out.push_back(base);
    }
    if (IndexPtr index = index_lookup(key.data(), NOUN)) {
        std::string self = categorySpelling(index->wd);
        if (std::find(out.begin(), out.end(), self) == out.end()) out.push_back(self);
        free_index(index);
    }
    known.emplace(word, out);
    return out;
}

namespace {

// The first word of each line of a WordNet file: the lemmas of an index, the inflected forms of an
// exception list. The index's licence lines start with a space.
void readFirstWords(const std::string& path, std::unordered_set<std::string>& into) {
    std::ifstream in(path);
    for (std::string line; std::getline(in, line);)
        if (!line.empty() && line.front() != ' ') into.insert(line.substr(0, line.find(' ')));
}

// What the noun index and exceptions hold, read when first asked (the caller holds the lock). Empty
// when the files cannot be read: mayBeNoun then leaves every word to the library.
const std::unordered_set<std::string>& nounForms() {
    static const std::unordered_set<std::string> forms = [] {
        std::unordered_set<std::string> out;
        const std::string dir = SetSearchdir();
        readFirstWords(dir + "/index.noun", out);
        readFirstWords(dir + "/noun.exc", out);
        return out;
    }();
    return forms;
}

}  // namespace

bool mayBeNoun(const std::string& word) {
    std::lock_guard guard(lock());
    if (!open() || word.empty()) return false;
    const auto& forms = nounForms();
    const std::string key = wordNetSpelling(word);
    if (forms.empty() || forms.count(key) > 0) return true;
    // WordNet's endings for nouns (morph.c: "boxes" -> box, "women" -> woman, "flies" -> fly), and
    // "-ful" measures ("cupsful"), which it reads by the word before.
    static constexpr std::array<std::pair<std::string_view, std::string_view>, 8> kEndings{{{"s", ""},
                                                                                            {"ses", "s"},
                                                                                            {"xes", "x"},
                                                                                            {"zes", "z"},
                                                                                            {"ches", "ch"},
                                                                                            {"shes", "sh"},
                                                                                            {"men", "man"},
                                                                                            {"ies", "y"}}};
    const std::string_view k = key;
    if (k.ends_with("ful")) return true;
    for (const auto& [ending, base] : kEndings)
        if (k.size() > ending.size() && k.ends_with(ending) &&
            forms.count(std::string(k.substr(0, k.size() - ending.size())) + std::string(base)) > 0)
            return true;
    return false;
}

std::vector<Sense> nounSenses(const std::string& word) {
    std::lock_guard guard(lock());
    // The categories of a scene are looked up with every question: keep what WordNet said (at most
    // its vocabulary).
    static std::map<std::string, std::vector<Sense>> known;
    if (auto it = known.find(word); it != known.end()) return it->second;
    std::vector<Sense> out;
    if (!open() || word.empty()) return out;
    std::string key = wordNetSpelling(word);
    IndexPtr index = index_lookup(key.data(), NOUN);
    if (!index) {
        known.emplace(word, out);
        return out;
    }
    for (int i = 0; i < index->off_cnt; ++i) {
        SynsetPtr synset = read_synset(NOUN, static_cast<long>(index->offset[i]), key.data());
        if (!synset) continue;
        Sense sense{static_cast<long>(index->offset[i]), {}, i < std::max(index->tagged_cnt, 1)};
        for (int w = 0; w < synset->wcount; ++w) sense.words.push_back(categorySpelling(synset->words[w]));
        free_synset(synset);
        out.push_back(std::move(sense));
    }
    free_index(index);
    known.emplace(word, out);
    return out;
}

std::vector<Sense> hypernyms(long offset) {
    std::lock_guard guard(lock());
    std::vector<Sense> out;
    if (!open()) return out;
    char noWord[] = "";  // no word to mark in the synset
    SynsetPtr synset = read_synset(NOUN, offset, noWord);
    if (!synset) return out;
    for (int p = 0; p < synset->ptrcount; ++p) {
        if ((synset->ptrtyp[p] != HYPERPTR && synset->ptrtyp[p] != INSTANCE) || synset->ppos[p] != NOUN) continue;
        SynsetPtr parent = read_synset(NOUN, synset->ptroff[p], noWord);
        if (!parent) continue;
        Sense sense{synset->ptroff[p], {}, true};
        for (int w = 0; w < parent->wcount; ++w) sense.words.push_back(categorySpelling(parent->words[w]));
        free_synset(parent);
        out.push_back(std::move(sense));
    }
    free_synset(synset);
    return out;
}

std::set<long> hypernymClosure(long offset) {
    std::lock_guard guard(lock());
    // A scene's categories are asked about again with every question; their closures never change.
    static std::map<long, std::set<long>> known;
    if (auto it = known.find(offset); it != known.end()) return it->second;
    std::set<long> seen{offset};
    if (!open()) return seen;
    std::vector<long> todo{offset};
    while (!todo.empty()) {
        long at = todo.back();
        todo.pop_back();
        char noWord[] = "";  // no word to mark in the synset
        SynsetPtr synset = read_synset(NOUN, at, noWord);
        if (!synset) continue;
        for (int p = 0; p < synset->ptrcount; ++p) {
            bool upward = synset->ptrtyp[p] == HYPERPTR || synset->ptrtyp[p] == INSTANCE;
            if (upward && synset->ppos[p] == NOUN && seen.insert(synset->ptroff[p]).second)
                todo.push_back(synset->ptroff[p]);
        }
        free_synset(synset);
    }
    known.emplace(offset, seen);
    return seen;
}

std::string gloss(long offset) {
    std::lock_guard guard(lock());
    static std::map<long, std::string> known;
    if (auto it = known.find(offset); it != known.end()) return it->second;
    std::string out;
    if (!open()) return out;
    char noWord[] = "";  // no word to mark in the synset
    if (SynsetPtr synset = read_synset(NOUN, offset, noWord)) {
        // "(an upholstered seat for more than one person; \"an example\")": the words up to the examples.
        out = synset->defn ? synset->defn : "";
        free_synset(synset);
        if (!out.empty() && out.front() == '(') out.erase(0, 1);
        if (auto examples = out.find("; \""); examples != std::string::npos) out.resize(examples);
        if (!out.empty() && out.back() == ')') out.pop_back();
    }
    known.emplace(offset, out);
    return out;
}

std::vector<std::string> baseForms(const std::string& word) {
    std::lock_guard guard(lock());
    static std::map<std::string, std::vector<std::string>> known;
    if (auto it = known.find(word); it != known.end()) return it->second;
    std::vector<std::string> out;
    auto add = [&](std::string form) {
        if (std::find(out.begin(), out.end(), form) == out.end()) out.push_back(std::move(form));
    };
    if (open() && !word.empty()) {
        std::string key = wordNetSpelling(word);
        for (int pos : {NOUN, VERB, ADJ, ADV}) {
            if (IndexPtr index = index_lookup(key.data(), pos)) {
                add(categorySpelling(index->wd));
                free_index(index);
            }
            for (char* form = morphstr(key.data(), pos); form; form = morphstr(nullptr, pos))
                add(categorySpelling(form));
        }
    }
    if (out.empty()) out.push_back(word);
    known.emplace(word, out);
    return out;
}

namespace {

// Whether WordNet knows the word, or a base form of it, in a part of speech (the caller holds the lock).
bool inIndex(std::string key, int pos) {
    if (IndexPtr index = index_lookup(key.data(), pos)) {
        free_index(index);
        return true;
    }
    return morphstr(key.data(), pos) != nullptr;
}

}  // namespace

namespace {

// Whether WordNet's index holds the word as `pos` (ADJ, VERB) and not as a noun; each part of speech keeps its answers.
bool onlyAs(const std::string& word, int pos) {
    std::lock_guard guard(lock());
    static std::map<std::pair<int, std::string>, bool> known;
    if (auto it = known.find({pos, word}); it != known.end()) return it->second;
    bool other = false, noun = false;
    if (open() && !word.empty()) {
        std::string key = wordNetSpelling(word);
        other = inIndex(key, pos);
        noun = inIndex(key, NOUN);
    }
    known.emplace(std::pair{pos, word}, other && !noun);
    return other && !noun;
}

}  // namespace

bool isAdjectiveOnly(const std::string& word) { return onlyAs(word, ADJ); }

bool isVerbNotNoun(const std::string& word) { return onlyAs(word, VERB); }

bool isKnown(const std::string& word) {
    std::lock_guard guard(lock());
    static std::map<std::string, bool> known;
    if (auto it = known.find(word); it != known.end()) return it->second;
    bool any = false;
    if (open() && !word.empty()) {
        std::string key = wordNetSpelling(word);
        for (int pos : {NOUN, VERB, ADJ, ADV}) any = any || inIndex(key, pos);
    }
    known.emplace(word, any);
    return any;
}

}  // namespace smql::ask::wordnet
