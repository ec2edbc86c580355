// The few WordNet look-ups the English front-end needs: base forms of a word (plurals), its noun
// senses with their synonyms, and the hypernyms above a sense. WordNet's C library keeps global
// state (open files, static buffers) and is not thread-safe: every call here takes one mutex, so
// engines in several threads may ask at once. The database files are the system's (Debian's
// wordnet-base, /usr/share/wordnet; WNSEARCHDIR overrides it), opened on first use.
#pragma once

#include <set>
#include <string>
#include <vector>

namespace smql::ask::wordnet {

// A noun sense: its synset's place in data.noun and the words of the synset (lower case,
// multi-word entries joined with '-', as the scene categories spell them: "coffee-table").
struct Sense {
    long offset = 0;
    std::vector<std::string> words;
    // Among the senses found in WordNet's tagged texts (always the first): the meanings people use.
    // Rare senses ("bed" as a layer) would let a general word cover the wrong categories.
    bool common = false;
};

// Whether the WordNet database could be opened; false leaves the front-end with exact names,
// plurals and spelling only.
bool available();
// The noun base forms WordNet knows for `word` ("mice" -> mouse, "benches" -> bench), the word
// itself first when it is a noun. A word in no index, no exception list and with no ending the
// library drops is answered from the files mapped in memory, without the library's searches, so a
// search over many candidates (the words a letter from a misspelling) costs little.
std::vector<std::string> nounBaseForms(const std::string& word);
// The noun senses of a base form, most frequent first; empty for a word WordNet does not know as
// a noun.
std::vector<Sense> nounSenses(const std::string& word);
// The synsets directly above `offset` (hypernyms and instance-of).
std::vector<Sense> hypernyms(long offset);
// Every synset above `offset` through hypernym and instance-of links, `offset` included.
std::set<long> hypernymClosure(long offset);
// The definition of the noun synset at `offset`, without its examples: "an upholstered seat for
// more than one person". Empty when WordNet is missing.
std::string gloss(long offset);
// The base forms of a word in every part of speech, nouns first, then verbs, adjectives and
// adverbs ("sitting" -> sitting, sit; "softer" -> soft; "chairs" -> chair); the word itself when
// WordNet knows none.
std::vector<std::string> baseForms(const std::string& word);

// Whether WordNet knows the word as an adjective and not as a noun ("rectangular", "leather" is
// also a noun): a modifier the memory keeps no attribute for.
bool isAdjectiveOnly(const std::string& word);

// Whether WordNet knows the word as a verb and not as a noun ("sits", "hanged", "affixed", "pushed"):
// after a noun it says what the thing does or how it is placed, and names no part of it.
bool isVerbNotNoun(const std::string& word);

// Whether WordNet knows the word, or a base form of it, in any part of speech.
bool isKnown(const std::string& word);

}  // namespace smql::ask::wordnet
