// What a connection remembers between statements: the scene it queries and
// the thresholds it set. USE and SET change it, when they run.
#pragma once

#include <string>

#include "engine/relations/thresholds.hpp"

namespace smql::exec {

struct Session {
    std::string sceneName;   // empty until chosen: USE SCENE, an import, or the most recent scene
    bool allScenes = false;  // USE SCENE '*': FIND and COUNT by category across every scene
    relations::Thresholds thresholds;
};

}  // namespace smql::exec
