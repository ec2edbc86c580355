#include "model/category.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <utility>

#include "model/types.hpp"

namespace smql::model {

namespace {

// Words that end in s but are singular, or that have no singular a person would write for the
// thing ("blinds", "scissors", "glasses" the eyewear): they stay as they are.
constexpr std::array<std::string_view, 30> kKeptAsWritten{
    "alias",   "atlas",   "bias",    "binoculars", "blinds",  "bus",      "canvas", "chassis",  "clothes",  "corps",
    "gas",     "glasses", "goggles", "iris",       "jeans",   "lens",     "means",  "news",     "pajamas",  "pants",
    "physics", "pliers",  "series",  "shorts",     "species", "scissors", "tongs",  "trousers", "tweezers", "yes"};

// Plurals that English endings get wrong: irregular ones, -f and -fe nouns, and -ies / -oes / -ses
// plurals whose singular ends otherwise than the rule says.
constexpr std::array<std::pair<std::string_view, std::string_view>, 39> kIrregularPlurals{{
    {"atlases", "atlas"},   {"buses", "bus"},       {"cacti", "cactus"},    {"calves", "calf"},
    {"canvases", "canvas"}, {"children", "child"},  {"cookies", "cookie"},  {"echoes", "echo"},
    {"feet", "foot"},       {"fungi", "fungus"},    {"gases", "gas"},       {"geese", "goose"},
    {"halves", "half"},     {"heroes", "hero"},     {"hoodies", "hoodie"},  {"indices", "index"},
    {"knives", "knife"},    {"leaves", "leaf"},     {"lenses", "lens"},     {"lives", "life"},
    {"loaves", "loaf"},     {"mangoes", "mango"},   {"matrices", "matrix"}, {"men", "man"},
    {"mice", "mouse"},      {"movies", "movie"},    {"people", "person"},   {"potatoes", "potato"},
    {"scarves", "scarf"},   {"selves", "self"},     {"shelves", "shelf"},   {"teeth", "tooth"},
    {"thieves", "thief"},   {"tomatoes", "tomato"}, {"vertices", "vertex"}, {"wives", "wife"},
    {"wolves", "wolf"},     {"women", "woman"},     {"zombies", "zombie"},
}};

bool separator(char c) { return c == ' ' || c == '-' || c == '_' || c == '\t' || c == '\n' || c == '\r'; }

}  // namespace

namespace {

// The singular of one lower-case word as what it is made of: `stem` (a view of the word or of the
// table of irregular plurals) followed by `ending`. A word that is no plural is its own stem.
struct Singular {
    std::string_view stem;
    std::string_view ending;
};

Singular singularOf(std::string_view word) {
    if (std::find(kKeptAsWritten.begin(), kKeptAsWritten.end(), word) != kKeptAsWritten.end()) return {word, {}};
    for (const auto& [plural, singular] : kIrregularPlurals)
        if (word == plural) return {singular, {}};
    // A possessive or a contraction ("it's", "o'brien's") is no plural.
    if (word.size() < 3 || !word.ends_with('s') || word.ends_with("'s")) return {word, {}};
    auto drop = [&](std::size_t n) { return word.substr(0, word.size() - n); };
    if (word.size() > 4 && word.ends_with("ies")) return {drop(3), "y"};  // shelves above; batteries
    for (std::string_view ending : {"sses", "shes", "ches", "xes", "zzes"})
        if (word.ends_with(ending)) return {drop(2), {}};  // dresses -> dress, switches -> switch, boxes -> box
    for (std::string_view ending : {"ss", "us", "is"})
        if (word.ends_with(ending)) return {word, {}};  // mattress, cactus, tennis: no plurals
    return {drop(1), {}};                               // chairs, vases, stoves, tvs
}

}  // namespace

std::string singularWord(std::string_view word) {
    const Singular singular = singularOf(word);
    std::string out;
    out.reserve(singular.stem.size() + singular.ending.size());
    return out.append(singular.stem).append(singular.ending);
}

std::string categoryWords(std::string_view category) {
    std::string words(category);
    std::replace_if(
        words.begin(), words.end(), [](char c) { return c == '-' || c == '_'; }, ' ');
    return words;
}

std::string categoryName(std::string_view written) {
    std::string out;
    out.reserve(written.size());
    bool pendingSeparator = false;
    for (char c : written) {
        if (separator(c)) {
            pendingSeparator = !out.empty();
            continue;
        }
        if (pendingSeparator) out.push_back('-');
        pendingSeparator = false;
        out.push_back(c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c);
    }
    const std::size_t lastWord = out.rfind('-') == std::string::npos ? 0 : out.rfind('-') + 1;
    const Singular singular = singularOf(std::string_view(out).substr(lastWord));
    out = std::string(out, 0, lastWord).append(singular.stem).append(singular.ending);
    return out;
}

bool isCategoryName(std::string_view written) {
    // What categoryName leaves as it is: no upper-case ASCII letter, words joined by single
    // hyphens (no other separator, none at either end), the last word its own singular. A scene's
    // first query and every node it decodes ask this of a stored name, so it builds no string.
    char previous = '-';
    for (char c : written) {
        if ((c >= 'A' && c <= 'Z') || (separator(c) && (c != '-' || previous == '-'))) return false;
        previous = c;
    }
    if (!written.empty() && previous == '-') return false;
    const std::size_t hyphen = written.rfind('-');
    const std::string_view last = written.substr(hyphen == std::string_view::npos ? 0 : hyphen + 1);
    const Singular singular = singularOf(last);
    return singular.ending.empty() && singular.stem == last;
}

void canonicaliseCategories(SceneData& scene) {
    for (Node& node : scene.nodes)
        if (node.kind != NodeKind::Scene && !node.category.empty() && !isCategoryName(node.category))
            node.category = categoryName(node.category);
}

std::string categoryPattern(std::string_view pattern) {
    std::string out;
    out.reserve(pattern.size());
    for (char c : pattern) {
        if (c == ' ' || c == '\t' || c == '-') {
            if (!out.empty() && out.back() == '-') continue;
            out += '-';
        } else {
            out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        }
    }
    return out;
}

}  // namespace smql::model
