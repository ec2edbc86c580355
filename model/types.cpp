#include "model/types.hpp"

#include <algorithm>
#include <array>

namespace smql::model {

namespace {
constexpr std::array<std::string_view, 6> kKindNames = {"scene", "room", "anchor", "object", "description", "frame"};
}  // namespace

std::string_view toString(NodeKind kind) { return kKindNames[static_cast<std::size_t>(kind)]; }

std::optional<NodeKind> nodeKindFromString(std::string_view text) {
    auto it = std::find(kKindNames.begin(), kKindNames.end(), text);
    if (it == kKindNames.end()) return std::nullopt;
    return static_cast<NodeKind>(it - kKindNames.begin());
}

constexpr std::array<std::string_view, 3> kGeometryNames = {"none", "box", "plane"};

std::string_view toString(GeometryKind kind) { return kGeometryNames[static_cast<std::size_t>(kind)]; }

std::optional<GeometryKind> geometryKindFromString(std::string_view text) {
    auto it = std::find(kGeometryNames.begin(), kGeometryNames.end(), text);
    if (it == kGeometryNames.end()) return std::nullopt;
    return static_cast<GeometryKind>(it - kGeometryNames.begin());
}

std::string_view toString(RelationType type) { return kRelationNames[static_cast<std::size_t>(type)]; }

std::string_view toString(ChangeKind kind) {
    switch (kind) {
        case ChangeKind::Added:
            return "added";
        case ChangeKind::Moved:
            return "moved";
        case ChangeKind::Missing:
            return "missing";
    }
    return "?";
}

std::optional<RelationType> relationTypeFromString(std::string_view text) {
    auto it = std::find(kRelationNames.begin(), kRelationNames.end(), text);
    if (it == kRelationNames.end()) return std::nullopt;
    return static_cast<RelationType>(it - kRelationNames.begin());
}

const std::string* Node::attribute(std::string_view name) const {
    for (const auto& a : attributes)
        if (a.name == name) return &a.value;
    return nullptr;
}

}  // namespace smql::model
