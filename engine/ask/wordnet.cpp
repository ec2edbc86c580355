#include "engine/ask/wordnet.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <map>
#include <mutex>
#include <string_view>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <wn.h>

namespace smql::ask::wordnet {

namespace {

// One lock for the whole library: its searches share static buffers and file positions.
std::mutex& lock() {
    static std::mutex m;
    return m;
}

// What WordNet's files hold, mapped when the library opens: each part of speech's index (which
// the library then searches in memory) and its exception list. Both are sorted by their lines'
// first words, byte by byte, as the library's own binary search reads them.
struct Dictionary {
    std::array<std::string_view, NUMPARTS + 1> index;  // by part of speech (NOUN ... ADV)
    std::array<std::string_view, NUMPARTS + 1> exceptions;
};

// A file mapped for the process's life (its pages read as a search touches them): empty when it
// cannot be.
std::string_view mappedFile(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return {};
    struct stat info {};
    void* at = MAP_FAILED;
    if (::fstat(fd, &info) == 0 && info.st_size > 0)
        at = ::mmap(nullptr, static_cast<std::size_t>(info.st_size), PROT_READ, MAP_PRIVATE, fd, 0);
    ::close(fd);
    if (at == MAP_FAILED) return {};
    return {static_cast<const char*>(at), static_cast<std::size_t>(info.st_size)};
}

// Whether a line of the sorted `text` starts with the word `key` (then a space): a binary search
// over the text's bytes, each step on the line that starts after the middle. The index's licence
// lines start with a space and sort first.
bool holdsWord(std::string_view text, std::string_view key) {
    // Lines that start before `low` have a smaller first word, those that start at `high` or after
    // a larger one.
    std::size_t low = 0, high = text.size();
    while (low < high) {
        const std::size_t middle = low + (high - low) / 2;
        // The first line that starts at `middle` or after it.
        std::size_t start = 0;
        if (middle > 0) {
            start = text.find('\n', middle - 1);
            start = start == std::string_view::npos ? text.size() : start + 1;
        }
        if (start >= high) {  // none starts in [middle, high)
            high = middle;
            continue;
        }
        const std::string_view line = text.substr(start, text.find('\n', start) - start);
        const std::string_view word = line.substr(0, line.find(' '));
        if (word == key) return true;
        if (word < key)
            low = start + line.size() + 1;
        else
            high = start;
    }
    return false;
}

Dictionary& dictionary() {
    static Dictionary d;
    return d;
}

// The library binary-searches its index files through stdio, and glibc's fseek drops the buffer, so
// each step of a search read the file again: a word's look-up cost 20-odd system calls. The index
// files are mapped instead, and the library searches them in memory (fmemopen reads the mapping,
// and a mode "r" stream never writes to it). Its exception lists stay its own streams (morph.c
// keeps them), so a look-up is first tested here, in memory. Where a file cannot be mapped, the
// library keeps its stream and listed() and inflects() pass every word.
void mapDictionary() {
    Dictionary& d = dictionary();
    const std::string dir = SetSearchdir();
    for (int pos = 1; pos <= NUMPARTS; ++pos) {
        const auto at = static_cast<std::size_t>(pos);
        d.exceptions[at] = mappedFile(dir + "/" + partnames[pos] + ".exc");
        if (d.exceptions[at].empty()) continue;
        d.index[at] = mappedFile(dir + "/index." + partnames[pos]);
        if (d.index[at].empty() || !indexfps[pos]) continue;
        if (FILE* memory = fmemopen(const_cast<char*>(d.index[at].data()), d.index[at].size(), "r")) {
            std::fclose(indexfps[pos]);
            indexfps[pos] = memory;
        }
    }
}

// Called with the lock held.
bool open() {
    static const bool opened = [] {
        if (wninit() != 0) return false;
        mapDictionary();
        return true;
    }();
    return opened;
}

// `key` as the library's searches read it: in lower case, a space as '_'.
std::string looked(std::string key) {
    for (char& c : key) c = c == ' ' ? '_' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return key;
}

// Whether index_lookup may find `key` in the part of speech's index: false only when the mapped
// index surely lacks it. Called with the lock held, after open(), as the two below.
bool listed(const std::string& key, int pos) {
    const std::string_view index = dictionary().index[static_cast<std::size_t>(pos)];
    return index.empty() || holdsWord(index, looked(key));
}

// Whether morphstr may find a base form of `key` in the part of speech: false only when the word is
// in no exception list and no ending the library's morphology drops (morph.c: "boxes" -> box,
// "women" -> woman, "flies" -> fly, "sitting" -> sit, "softer" -> soft) leaves a word of the index.
// Phrases and words with hyphens or periods, which the library also reads in other spellings, and
// "-ful" measures, which it reads by the word before, pass.
bool inflects(const std::string& word, int pos) {
    const Dictionary& d = dictionary();
    const std::string_view index = d.index[static_cast<std::size_t>(pos)];
    const std::string key = looked(word);
    if (index.empty() || holdsWord(d.exceptions[static_cast<std::size_t>(pos)], key) ||
        key.find_first_of("_-.") != std::string::npos || (pos == NOUN && key.ends_with("ful")))
        return true;
    struct Ending {
        int pos;
        std::string_view suffix, base;
    };
    static constexpr std::array<Ending, 20> kEndings{{
        {NOUN, "s", ""},      {NOUN, "ses", "s"},   {NOUN, "xes", "x"}, {NOUN, "zes", "z"}, {NOUN, "ches", "ch"},
        {NOUN, "shes", "sh"}, {NOUN, "men", "man"}, {NOUN, "ies", "y"}, {VERB, "s", ""},    {VERB, "ies", "y"},
        {VERB, "es", "e"},    {VERB, "es", ""},     {VERB, "ed", "e"},  {VERB, "ed", ""},   {VERB, "ing", "e"},
        {VERB, "ing", ""},    {ADJ, "er", ""},      {ADJ, "est", ""},   {ADJ, "er", "e"},   {ADJ, "est", "e"},
    }};
    const std::string_view k = key;
    for (const auto& e : kEndings)
        if (e.pos == pos && k.size() > e.suffix.size() && k.ends_with(e.suffix) &&
            holdsWord(index, std::string(k.substr(0, k.size() - e.suffix.size())) + std::string(e.base)))
            return true;
    return false;
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
    // Each word of a question is looked up with every question (at most the nouns and near-nouns asked).
    static std::map<std::string, std::vector<std::string>> known;
    if (auto it = known.find(word); it != known.end()) return it->second;
    std::vector<std::string> out;
    if (!open() || word.empty()) return out;
    std::string key = wordNetSpelling(word);
    const bool inIndex = listed(key, NOUN), inflected = inflects(key, NOUN);
    // Surely no noun: answered in memory, and not kept (a misspelling's search asks of 700 such words).
    if (!inIndex && !inflected) return out;
    // morphstr returns the first base form, then the next ones for a null argument. Its forms
    // come first: "seats" is also a noun of its own in WordNet, but people mean seat.
    if (inflected)
        for (char* form = morphstr(key.data(), NOUN); form; form = morphstr(nullptr, NOUN)) {
            std::string base = categorySpelling(form);
            if (std::find(out.begin(), out.end(), base) == out.end()) out.push_back(base);
        }
    if (IndexPtr index = inIndex ? index_lookup(key.data(), NOUN) : nullptr) {
        std::string self = categorySpelling(index->wd);
        if (std::find(out.begin(), out.end(), self) == out.end()) out.push_back(self);
        free_index(index);
    }
    known.emplace(word, out);
    return out;
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
            if (IndexPtr index = listed(key, pos) ? index_lookup(key.data(), pos) : nullptr) {
                add(categorySpelling(index->wd));
                free_index(index);
            }
            if (inflects(key, pos))
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
    if (IndexPtr index = listed(key, pos) ? index_lookup(key.data(), pos) : nullptr) {
        free_index(index);
        return true;
    }
    return inflects(key, pos) && morphstr(key.data(), pos) != nullptr;
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
