// `smql map` and `smql guide`: top-down pictures of a scene and guidance plans as files
// (docs/guidance.md). Built into smql-ingest, which links OpenCV.
#pragma once

#include <string>

#include "view/map.hpp"

namespace smql::shell {

// `smql map DB [--scene S] [--fixtures] --out map.png|map.svg`: the scene from above with its
// anchors, objects, labels, a legend, a scale bar and the decision-point graph (view/map.hpp).
int mapCommand(const std::string& dbDir, const std::string& scene, const std::string& outFile,
               const view::MapOptions& options);

// `smql guide DB --from REF --to REF [--scene S] --out DIR`: runs GUIDE and writes DIR/guide.json,
// DIR/guide.md and DIR/guide.png (the map with the route and its numbered steps).
int guideCommand(const std::string& dbDir, const std::string& scene, const std::string& from, const std::string& to,
                 const std::string& outDir);

}  // namespace smql::shell
