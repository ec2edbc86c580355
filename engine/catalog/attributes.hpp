// The attributes a statement can read of a node: built-in fields (id, category, height, x ...) in
// one table, which WHERE, ORDER BY, RETURN and SHOW ATTRIBUTES all read, and the attributes an
// importer or ingest stored on the nodes (color, material ...), which are text.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/catalog/scene_snapshot.hpp"
#include "model/error.hpp"
#include "model/result.hpp"

namespace smql::catalog {

// What a comparison's literal must be for an attribute.
enum class AttributeMeasure {
    Text,    // compared as text, case-insensitive; LIKE works
    Number,  // a bare number (ids, ratios, counts)
    Length,  // metres: the literal needs a unit (m, cm, mm)
    Volume,  // cubic metres: a bare number
    None,    // not comparable (a box, a point, a path): RETURN only
};

struct AttributeInfo {
    std::string_view name;
    ValueType type;  // the column type RETURN gives it
    AttributeMeasure measure;
    std::string_view unit;  // "m", "m^3", "" for none
    std::string_view meaning;
};

// The built-in attributes, in the order SHOW ATTRIBUTES lists them.
const std::vector<AttributeInfo>& builtInAttributes();
const AttributeInfo* builtInAttribute(std::string_view name);
// The attribute of a stored name (color, captures ...): text, compared as text or as a number.
AttributeInfo storedAttribute(std::string_view name);
// The attribute `name` in `scene`: built-in, or stored on some node of the scene; nothing if neither.
std::optional<AttributeInfo> attributeIn(const SceneSnapshot& scene, std::string_view name);

// SHOW ATTRIBUTES: the built-in attributes, distance(x), then the stored ones named, each with its
// type, unit, use and meaning.
ResultSet attributeTable(const std::vector<std::string>& storedNames);

// How a comparison's literal was written: quoted text, a number with a unit (`80 cm`), or a
// value bound to a placeholder (a number there is metres where a length goes).
struct LiteralForm {
    bool text = false;
    bool withUnit = false;
    bool bound = false;
};
// Lengths are written with their unit (`height > 80 cm`), so a bare `2` never silently means
// metres; text attributes take a quoted string, numbers a number. Throws Error(Binding) at `where`.
void checkLiteral(AttributeMeasure measure, LiteralForm literal, std::string_view what,
                  const std::optional<SourceLocation>& where);

// The value of an attribute of one node, typed as its column; null where the node has none.
Value attributeValue(const SceneSnapshot& scene, Slot slot, const AttributeInfo& attribute);

}  // namespace smql::catalog
