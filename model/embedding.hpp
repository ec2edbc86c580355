// A node's vector from an external model (an open-vocabulary detector's image embedding, say): the
// node's blob named `embedding`, its floats as little-endian IEEE-754 float32 one after another,
// media type application/x-float32. Ingest writes it from detections.json, the scene JSON carries
// it as any blob, storage refuses a scene whose embeddings are malformed or differ in length, and
// SIMILAR TO with a bound vector ranks the nodes by it (docs/similarity.md, "Vectors from elsewhere").
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "model/types.hpp"

namespace smql::model {

inline constexpr std::string_view kEmbeddingBlob = "embedding";
inline constexpr std::string_view kEmbeddingMediaType = "application/x-float32";
// Larger than any image or text model's vectors in use (CLIP: 512 to 1024, text models: up to 4096).
inline constexpr std::size_t kMaxEmbeddingDimensions = 4096;

// Why `vector` cannot be an embedding: empty, longer than kMaxEmbeddingDimensions, a value not
// finite, or all zeros (which has no direction to compare). Nothing when it can.
std::optional<std::string> embeddingProblem(std::span<const float> vector);

// The blob `embedding` of `node` holding `vector` (which embeddingProblem accepts).
Blob embeddingBlob(NodeId node, std::span<const float> vector);

// The vector an embedding blob holds. Throws Error(Input) saying what is wrong: another media type,
// a size that is not a whole number of floats, or a vector embeddingProblem refuses.
std::vector<float> readEmbedding(const Blob& blob);

}  // namespace smql::model
