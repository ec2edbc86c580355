// The smql JSON scene format (docs/formats.md, "smql JSON scene"): a whole
// SceneData, written in a fixed key order and read back with full validation.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "ingest/import/common.hpp"
#include "ingest/import/floor.hpp"
#include "ingest/import/importers.hpp"
#include "ingest/import/json_field.hpp"
#include "model/base64.hpp"
#include "model/instant.hpp"

namespace smql::import {

namespace {

using detail::Field;
using detail::Json;
using detail::kMaxSize;
using detail::vec3Json;

constexpr std::int64_t kFormatVersion = 1;

// A float written as its shortest decimal ("0.7", not 0.699999988...); read
// back as a double and narrowed, it gives the same float.
double shortestFloat(float value) { return std::strtod(fmt::format("{}", value).c_str(), nullptr); }

Json nodeJson(const model::Node& node) {
    Json out;
    out["id"] = node.id;
    out["kind"] = model::toString(node.kind);
    out["parent"] = node.parent;
    out["category"] = node.category;
    out["geometry"] = model::toString(node.geometry);
    // A box without geometry carries nothing, but is kept when set so that nothing is lost.
    if (node.geometry != model::GeometryKind::None || node.box != model::Box{})
        out["box"] = {{"center", vec3Json(node.box.center)}, {"size", vec3Json(node.box.size)}, {"yaw", node.box.yaw}};
    out["attributes"] = Json::object();
    for (const model::Attribute& a : node.attributes) out["attributes"][a.name] = a.value;
    out["confidence"] = shortestFloat(node.confidence);
    if (node.sourceId) out["source_id"] = *node.sourceId;
    out["text"] = node.text;
    out["hidden"] = node.hidden;
    return out;
}

Json relationJson(const model::Relation& relation) {
    Json out;
    out["subject"] = relation.subject;
    out["object"] = relation.object;
    out["type"] = model::toString(relation.type);
    out["score"] = shortestFloat(relation.score);
    out["support"] = relation.support;
    out["frame"] = relation.frame;
    return out;
}

// Text that is not UTF-8 is written with U+FFFD in its place rather than
// failing the export: imports reject it, but a database written before they
// did may hold some.
std::string jsonText(const Json& value) { return value.dump(-1, ' ', false, Json::error_handler_t::replace); }

// Like dump(2), except that arrays of plain values (coordinates, the
// alignment matrix) stay on one line instead of one number per line.
void writePretty(const Json& value, int level, std::string& out) {
    auto newline = [&](int indent) {
        out += '\n';
        out.append(static_cast<std::size_t>(indent) * 2, ' ');
    };
    bool structured = std::any_of(value.begin(), value.end(), [](const Json& v) { return v.is_structured(); });
    if (value.is_object() && !value.empty()) {
        out += '{';
        const char* separator = "";
        for (const auto& [key, member] : value.items()) {
            out += separator;
            separator = ",";
            newline(level + 1);
            out += jsonText(Json(key)) + ": ";
            writePretty(member, level + 1, out);
        }
        newline(level);
        out += '}';
    } else if (value.is_array() && structured) {
        out += '[';
        const char* separator = "";
        for (const Json& element : value) {
            out += separator;
            separator = ",";
            newline(level + 1);
            writePretty(element, level + 1, out);
        }
        newline(level);
        out += ']';
    } else if (value.is_array()) {
        out += '[';
        const char* separator = "";
        for (const Json& element : value) {
            out += separator + jsonText(element);
            separator = ", ";
        }
        out += ']';
    } else {
        out += jsonText(value);
    }
}

// ---- reading ----------------------------------------------------------------

double numberIn(const Field& field, double min, double max) {
    double value = field.number();
    if (value < min || value > max) field.fail(fmt::format("{} is out of range [{}, {}]", value, min, max));
    return value;
}

double angle(const Field& field) {
    double value = field.number();
    if (std::string problem = detail::angleProblem(value); !problem.empty()) field.fail(problem);
    return value;
}

model::Box readBox(const Field& field, bool needsExtent) {
    field.allowOnly({"center", "size", "yaw"});
    model::Box box;
    box.center = field.at("center").coordinates();
    Field sizeField = field.at("size");
    box.size = sizeField.vec3();
    for (double s : {box.size.x, box.size.y, box.size.z})
        if ((needsExtent ? !(s > 0) : s < 0) || s > kMaxSize)
            sizeField.fail(fmt::format("size {} is out of range: sizes must be in {}0, {}] m", s,
                                       needsExtent ? "(" : "[", kMaxSize));
    if (auto yaw = field.find("yaw")) box.yaw = angle(*yaw);
    return box;
}

// Metres per capture unit: a capture in kilometres or in microns is no room.
constexpr double kMinScale = 1e-6, kMaxScale = 1e6;

// The capture -> scene transform: a rotation times a scale (each column as long as the others, at
// right angles), a finite translation, and 0 0 0 1 below.
void checkAlignment(const Field& field, const std::array<double, 16>& m) {
    auto column = [&](int c) { return std::sqrt(m[c] * m[c] + m[4 + c] * m[4 + c] + m[8 + c] * m[8 + c]); };
    const double s = column(0);
    bool ok = m[12] == 0 && m[13] == 0 && m[14] == 0 && m[15] == 1 && s > kMinScale && s < kMaxScale;
    for (int c = 0; c < 3 && ok; ++c)
        ok = std::abs(column(c) - s) <= 1e-6 * s && std::isfinite(m[4 * c + 3]) && std::abs(m[4 * c + 3]) < 1e9;
    for (int a = 0; a < 3 && ok; ++a)
        for (int b = a + 1; b < 3 && ok; ++b)
            ok = std::abs(m[a] * m[b] + m[4 + a] * m[4 + b] + m[8 + a] * m[8 + b]) <= 1e-6 * s * s;
    if (!ok) field.fail("not a rotation and a scale with a translation (4 x 4, row after row, the last row 0 0 0 1)");
}

void readInfo(const Field& field, model::SceneInfo& info) {
    field.allowOnly({"name", "source", "capture_time", "alignment", "scale", "viewpoint", "viewpoint_note"});
    Field name = field.at("name");
    info.name = name.string();
    if (info.name.empty()) name.fail("the scene name is empty");
    if (auto f = field.find("source")) info.source = f->string();
    if (auto f = field.find("capture_time"); f && !f->string().empty()) {
        // An instant, written in UTC: AS OF and the history compare times, which "yesterday-ish" is not.
        auto instant = model::utcInstant(f->string());
        if (!instant)
            f->fail(fmt::format("'{}' is no date and time (2026-11-21T10:00:00Z, 2026-11-21 10:00 or a date)",
                                f->string()));
        info.captureTime = *instant;
    }
    if (auto f = field.find("alignment")) {
        std::vector<double> values = f->numbers(16);
        std::copy(values.begin(), values.end(), info.alignment.begin());
        checkAlignment(*f, info.alignment);
    }
    if (auto f = field.find("scale")) {
        info.scale = f->number();
        if (!(info.scale > kMinScale && info.scale < kMaxScale))
            f->fail(fmt::format("scale {} is not a plausible number of metres per capture unit ({:g} to {:g})",
                                info.scale, kMinScale, kMaxScale));
    }
    if (auto f = field.find("viewpoint")) {
        f->allowOnly({"position", "facing_yaw"});
        info.viewpoint.position = f->at("position").coordinates();
        info.viewpoint.facingYaw = angle(f->at("facing_yaw"));
    }
    if (auto f = field.find("viewpoint_note")) info.viewpointNote = f->string();
}

model::Node readNode(const Field& field) {
    field.allowOnly({"id", "kind", "parent", "category", "geometry", "box", "attributes", "confidence", "source_id",
                     "text", "hidden"});
    model::Node node;
    node.id = field.at("id").unsignedInteger();

    Field kind = field.at("kind");
    auto parsedKind = model::nodeKindFromString(kind.string());
    if (!parsedKind)
        kind.fail(fmt::format("unknown kind '{}' (expected room, anchor, object, description or frame)",
                              kind.json().get<std::string>()));
    if (*parsedKind == model::NodeKind::Scene)
        kind.fail("kind 'scene' cannot be a node here: the scene is the file's \"scene\" object");
    node.kind = *parsedKind;

    if (auto f = field.find("parent")) node.parent = f->unsignedInteger();
    if (auto f = field.find("category")) node.category = f->string();

    std::optional<Field> box = field.find("box");
    node.geometry = box ? model::GeometryKind::Box : model::GeometryKind::None;
    if (auto f = field.find("geometry")) {
        auto geometry = model::geometryKindFromString(f->string());
        if (!geometry) f->fail(fmt::format("unknown geometry '{}' (expected none, box or plane)", f->string()));
        node.geometry = *geometry;
    }
    if (node.geometry != model::GeometryKind::None && !box)
        field.fail(fmt::format("missing field 'box' (geometry is {})", model::toString(node.geometry)));
    if (box) node.box = readBox(*box, node.geometry != model::GeometryKind::None);

    if (auto f = field.find("attributes"))
        for (const auto& [name, value] : f->members()) {
            if (name.empty()) value.fail("empty attribute name");
            node.attributes.push_back({name, value.string()});
        }
    if (auto f = field.find("confidence")) node.confidence = static_cast<float>(numberIn(*f, 0, 1));
    if (auto f = field.find("source_id")) node.sourceId = f->integer();
    if (auto f = field.find("text")) node.text = f->string();
    if (auto f = field.find("hidden")) node.hidden = f->boolean();
    return node;
}

model::Relation readRelation(const Field& field) {
    field.allowOnly({"subject", "object", "type", "score", "support", "frame"});
    model::Relation relation;
    relation.subject = field.at("subject").unsignedInteger();
    relation.object = field.at("object").unsignedInteger();
    Field type = field.at("type");
    auto parsedType = model::relationTypeFromString(type.string());
    if (!parsedType)
        type.fail(
            fmt::format("unknown relation type '{}' (expected on, in, above, below, near, attached, left_of, "
                        "right_of, in_front_of, behind or between)",
                        type.json().get<std::string>()));
    relation.type = *parsedType;
    if (auto f = field.find("score")) relation.score = static_cast<float>(numberIn(*f, 0, 1));
    if (auto f = field.find("support")) {
        std::uint64_t support = f->unsignedInteger();
        if (support == 0 || support > std::numeric_limits<std::uint32_t>::max())
            f->fail(
                fmt::format("support {} is out of range [1, {}]", support, std::numeric_limits<std::uint32_t>::max()));
        relation.support = static_cast<std::uint32_t>(support);
    }
    if (auto f = field.find("frame")) relation.frame = f->unsignedInteger();
    return relation;
}

// Local ids must be 1..n (the storage layer maps them in one pass); parents
// must name nodes of the file and must not loop.
void checkTree(const Field& nodesField, const std::vector<model::Node>& nodes) {
    std::size_t n = nodes.size();
    std::vector<std::size_t> indexOfId(n + 1, n);  // n = unused
    for (std::size_t i = 0; i < n; ++i) {
        model::NodeId id = nodes[i].id;
        Field idField = nodesField[i].at("id");
        if (id < 1 || id > n)
            idField.fail(fmt::format("id {} is out of range: local ids run from 1 to {} (the number of nodes)", id, n));
        if (indexOfId[id] != n) idField.fail(fmt::format("duplicate id {} (also nodes[{}].id)", id, indexOfId[id]));
        indexOfId[id] = i;
    }
    for (std::size_t i = 0; i < n; ++i)
        if (nodes[i].parent > n)
            nodesField[i].at("parent").fail(
                fmt::format("parent {} is not the id of a node in this file", nodes[i].parent));

    enum class Mark { Unvisited, OnPath, Done };
    std::vector<Mark> mark(n + 1, Mark::Unvisited);
    for (const model::Node& start : nodes) {
        std::vector<model::NodeId> path;
        model::NodeId at = start.id;
        while (at != model::kNoNode && mark[at] == Mark::Unvisited) {
            mark[at] = Mark::OnPath;
            path.push_back(at);
            at = nodes[indexOfId[at]].parent;
        }
        if (at != model::kNoNode && mark[at] == Mark::OnPath) {
            auto loopStart = std::find(path.begin(), path.end(), at);
            std::vector<model::NodeId> loop(loopStart, path.end());
            loop.push_back(at);
            nodesField[indexOfId[at]].at("parent").fail(
                fmt::format("parents form a cycle: {}", fmt::join(loop, " -> ")));
        }
        for (model::NodeId id : path) mark[id] = Mark::Done;
    }
}

void checkRelations(const Field& relationsField, const std::vector<model::Relation>& relations,
                    const std::vector<model::Node>& nodes) {
    auto nodeOf = [&](model::NodeId id) { return id >= 1 && id <= nodes.size() ? &nodes[id - 1] : nullptr; };
    for (std::size_t i = 0; i < relations.size(); ++i) {
        const model::Relation& r = relations[i];
        Field field = relationsField[i];
        for (auto [key, id] : {std::pair{"subject", r.subject}, std::pair{"object", r.object}})
            if (!nodeOf(id)) field.at(key).fail(fmt::format("{} is not the id of a node in this file", id));
        if (r.subject == r.object) field.at("object").fail("a relation needs two different nodes");
        if (r.frame != model::kNoNode) {
            const model::Node* frame = nodeOf(r.frame);
            if (!frame) field.at("frame").fail(fmt::format("{} is not the id of a node in this file", r.frame));
            if (frame->kind != model::NodeKind::Frame)
                field.at("frame").fail(
                    fmt::format("node {} has kind {}, not frame", r.frame, model::toString(frame->kind)));
        }
    }
}

}  // namespace

namespace {

std::string fromBase64(const Field& field) {
    std::string text = field.string();
    if (text.size() % 4 != 0) field.fail("base64 text must come in groups of 4 characters");
    std::string out;
    out.reserve(text.size() / 4 * 3);
    for (std::size_t i = 0; i < text.size(); i += 4) {
        std::uint32_t chunk = 0;
        int padding = 0;
        for (std::size_t k = 0; k < 4; ++k) {
            char c = text[i + k];
            std::size_t value = 0;
            if (c == '=' && i + 4 == text.size() && k >= 2) {
                ++padding;
            } else {
                value = model::kBase64Digits.find(c);
                if (value == std::string_view::npos || padding)
                    field.fail(fmt::format("'{}' at {} is not base64", c, i + k));
            }
            chunk = chunk << 6 | static_cast<std::uint32_t>(value);
        }
        out += static_cast<char>(chunk >> 16 & 255);
        if (padding < 2) out += static_cast<char>(chunk >> 8 & 255);
        if (padding < 1) out += static_cast<char>(chunk & 255);
    }
    return out;
}

model::Blob readBlob(const Field& field, const std::vector<model::Node>& nodes) {
    field.allowOnly({"node", "name", "media_type", "base64"});
    model::Blob blob;
    Field node = field.at("node");
    blob.node = node.unsignedInteger();
    // 0 is the scene itself (its points).
    if (blob.node != model::kNoNode &&
        std::none_of(nodes.begin(), nodes.end(), [&](const model::Node& n) { return n.id == blob.node; }))
        node.fail(fmt::format("{} is not the id of a node", blob.node));
    Field name = field.at("name");
    blob.name = name.string();
    if (blob.name.empty()) name.fail("a blob needs a name");
    blob.mediaType = field.at("media_type").string();
    blob.bytes = fromBase64(field.at("base64"));
    return blob;
}

}  // namespace

std::string writeSceneJson(const model::SceneData& scene) {
    const model::SceneInfo& info = scene.info;
    Json root;
    root["smql_scene"] = kFormatVersion;
    Json& sceneJson = root["scene"];
    sceneJson["name"] = info.name;
    sceneJson["source"] = info.source;
    sceneJson["capture_time"] = info.captureTime;
    sceneJson["alignment"] = info.alignment;
    sceneJson["scale"] = info.scale;
    sceneJson["viewpoint"] = {{"position", vec3Json(info.viewpoint.position)},
                              {"facing_yaw", info.viewpoint.facingYaw}};
    sceneJson["viewpoint_note"] = info.viewpointNote;
    root["nodes"] = Json::array();
    for (const model::Node& node : scene.nodes) root["nodes"].push_back(nodeJson(node));
    root["relations"] = Json::array();
    for (const model::Relation& relation : scene.relations) root["relations"].push_back(relationJson(relation));
    // Evidence crops travel as base64; scenes without any keep the shorter form.
    if (!scene.blobs.empty()) {
        root["blobs"] = Json::array();
        for (const model::Blob& blob : scene.blobs)
            root["blobs"].push_back({{"node", blob.node},
                                     {"name", blob.name},
                                     {"media_type", blob.mediaType},
                                     {"base64", model::toBase64(blob.bytes)}});
    }
    std::string out;
    writePretty(root, 0, out);
    return out + "\n";
}

model::SceneData readSceneJson(const std::string& path, const std::string& sceneName) {
    detail::JsonSource source{path,
                              "expected an smql scene file: {\"smql_scene\": 1, \"scene\": {...}, \"nodes\": [...], "
                              "\"relations\": [...]} (docs/formats.md)"};
    Json root = detail::parseJsonFile(source);
    Field top(root, source);
    top.allowOnly({"smql_scene", "scene", "nodes", "relations", "blobs"});
    Field version = top.at("smql_scene");
    if (version.integer() != kFormatVersion)
        version.fail(
            fmt::format("unsupported version {} (this build reads version {})", version.integer(), kFormatVersion));

    model::SceneData scene;
    readInfo(top.at("scene"), scene.info);
    Field nodes = top.at("nodes");
    for (std::size_t i = 0; i < nodes.size(); ++i) scene.nodes.push_back(readNode(nodes[i]));
    checkTree(nodes, scene.nodes);
    if (auto relations = top.find("relations")) {
        for (std::size_t i = 0; i < relations->size(); ++i) scene.relations.push_back(readRelation((*relations)[i]));
        checkRelations(*relations, scene.relations, scene.nodes);
    }
    if (auto blobs = top.find("blobs"))
        for (std::size_t i = 0; i < blobs->size(); ++i) scene.blobs.push_back(readBlob((*blobs)[i], scene.nodes));
    scene.info.nodeCount = scene.nodes.size();
    if (!sceneName.empty()) scene.info.name = sceneName;
    detail::standOnFloor(scene);
    return scene;
}

}  // namespace smql::import
