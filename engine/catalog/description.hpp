// DESCRIBE's rows of one node, from the node, its path, its children and its evidence, so that the
// engine (from a snapshot) and the fleet store (from its tables) describe a node alike.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "model/result.hpp"
#include "model/types.hpp"

namespace smql::catalog {

// One piece of evidence: a blob's name, media type and size.
struct EvidenceInfo {
    std::string name;
    std::string mediaType;
    std::uint64_t size = 0;
};

// Appends `node`'s rows (id, field, value): kind, category, path, source id, the box's centre,
// dimensions, yaw and geometry, confidence, stored attributes, text, hidden, its descriptions (the
// children of that kind), the other children's labels ("sofa#12") and its evidence.
void describeNode(ResultSet& rows, const model::Node& node, std::string_view path,
                  const std::vector<const model::Node*>& children, const std::vector<EvidenceInfo>& evidence);

}  // namespace smql::catalog
