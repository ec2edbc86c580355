// The named thresholds of the spatial predicates (docs/relations.md gives the
// formulas). Users see them with SHOW SETTINGS and change them with SET.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "model/error.hpp"

namespace smql::relations {

struct Thresholds {
    // near: the gap may reach the sum of the two things' sizes (twice their mean size), never less
    // than near.min_distance nor more than near.distance (m); ReferIt3D's Sr3D gives all three.
    double nearDistance = 1.0;
    double nearMinDistance = 0.15;
    double onMinOverlap = 0.5;      // on: share of a's own footprint over b; in: share of the smaller footprint
    double onMinRise = 0.5;         // on/in: a's centre at least this share of b's height above b's bottom
    double onMaxGap = 0.1;          // on/in: a's bottom at most this far above b's top (m)
    double inMinInside = 0.5;       // in: share of a's volume inside b
    double aboveMinOverlap = 0.1;   // above/below: footprint overlap over the smaller footprint
    double aboveTolerance = 0.05;   // above/below: a's bottom may sink this far under b's top (m)
    double attachedMaxGap = 0.05;   // attached: gap to a wall, door, window, pillar or ceiling at most this (m)
    double attachedMinRise = 0.1;   // attached to a wall: a's bottom at least this far above the wall's foot (m)
    double lateralMinOffset = 0.1;  // left_of, right_of, in_front_of, behind: centre offset at least this (m)
    double betweenMaxOffset = 0.5;  // between: a's centre at most this far from the segment b-c (m)
    double visibleMinShare = 0.25;  // visible_from: share of a's sample points the eye sees
};

enum class SettingUnit { Metres, Ratio };

struct SettingInfo {
    std::string name;  // "near.distance"
    SettingUnit unit;
    double Thresholds::*field;
    std::string meaning;
};

const std::vector<SettingInfo>& settingsCatalogue();
// Finds a setting by name or short alias (`near` = `near.distance`).
const SettingInfo* findSetting(std::string_view name);

// The value `SET setting = ...` gives, checked for its unit and range: `metres` when written with
// a unit, else `number` (metres for a distance setting); neither for text. Throws Error(Binding)
// at `where`.
double settingValue(const SettingInfo& setting, std::optional<double> metres, std::optional<double> number,
                    const std::optional<SourceLocation>& where);

}  // namespace smql::relations
