// Reading JSON with errors that name the file and the field's path
// ("objects[12].oriented_bbox.abb.sizes"). Internal to ingest/import.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/types.hpp"

namespace smql::import::detail {

// Ordered, so that object members (attributes) keep the file's order.
using Json = nlohmann::ordered_json;

// The most members one JSON object of an imported file may have (docs/formats.md, "Bounds"): an
// ordered object finds a member by looking along its members, so its cost grows with their square.
inline constexpr std::size_t kMaxObjectMembers = 10000;

// Which file a JSON value came from, and what to tell the user on an error.
struct JsonSource {
    std::string file;
    std::string hint;
};

// A vector as the JSON array [x, y, z] the importers read with Field::vec3().
inline Json vec3Json(const model::Vec3& v) { return Json::array({v.x, v.y, v.z}); }

// Parses the file. Syntax errors carry line and column; a key repeated in one
// object is an error too, since the parser would silently keep only one.
Json parseJsonFile(const JsonSource& source);

// A JSON value and its path from the root, with typed accessors that throw
// an Input error "<file>: <path>: <what>" when the value does not fit.
class Field {
public:
    Field(const Json& value, const JsonSource& source, std::string path = {})
        : value_(&value), source_(&source), path_(std::move(path)) {}

    const Json& json() const { return *value_; }
    const std::string& path() const { return path_; }
    [[noreturn]] void fail(std::string_view what) const;

    // Objects.
    Field at(std::string_view key) const;  // required member
    std::optional<Field> find(std::string_view key) const;
    // Rejects members not in `keys` (catches misspelt optional fields).
    void allowOnly(std::initializer_list<std::string_view> keys) const;
    std::vector<std::pair<std::string, Field>> members() const;

    // Arrays.
    std::size_t size() const;
    Field operator[](std::size_t index) const;

    // Scalars.
    double number() const;
    std::int64_t integer() const;
    std::uint64_t unsignedInteger() const;
    std::string string() const;
    bool boolean() const;
    std::vector<double> numbers(std::size_t count) const;  // an array of exactly `count` numbers
    model::Vec3 vec3() const;
    // vec3() of a point: each coordinate within kMaxCoordinate of the origin (common.hpp).
    model::Vec3 coordinates() const;

private:
    void expectObject() const;
    const Json* value_;
    const JsonSource* source_;
    std::string path_;
};

}  // namespace smql::import::detail
