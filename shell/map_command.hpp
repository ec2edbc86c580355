// `smql map` and `smql guide`: top-down pictures of a scene and guidance plans as files
// (docs/guidance.md). Built into smql-ingest, which links OpenCV.
#pragma once

#include <string>

namespace smql::shell {

// `smql map DB [--scene S] --out map.png`: the scene from above with its anchors, objects and the
// decision-point graph.
int mapCommand(const std::string& dbDir, const std::string& scene, const std::string& outFile);

// `smql guide DB --from REF --to REF [--scene S] --out DIR`: runs GUIDE and writes DIR/guide.json,
// DIR/guide.md and DIR/guide.png (the map with the route and its numbered steps).
int guideCommand(const std::string& dbDir, const std::string& scene, const std::string& from, const std::string& to,
                 const std::string& outDir);

}  // namespace smql::shell
