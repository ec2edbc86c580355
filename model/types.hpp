// The memory model: nodes, relations and scenes, in the engine's own types.
// Units are metres, the frame is z-up. Every stage (storage, importers, exec)
// speaks these types at its boundary.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace smql::model {

// One id space for the whole database; 0 means "no node".
using NodeId = std::uint64_t;
inline constexpr NodeId kNoNode = 0;

enum class NodeKind : std::uint8_t { Scene = 0, Room = 1, Anchor = 2, Object = 3, Description = 4, Frame = 5 };

std::string_view toString(NodeKind kind);
std::optional<NodeKind> nodeKindFromString(std::string_view text);

struct Vec3 {
    double x = 0, y = 0, z = 0;
    friend bool operator==(const Vec3&, const Vec3&) = default;
};

// An upright oriented box: `size` holds the full extents along the box's own
// axes, `yaw` (radians, counter-clockwise about +z) turns the box's x axis
// away from the world x axis. Plane segments (walls, doors, windows) are thin
// boxes whose smallest extent is the plane's thickness.
struct Box {
    Vec3 center;
    Vec3 size;
    double yaw = 0;
    friend bool operator==(const Box&, const Box&) = default;
};

enum class GeometryKind : std::uint8_t { None = 0, Box = 1, Plane = 2 };

// "none", "box", "plane": the words files and answers use.
std::string_view toString(GeometryKind kind);
std::optional<GeometryKind> geometryKindFromString(std::string_view text);

struct Attribute {
    std::string name;
    std::string value;
    friend bool operator==(const Attribute&, const Attribute&) = default;
};

struct Node {
    NodeId id = kNoNode;
    NodeKind kind = NodeKind::Object;
    NodeId scene = kNoNode;   // the scene (root) this node belongs to; a scene node's own id
    NodeId parent = kNoNode;  // tree parent; kNoNode only for scene nodes
    std::string category;     // "sofa", "wall", "cushion"; a scene's name for scene nodes
    GeometryKind geometry = GeometryKind::None;
    Box box;
    std::vector<Attribute> attributes;  // color, material, size ... (unique names)
    float confidence = 1.0f;
    std::optional<std::int64_t> sourceId;  // the id it had in an imported file
    std::string text;
    // Nodes hidden from queries by default (e.g. Replica's `undefined` parts).
    bool hidden = false;

    const std::string* attribute(std::string_view name) const;
    friend bool operator==(const Node&, const Node&) = default;
};

// The relation vocabulary as stored: a code on disk and a word in files. New codes go at the end.
// Each code is a predicate of the query language; relations/predicates.cpp gives each its
// formula in one table, which the compiler checks against this list.
enum class RelationType : std::uint8_t {
    On = 0,
    In,
    Above,
    Below,
    Near,
    Attached,
    LeftOf,
    RightOf,
    InFrontOf,
    Behind,
    Between,
    VisibleFrom,
    Facing,
    AtFrontOf,
    AtBackOf
};
inline constexpr auto kRelationNames = std::to_array<std::string_view>(
    {"on", "in", "above", "below", "near", "attached", "left_of", "right_of", "in_front_of", "behind", "between",
     "visible_from", "facing", "at_front_of", "at_back_of"});
inline constexpr std::size_t kRelationTypeCount = kRelationNames.size();
std::string_view toString(RelationType type);
std::optional<RelationType> relationTypeFromString(std::string_view text);

// A typed relation edge besides the tree. `frame` is the frame node it was
// observed from (view-local), or kNoNode for an allocentric relation.
struct Relation {
    NodeId subject = kNoNode;
    NodeId object = kNoNode;
    RelationType type = RelationType::Near;
    float score = 1.0f;
    std::uint32_t support = 1;
    NodeId frame = kNoNode;
    friend bool operator==(const Relation&, const Relation&) = default;
};

// The viewpoint that gives `left`/`right`/`front`/`back` a meaning: a position
// on the floor and the direction the observer faces (radians about +z, 0 = +x).
struct Viewpoint {
    Vec3 position;
    double facingYaw = 0;
    friend bool operator==(const Viewpoint&, const Viewpoint&) = default;
};

// Row-major 4x4 transform from the capture's frame into the aligned frame.
using Transform = std::array<double, 16>;
inline constexpr Transform kIdentity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

struct SceneInfo {
    NodeId id = kNoNode;
    std::string name;
    std::string source;       // what it was imported from ("replica:/path/info_semantic.json")
    std::string captureTime;  // ISO 8601, may be empty
    Transform alignment = kIdentity;
    double scale = 1.0;
    Viewpoint viewpoint;
    std::string viewpointNote;  // how the default viewpoint was chosen, for docs and SHOW SCENES
    std::uint64_t nodeCount = 0;
    std::uint64_t version = 0;  // bumped on every write that touches the scene
    friend bool operator==(const SceneInfo&, const SceneInfo&) = default;
};

// A binary attachment of a node: an evidence crop (JPEG) of an object, say.
// `node` is a local id in SceneData, a database id once stored.
struct Blob {
    NodeId node = kNoNode;
    std::string name;       // unique per node: "evidence-1.jpg"
    std::string mediaType;  // "image/jpeg"
    std::string bytes;
    friend bool operator==(const Blob&, const Blob&) = default;
};

// A whole scene as an importer produces it, before it has database ids.
// Node ids here are local (1..n, unique within the scene data); `parent`
// refers to local ids, kNoNode meaning "child of the scene root". Relations
// refer to local ids too. The storage layer maps them to database ids in the
// one write transaction that stores the scene.
struct SceneData {
    SceneInfo info;
    std::vector<Node> nodes;
    std::vector<Relation> relations;
    std::vector<Blob> blobs;
};

// What an update of a scene (a new capture of the same place) found for one object. Objects
// seen again where they were are not changes; docs/history.md says how objects are matched.
enum class ChangeKind : std::uint8_t { Added = 0, Moved = 1, Missing = 2 };
std::string_view toString(ChangeKind kind);  // "added", "moved", "missing"

struct ObjectChange {
    ChangeKind kind = ChangeKind::Added;
    std::string category;
    NodeId before = kNoNode;  // the object in the superseded version (moved, missing)
    NodeId after = kNoNode;   // the object in the new version (added, moved)
    Box from;                 // where it was (moved, missing)
    Box to;                   // where it is (added, moved)
    friend bool operator==(const ObjectChange&, const ObjectChange&) = default;
};

// A superseded state of a scene, kept when an update replaced it, with what that update changed.
// Its ids are the database ids the scene had then (no longer live: the new version has its own).
struct SceneVersion {
    std::uint64_t number = 0;  // 1 for the first capture of the place, then counting up
    SceneInfo info;
    std::vector<Node> nodes;  // the scene node first, then the rest in id order
    std::vector<Relation> relations;
    std::string supersededAt;  // the capture time of the update that replaced it
    std::vector<ObjectChange> changes;
    friend bool operator==(const SceneVersion&, const SceneVersion&) = default;
};

}  // namespace smql::model
