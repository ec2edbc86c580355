// The documented default viewpoint of an imported scene (docs/formats.md,
// "Default viewpoint"): it gives left/right/front/back their meaning until a
// user sets another one. Internal to ingest/import.
#pragma once

#include <string>
#include <vector>

#include "model/types.hpp"

namespace smql::import::detail {

inline constexpr double kEyeHeight = 1.6;   // above the floor, metres
inline constexpr double kStepInside = 0.5;  // from the door's centre into the room, metres

struct ViewpointChoice {
    model::Viewpoint viewpoint;
    std::string note;  // how it was chosen, for SceneInfo::viewpointNote
};

// `nodes` must hold at least one node with geometry.
ViewpointChoice defaultViewpoint(const std::vector<model::Node>& nodes);

// The last step of every importer: stands the scene on its floor (floor.hpp), makes wall boxes of several
// faces the faces they are (wall_faces.hpp), names it, records its source and node count, and sets the
// default viewpoint.
void finishScene(model::SceneData& scene, const std::string& name, std::string source);

}  // namespace smql::import::detail
