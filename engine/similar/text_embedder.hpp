// The built-in text embedder of SIMILAR TO: local, deterministic, no model file. A node is
// described by its category, its attributes' values and its description; a query by its words.
// Both become bags of weighted features hashed into one vector of kDimensions floats (the
// "hashing trick", each feature with a hashed sign so collisions cancel on average), unit length,
// so similarity is a dot product. docs/similarity.md lists the features and their weights.
//
// What makes it more than word overlap is WordNet (engine/ask/wordnet.hpp): a category brings its
// synonyms, the hypernyms above it (a sofa is a seat, furniture ...) and the words of their
// definitions (a seat is "furniture that is designed for sitting on"), so 'couch', 'furniture'
// and 'something to sit on' all reach a sofa. Character trigrams of every word let a misspelling
// ('sofaa') still land near the word it misses.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <string_view>

#include "model/types.hpp"

namespace smql::similar {

inline constexpr std::size_t kDimensions = 512;
using Vector = std::array<float, kDimensions>;

// The vector of what a node says about itself. A node with no words (a scene node, a node without
// category) gets the zero vector, which is similar to nothing.
Vector embedNode(const model::Node& node);
// The vector of a query ('soft thing to sit on'). Zero when the text has no word the embedder
// reads (only stop words, or no letters).
Vector embedQuery(std::string_view text);
// Below this similarity a node and a text share a character trigram or a hash collision, not a
// meaning: SIMILAR TO leaves such nodes out (a misspelt word's own match scores about 0.05).
inline constexpr float kLeastSimilarity = 0.02F;
// Cosine similarity of two unit-length (or zero) vectors of one length, made here or stored from an
// external model: their dot product.
float similarity(std::span<const float> a, std::span<const float> b);
bool isZero(std::span<const float> v);

}  // namespace smql::similar
