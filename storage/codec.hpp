// Compact binary records and index keys of the on-disk layout (docs/storage.md
// describes every byte). Private to storage/: callers only ever see model types.
//
// Records are little-endian with a format-version byte first, a fixed header,
// then length-prefixed strings (LEB128 lengths), and end in a CRC32C of their
// key and their bytes. Keys and index entries hold ids big-endian, so LMDB's
// default memcmp order is numeric order. Decoding checks the checksum first,
// reads straight from the bytes it is given (the memory map) and throws
// CorruptRecord instead of reading past the end or answering from damaged bytes.
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <string_view>

#include "model/error.hpp"
#include "model/types.hpp"
#include "storage/database.hpp"
#include "storage/scene_index.hpp"

namespace smql::storage::codec {

// Format 2 added the checksum (schema version 2).
inline constexpr std::uint8_t kNodeFormat = 2;
inline constexpr std::uint8_t kBlobFormat = 2;
inline constexpr std::uint8_t kSceneFormat = 2;
inline constexpr std::uint8_t kRelationFormat = 2;
inline constexpr std::uint8_t kVersionFormat = 1;
// Scene index format 2 holds the bounds in single precision (IndexBounds, schema version 6); format
// 1's doubles are still read, rounded outward as they are.
inline constexpr std::uint8_t kSceneIndexFormat = 2;
// The CRC32C at the end of every record and relation entry.
inline constexpr std::size_t kChecksumSize = 4;

// What every decoder throws: an Error(Storage) "corrupt <detail>", where the
// detail names the record ("node record for id 42: checksum mismatch"). The
// codec does not know the scene; the reader that does adds it.
class CorruptRecord : public Error {
public:
    explicit CorruptRecord(std::string detail);
    const std::string& detail() const { return detail_; }

private:
    std::string detail_;
};

using IdKey = std::array<std::uint8_t, 8>;
IdKey idKey(model::NodeId id);
// Throws when `bytes` is not 8 bytes long; `what` names the index for the message.
model::NodeId idFromKey(std::string_view bytes, std::string_view what);

// Node record (key: idKey(node.id)). The id is the key, so it is not stored twice.
void encodeNode(const model::Node& node, std::string& out);
// Decodes into `out`, reusing its string and vector capacity (hot loops keep one Node).
void decodeNode(model::NodeId id, std::string_view bytes, model::Node& out);
model::Node decodeNode(model::NodeId id, std::string_view bytes);

// Scene record (key: idKey(scene.id)).
void encodeScene(const model::SceneInfo& scene, std::string& out);
model::SceneInfo decodeScene(model::NodeId id, std::string_view bytes);

// A relation is stored twice, once under each end; the entry says which end
// the key is and holds the other one. Fixed size, so the relation index can
// be a DUPFIXED table read a page at a time.
enum class RelationSide : std::uint8_t { Subject = 0, Object = 1 };
inline constexpr std::size_t kRelationEntrySize = 27 + kChecksumSize;
using RelationEntry = std::array<std::uint8_t, kRelationEntrySize>;
RelationEntry encodeRelationEntry(const model::Relation& relation, RelationSide keySide);
RelationSide relationEntrySide(std::string_view entry);
model::Relation decodeRelationEntry(model::NodeId keyId, std::string_view entry);

// Label index entry (duplicate value under the category key): scene id then node id (big-endian,
// so one scene's nodes of a category are one contiguous range, in id order), then what a search of
// the category across scenes shows of the node, so that it answers without reading the node
// records: format byte, flags (1 has source id), geometry kind, source id (i64 LE), box (7 f64
// LE), and a CRC32C of the category (the key) and the bytes before it. Schema version 5; before it
// an entry was the two ids alone (kIdsOnlyLabelEntrySize), which a read-only open still reads.
inline constexpr std::uint8_t kLabelFormat = 1;
inline constexpr std::size_t kIdsOnlyLabelEntrySize = 16;
inline constexpr std::size_t kLabelEntrySize = 83 + kChecksumSize;
using LabelEntry = std::array<std::uint8_t, kLabelEntrySize>;
using LabelPrefix = std::array<std::uint8_t, kIdsOnlyLabelEntrySize>;
// The entry of node `nodeId` of scene `sceneId` under `category`, with `node`'s source id, geometry
// and box (as its record holds them).
LabelEntry labelEntry(std::string_view category, model::NodeId sceneId, model::NodeId nodeId, const model::Node& node);
// The two ids alone: the start of a scene's range (node 0), and a version-4 entry.
LabelPrefix labelPrefix(model::NodeId sceneId, model::NodeId nodeId);
// The ids of an entry of either size (the first 16 bytes).
inline model::NodeId labelEntryScene(std::string_view entry);
inline model::NodeId labelEntryNode(std::string_view entry);
// Checks the entry's size, checksum and codes and returns its row; throws CorruptRecord.
CategoryRow decodeLabelEntry(std::string_view category, std::string_view entry);
// The same, with the CRC32C of the category computed once for the many entries of a key.
CategoryRow decodeLabelEntry(std::string_view category, std::uint32_t categoryCrc, std::string_view entry);
// The checksums decodeLabelEntry compares, of `count` entries one after another from `entries` (a
// block of the label index's page), computed side by side into out[i].
void labelEntryChecksums(std::uint32_t categoryCrc, const char* entries, std::size_t count, std::uint32_t* out);
// decodeLabelEntry with the entry's checksum computed already (labelEntryChecksums).
CategoryRow decodeLabelEntryWithChecksum(std::string_view category, std::string_view entry, std::uint32_t checksum);

// Source-id index key: scene id then the source id, sign-flipped big-endian so
// negative ids sort before positive ones.
using SourceKey = std::array<std::uint8_t, 16>;
SourceKey sourceKey(model::NodeId sceneId, std::int64_t sourceId);

// Blob key: the node id (big-endian) then the blob's name, so a node's blobs are one range.
std::string blobKey(model::NodeId nodeId, std::string_view name);
// Blob record: format byte, media type, then the bytes. `key` is the blob key
// it is stored under (the blob's node id is a local id during an import).
void encodeBlob(std::string_view key, const model::Blob& blob, std::string& out);
// `key` is the blob key the record was stored under.
model::Blob decodeBlob(std::string_view key, std::string_view bytes);
// Name and media type without copying the bytes; `size` gets the byte count.
std::pair<std::string_view, std::string_view> peekBlob(std::string_view key, std::string_view bytes,
                                                       std::uint64_t& size);

// History key: the scene's name, a zero byte, then the version number big-endian, so one scene's
// superseded versions are one range in number order. Scene names hold no zero byte.
std::string historyKey(std::string_view sceneName, std::uint64_t number);
// The prefix of every history key of a scene.
std::string historyPrefix(std::string_view sceneName);
// History record: a superseded version of a scene (its scene record, node records and relations
// as they were) and the changes of the update that replaced it.
void encodeVersion(std::string_view key, const model::SceneVersion& version, std::string& out);
model::SceneVersion decodeVersion(std::string_view key, std::string_view bytes);

// Scene index record (key: idKey(scene id)): format byte, the scene version, the categories, then
// the entries as one array of SceneIndexEntry's bytes (little-endian, as every record), sealed.
// Format 1 (bounds as doubles) is read too.
void encodeSceneIndex(model::NodeId sceneId, const SceneIndex& index, std::string& out);
// How the decoder copies a span of `bytes` (the record it was given) into its own memory: the
// record's first 2 KiB (its header, unless it names hundreds of categories, when the header is read
// in place), then the arrays and the checksum in one piece, checksummed as copied. Null copies
// with memcpy; the database reads a record in its memory map through the file instead
// (Environment::copyOut says why).
using CopyOut = std::function<void(void* into, std::string_view from)>;
SceneIndex decodeSceneIndex(model::NodeId sceneId, std::string_view bytes, const CopyOut& copyOut = nullptr);

// Little-endian fixed-width values for meta entries.
std::string encodeU64(std::uint64_t value);
std::uint64_t decodeU64(std::string_view bytes, std::string_view what);

// One load (and a byte swap on a little-endian machine), where GCC does not turn a loop of shifts into one.
inline std::uint64_t readBigEndian64(const std::uint8_t* p) {
    std::uint64_t v;
    std::memcpy(&v, p, sizeof v);
    if constexpr (std::endian::native == std::endian::little) v = __builtin_bswap64(v);
    return v;
}

inline model::NodeId labelEntryScene(std::string_view entry) {
    return readBigEndian64(reinterpret_cast<const std::uint8_t*>(entry.data()));
}
inline model::NodeId labelEntryNode(std::string_view entry) {
    return readBigEndian64(reinterpret_cast<const std::uint8_t*>(entry.data()) + 8);
}

}  // namespace smql::storage::codec
