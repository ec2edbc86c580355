// What a connection remembers between statements: the scene it queries, the
// thresholds and limits it set. USE and SET change it, when they run.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "engine/ask/translator.hpp"
#include "relations/thresholds.hpp"

namespace smql::catalog {

// Bounds on what one statement may build, so a query over large sets fails with a clear error instead
// of exhausting memory (RELATE object TO object on a 2,000-node scene is four million pairs).
struct Limits {
    std::int64_t maxRows = 1'000'000;  // rows of one result
    std::int64_t maxPairs = 100'000;   // node pairs RELATE may compare
    // Statement shapes the engine keeps parsed, so that new literals skip the parser (0: none;
    // engine/binder/shape_cache.hpp).
    std::int64_t shapeCache = 1024;
};

struct LimitSetting {
    std::string_view name;
    std::int64_t Limits::*field;
    std::string_view meaning;
    std::int64_t least = 1;  // the smallest value SET takes
};
const std::vector<LimitSetting>& limitSettings();
const LimitSetting* findLimit(std::string_view name);

struct Session {
    std::string sceneName;   // empty until chosen: USE SCENE, an import, or the most recent scene
    bool allScenes = false;  // USE SCENE '*': FIND and COUNT by category across every scene
    relations::Thresholds thresholds;
    Limits limits;
    // ASK's translator; null is the built-in rule-based one (Engine::setAskTranslator).
    std::shared_ptr<const ask::Translator> askTranslator;
};

}  // namespace smql::catalog
