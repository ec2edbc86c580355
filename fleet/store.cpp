#include "fleet/store.hpp"

#include <bit>
#include <charconv>
#include <cstring>

#include <fmt/format.h>

#include "fleet/schema.hpp"
#include "model/embedding.hpp"
#include "model/error.hpp"
#include "model/geometry.hpp"

namespace smql::fleet {

namespace {

static_assert(std::endian::native == std::endian::little, "embedding blobs are little-endian float32");

using Rows = std::string;  // rows in COPY's text format

constexpr const char* kInsertScene =
    "INSERT INTO smql.scenes(id, device, name, version, source, capture_time, alignment, scale, viewpoint_x, "
    "viewpoint_y, viewpoint_z, viewpoint_yaw, viewpoint_note, node_count, relation_count, blob_count, change_count, "
    "superseded_at) VALUES ($1, $2, $3, $4, $5, $6, $7, $8, $9, $10, $11, $12, $13, $14, $15, $16, $17, "
    "NULLIF($18, '')) ON CONFLICT DO NOTHING RETURNING id";

// An embedding blob travels as a float4[] (the column queries read); any other blob as bytea.
bool isEmbedding(const model::Blob& blob) {
    return blob.name == model::kEmbeddingBlob && blob.mediaType == model::kEmbeddingMediaType && !blob.bytes.empty() &&
           blob.bytes.size() % sizeof(float) == 0;
}

template <typename Number>
std::vector<Number> parseArray(std::string_view text) {
    std::vector<Number> out;
    if (text.size() < 2) return out;
    text = text.substr(1, text.size() - 2);  // {a,b,c}
    while (!text.empty()) {
        std::size_t comma = text.find(',');
        std::string_view item = text.substr(0, comma);
        Number value{};
        std::from_chars(item.data(), item.data() + item.size(), value);
        out.push_back(value);
        text = comma == std::string_view::npos ? std::string_view() : text.substr(comma + 1);
    }
    return out;
}

template <typename Range>
std::string arrayText(const Range& values) {
    return fmt::format("{{{}}}", fmt::join(values, ","));
}

void appendBox(Rows& out, const model::Box& b) {
    fmt::format_to(std::back_inserter(out), "{}\t{}\t{}\t{}\t{}\t{}\t{}", b.center.x, b.center.y, b.center.z, b.size.x,
                   b.size.y, b.size.z, b.yaw);
}

// The nodes' rows: the box, and for a node with geometry its footprint (the world bounds seen from
// above, the region the GiST index holds) and z range.
Rows nodeRows(std::int64_t key, const model::SceneData& data) {
    Rows out;
    auto it = std::back_inserter(out);
    for (const model::Node& n : data.nodes) {
        fmt::format_to(it, "{}\t{}\t{}\t{}\t", key, n.id, n.parent, static_cast<int>(n.kind));
        pg::appendCopyText(out, n.category);
        fmt::format_to(it, "\t{}\t", static_cast<int>(n.geometry));
        appendBox(out, n.box);
        fmt::format_to(it, "\t{}\t{}\t", n.hidden ? "t" : "f", n.confidence);
        if (n.sourceId)
            fmt::format_to(it, "{}", *n.sourceId);
        else
            out += "\\N";
        out += '\t';
        pg::appendCopyText(out, n.text);
        if (n.geometry == model::GeometryKind::None) {
            out += "\t\\N\t\\N\t\\N\n";
            continue;
        }
        model::Aabb b = model::worldAabb(n.box);
        fmt::format_to(it, "\t{}\t{}\tPOLYGON(({} {},{} {},{} {},{} {},{} {}))\n", b.min.z, b.max.z, b.min.x, b.min.y,
                       b.min.x, b.max.y, b.max.x, b.max.y, b.max.x, b.min.y, b.min.x, b.min.y);
    }
    return out;
}

Rows attributeRows(std::int64_t key, const model::SceneData& data) {
    Rows out;
    for (const model::Node& n : data.nodes)
        for (std::size_t i = 0; i < n.attributes.size(); ++i) {
            fmt::format_to(std::back_inserter(out), "{}\t{}\t{}\t", key, n.id, i);
            pg::appendCopyText(out, n.attributes[i].name);
            out += '\t';
            pg::appendCopyText(out, n.attributes[i].value);
            out += '\n';
        }
    return out;
}

Rows relationRows(std::int64_t key, const model::SceneData& data) {
    Rows out;
    for (std::size_t i = 0; i < data.relations.size(); ++i) {
        const model::Relation& r = data.relations[i];
        fmt::format_to(std::back_inserter(out), "{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\n", key, i, r.subject, r.object,
                       static_cast<int>(r.type), r.frame, r.score, r.support);
    }
    return out;
}

// The blobs' rows and the embeddings' rows.
std::pair<Rows, Rows> blobRows(std::int64_t key, const model::SceneData& data) {
    Rows blobs, embeddings;
    for (const model::Blob& b : data.blobs) {
        if (isEmbedding(b)) {
            std::vector<float> vector(b.bytes.size() / sizeof(float));
            std::memcpy(vector.data(), b.bytes.data(), b.bytes.size());
            fmt::format_to(std::back_inserter(embeddings), "{}\t{}\t{}\n", key, b.node, arrayText(vector));
            continue;
        }
        fmt::format_to(std::back_inserter(blobs), "{}\t{}\t", key, b.node);
        pg::appendCopyText(blobs, b.name);
        blobs += '\t';
        pg::appendCopyText(blobs, b.mediaType);
        blobs += '\t';
        pg::appendCopyBytes(blobs, b.bytes);
        blobs += '\n';
    }
    return {std::move(blobs), std::move(embeddings)};
}

Rows changeRows(std::int64_t key, const SceneVersionData& version) {
    Rows out;
    for (std::size_t i = 0; i < version.changes.size(); ++i) {
        const model::ObjectChange& c = version.changes[i];
        fmt::format_to(std::back_inserter(out), "{}\t{}\t{}\t", key, i, static_cast<int>(c.kind));
        pg::appendCopyText(out, c.category);
        fmt::format_to(std::back_inserter(out), "\t{}\t{}\t", c.before, c.after);
        appendBox(out, c.from);
        out += '\t';
        appendBox(out, c.to);
        out += '\n';
    }
    return out;
}

model::Box boxAt(const pg::Result& r, int row, int first) {
    return {{r.real(row, first), r.real(row, first + 1), r.real(row, first + 2)},
            {r.real(row, first + 3), r.real(row, first + 4), r.real(row, first + 5)},
            r.real(row, first + 6)};
}

// Ends the transaction it began with ROLLBACK unless it was committed: an error, or an exception
// from the caller, never leaves half a scene behind (the server also rolls back on a lost connection).
class Transaction {
public:
    Transaction(pg::Connection& c, const char* begin) : c_(c) { c_.exec(begin, "beginning a transaction"); }
    ~Transaction() {
        if (open_) try {
                c_.exec("ROLLBACK", "rolling back");
            } catch (const Error&) {
                // The connection is gone: the server has rolled back already.
            }
    }
    Transaction(const Transaction&) = delete;
    Transaction& operator=(const Transaction&) = delete;
    void commit(std::string_view what) {
        c_.exec("COMMIT", what);
        open_ = false;
    }

private:
    pg::Connection& c_;
    bool open_ = true;
};

std::string sceneParameters(pg::Parameters& p, std::int64_t key, const std::string& device, const SceneVersionData& v) {
    const model::SceneInfo& info = v.data.info;
    p.add(key).add(device).add(info.name).add(static_cast<std::int64_t>(v.version)).add(info.source);
    p.add(info.captureTime).add(arrayText(info.alignment)).add(fmt::format("{}", info.scale));
    p.add(fmt::format("{}", info.viewpoint.position.x)).add(fmt::format("{}", info.viewpoint.position.y));
    p.add(fmt::format("{}", info.viewpoint.position.z)).add(fmt::format("{}", info.viewpoint.facingYaw));
    p.add(info.viewpointNote).add(static_cast<std::int64_t>(v.data.nodes.size()));
    p.add(static_cast<std::int64_t>(v.data.relations.size())).add(static_cast<std::int64_t>(v.data.blobs.size()));
    p.add(static_cast<std::int64_t>(v.changes.size())).add(v.supersededAt);
    return info.name;
}

}  // namespace

std::int64_t sceneKey(const std::string& device, const std::string& scene, std::uint64_t version) {
    // FNV-1a, 64 bits, over the three parts with a NUL between them (a scene name holds no NUL).
    std::uint64_t hash = 14695981039346656037ULL;
    auto mix = [&hash](std::string_view bytes) {
        for (unsigned char c : bytes) hash = (hash ^ c) * 1099511628211ULL;
    };
    mix(device);
    mix(std::string_view("\0", 1));
    mix(scene);
    mix(std::string_view("\0", 1));
    mix(fmt::format("{}", version));
    return static_cast<std::int64_t>(hash >> 1);
}

Store::Store(const std::string& url) : connection_(url, pg::describeUrl(url)) {
    connection_.exec("SET bytea_output = 'hex'; SET extra_float_digits = 1", "setting up the session");
}

std::set<std::pair<std::string, std::uint64_t>> Store::versionsOf(const std::string& device) {
    pg::Result r = connection_.exec("SELECT name, version FROM smql.scenes WHERE device = $1",
                                    pg::Parameters().add(device), "listing the device's scene versions");
    std::set<std::pair<std::string, std::uint64_t>> out;
    for (int i = 0; i < r.rows(); ++i)
        out.emplace(std::string(r.text(i, 0)), static_cast<std::uint64_t>(r.integer(i, 1)));
    return out;
}

void Store::requireWriteAccess() {
    pg::Result r = connection_.exec(
        "SELECT current_user, has_table_privilege('smql.scenes', 'INSERT') AND "
        "has_table_privilege('smql.nodes', 'INSERT')",
        "checking the role's privileges");
    if (r.text(0, 1) != "t")
        throw Error(ErrorKind::Storage,
                    fmt::format("the role {} may not push to the fleet store {}: it may not insert scenes",
                                r.text(0, 0), connection_.where()),
                    std::nullopt,
                    "push as a role with INSERT on the smql schema's tables (docs/fleet.md, \"Access\"); a "
                    "read-only role can query and pull");
}

// The stage tables of a coordinator (fleet/shards.hpp): PostgreSQL 15 sends the rows of a COPY into
// a foreign partition one remote INSERT at a time, an INSERT ... SELECT in batches (the servers'
// batch_size), so rows are copied into a temporary table of the session and inserted from there.
void Store::prepareStaging() {
    if (staging_) return;
    pg::Result sharded = connection_.exec("SELECT to_regclass('smql.shards') IS NOT NULL", "looking for shards");
    staging_ = sharded.text(0, 0) == "t" ? Staging::Staged : Staging::Direct;
    if (*staging_ == Staging::Direct) return;
    for (const char* table : {"nodes", "attributes", "relations", "blobs", "embeddings", "changes"})
        connection_.exec(fmt::format("CREATE TEMPORARY TABLE stage_{0} (LIKE smql.{0}) ON COMMIT DELETE ROWS", table),
                         "preparing the stage tables");
}

void Store::copyRows(const char* table, const char* columns, const std::string& rows, const std::string& what) {
    if (*staging_ == Staging::Direct) {
        connection_.copyIn(fmt::format("COPY smql.{}({}) FROM STDIN", table, columns), rows, what);
        return;
    }
    connection_.copyIn(fmt::format("COPY stage_{}({}) FROM STDIN", table, columns), rows, what);
    connection_.exec(fmt::format("INSERT INTO smql.{0}({1}) SELECT {1} FROM stage_{0}", table, columns), what);
}

bool Store::put(const std::string& device, const SceneVersionData& version) {
    const std::int64_t key = sceneKey(device, version.data.info.name, version.version);
    prepareStaging();
    Transaction txn(connection_, "BEGIN");
    pg::Parameters scene;
    const std::string name = sceneParameters(scene, key, device, version);
    const std::string what = fmt::format("storing version {} of scene '{}'", version.version, name);
    if (connection_.exec(kInsertScene, scene, what).rows() == 0) {
        // Already there: the same key from this device, or (63-bit hash) another key that collides.
        pg::Result held = connection_.exec("SELECT device, name, version FROM smql.scenes WHERE id = $1",
                                           pg::Parameters().add(key), what);
        if (held.rows() == 1 && (held.text(0, 0) != device || held.text(0, 1) != name ||
                                 static_cast<std::uint64_t>(held.integer(0, 2)) != version.version))
            throw Error(ErrorKind::Storage, fmt::format("{}: its key {} is taken by version {} of scene '{}' of "
                                                        "device {}",
                                                        what, key, held.text(0, 2), held.text(0, 1), held.text(0, 0)));
        return false;
    }
    copyRows("nodes",
             "scene, id, parent, kind, category, geometry, cx, cy, cz, sx, sy, sz, yaw, hidden, confidence, source_id, "
             "text, min_z, max_z, footprint",
             nodeRows(key, version.data), what);
    copyRows("attributes", "scene, node, position, name, value", attributeRows(key, version.data), what);
    copyRows("relations", "scene, position, subject, object, type, frame, score, support",
             relationRows(key, version.data), what);
    auto [blobs, embeddings] = blobRows(key, version.data);
    copyRows("blobs", "scene, node, name, media_type, bytes", blobs, what);
    copyRows("embeddings", "scene, node, vector", embeddings, what);
    copyRows("changes",
             "scene, position, kind, category, before, after, from_cx, from_cy, from_cz, from_sx, from_sy, from_sz, "
             "from_yaw, to_cx, to_cy, to_cz, to_sx, to_sy, to_sz, to_yaw",
             changeRows(key, version), what);
    txn.commit(what);
    return true;
}

std::vector<StoredVersion> Store::versionsNamed(const std::string& scene, const std::string& devicePrefix) {
    pg::Result r = connection_.exec(
        "SELECT id, device, version FROM smql.scenes WHERE name = $1 AND starts_with(device, $2) "
        "ORDER BY device, version",
        pg::Parameters().add(scene).add(devicePrefix), fmt::format("looking for scene '{}'", scene));
    std::vector<StoredVersion> out;
    for (int i = 0; i < r.rows(); ++i)
        out.push_back({r.integer(i, 0), std::string(r.text(i, 1)), scene, static_cast<std::uint64_t>(r.integer(i, 2))});
    return out;
}

std::vector<StoredVersion> Store::newestVersions(const std::string& devicePrefix) {
    pg::Result r = connection_.exec(
        "SELECT DISTINCT ON (device, name) id, device, name, version FROM smql.scenes WHERE starts_with(device, $1) "
        "ORDER BY device, name, version DESC",
        pg::Parameters().add(devicePrefix), "listing the scenes");
    std::vector<StoredVersion> out;
    for (int i = 0; i < r.rows(); ++i)
        out.push_back({r.integer(i, 0), std::string(r.text(i, 1)), std::string(r.text(i, 2)),
                       static_cast<std::uint64_t>(r.integer(i, 3))});
    return out;
}

namespace {

template <typename Enum>
Enum enumAt(const pg::Result& r, int row, int column, int count, std::string_view what) {
    std::int64_t value = r.integer(row, column);
    if (value < 0 || value >= count)
        throw Error(ErrorKind::Storage,
                    fmt::format("the fleet store holds a {} code {} this smql does not know", what, value));
    return static_cast<Enum>(value);
}

void readSceneRow(pg::Connection& c, const StoredVersion& stored, SceneVersionData& out) {
    pg::Result r = c.exec(
        "SELECT source, capture_time, alignment, scale, viewpoint_x, viewpoint_y, viewpoint_z, viewpoint_yaw, "
        "viewpoint_note, coalesce(superseded_at, '') FROM smql.scenes WHERE id = $1",
        pg::Parameters().add(stored.key), "reading a scene");
    if (r.rows() != 1)
        throw Error(ErrorKind::Storage, fmt::format("the fleet store {} lost version {} of scene '{}'", c.where(),
                                                    stored.version, stored.scene));
    model::SceneInfo& info = out.data.info;
    info.name = stored.scene;
    info.source = r.text(0, 0);
    info.captureTime = r.text(0, 1);
    std::vector<double> alignment = parseArray<double>(r.text(0, 2));
    if (alignment.size() != info.alignment.size())
        throw Error(ErrorKind::Storage, fmt::format("scene '{}' in the fleet store has an alignment of {} numbers",
                                                    stored.scene, alignment.size()));
    std::copy(alignment.begin(), alignment.end(), info.alignment.begin());
    info.scale = r.real(0, 3);
    info.viewpoint = {{r.real(0, 4), r.real(0, 5), r.real(0, 6)}, r.real(0, 7)};
    info.viewpointNote = r.text(0, 8);
    out.supersededAt = r.text(0, 9);
    out.version = stored.version;
}

void readNodes(pg::Connection& c, std::int64_t key, model::SceneData& data) {
    pg::Result r = c.exec(
        "SELECT id, parent, kind, category, geometry, cx, cy, cz, sx, sy, sz, yaw, hidden, confidence, source_id, "
        "text FROM smql.nodes WHERE scene = $1 ORDER BY id",
        pg::Parameters().add(key), "reading a scene's nodes");
    data.nodes.resize(static_cast<std::size_t>(r.rows()));
    for (int i = 0; i < r.rows(); ++i) {
        model::Node& n = data.nodes[static_cast<std::size_t>(i)];
        n.id = static_cast<model::NodeId>(r.integer(i, 0));
        n.parent = static_cast<model::NodeId>(r.integer(i, 1));
        n.kind = enumAt<model::NodeKind>(r, i, 2, 6, "node kind");
        n.category = r.text(i, 3);
        n.geometry = enumAt<model::GeometryKind>(r, i, 4, 3, "geometry kind");
        n.box = boxAt(r, i, 5);
        n.hidden = r.text(i, 12) == "t";
        n.confidence = r.real4(i, 13);
        if (!r.null(i, 14)) n.sourceId = r.integer(i, 14);
        n.text = r.text(i, 15);
        if (n.id != static_cast<model::NodeId>(i) + 1)
            throw Error(ErrorKind::Storage, fmt::format("a scene in the fleet store has no node {}", i + 1));
    }
    pg::Result a = c.exec("SELECT node, name, value FROM smql.attributes WHERE scene = $1 ORDER BY node, position",
                          pg::Parameters().add(key), "reading a scene's attributes");
    for (int i = 0; i < a.rows(); ++i) {
        auto node = static_cast<std::size_t>(a.integer(i, 0));
        if (node == 0 || node > data.nodes.size())
            throw Error(ErrorKind::Storage, fmt::format("an attribute in the fleet store names no node ({})", node));
        data.nodes[node - 1].attributes.push_back({std::string(a.text(i, 1)), std::string(a.text(i, 2))});
    }
}

void readRelationsAndBlobs(pg::Connection& c, std::int64_t key, model::SceneData& data) {
    pg::Result r = c.exec(
        "SELECT subject, object, type, frame, score, support FROM smql.relations WHERE scene = $1 ORDER BY position",
        pg::Parameters().add(key), "reading a scene's relations");
    for (int i = 0; i < r.rows(); ++i)
        data.relations.push_back(
            {static_cast<model::NodeId>(r.integer(i, 0)), static_cast<model::NodeId>(r.integer(i, 1)),
             enumAt<model::RelationType>(r, i, 2, model::kRelationTypeCount, "relation type"), r.real4(i, 4),
             static_cast<std::uint32_t>(r.integer(i, 5)), static_cast<model::NodeId>(r.integer(i, 3))});
    pg::Result b = c.exec("SELECT node, name, media_type, bytes FROM smql.blobs WHERE scene = $1 ORDER BY node, name",
                          pg::Parameters().add(key), "reading a scene's blobs");
    for (int i = 0; i < b.rows(); ++i)
        data.blobs.push_back({static_cast<model::NodeId>(b.integer(i, 0)), std::string(b.text(i, 1)),
                              std::string(b.text(i, 2)), pg::decodeBytea(b.text(i, 3))});
    pg::Result e = c.exec("SELECT node, vector FROM smql.embeddings WHERE scene = $1 ORDER BY node",
                          pg::Parameters().add(key), "reading a scene's embeddings");
    for (int i = 0; i < e.rows(); ++i) {
        std::vector<float> vector = parseArray<float>(e.text(i, 1));
        std::string bytes(vector.size() * sizeof(float), '\0');
        std::memcpy(bytes.data(), vector.data(), bytes.size());
        data.blobs.push_back({static_cast<model::NodeId>(e.integer(i, 0)), std::string(model::kEmbeddingBlob),
                              std::string(model::kEmbeddingMediaType), std::move(bytes)});
    }
}

void readChanges(pg::Connection& c, std::int64_t key, SceneVersionData& out) {
    pg::Result r = c.exec(
        "SELECT kind, category, before, after, from_cx, from_cy, from_cz, from_sx, from_sy, from_sz, from_yaw, "
        "to_cx, to_cy, to_cz, to_sx, to_sy, to_sz, to_yaw FROM smql.changes WHERE scene = $1 ORDER BY position",
        pg::Parameters().add(key), "reading a scene's changes");
    for (int i = 0; i < r.rows(); ++i)
        out.changes.push_back({enumAt<model::ChangeKind>(r, i, 0, 3, "change kind"), std::string(r.text(i, 1)),
                               static_cast<model::NodeId>(r.integer(i, 2)), static_cast<model::NodeId>(r.integer(i, 3)),
                               boxAt(r, i, 4), boxAt(r, i, 11)});
}

}  // namespace

SceneVersionData Store::get(const StoredVersion& stored) {
    SceneVersionData out;
    Transaction txn(connection_, "BEGIN ISOLATION LEVEL REPEATABLE READ READ ONLY");
    readSceneRow(connection_, stored, out);
    readNodes(connection_, stored.key, out.data);
    readRelationsAndBlobs(connection_, stored.key, out.data);
    readChanges(connection_, stored.key, out);
    txn.commit("reading a scene");
    return out;
}

}  // namespace smql::fleet
