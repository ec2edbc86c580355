#include "engine/similar/text_embedder.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "engine/ask/wordnet.hpp"

namespace smql::similar {

namespace {

// The weights of docs/similarity.md. A node's own words count most, then what WordNet says it is.
constexpr float kCategoryWeight = 3.0F;
constexpr float kSynonymWeight = 2.0F;
constexpr float kDefinitionWeight = 1.0F;
constexpr float kHypernymWeight = 1.5F;
constexpr float kHypernymDefinitionWeight = 0.7F;
constexpr float kLevelDecay = 0.6F;  // each level up the hypernyms weighs this much of the one below
constexpr int kHypernymLevels = 3;   // above that every object is an "artifact": it would tell nothing
constexpr int kDefinitionLevels = 2;
constexpr float kAttributeWeight = 1.5F;
constexpr float kDescriptionWeight = 0.5F;
constexpr float kQueryWordWeight = 1.0F;
constexpr float kQuerySynonymWeight = 0.8F;
constexpr float kQueryHypernymWeight = 0.5F;  // a pillow is a cushion: one level up
constexpr float kTrigramShare = 0.2F;         // each character trigram of a word, relative to the word

using Features = std::map<std::string, float>;

bool isStopWord(const std::string& word) {
    // Function words, and the words a query uses for "any object", which name nothing to match.
    static const std::vector<std::string> kStopWords = {
        "a",    "an",    "and",   "any",     "are",   "as",        "at",     "be",   "by",    "e.g",
        "etc",  "for",   "from",  "has",     "have",  "i",         "in",     "into", "is",    "it",
        "its",  "me",    "more",  "most",    "my",    "of",        "on",     "one",  "or",    "such",
        "than", "that",  "the",   "their",   "them",  "there",     "these",  "they", "thing", "things",
        "this", "those", "to",    "usually", "used",  "something", "object", "item", "stuff", "what",
        "with", "which", "where", "who",     "whose", "objects",   "items",  "some", "can",   "you"};
    return std::find(kStopWords.begin(), kStopWords.end(), word) != kStopWords.end();
}

// Lower-case runs of letters; a hyphen joins letters ("coffee-table" is one word here).
std::vector<std::string> words(std::string_view text) {
    std::vector<std::string> out;
    std::string word;
    auto flush = [&] {
        while (!word.empty() && word.back() == '-') word.pop_back();
        if (!word.empty() && !isStopWord(word)) out.push_back(word);
        word.clear();
    };
    for (char raw : text) {
        auto c = static_cast<unsigned char>(raw);
        if (std::isalpha(c))
            word.push_back(static_cast<char>(std::tolower(c)));
        else if ((c == '-' || c == '_') && !word.empty())
            word.push_back('-');
        else
            flush();
    }
    flush();
    return out;
}

void addTrigrams(const std::string& word, float weight, Features& features) {
    const std::string padded = "#" + word + "#";
    for (std::size_t i = 0; i + 3 <= padded.size(); ++i) features["t:" + padded.substr(i, 3)] += weight;
}

// A word as its base forms ("sitting": sitting and sit), and optionally its spelling as trigrams.
// A hyphenated word also counts as its parts ("coffee-table": coffee, table).
void addWord(const std::string& word, float weight, bool spelling, Features& features) {
    for (const std::string& form : ask::wordnet::baseForms(word)) features["w:" + form] += weight;
    if (spelling) addTrigrams(word, weight * kTrigramShare, features);
    if (word.find('-') == std::string::npos) return;
    std::size_t start = 0;
    while (start < word.size()) {
        std::size_t end = std::min(word.find('-', start), word.size());
        if (end > start) addWord(word.substr(start, end - start), weight / 2, spelling, features);
        start = end + 1;
    }
}

void addText(std::string_view text, float weight, Features& features) {
    for (const std::string& word : words(text)) addWord(word, weight, false, features);
}

// The first (most used) noun sense of a word, as WordNet lists it.
std::optional<ask::wordnet::Sense> firstSense(const std::string& word) {
    auto senses = ask::wordnet::nounSenses(word);
    if (senses.empty())
        for (const std::string& base : ask::wordnet::nounBaseForms(word))
            if (senses = ask::wordnet::nounSenses(base); !senses.empty()) break;
    if (senses.empty()) return std::nullopt;
    return senses.front();
}

// What a category is, from WordNet: synonyms, its definition, the hypernyms above it and their
// definitions. Kept per category: a scene has few, and each is asked about once per object.
const Features& categoryFeatures(const std::string& category) {
    static std::mutex mutex;
    static std::map<std::string, Features> known;
    std::lock_guard guard(mutex);
    if (auto it = known.find(category); it != known.end()) return it->second;
    Features features;
    addWord(category, kCategoryWeight, true, features);
    if (auto sense = firstSense(category)) {
        for (const std::string& synonym : sense->words)
            if (synonym != category) addWord(synonym, kSynonymWeight, false, features);
        addText(ask::wordnet::gloss(sense->offset), kDefinitionWeight, features);
        std::vector<long> level{sense->offset};
        float scale = 1.0F;
        for (int depth = 1; depth <= kHypernymLevels && !level.empty(); ++depth) {
            std::vector<long> above;
            for (long offset : level)
                for (const auto& hypernym : ask::wordnet::hypernyms(offset)) {
                    for (const std::string& word : hypernym.words)
                        addWord(word, kHypernymWeight * scale, false, features);
                    if (depth <= kDefinitionLevels)
                        addText(ask::wordnet::gloss(hypernym.offset), kHypernymDefinitionWeight * scale, features);
                    above.push_back(hypernym.offset);
                }
            level = std::move(above);
            scale *= kLevelDecay;
        }
    }
    return known.emplace(category, std::move(features)).first->second;
}

std::uint64_t fnv1a(const std::string& text) {
    std::uint64_t hash = 14695981039346656037ULL;
    for (char c : text) {
        hash ^= static_cast<unsigned char>(c);
        hash *= 1099511628211ULL;
    }
    return hash;
}

Vector hashed(const Features& features) {
    Vector v{};
    for (const auto& [feature, weight] : features) {
        const std::uint64_t hash = fnv1a(feature);
        v[hash % kDimensions] += (hash >> 63) != 0 ? -weight : weight;
    }
    float norm = 0;
    for (float x : v) norm += x * x;
    if (norm > 0) {
        const float scale = 1.0F / std::sqrt(norm);
        for (float& x : v) x *= scale;
    }
    return v;
}

bool hasDigit(const std::string& text) {
    return std::any_of(text.begin(), text.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
}

}  // namespace

Vector embedNode(const model::Node& node) {
    if (node.kind == model::NodeKind::Scene || node.category.empty()) return Vector{};
    Features features = categoryFeatures(node.category);
    for (const auto& attribute : node.attributes)
        if (!hasDigit(attribute.value))  // a colour or a material, not a measurement
            for (const std::string& word : words(attribute.value)) addWord(word, kAttributeWeight, true, features);
    addText(node.text, kDescriptionWeight, features);
    return hashed(features);
}

Vector embedQuery(std::string_view text) {
    Features features;
    const std::vector<std::string> query = words(text);
    for (std::size_t i = 0; i < query.size(); ++i) {
        addWord(query[i], kQueryWordWeight, true, features);
        if (auto sense = firstSense(query[i])) {
            for (const std::string& synonym : sense->words)
                if (synonym != query[i]) addWord(synonym, kQuerySynonymWeight, false, features);
            for (const auto& hypernym : ask::wordnet::hypernyms(sense->offset))
                for (const std::string& word : hypernym.words) addWord(word, kQueryHypernymWeight, false, features);
        }
        // Two words WordNet knows as one noun ("coffee table", "tv screen") also count joined.
        if (i + 1 < query.size()) {
            std::string joined = query[i] + "-" + query[i + 1];
            if (!ask::wordnet::nounSenses(joined).empty()) addWord(joined, kQueryWordWeight, false, features);
        }
    }
    return hashed(features);
}

namespace {

// Eight running sums the compiler keeps in SIMD registers: a single sum would have to add in
// order (floating point does not reassociate without -ffast-math), one product at a time.
float dotOf(const float* a, const float* b, std::size_t length) {
    constexpr std::size_t kLanes = 8;
    std::array<float, kLanes> sums{};
    const std::size_t whole = length - length % kLanes;
    for (std::size_t i = 0; i < whole; i += kLanes)
        for (std::size_t lane = 0; lane < kLanes; ++lane) sums[lane] += a[i + lane] * b[i + lane];
    float dot = 0;
    for (float sum : sums) dot += sum;
    for (std::size_t i = whole; i < length; ++i) dot += a[i] * b[i];
    return dot;
}

}  // namespace

float similarity(std::span<const float> a, std::span<const float> b) {
    // The embedder's own length as a constant lets the compiler unroll the loop: exact scans run a
    // fifth faster than with the length known only at run time (make bench-similar).
    if (a.size() == kDimensions) return dotOf(a.data(), b.data(), kDimensions);
    return dotOf(a.data(), b.data(), a.size());
}

bool isZero(std::span<const float> v) {
    return std::all_of(v.begin(), v.end(), [](float x) { return x == 0.0F; });
}

}  // namespace smql::similar
