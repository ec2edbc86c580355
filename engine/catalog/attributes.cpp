#include "engine/catalog/attributes.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "model/geometry.hpp"

namespace smql::catalog {

namespace {

using M = AttributeMeasure;

const std::vector<AttributeInfo> kBuiltIn = {
    {"id", ValueType::Integer, M::Number, "", "the node's id, global in the database"},
    {"category", ValueType::Text, M::Text, "", "what the node is: sofa, wall, mug"},
    {"kind", ValueType::Text, M::Text, "", "object, anchor, room, frame or description"},
    {"source_id", ValueType::Integer, M::Number, "", "the id it had in the imported file"},
    {"confidence", ValueType::Real, M::Number, "", "how sure the importer or ingest was, 0 to 1"},
    {"text", ValueType::Text, M::Text, "", "the node's text (descriptions)"},
    {"height", ValueType::Real, M::Length, "m", "the box's vertical size"},
    {"width", ValueType::Real, M::Length, "m", "the box's larger horizontal size"},
    {"depth", ValueType::Real, M::Length, "m", "the box's smaller horizontal size"},
    {"volume", ValueType::Real, M::Volume, "m^3", "the box's volume"},
    {"x", ValueType::Real, M::Length, "m", "the box centre's x in the scene's frame"},
    {"y", ValueType::Real, M::Length, "m", "the box centre's y in the scene's frame"},
    {"z", ValueType::Real, M::Length, "m", "the box centre's height above the floor"},
    {"center", ValueType::Text, M::None, "m", "the box centre as (x, y, z)"},
    {"box", ValueType::Box, M::None, "m", "the oriented box: centre, size and yaw"},
    {"parent", ValueType::Text, M::None, "", "the node it hangs below in the tree, as wall#3"},
    {"path", ValueType::Text, M::None, "", "the way from the scene down to the node"},
};

bool placed(const model::Node& n) { return n.geometry != model::GeometryKind::None; }

}  // namespace

const std::vector<AttributeInfo>& builtInAttributes() { return kBuiltIn; }

const AttributeInfo* builtInAttribute(std::string_view name) {
    auto it = std::find_if(kBuiltIn.begin(), kBuiltIn.end(), [&](const AttributeInfo& a) { return a.name == name; });
    return it == kBuiltIn.end() ? nullptr : &*it;
}

AttributeInfo storedAttribute(std::string_view name) {
    return {name, ValueType::Text, M::Text, "", "stored by the importer or ingest"};
}

std::optional<AttributeInfo> attributeIn(const SceneSnapshot& scene, std::string_view name) {
    if (const AttributeInfo* builtIn = builtInAttribute(name)) return *builtIn;
    const auto& stored = scene.attributeNames();
    if (std::binary_search(stored.begin(), stored.end(), name, std::less<>())) return storedAttribute(name);
    return std::nullopt;
}

ResultSet attributeTable(const std::vector<std::string>& storedNames) {
    ResultSet rs;
    rs.columns = {{"attribute", ValueType::Text},
                  {"type", ValueType::Text},
                  {"unit", ValueType::Text},
                  {"use", ValueType::Text},
                  {"meaning", ValueType::Text}};
    auto add = [&](const AttributeInfo& a) {
        std::string_view type = a.type == ValueType::Integer ? "integer"
                                : a.type == ValueType::Real  ? "real"
                                : a.type == ValueType::Box   ? "box"
                                                             : "text";
        std::string use = a.measure == M::None ? "RETURN" : "WHERE, ORDER BY, RETURN";
        rs.rows.push_back({std::string(a.name), std::string(type), std::string(a.unit), use, std::string(a.meaning)});
    };
    for (const auto& a : kBuiltIn) add(a);
    // Not an attribute of the node alone: it measures from a reference.
    rs.rows.push_back({std::string("distance(x)"), std::string("real"), std::string("m"),
                       std::string("WHERE, ORDER BY; RETURN distance after ORDER BY distance(x) or NEAREST TO x"),
                       std::string("the gap between the node's box and the nearest box x names")});
    for (const auto& name : storedNames) add(storedAttribute(name));
    return rs;
}

void checkLiteral(AttributeMeasure measure, LiteralForm literal, std::string_view what,
                  const std::optional<SourceLocation>& where) {
    switch (measure) {
        case M::Length:
            if (literal.text || !(literal.withUnit || literal.bound))
                throw Error(ErrorKind::Binding, fmt::format("{} is a length: write the unit", what), where,
                            fmt::format("as in {} > 1.5 m, or 80 cm, or 300 mm", what));
            return;
        case M::Volume:
        case M::Number:
            if (literal.text || (literal.withUnit && !literal.bound))
                throw Error(ErrorKind::Binding,
                            fmt::format("{} is a number{}", what, measure == M::Volume ? " of cubic metres" : ""),
                            where, fmt::format("write a bare number, as in {} > 0.5", what));
            return;
        case M::Text:
        case M::None:
            return;  // stored attributes are text that may hold numbers (captures >= 2)
    }
}

Value attributeValue(const SceneSnapshot& scene, Slot slot, const AttributeInfo& attribute) {
    const model::Node& n = scene.node(slot);
    const std::string_view name = attribute.name;
    if (!builtInAttribute(name)) {
        if (const std::string* value = n.attribute(name)) return *value;
        return std::monostate{};
    }
    if (name == "id") return static_cast<std::int64_t>(n.id);
    if (name == "category") return n.category;
    if (name == "kind") return std::string(model::toString(n.kind));
    if (name == "source_id") return n.sourceId ? Value(*n.sourceId) : Value(std::monostate{});
    if (name == "confidence") return static_cast<double>(n.confidence);
    if (name == "text") return n.text;
    if (name == "path") return scene.path(slot);
    if (name == "parent") {
        auto parent = scene.slotOf(n.parent);
        return parent ? Value(SceneSnapshot::label(scene.node(*parent))) : Value(std::monostate{});
    }
    if (!placed(n)) return std::monostate{};  // the measures of a box need a box
    const model::Box& b = n.box;
    if (name == "height") return b.size.z;
    if (name == "width") return std::max(b.size.x, b.size.y);
    if (name == "depth") return std::min(b.size.x, b.size.y);
    if (name == "volume") return model::volume(b);
    if (name == "x") return b.center.x;
    if (name == "y") return b.center.y;
    if (name == "z") return b.center.z;
    if (name == "center") return fmt::format("({:.3f}, {:.3f}, {:.3f})", b.center.x, b.center.y, b.center.z);
    return b;  // box
}

}  // namespace smql::catalog
