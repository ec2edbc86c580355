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
// children of that kind), the other children's labels ("sofa#12"), how many camera frames hang below it (not
// listed: a capture's hundreds say nothing one by one) and its evidence.
void describeNode(ResultSet& rows, const model::Node& node, std::string_view path,
                  const std::vector<const model::Node*>& children, const std::vector<EvidenceInfo>& evidence);

// Appends the rows that sum up a place (a scene's own node) from the nodes in it: its floor's size, its height
// (floor to ceiling, where both are stored), how many walls, its doors and windows, and the things in it by kind
// ("29: chair 5, table 3, bed 1").
void describePlace(ResultSet& rows, const model::Node& place, const std::vector<const model::Node*>& within);

}  // namespace smql::catalog
