#include "model/embedding.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include <fmt/format.h>

#include "model/error.hpp"

namespace smql::model {

std::optional<std::string> embeddingProblem(std::span<const float> vector) {
    if (vector.empty()) return "an embedding needs at least one number";
    if (vector.size() > kMaxEmbeddingDimensions)
        return fmt::format("{} numbers; an embedding has at most {}", vector.size(), kMaxEmbeddingDimensions);
    for (std::size_t i = 0; i < vector.size(); ++i)
        if (!std::isfinite(vector[i])) return fmt::format("value {} is not a finite single-precision number", i);
    if (std::all_of(vector.begin(), vector.end(), [](float x) { return x == 0.0F; }))
        return "every value is 0: a zero vector has no direction to compare";
    return std::nullopt;
}

Blob embeddingBlob(NodeId node, std::span<const float> vector) {
    Blob blob{node, std::string(kEmbeddingBlob), std::string(kEmbeddingMediaType), {}};
    blob.bytes.reserve(vector.size() * 4);
    for (float value : vector) {
        const auto bits = std::bit_cast<std::uint32_t>(value);
        for (int shift = 0; shift < 32; shift += 8) blob.bytes.push_back(static_cast<char>((bits >> shift) & 0xFFU));
    }
    return blob;
}

std::vector<float> readEmbedding(const Blob& blob) {
    auto fail = [](std::string what) {
        throw Error(
            ErrorKind::Input, std::move(what), std::nullopt,
            fmt::format("an embedding blob holds little-endian float32 values, media type {}", kEmbeddingMediaType));
    };
    if (blob.mediaType != kEmbeddingMediaType)
        fail(fmt::format("media type '{}', not {}", blob.mediaType, kEmbeddingMediaType));
    if (blob.bytes.size() % 4 != 0) fail(fmt::format("{} bytes are not a whole number of floats", blob.bytes.size()));
    std::vector<float> vector(blob.bytes.size() / 4);
    for (std::size_t i = 0; i < vector.size(); ++i) {
        std::uint32_t bits = 0;
        for (int b = 0; b < 4; ++b)
            bits |= static_cast<std::uint32_t>(static_cast<unsigned char>(blob.bytes[4 * i + b])) << (8 * b);
        vector[i] = std::bit_cast<float>(bits);
    }
    if (auto problem = embeddingProblem(vector)) fail(*problem);
    return vector;
}

}  // namespace smql::model
