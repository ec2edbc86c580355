// USE and SET: the statements that change the session, when they run.
#include <fmt/format.h>

#include "engine/exec/executor.hpp"

namespace smql::exec {

ResultSet Executor::run(const binder::BoundUse& use) {
    ResultSet rs;
    session_.allScenes = use.allScenes;
    if (use.allScenes) {
        rs.message = "using all scenes: FIND and COUNT by category and attributes";
        return rs;
    }
    session_.sceneName = use.scene;
    rs.message = fmt::format("using scene '{}'", use.scene);
    return rs;
}

ResultSet Executor::run(const binder::BoundSet& set) {
    ResultSet rs;
    if (set.setsTranslator) {
        session_.askTranslator = set.translator;
        rs.message = set.translator ? fmt::format(
                                          "translator = '{}' (ASK falls back to the built-in reader when it "
                                          "fails)",
                                          set.translatorUrl)
                                    : "translator = the built-in reader";
        return rs;
    }
    if (set.limit) {
        session_.limits.*(set.limit->field) = static_cast<std::int64_t>(set.value);
        rs.message = fmt::format("{} = {}", set.limit->name, session_.limits.*(set.limit->field));
        return rs;
    }
    session_.thresholds.*(set.threshold->field) = set.value;
    bool ratio = set.threshold->unit == relations::SettingUnit::Ratio;
    rs.message = fmt::format("{} = {}{}", set.threshold->name, set.value, ratio ? "" : " m");
    return rs;
}

}  // namespace smql::exec
