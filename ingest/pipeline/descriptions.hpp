// Two-layer descriptions (docs/ingest.md, "Lateral relations and
// descriptions"). Layer 2, the scene level, is each object's text: the colour
// when enough views agree, the category, its support, and one lateral phrase.
// Layer 1, the image level, is one description node per object per view,
// below the object, naming the colour that view shows.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "ingest/capture/capture.hpp"
#include "ingest/pipeline/pipeline.hpp"
#include "ingest/pipeline/stage_data.hpp"
#include "model/types.hpp"

namespace smql::ingest {

// Per object, the consolidated lateral relations as phrases ("left of the
// lamp"), in the order they were found.
using LateralPhrases = std::map<model::NodeId, std::vector<std::string>>;

// Sets the text of every object of `scene` and adds the description nodes.
// Runs after the relations: the support phrase comes from the stored `on`/`in` edges.
void describeObjects(model::SceneData& scene, const std::vector<TrackedNode>& tracked, const LateralPhrases& lateral,
                     const Capture& capture, const IngestOptions& options);

}  // namespace smql::ingest
