// What the page is sent: a scene's nodes with their paths, and a statement's answer with the nodes
// to highlight and the route to draw.
#pragma once

#include <nlohmann/json.hpp>

#include "model/result.hpp"
#include "model/types.hpp"

namespace smql::view {

// {"name", "info": {...}, "nodes": [{"id", "kind", "category", "parent", "geometry", "box", "path",
// "text", "attributes"}]}: the nodes the page draws (hidden nodes and camera frames left out).
nlohmann::ordered_json sceneJson(const model::SceneData& scene);

// resultJson's columns, rows and message, and "hits" (the node ids the answer names: its `id`
// column, a GUIDE's goal) and "route" (a GUIDE's steps: step, x, y, instruction).
nlohmann::ordered_json answerJson(const ResultSet& result);

}  // namespace smql::view
