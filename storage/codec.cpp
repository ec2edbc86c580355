#include "storage/codec.hpp"

#include <bit>
#include <cstddef>
#include <cstring>

#include <fmt/format.h>

#include "model/error.hpp"
#include "storage/crc32c.hpp"

namespace smql::storage::codec {

namespace {

constexpr std::string_view kCorruptHint =
    "the database file is damaged; restore it from a backup, or drop the scene and import it again";

enum NodeFlags : std::uint8_t { kHidden = 1, kHasSourceId = 2, kHasBox = 4 };

constexpr auto kLastNodeKind = static_cast<std::uint8_t>(model::NodeKind::Frame);
constexpr auto kLastGeometry = static_cast<std::uint8_t>(model::GeometryKind::Plane);

void putBigEndian64(std::uint8_t* p, std::uint64_t v) {
    for (int i = 7; i >= 0; --i) {
        p[i] = static_cast<std::uint8_t>(v);
        v >>= 8;
    }
}

void putLittleEndian(std::uint8_t* p, std::uint64_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) {
        p[i] = static_cast<std::uint8_t>(v);
        v >>= 8;
    }
}

std::uint64_t getLittleEndian(const std::uint8_t* p, int bytes) {
    // The record's fields of 4 and 8 bytes as one load when the machine is little-endian.
    if constexpr (std::endian::native == std::endian::little) {
        if (bytes == 8) {
            std::uint64_t v;
            std::memcpy(&v, p, sizeof v);
            return v;
        }
        if (bytes == 4) {
            std::uint32_t v;
            std::memcpy(&v, p, sizeof v);
            return v;
        }
    }
    std::uint64_t v = 0;
    for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | p[i];
    return v;
}

class Writer {
public:
    explicit Writer(std::string& out) : out_(out) {}

    void u8(std::uint8_t v) { out_.push_back(static_cast<char>(v)); }
    void u32(std::uint32_t v) { fixed(v, 4); }
    void u64(std::uint64_t v) { fixed(v, 8); }
    void f32(float v) { u32(std::bit_cast<std::uint32_t>(v)); }
    void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
    void varint(std::uint64_t v) {
        while (v >= 0x80) {
            u8(static_cast<std::uint8_t>(v | 0x80));
            v >>= 7;
        }
        u8(static_cast<std::uint8_t>(v));
    }
    void str(std::string_view s) {
        varint(s.size());
        out_.append(s);
    }

private:
    void fixed(std::uint64_t v, int bytes) {
        std::uint8_t buf[8];
        putLittleEndian(buf, v, bytes);
        out_.append(reinterpret_cast<const char*>(buf), bytes);
    }
    std::string& out_;
};

std::string_view keyView(const IdKey& key) { return {reinterpret_cast<const char*>(key.data()), key.size()}; }

// Appends the CRC32C of `key` and everything in `out` so far.
void seal(std::string_view key, std::string& out) {
    std::uint8_t crc[kChecksumSize];
    putLittleEndian(crc, crc32c(out, crc32c(key)), kChecksumSize);
    out.append(reinterpret_cast<const char*>(crc), kChecksumSize);
}

class Reader {
public:
    Reader(std::string_view bytes, std::string_view what, model::NodeId id)
        : begin_(reinterpret_cast<const std::uint8_t*>(bytes.data())),
          p_(begin_),
          end_(begin_ + bytes.size()),
          what_(what),
          id_(id) {}

    // Checks the CRC32C at the end of the record against `key` and the bytes
    // before it, then leaves those bytes to be read: a damaged record is
    // refused before any of its fields is believed.
    void checkSealed(std::string_view key) {
        const std::uint8_t* seal = openSeal();
        std::uint32_t stored = static_cast<std::uint32_t>(getLittleEndian(seal, kChecksumSize));
        checkSeal(stored, crc32c(std::string_view(reinterpret_cast<const char*>(begin_), end_ - begin_), crc32c(key)));
    }
    // The record's bytes before its CRC32C are left to be read, and the CRC's bytes returned, for a
    // reader that checksums the record as it copies it out (then checkSeal).
    const std::uint8_t* openSeal() {
        if (remaining() < kChecksumSize + 1) corrupt("truncated");
        end_ -= kChecksumSize;
        return end_;
    }
    void checkSeal(std::uint32_t stored, std::uint32_t actual) {
        if (stored == actual) return;
        end_ += kChecksumSize;
        corrupt(fmt::format("checksum mismatch (stored {:08x}, computed {:08x})", stored, actual));
    }

    std::uint8_t u8() { return *take(1); }
    std::uint32_t u32() { return static_cast<std::uint32_t>(getLittleEndian(take(4), 4)); }
    std::uint64_t u64() { return getLittleEndian(take(8), 8); }
    float f32() { return std::bit_cast<float>(u32()); }
    double f64() { return std::bit_cast<double>(u64()); }
    std::uint64_t varint() {
        std::uint64_t v = 0;
        for (int shift = 0; shift < 64; shift += 7) {
            std::uint8_t b = u8();
            v |= std::uint64_t(b & 0x7f) << shift;
            if (!(b & 0x80)) return v;
        }
        corrupt("a length field is malformed");
    }
    std::string_view str() {
        std::uint64_t n = varint();
        if (n > remaining()) corrupt(fmt::format("a string of {} bytes runs past the end", n));
        auto s = std::string_view(reinterpret_cast<const char*>(p_), n);
        p_ += n;
        return s;
    }
    // `n` bytes to copy out as they are.
    const std::uint8_t* bytes(std::size_t n) { return take(n); }
    std::size_t remaining() const { return static_cast<std::size_t>(end_ - p_); }
    std::size_t offset() const { return static_cast<std::size_t>(p_ - begin_); }
    void expectEnd() {
        if (p_ != end_) corrupt(fmt::format("{} unexpected bytes at the end", remaining()));
    }
    void expectFormat(std::uint8_t expected) {
        std::uint8_t format = u8();
        if (format != expected)
            corrupt(fmt::format("format version {} (this smql reads version {})", format, expected));
    }
    [[noreturn]] void corrupt(std::string_view why) const {
        // Id 0 is never a node: it marks records that are not keyed by id (meta entries).
        std::string subject =
            id_ == model::kNoNode ? std::string(what_) : fmt::format("{} record for id {}", what_, id_);
        throw CorruptRecord(fmt::format("{}: {} (byte {} of {})", subject, why, p_ - begin_, end_ - begin_));
    }

private:
    const std::uint8_t* take(std::size_t n) {
        if (remaining() < n) corrupt("truncated");
        const std::uint8_t* at = p_;
        p_ += n;
        return at;
    }

    const std::uint8_t* begin_;
    const std::uint8_t* p_;
    const std::uint8_t* end_;
    std::string_view what_;
    model::NodeId id_;
};

}  // namespace

CorruptRecord::CorruptRecord(std::string detail)
    : Error(ErrorKind::Storage, "corrupt " + detail, std::nullopt, std::string(kCorruptHint)),
      detail_(std::move(detail)) {}

IdKey idKey(model::NodeId id) {
    IdKey key;
    putBigEndian64(key.data(), id);
    return key;
}

model::NodeId idFromKey(std::string_view bytes, std::string_view what) {
    if (bytes.size() != 8) throw CorruptRecord(fmt::format("{} key: {} bytes instead of 8", what, bytes.size()));
    return readBigEndian64(reinterpret_cast<const std::uint8_t*>(bytes.data()));
}

void encodeNode(const model::Node& node, std::string& out) {
    out.clear();
    std::size_t strings = node.category.size() + node.text.size();
    for (const auto& a : node.attributes) strings += a.name.size() + a.value.size() + 4;
    out.reserve(24 + 8 + 56 + strings + 8 + kChecksumSize);

    const bool hasBox = node.box != model::Box{};
    std::uint8_t flags = (node.hidden ? kHidden : 0) | (node.sourceId ? kHasSourceId : 0) | (hasBox ? kHasBox : 0);
    Writer w(out);
    w.u8(kNodeFormat);
    w.u8(static_cast<std::uint8_t>(node.kind));
    w.u8(static_cast<std::uint8_t>(node.geometry));
    w.u8(flags);
    w.u64(node.scene);
    w.u64(node.parent);
    w.f32(node.confidence);
    if (node.sourceId) w.u64(static_cast<std::uint64_t>(*node.sourceId));
    if (hasBox) {
        const auto& b = node.box;
        for (double v : {b.center.x, b.center.y, b.center.z, b.size.x, b.size.y, b.size.z, b.yaw}) w.f64(v);
    }
    w.str(node.category);
    w.varint(node.attributes.size());
    for (const auto& a : node.attributes) {
        w.str(a.name);
        w.str(a.value);
    }
    w.str(node.text);
    seal(keyView(idKey(node.id)), out);
}

void decodeNode(model::NodeId id, std::string_view bytes, model::Node& out) {
    Reader r(bytes, "node", id);
    r.checkSealed(keyView(idKey(id)));
    r.expectFormat(kNodeFormat);
    std::uint8_t kind = r.u8();
    if (kind > kLastNodeKind) r.corrupt(fmt::format("unknown node kind {}", kind));
    std::uint8_t geometry = r.u8();
    if (geometry > kLastGeometry) r.corrupt(fmt::format("unknown geometry kind {}", geometry));
    std::uint8_t flags = r.u8();
    if (flags & ~(kHidden | kHasSourceId | kHasBox)) r.corrupt(fmt::format("unknown flags {:#x}", flags));

    out.id = id;
    out.kind = static_cast<model::NodeKind>(kind);
    out.geometry = static_cast<model::GeometryKind>(geometry);
    out.hidden = flags & kHidden;
    out.scene = r.u64();
    out.parent = r.u64();
    out.confidence = r.f32();
    if (flags & kHasSourceId)
        out.sourceId = static_cast<std::int64_t>(r.u64());
    else
        out.sourceId.reset();
    if (flags & kHasBox) {
        auto& b = out.box;
        for (double* v : {&b.center.x, &b.center.y, &b.center.z, &b.size.x, &b.size.y, &b.size.z, &b.yaw}) *v = r.f64();
    } else {
        out.box = model::Box{};
    }
    out.category.assign(r.str());
    std::uint64_t attributes = r.varint();
    // Each attribute takes at least two length bytes: a bound that keeps a
    // corrupt count from reserving gigabytes.
    if (attributes > r.remaining() / 2) r.corrupt(fmt::format("attribute count {} exceeds the record", attributes));
    out.attributes.resize(attributes);
    for (auto& a : out.attributes) {
        a.name.assign(r.str());
        a.value.assign(r.str());
    }
    out.text.assign(r.str());
    r.expectEnd();
}

model::Node decodeNode(model::NodeId id, std::string_view bytes) {
    model::Node node;
    decodeNode(id, bytes, node);
    return node;
}

void encodeScene(const model::SceneInfo& scene, std::string& out) {
    out.clear();
    out.reserve(1 + 8 * 23 + scene.name.size() + scene.source.size() + scene.captureTime.size() +
                scene.viewpointNote.size() + 16 + kChecksumSize);
    Writer w(out);
    w.u8(kSceneFormat);
    for (double v : scene.alignment) w.f64(v);
    w.f64(scene.scale);
    w.f64(scene.viewpoint.position.x);
    w.f64(scene.viewpoint.position.y);
    w.f64(scene.viewpoint.position.z);
    w.f64(scene.viewpoint.facingYaw);
    w.u64(scene.nodeCount);
    w.u64(scene.version);
    w.str(scene.name);
    w.str(scene.source);
    w.str(scene.captureTime);
    w.str(scene.viewpointNote);
    seal(keyView(idKey(scene.id)), out);
}

model::SceneInfo decodeScene(model::NodeId id, std::string_view bytes) {
    Reader r(bytes, "scene", id);
    r.checkSealed(keyView(idKey(id)));
    r.expectFormat(kSceneFormat);
    model::SceneInfo scene;
    scene.id = id;
    for (double& v : scene.alignment) v = r.f64();
    scene.scale = r.f64();
    scene.viewpoint.position.x = r.f64();
    scene.viewpoint.position.y = r.f64();
    scene.viewpoint.position.z = r.f64();
    scene.viewpoint.facingYaw = r.f64();
    scene.nodeCount = r.u64();
    scene.version = r.u64();
    scene.name = r.str();
    scene.source = r.str();
    scene.captureTime = r.str();
    scene.viewpointNote = r.str();
    r.expectEnd();
    return scene;
}

// Layout: format, side, other end (BE), type, frame (BE), score (f32 LE), support (u32 LE),
// CRC32C of the key (the id the entry is stored under) and the 27 bytes before it.
RelationEntry encodeRelationEntry(const model::Relation& relation, RelationSide keySide) {
    RelationEntry e{};
    e[0] = kRelationFormat;
    e[1] = static_cast<std::uint8_t>(keySide);
    putBigEndian64(&e[2], keySide == RelationSide::Subject ? relation.object : relation.subject);
    e[10] = static_cast<std::uint8_t>(relation.type);
    putBigEndian64(&e[11], relation.frame);
    putLittleEndian(&e[19], std::bit_cast<std::uint32_t>(relation.score), 4);
    putLittleEndian(&e[23], relation.support, 4);
    auto key = idKey(keySide == RelationSide::Subject ? relation.subject : relation.object);
    std::string_view body(reinterpret_cast<const char*>(e.data()), kRelationEntrySize - kChecksumSize);
    putLittleEndian(&e[27], crc32c(body, crc32c(keyView(key))), kChecksumSize);
    return e;
}

RelationSide relationEntrySide(std::string_view entry) {
    return static_cast<RelationSide>(static_cast<std::uint8_t>(entry[1]));
}

model::Relation decodeRelationEntry(model::NodeId keyId, std::string_view entry) {
    Reader r(entry, "relation", keyId);
    if (entry.size() != kRelationEntrySize)
        r.corrupt(fmt::format("{} bytes instead of {}", entry.size(), kRelationEntrySize));
    r.checkSealed(keyView(idKey(keyId)));
    r.expectFormat(kRelationFormat);
    std::uint8_t side = r.u8();
    if (side > 1) r.corrupt(fmt::format("unknown relation side {}", side));
    const auto* p = reinterpret_cast<const std::uint8_t*>(entry.data());
    model::NodeId other = readBigEndian64(p + 2);
    std::uint8_t type = p[10];
    if (type >= model::kRelationTypeCount) r.corrupt(fmt::format("unknown relation type {}", type));

    model::Relation relation;
    relation.subject = side == 0 ? keyId : other;
    relation.object = side == 0 ? other : keyId;
    relation.type = static_cast<model::RelationType>(type);
    relation.frame = readBigEndian64(p + 11);
    relation.score = std::bit_cast<float>(static_cast<std::uint32_t>(getLittleEndian(p + 19, 4)));
    relation.support = static_cast<std::uint32_t>(getLittleEndian(p + 23, 4));
    return relation;
}

LabelPrefix labelPrefix(model::NodeId sceneId, model::NodeId nodeId) {
    LabelPrefix e;
    putBigEndian64(e.data(), sceneId);
    putBigEndian64(e.data() + 8, nodeId);
    return e;
}

namespace {

constexpr std::uint8_t kLabelHasSourceId = 1;
constexpr std::size_t kLabelSourceAt = 19, kLabelBoxAt = 27, kLabelChecksumAt = kLabelEntrySize - kChecksumSize;

}  // namespace

// Layout: scene (BE), node (BE), format, flags, geometry kind, source id (i64 LE), box (7 f64 LE),
// CRC32C of the category and the 83 bytes before it.
LabelEntry labelEntry(std::string_view category, model::NodeId sceneId, model::NodeId nodeId, const model::Node& node) {
    LabelEntry e{};
    putBigEndian64(&e[0], sceneId);
    putBigEndian64(&e[8], nodeId);
    e[16] = kLabelFormat;
    e[17] = node.sourceId ? kLabelHasSourceId : 0;
    e[18] = static_cast<std::uint8_t>(node.geometry);
    putLittleEndian(&e[kLabelSourceAt], static_cast<std::uint64_t>(node.sourceId.value_or(0)), 8);
    const double box[7] = {node.box.center.x, node.box.center.y, node.box.center.z, node.box.size.x,
                           node.box.size.y,   node.box.size.z,   node.box.yaw};
    for (int i = 0; i < 7; ++i) putLittleEndian(&e[kLabelBoxAt + 8 * i], std::bit_cast<std::uint64_t>(box[i]), 8);
    std::string_view body(reinterpret_cast<const char*>(e.data()), kLabelChecksumAt);
    putLittleEndian(&e[kLabelChecksumAt], crc32c(body, crc32c(category)), kChecksumSize);
    return e;
}

CategoryRow decodeLabelEntry(std::string_view category, std::string_view entry) {
    return decodeLabelEntry(category, crc32c(category), entry);
}

namespace {

// A little-endian field of a label entry, read as the machine holds it when it is little-endian.
template <class T>
T littleEndianAt(const std::uint8_t* p) {
    static_assert(sizeof(T) == 8);
    if constexpr (std::endian::native == std::endian::little) {
        T v;
        std::memcpy(&v, p, sizeof v);
        return v;
    } else {
        return std::bit_cast<T>(getLittleEndian(p, 8));
    }
}

[[noreturn]] void corruptLabel(std::string_view category, std::string_view entry, std::string_view why) {
    throw CorruptRecord(fmt::format("label index entry under '{}': {} ({} bytes)", category, why, entry.size()));
}

}  // namespace

CategoryRow decodeLabelEntry(std::string_view category, std::uint32_t categoryCrc, std::string_view entry) {
    if (entry.size() != kLabelEntrySize)
        corruptLabel(category, entry, fmt::format("{} bytes instead of {}", entry.size(), kLabelEntrySize));
    return decodeLabelEntryWithChecksum(category, entry, crc32c(entry.substr(0, kLabelChecksumAt), categoryCrc));
}

void labelEntryChecksums(std::uint32_t categoryCrc, const char* entries, std::size_t count, std::uint32_t* out) {
    crc32cOfRuns(entries, kLabelEntrySize, kLabelChecksumAt, count, categoryCrc, out);
}

CategoryRow decodeLabelEntryWithChecksum(std::string_view category, std::string_view entry, std::uint32_t actual) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(entry.data());
    if (entry.size() != kLabelEntrySize)
        corruptLabel(category, entry, fmt::format("{} bytes instead of {}", entry.size(), kLabelEntrySize));
    const auto stored = static_cast<std::uint32_t>(getLittleEndian(p + kLabelChecksumAt, kChecksumSize));
    if (stored != actual)
        corruptLabel(category, entry,
                     fmt::format("checksum mismatch (stored {:08x}, computed {:08x})", stored, actual));
    if (p[16] != kLabelFormat)
        corruptLabel(category, entry,
                     fmt::format("format version {} (this smql reads version {})", p[16], kLabelFormat));
    const std::uint8_t flags = p[17];
    if (flags & ~kLabelHasSourceId) corruptLabel(category, entry, fmt::format("unknown flags {:#x}", flags));
    if (p[18] > kLastGeometry) corruptLabel(category, entry, fmt::format("unknown geometry kind {}", p[18]));
    CategoryRow out;
    out.scene = readBigEndian64(p);
    out.id = readBigEndian64(p + 8);
    if (flags & kLabelHasSourceId) out.sourceId = littleEndianAt<std::int64_t>(p + kLabelSourceAt);
    out.geometry = static_cast<model::GeometryKind>(p[18]);
    const std::uint8_t* box = p + kLabelBoxAt;
    out.box = {{littleEndianAt<double>(box), littleEndianAt<double>(box + 8), littleEndianAt<double>(box + 16)},
               {littleEndianAt<double>(box + 24), littleEndianAt<double>(box + 32), littleEndianAt<double>(box + 40)},
               littleEndianAt<double>(box + 48)};
    return out;
}

SourceKey sourceKey(model::NodeId sceneId, std::int64_t sourceId) {
    SourceKey k;
    putBigEndian64(k.data(), sceneId);
    putBigEndian64(k.data() + 8, static_cast<std::uint64_t>(sourceId) ^ (std::uint64_t(1) << 63));
    return k;
}

std::string encodeU64(std::uint64_t value) {
    std::string out;
    Writer(out).u64(value);
    return out;
}

std::uint64_t decodeU64(std::string_view bytes, std::string_view what) {
    Reader r(bytes, what, 0);
    std::uint64_t v = r.u64();
    r.expectEnd();
    return v;
}

std::string blobKey(model::NodeId nodeId, std::string_view name) {
    auto id = idKey(nodeId);
    std::string key(reinterpret_cast<const char*>(id.data()), id.size());
    key.append(name);
    return key;
}

void encodeBlob(std::string_view key, const model::Blob& blob, std::string& out) {
    out.clear();
    out.reserve(2 + blob.mediaType.size() + 10 + blob.bytes.size() + kChecksumSize);
    Writer w(out);
    w.u8(kBlobFormat);
    w.str(blob.mediaType);
    w.str(blob.bytes);
    seal(key, out);
}

std::pair<std::string_view, std::string_view> peekBlob(std::string_view key, std::string_view bytes,
                                                       std::uint64_t& size) {
    model::NodeId node = idFromKey(key.substr(0, std::min<std::size_t>(key.size(), 8)), "blob");
    Reader r(bytes, "blob", node);
    r.checkSealed(key);
    r.expectFormat(kBlobFormat);
    std::string_view mediaType = r.str();
    size = r.str().size();
    r.expectEnd();
    return {key.substr(8), mediaType};
}

model::Blob decodeBlob(std::string_view key, std::string_view bytes) {
    model::NodeId node = idFromKey(key.substr(0, std::min<std::size_t>(key.size(), 8)), "blob");
    Reader r(bytes, "blob", node);
    r.checkSealed(key);
    r.expectFormat(kBlobFormat);
    model::Blob blob;
    blob.node = node;
    blob.name = std::string(key.substr(8));
    blob.mediaType = std::string(r.str());
    blob.bytes = std::string(r.str());
    r.expectEnd();
    return blob;
}

std::string historyPrefix(std::string_view sceneName) {
    std::string key(sceneName);
    key.push_back('\0');
    return key;
}

std::string historyKey(std::string_view sceneName, std::uint64_t number) {
    std::string key = historyPrefix(sceneName);
    std::uint8_t be[8];
    putBigEndian64(be, number);
    key.append(reinterpret_cast<const char*>(be), sizeof be);
    return key;
}

namespace {

void writeBox(Writer& w, const model::Box& b) {
    for (double v : {b.center.x, b.center.y, b.center.z, b.size.x, b.size.y, b.size.z, b.yaw}) w.f64(v);
}

model::Box readBox(Reader& r) {
    model::Box b;
    for (double* v : {&b.center.x, &b.center.y, &b.center.z, &b.size.x, &b.size.y, &b.size.z, &b.yaw}) *v = r.f64();
    return b;
}

constexpr auto kLastChangeKind = static_cast<std::uint8_t>(model::ChangeKind::Missing);

}  // namespace

void encodeVersion(std::string_view key, const model::SceneVersion& version, std::string& out) {
    out.clear();
    Writer w(out);
    w.u8(kVersionFormat);
    w.u64(version.number);
    std::string record;
    encodeScene(version.info, record);
    w.u64(version.info.id);
    w.str(record);
    w.varint(version.nodes.size());
    for (const auto& node : version.nodes) {
        encodeNode(node, record);
        w.u64(node.id);
        w.str(record);
    }
    w.varint(version.relations.size());
    for (const auto& r : version.relations) {
        w.u64(r.subject);
        w.u64(r.object);
        w.u8(static_cast<std::uint8_t>(r.type));
        w.u64(r.frame);
        w.f32(r.score);
        w.u32(r.support);
    }
    w.str(version.supersededAt);
    w.varint(version.changes.size());
    for (const auto& c : version.changes) {
        w.u8(static_cast<std::uint8_t>(c.kind));
        w.str(c.category);
        w.u64(c.before);
        w.u64(c.after);
        writeBox(w, c.from);
        writeBox(w, c.to);
    }
    seal(key, out);
}

model::SceneVersion decodeVersion(std::string_view key, std::string_view bytes) {
    Reader r(bytes, "history", model::kNoNode);
    r.checkSealed(key);
    r.expectFormat(kVersionFormat);
    model::SceneVersion version;
    version.number = r.u64();
    model::NodeId sceneId = r.u64();
    version.info = decodeScene(sceneId, r.str());
    // Every node record is at least a dozen bytes, every relation 33: bounds that keep a
    // corrupt count from reserving gigabytes.
    std::uint64_t nodes = r.varint();
    if (nodes > r.remaining() / 12) r.corrupt(fmt::format("node count {} exceeds the record", nodes));
    version.nodes.resize(nodes);
    for (auto& node : version.nodes) {
        model::NodeId id = r.u64();
        decodeNode(id, r.str(), node);
    }
    std::uint64_t relations = r.varint();
    if (relations > r.remaining() / 33) r.corrupt(fmt::format("relation count {} exceeds the record", relations));
    version.relations.resize(relations);
    for (auto& rel : version.relations) {
        rel.subject = r.u64();
        rel.object = r.u64();
        std::uint8_t type = r.u8();
        if (type >= model::kRelationTypeCount) r.corrupt(fmt::format("unknown relation type {}", type));
        rel.type = static_cast<model::RelationType>(type);
        rel.frame = r.u64();
        rel.score = r.f32();
        rel.support = r.u32();
    }
    version.supersededAt = std::string(r.str());
    std::uint64_t changes = r.varint();
    if (changes > r.remaining() / 130) r.corrupt(fmt::format("change count {} exceeds the record", changes));
    version.changes.resize(changes);
    for (auto& c : version.changes) {
        std::uint8_t kind = r.u8();
        if (kind > kLastChangeKind) r.corrupt(fmt::format("unknown change kind {}", kind));
        c.kind = static_cast<model::ChangeKind>(kind);
        c.category = std::string(r.str());
        c.before = r.u64();
        c.after = r.u64();
        c.from = readBox(r);
        c.to = readBox(r);
    }
    r.expectEnd();
    return version;
}

// The entries are the host's bytes of SceneIndexEntry: little-endian, as every stored number.
static_assert(std::endian::native == std::endian::little, "the scene index stores its arrays as memory holds them");

namespace {

template <class T>
void appendArray(std::string& out, const std::vector<T>& values) {
    out.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

// Moves `count` values of T from `bytes` (at `at`, which it advances) into `into`.
template <class T>
void takeArray(const char* bytes, std::size_t& at, std::uint64_t count, std::vector<T>& into) {
    into.resize(count);
    std::memcpy(into.data(), bytes + at, count * sizeof(T));
    at += count * sizeof(T);
}

// What a damaged index would answer wrongly from: unknown codes, an order that is not the
// nodes with geometry once each, blocks that do not cover it.
void checkSceneIndex(const SceneIndex& index, Reader& r) {
    std::size_t spatial = 0;
    for (const SceneIndexEntry& e : index.entries) {
        if (e.category >= index.categories.size() || static_cast<std::uint8_t>(e.kind) > kLastNodeKind ||
            static_cast<std::uint8_t>(e.geometry) > kLastGeometry || e.hidden > 1 || e.reserved != 0)
            r.corrupt("an entry holds an unknown category, kind, geometry or flag");
        spatial += e.kind != model::NodeKind::Scene && e.geometry != model::GeometryKind::None;
    }
    std::vector<std::uint8_t> seen(index.entries.size());
    for (std::uint32_t s : index.spatialOrder) {
        if (s >= index.entries.size() || seen[s] || index.entries[s].kind == model::NodeKind::Scene ||
            index.entries[s].geometry == model::GeometryKind::None)
            r.corrupt(fmt::format("the spatial order holds slot {} wrongly", s));
        seen[s] = 1;
    }
    if (index.spatialOrder.size() != spatial ||
        index.blockBounds.size() != (spatial + SceneIndex::kBlock - 1) / SceneIndex::kBlock)
        r.corrupt("the spatial order or its blocks miss nodes");
}

}  // namespace

void encodeSceneIndex(model::NodeId sceneId, const SceneIndex& index, std::string& out) {
    out.clear();
    out.reserve(64 + index.entries.size() * sizeof(SceneIndexEntry) + index.spatialOrder.size() * 4 +
                index.blockBounds.size() * sizeof(IndexBounds) + index.categories.size() * 16 + kChecksumSize);
    Writer w(out);
    w.u8(kSceneIndexFormat);
    w.u64(index.version);
    w.varint(index.categories.size());
    for (const auto& category : index.categories) w.str(category);
    w.varint(index.entries.size());
    w.varint(index.spatialOrder.size());
    w.varint(index.blockBounds.size());
    appendArray(out, index.entries);
    appendArray(out, index.spatialOrder);
    appendArray(out, index.blockBounds);
    seal(keyView(idKey(sceneId)), out);
}

namespace {

// What comes before a scene index's arrays.
struct SceneIndexHeader {
    std::uint8_t format = kSceneIndexFormat;
    std::uint64_t version = 0;
    std::vector<std::string> categories;
    std::uint64_t entries = 0, ordered = 0, blocks = 0;
};

// Format 1's line: the bounds as model::Aabb, then the category, kind, geometry, hidden and
// reserved bytes as SceneIndexEntry lays them out after its own bounds.
constexpr std::size_t kFormat1Codes = sizeof(model::Aabb);
constexpr std::size_t kFormat1EntrySize = kFormat1Codes + sizeof(SceneIndexEntry) - offsetof(SceneIndexEntry, category);
static_assert(kFormat1EntrySize == 56, "format 1 stored 56 bytes a node");

SceneIndexHeader readSceneIndexHeader(Reader& r) {
    SceneIndexHeader header;
    header.format = r.u8();
    if (header.format != kSceneIndexFormat && header.format != 1)
        r.corrupt(
            fmt::format("format version {} (this smql reads versions 1 and {})", header.format, kSceneIndexFormat));
    header.version = r.u64();
    std::uint64_t categories = r.varint();
    if (categories > r.remaining()) r.corrupt(fmt::format("category count {} exceeds the record", categories));
    header.categories.reserve(categories);
    for (std::uint64_t i = 0; i < categories; ++i) header.categories.emplace_back(r.str());
    header.entries = r.varint();
    header.ordered = r.varint();
    header.blocks = r.varint();
    return header;
}

// The header is read from a copy of the record's first bytes, which hold it unless the scene has
// hundreds of categories, so that a record in the memory map has none of its pages touched.
constexpr std::size_t kHeaderCopy = 2048;

}  // namespace

SceneIndex decodeSceneIndex(model::NodeId sceneId, std::string_view bytes, const CopyOut& copyOut) {
    const CopyOut copy =
        copyOut ? copyOut : [](void* into, std::string_view from) { std::memcpy(into, from.data(), from.size()); };
    // Read once: the header from a copy, the arrays checksummed as they are copied out, and nothing
    // of the record believed before its checksum agrees (until then the header's counts are only
    // bounded by the record's length).
    Reader r(bytes, "scene index", sceneId);
    r.openSeal();
    std::array<char, kHeaderCopy> first;
    const std::string_view start = bytes.substr(0, std::min(r.remaining(), first.size()));
    copy(first.data(), start);
    std::string_view headerBytes(first.data(), start.size());
    SceneIndexHeader header;
    try {
        Reader head(headerBytes, "scene index", sceneId);
        header = readSceneIndexHeader(head);
        headerBytes = headerBytes.substr(0, head.offset());
        r.bytes(head.offset());
    } catch (const CorruptRecord&) {
        if (start.size() == r.remaining()) throw;  // the copy was the whole record: its error stands
        header = readSceneIndexHeader(r);
        headerBytes = bytes.substr(0, r.offset());
    }
    SceneIndex index;
    index.version = header.version;
    index.categories = std::move(header.categories);
    const bool doubles = header.format == 1;
    const std::size_t entrySize = doubles ? kFormat1EntrySize : sizeof(SceneIndexEntry);
    const std::size_t blockSize = doubles ? sizeof(model::Aabb) : sizeof(IndexBounds);
    const std::uint64_t entries = header.entries, ordered = header.ordered, blocks = header.blocks;
    // Each count is checked against what is left before the arrays are sized by it.
    const std::uint64_t left = r.remaining();
    if (entries > left / entrySize || ordered > left / 4 || blocks > left / blockSize ||
        entries * entrySize + ordered * 4 + blocks * blockSize != left)
        r.corrupt(fmt::format("{} entries, {} in spatial order and {} blocks do not fill the {} bytes left", entries,
                              ordered, blocks, left));
    const std::size_t tail = left + kChecksumSize;
    auto checkCopy = [&](const char* copied) {
        const std::uint32_t crc = crc32c({copied, left}, crc32c(headerBytes, crc32c(keyView(idKey(sceneId)))));
        r.checkSeal(static_cast<std::uint32_t>(
                        getLittleEndian(reinterpret_cast<const std::uint8_t*>(copied + left), kChecksumSize)),
                    crc);
    };
    if (doubles) {
        // Read into a buffer of its own and rounded outward line by line; the spatial order and
        // blocks are packed again from the rounded bounds, as a write of the scene would store them.
        std::vector<char> copied(tail);
        copy(copied.data(), {reinterpret_cast<const char*>(r.bytes(left)), tail});
        r.expectEnd();
        checkCopy(copied.data());
        index.entries.resize(entries);
        for (std::size_t e = 0; e < entries; ++e) {
            const char* line = copied.data() + e * kFormat1EntrySize;
            model::Aabb exact;
            std::memcpy(&exact, line, sizeof exact);
            SceneIndexEntry& entry = index.entries[e];
            entry.bounds = IndexBounds::around(exact);
            auto code = [&](auto& field, std::size_t at) {
                std::memcpy(&field, line + kFormat1Codes + at - offsetof(SceneIndexEntry, category), sizeof field);
            };
            code(entry.category, offsetof(SceneIndexEntry, category));
            code(entry.kind, offsetof(SceneIndexEntry, kind));
            code(entry.geometry, offsetof(SceneIndexEntry, geometry));
            code(entry.hidden, offsetof(SceneIndexEntry, hidden));
            code(entry.reserved, offsetof(SceneIndexEntry, reserved));
        }
        index.pack();
    } else {
        // The arrays and the checksum after them are copied in one piece into the entries' memory,
        // sized to hold them all; the spatial order and the blocks (a fifth of it) then move out.
        index.entries.resize(
            std::max<std::size_t>(entries, (tail + sizeof(SceneIndexEntry) - 1) / sizeof(SceneIndexEntry)));
        const auto* copied = reinterpret_cast<const char*>(index.entries.data());
        copy(index.entries.data(), {reinterpret_cast<const char*>(r.bytes(left)), tail});
        r.expectEnd();
        checkCopy(copied);
        std::size_t at = entries * sizeof(SceneIndexEntry);
        takeArray(copied, at, ordered, index.spatialOrder);
        takeArray(copied, at, blocks, index.blockBounds);
        index.entries.resize(entries);
    }
    checkSceneIndex(index, r);
    return index;
}

}  // namespace smql::storage::codec
