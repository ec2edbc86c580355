#include "engine/catalog/session.hpp"

namespace smql::catalog {

const std::vector<LimitSetting>& limitSettings() {
    static const std::vector<LimitSetting> settings = {
        {"max_rows", &Limits::maxRows, "most rows one statement may return"},
        {"max_pairs", &Limits::maxPairs, "most node pairs one RELATE may compare"},
        {"shape_cache", &Limits::shapeCache, "statement shapes kept parsed for new literals (0: off)", 0},
    };
    return settings;
}

const LimitSetting* findLimit(std::string_view name) {
    for (const auto& s : limitSettings())
        if (s.name == name) return &s;
    return nullptr;
}

}  // namespace smql::catalog
