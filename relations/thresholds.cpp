#include "relations/thresholds.hpp"

#include <cmath>

#include <fmt/format.h>

namespace smql::relations {

const std::vector<SettingInfo>& settingsCatalogue() {
    static const std::vector<SettingInfo> catalogue = {
        {"near.distance", SettingUnit::Metres, &Thresholds::nearDistance,
         "near: largest gap between the two boxes, however large they are"},
        {"near.min_distance", SettingUnit::Metres, &Thresholds::nearMinDistance,
         "near: a gap this small is near, however small the two things are"},
        {"on.min_overlap", SettingUnit::Ratio, &Thresholds::onMinOverlap,
         "on: share of a's footprint over b; in: share of the smaller footprint"},
        {"on.min_rise", SettingUnit::Ratio, &Thresholds::onMinRise,
         "on/in: height of a's centre above b's bottom, as a share of b's height"},
        {"on.max_gap", SettingUnit::Metres, &Thresholds::onMaxGap, "on/in: largest gap from b's top up to a's bottom"},
        {"in.min_inside", SettingUnit::Ratio, &Thresholds::inMinInside, "in: share of a's volume inside b's box"},
        {"above.min_overlap", SettingUnit::Ratio, &Thresholds::aboveMinOverlap,
         "above/below: footprint overlap as a share of the smaller footprint"},
        {"above.tolerance", SettingUnit::Metres, &Thresholds::aboveTolerance,
         "above/below: how far a's bottom may sink under b's top"},
        {"attached.max_gap", SettingUnit::Metres, &Thresholds::attachedMaxGap,
         "attached: largest gap to a wall, door, window, pillar or ceiling"},
        {"attached.min_rise", SettingUnit::Metres, &Thresholds::attachedMinRise,
         "attached to a wall: how far above the wall's foot a thing's bottom is (lower, it stands by the wall)"},
        {"lateral.min_offset", SettingUnit::Metres, &Thresholds::lateralMinOffset,
         "left_of/right_of/in_front_of/behind: smallest centre offset along the viewer's axis"},
        {"between.max_offset", SettingUnit::Metres, &Thresholds::betweenMaxOffset,
         "between: largest distance of a's centre from the segment joining the other two"},
        {"visible.min_share", SettingUnit::Ratio, &Thresholds::visibleMinShare,
         "visible_from: share of a's sample points in sight of the eye"},
    };
    return catalogue;
}

const SettingInfo* findSetting(std::string_view name) {
    // Predicates with a single threshold answer to their own name (`SET near = 0.8 m`).
    static const std::pair<std::string_view, std::string_view> aliases[] = {
        {"near", "near.distance"}, {"attached", "attached.max_gap"}, {"between", "between.max_offset"}};
    for (const auto& [alias, full] : aliases)
        if (name == alias) name = full;
    for (const auto& s : settingsCatalogue())
        if (s.name == name) return &s;
    return nullptr;
}

double settingValue(const SettingInfo& setting, std::optional<double> metres, std::optional<double> number,
                    const std::optional<SourceLocation>& where) {
    const bool ratio = setting.unit == SettingUnit::Ratio;
    if (metres && ratio)
        throw Error(ErrorKind::Binding, fmt::format("{} is a ratio, not a distance", setting.name), where,
                    fmt::format("SET {} = 0.5", setting.name));
    if (!metres && !number)
        throw Error(ErrorKind::Binding, fmt::format("{} takes a number", setting.name), where,
                    ratio ? fmt::format("SET {} = 0.5", setting.name) : fmt::format("SET {} = 0.8 m", setting.name));
    const double value = metres ? *metres : *number;  // a bare number for a distance setting is metres
    if (!std::isfinite(value) || value < 0 || (ratio && value > 1) || (!ratio && value > 100))
        throw Error(ErrorKind::Binding, fmt::format("{} out of range for {}", value, setting.name), where,
                    ratio ? "ratios lie in [0, 1]" : "distances lie in [0, 100] m");
    return value;
}

}  // namespace smql::relations
