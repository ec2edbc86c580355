#include <catch2/catch.hpp>

#include <cstring>

#include <cmath>
#include <limits>

#include "model/error.hpp"
#include "storage/codec.hpp"
#include "storage/crc32c.hpp"

using namespace smql;
using namespace smql::storage;

namespace {

model::Node fullNode() {
    model::Node node;
    node.id = 42;
    node.kind = model::NodeKind::Object;
    node.scene = 7;
    node.parent = 41;
    node.category = "mug";
    node.geometry = model::GeometryKind::Box;
    node.box = {{1.25, -2.5, 0.75}, {0.08, 0.08, 0.1}, -1.5707963267948966};
    node.attributes = {{"color", "red"}, {"material", "ceramic"}, {"note", ""}};
    node.confidence = 0.875f;
    node.sourceId = -1234567890123LL;
    node.text = "eine rote Tasse ☕ — 赤いマグ";
    node.hidden = true;
    return node;
}

std::string encoded(const model::Node& node) {
    std::string bytes;
    codec::encodeNode(node, bytes);
    return bytes;
}

void requireCorrupt(const std::function<void()>& decode) {
    try {
        decode();
        FAIL("decoding did not throw");
    } catch (const Error& e) {
        REQUIRE(e.kind() == ErrorKind::Storage);
        REQUIRE_THAT(e.message(), Catch::Contains("corrupt"));
    }
}

}  // namespace

TEST_CASE("node records round-trip every field", "[storage][codec]") {
    model::Node node = fullNode();
    REQUIRE(codec::decodeNode(42, encoded(node)) == node);

    SECTION("without a source id, box or attributes") {
        model::Node bare;
        bare.id = 9;
        bare.kind = model::NodeKind::Description;
        bare.scene = 1;
        bare.parent = 3;
        bare.text = "a red mug on the table";
        model::Node decoded = codec::decodeNode(9, encoded(bare));
        REQUIRE(decoded == bare);
        REQUIRE_FALSE(decoded.sourceId.has_value());
    }
    SECTION("a source id of zero is present, not absent") {
        node.sourceId = 0;
        REQUIRE(codec::decodeNode(42, encoded(node)).sourceId == std::optional<std::int64_t>(0));
    }
    SECTION("extreme values") {
        node.sourceId = std::numeric_limits<std::int64_t>::min();
        node.parent = std::numeric_limits<std::uint64_t>::max();
        node.confidence = 0.0f;
        node.box.yaw = -0.0;
        node.category = std::string(300, 'x');
        node.text = std::string(100000, 'y');  // lengths past one varint byte
        REQUIRE(codec::decodeNode(42, encoded(node)) == node);
    }
    SECTION("every kind and geometry") {
        for (int kind = 0; kind <= 5; ++kind)
            for (int geometry = 0; geometry <= 2; ++geometry) {
                node.kind = static_cast<model::NodeKind>(kind);
                node.geometry = static_cast<model::GeometryKind>(geometry);
                REQUIRE(codec::decodeNode(42, encoded(node)) == node);
            }
    }
    SECTION("decoding into a used Node replaces every field") {
        model::Node reused = fullNode();
        model::Node other;
        other.id = 5;
        other.scene = 1;
        other.category = "wall";
        codec::decodeNode(5, encoded(other), reused);
        REQUIRE(reused == other);
    }
}

TEST_CASE("a node record with nothing set is small", "[storage][codec]") {
    model::Node node;
    node.id = 2;
    node.scene = 1;
    node.parent = 1;
    node.category = "chair";
    // 24-byte header + 1+5 category + 1 attribute count + 1 text length + 4 checksum.
    REQUIRE(encoded(node).size() == 36);
}

TEST_CASE("corrupt node records throw instead of reading out of bounds", "[storage][codec]") {
    const std::string bytes = encoded(fullNode());

    SECTION("every truncation") {
        for (std::size_t size = 0; size < bytes.size(); ++size)
            requireCorrupt([&] { codec::decodeNode(42, std::string_view(bytes.data(), size)); });
    }
    SECTION("trailing bytes") {
        requireCorrupt([&] { codec::decodeNode(42, bytes + "x"); });
    }
    SECTION("another format version") {
        // A record with a valid checksum but a format this smql does not read.
        std::string changed = bytes.substr(0, bytes.size() - codec::kChecksumSize);
        changed[0] = 9;
        auto key = codec::idKey(42);
        std::uint32_t crc = crc32c(changed, crc32c(std::string_view(reinterpret_cast<const char*>(key.data()), 8)));
        for (int i = 0; i < 4; ++i) changed.push_back(static_cast<char>(crc >> (8 * i)));
        try {
            codec::decodeNode(42, changed);
            FAIL("no error");
        } catch (const Error& e) {
            REQUIRE_THAT(e.message(), Catch::Contains("format version 9"));
            REQUIRE_THAT(e.message(), Catch::Contains("id 42"));
        }
    }
    SECTION("unknown kind") {
        std::string changed = bytes;
        changed[1] = 17;
        requireCorrupt([&] { codec::decodeNode(42, changed); });
    }
    SECTION("a string length past the end") {
        model::Node node;
        node.category = "ab";
        std::string changed = encoded(node);
        changed[24] = 100;  // the category's length byte
        requireCorrupt([&] { codec::decodeNode(1, changed); });
    }
    SECTION("an absurd attribute count") {
        model::Node node;
        std::string changed = encoded(node);
        // header, empty category, then the attribute count: make it 2^62.
        changed.replace(25, 1, std::string("\x80\x80\x80\x80\x80\x80\x80\x80\x40", 9));
        requireCorrupt([&] { codec::decodeNode(1, changed); });
    }
}

TEST_CASE("scene records round-trip", "[storage][codec]") {
    model::SceneInfo scene;
    scene.id = 100;
    scene.name = "wohnzimmer-über";
    scene.source = "replica:/data/room0/info_semantic.json";
    scene.captureTime = "2024-05-01T10:00:00Z";
    for (std::size_t i = 0; i < 16; ++i) scene.alignment[i] = 0.5 * double(i) - 3;
    scene.scale = 0.98;
    scene.viewpoint = {{1.5, 2.0, 1.6}, 3.14};
    scene.viewpointNote = "centre of the largest room, facing the door";
    scene.nodeCount = 1234;
    scene.version = 3;

    std::string bytes;
    codec::encodeScene(scene, bytes);
    REQUIRE(codec::decodeScene(100, bytes) == scene);
    for (std::size_t size = 0; size < bytes.size(); ++size)
        requireCorrupt([&] { codec::decodeScene(100, std::string_view(bytes.data(), size)); });
}

TEST_CASE("relation entries round-trip from either end", "[storage][codec]") {
    model::Relation relation{10, 20, model::RelationType::InFrontOf, 0.625f, 17, 33};
    auto asSubject = codec::encodeRelationEntry(relation, codec::RelationSide::Subject);
    auto asObject = codec::encodeRelationEntry(relation, codec::RelationSide::Object);
    auto view = [](const codec::RelationEntry& e) {
        return std::string_view(reinterpret_cast<const char*>(e.data()), e.size());
    };

    REQUIRE(codec::relationEntrySide(view(asSubject)) == codec::RelationSide::Subject);
    REQUIRE(codec::relationEntrySide(view(asObject)) == codec::RelationSide::Object);
    REQUIRE(codec::decodeRelationEntry(10, view(asSubject)) == relation);
    REQUIRE(codec::decodeRelationEntry(20, view(asObject)) == relation);
    // Subject-side entries sort first under a key, which scene scans rely on.
    REQUIRE(asSubject < asObject);

    auto broken = asSubject;
    broken[10] = 200;  // relation type
    requireCorrupt([&] { codec::decodeRelationEntry(10, view(broken)); });
    requireCorrupt([&] { codec::decodeRelationEntry(10, view(asSubject).substr(0, 20)); });
}

TEST_CASE("keys sort numerically under memcmp", "[storage][codec]") {
    REQUIRE(codec::idKey(255) < codec::idKey(256));
    REQUIRE(codec::idKey(1) < codec::idKey(std::uint64_t(1) << 40));
    auto key = codec::idKey(0x0102030405060708ULL);
    REQUIRE(codec::idFromKey(std::string_view(reinterpret_cast<const char*>(key.data()), key.size()), "test") ==
            0x0102030405060708ULL);
    REQUIRE(codec::sourceKey(3, -1) < codec::sourceKey(3, 0));
    REQUIRE(codec::sourceKey(3, std::numeric_limits<std::int64_t>::max()) < codec::sourceKey(4, -100));
    REQUIRE(codec::labelPrefix(1, 900) < codec::labelPrefix(2, 3));
    model::Node node;
    REQUIRE(codec::labelEntry("mug", 1, 900, node) < codec::labelEntry("mug", 2, 3, node));
    // The prefix sorts before every entry of its ids, so a scene's range starts at (scene, 0).
    auto prefix = codec::labelPrefix(2, 0);
    auto entry = codec::labelEntry("mug", 2, 0, node);
    REQUIRE(std::memcmp(prefix.data(), entry.data(), prefix.size()) == 0);
    REQUIRE_THROWS_AS(codec::idFromKey("short", "test"), Error);
}

TEST_CASE("crc32c matches the Castagnoli check values", "[storage][codec]") {
    REQUIRE(crc32c("") == 0);
    REQUIRE(crc32c("123456789") == 0xE3069283u);              // the standard check value
    REQUIRE(crc32c(std::string(32, '\0')) == 0x8A9136AAu);    // RFC 3720 B.4: 32 bytes of zeros
    REQUIRE(crc32c(std::string(32, '\xff')) == 0x62A8AB43u);  // RFC 3720 B.4: 32 bytes of ones
    // Any split of the input continues the same checksum, at every alignment.
    const std::string text = "the quick brown fox jumps over the lazy dog, twice over";
    for (std::size_t cut = 0; cut <= text.size(); ++cut)
        REQUIRE(crc32c(text.substr(cut), crc32c(text.substr(0, cut))) == crc32c(text));
    // Long inputs are checksummed in runs side by side (three of 8 KiB, then of 256 bytes), joined:
    // a known value, and splits that move every byte between those runs and the plain loop.
    std::string bytes(100000, '\0');
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>((i * 7 + (i >> 8) * 13) & 0xff);
    REQUIRE(crc32c(bytes) == 0xAC4A64B0u);  // computed bit by bit, without the instruction
    const std::string_view all(bytes);
    for (std::size_t cut : {1u, 7u, 255u, 769u, 8191u, 24577u, 50000u, 99999u})
        REQUIRE(crc32c(all.substr(cut), crc32c(all.substr(0, cut))) == crc32c(all));
}

TEST_CASE("crc32cOfRuns gives each run's crc32c, four runs side by side", "[storage][codec]") {
    std::string bytes(40 * 90, '\0');
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>((i * 31 + (i >> 5)) & 0xff);
    // Counts on both sides of the groups of four, lengths with and without a tail of single bytes
    // (a label entry's checked bytes are 83), a seed of 0 and a category's checksum.
    for (std::uint32_t seed : {0u, crc32c("coffee table")})
        for (std::size_t length : {0u, 1u, 8u, 13u, 83u})
            for (std::size_t count : {0u, 1u, 3u, 4u, 5u, 9u, 40u}) {
                const std::size_t stride = 87;
                if (count > 0 && (count - 1) * stride + length > bytes.size()) continue;
                std::vector<std::uint32_t> out(count + 1, 0xdeadbeef);
                crc32cOfRuns(bytes.data(), stride, length, count, seed, out.data());
                for (std::size_t i = 0; i < count; ++i)
                    REQUIRE(out[i] == crc32c(std::string_view(bytes).substr(i * stride, length), seed));
                REQUIRE(out[count] == 0xdeadbeef);  // nothing written past the last run
            }
}

TEST_CASE("every byte flip in a record is caught by its checksum", "[storage][codec]") {
    SECTION("node records") {
        const std::string bytes = encoded(fullNode());
        for (std::size_t at = 0; at < bytes.size(); ++at)
            for (unsigned char bit : {0x01, 0x80}) {
                std::string flipped = bytes;
                flipped[at] = static_cast<char>(flipped[at] ^ bit);
                try {
                    codec::decodeNode(42, flipped);
                    FAIL("byte " << at << " flipped was decoded");
                } catch (const codec::CorruptRecord& e) {
                    REQUIRE_THAT(e.message(), Catch::Contains("node record for id 42"));
                    REQUIRE_THAT(e.message(), Catch::Contains("checksum mismatch"));
                }
            }
    }
    SECTION("a record under another key") {
        // A flipped bit in a key moves a record to another id: the key is in the checksum.
        requireCorrupt([&] { codec::decodeNode(43, encoded(fullNode())); });
    }
    SECTION("scene records and relation entries") {
        model::SceneInfo scene;
        scene.id = 5;
        scene.name = "kitchen";
        std::string bytes;
        codec::encodeScene(scene, bytes);
        bytes[bytes.size() / 2] ^= 0x10;
        requireCorrupt([&] { codec::decodeScene(5, bytes); });

        auto entry =
            codec::encodeRelationEntry({10, 20, model::RelationType::On, 0.5f, 1, 0}, codec::RelationSide::Subject);
        entry[20] ^= 0x01;  // the score
        requireCorrupt([&] {
            codec::decodeRelationEntry(10, std::string_view(reinterpret_cast<const char*>(entry.data()), entry.size()));
        });
    }
}
