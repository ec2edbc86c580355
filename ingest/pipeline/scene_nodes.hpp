// Adding nodes to the scene the stages build. A node's local id is its
// position + 1, so ids follow the order the stages add nodes in.
#pragma once

#include <string>

#include "model/types.hpp"

namespace smql::ingest {

// The reference is valid until the next node is added.
model::Node& addNode(model::SceneData& scene, model::NodeKind kind, std::string category, model::GeometryKind geometry,
                     const model::Box& box);

const model::Node& nodeById(const model::SceneData& scene, model::NodeId id);

// The `size` attribute of an object: small < 0.01 m³ <= medium < 0.3 m³ <= large.
std::string sizeWord(const model::Box& box);

}  // namespace smql::ingest
