#include "engine/ask/units.hpp"

#include <cmath>

#include <fmt/format.h>

namespace smql::ask {

namespace {

constexpr LengthUnit kLengthUnits[] = {
    {"m", 1.0, 2, "m|meter|meters|metre|metres|mtr|mtrs"},
    {"cm", 0.01, 0, "cm|cms|centimeter|centimeters|centimetre|centimetres"},
    {"mm", 0.001, 0, "mm|millimeter|millimeters|millimetre|millimetres"},
    {"ft", 0.3048, 1, "ft|foot|feet"},
    {"in", 0.0254, 0, "inch|inches"},
    {"yd", 0.9144, 1, "yd|yard|yards"},
};

bool listed(std::string_view words, std::string_view word) {
    while (!words.empty()) {
        std::size_t bar = words.find('|');
        if (words.substr(0, bar) == word) return true;
        words = bar == std::string_view::npos ? std::string_view{} : words.substr(bar + 1);
    }
    return false;
}

}  // namespace

const LengthUnit* lengthUnitNamed(std::string_view word) {
    for (const auto& unit : kLengthUnits)
        if (listed(unit.words, word)) return &unit;
    return nullptr;
}

const LengthUnit& lengthUnit(std::string_view symbol) {
    for (const auto& unit : kLengthUnits)
        if (unit.symbol == symbol) return unit;
    return kLengthUnits[0];
}

std::string formatLength(double metres, std::string_view symbol) {
    const LengthUnit& unit = lengthUnit(symbol);
    return fmt::format("{:.{}f} {}", metres / unit.metres, unit.decimals, unit.symbol);
}

}  // namespace smql::ask
