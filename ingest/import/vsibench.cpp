// VSI-Bench's meta-info JSON (ScanNet and ARKitScenes rooms as oriented boxes) -> SceneData
// (docs/formats.md, "VSI-Bench layouts").
#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "ingest/import/common.hpp"
#include "ingest/import/importers.hpp"
#include "ingest/import/json_field.hpp"
#include "ingest/import/viewpoint.hpp"
#include "model/category.hpp"
#include "model/error.hpp"
#include "model/geometry.hpp"

namespace smql::import {

namespace {

using detail::Field;
using detail::kMaxCoordinate;
using detail::kMaxSize;

const char* const kVsiBenchHint =
    "expected VSI-Bench's meta-info JSON: {\"<room>\": {\"object_bbox\": {\"<category>\": [{\"centroid\": [x, y, z], "
    "\"axesLengths\": [a, b, c], \"normalizedAxes\": [9 numbers, one axis a row]}]}}}";

// Tilts below this (degrees) are a scan's noise and are not worth an attribute.
constexpr double kTiltWorthNoting = 1.0;
// Axes further than this from unit length, or from perpendicular, are not a rotation.
constexpr double kAxisTolerance = 1e-2;

using Axes = std::array<model::Vec3, 3>;

double dot(const model::Vec3& a, const model::Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

Axes readAxes(const Field& field) {
    std::vector<double> v = field.numbers(9);
    Axes axes{model::Vec3{v[0], v[1], v[2]}, model::Vec3{v[3], v[4], v[5]}, model::Vec3{v[6], v[7], v[8]}};
    for (std::size_t i = 0; i < 3; ++i) {
        if (std::abs(dot(axes[i], axes[i]) - 1) > kAxisTolerance)
            field.fail(
                fmt::format("axis {} has length {:.4g}, expected unit axes", i, std::sqrt(dot(axes[i], axes[i]))));
        for (std::size_t j = i + 1; j < 3; ++j)
            if (std::abs(dot(axes[i], axes[j])) > kAxisTolerance)
                field.fail(fmt::format("axes {} and {} are not perpendicular", i, j));
    }
    return axes;
}

// The upright box around an oriented one: its up axis is the one nearest world z, its yaw that of
// the other axis that lies flattest, its extents those of the oriented box along the upright
// box's axes. Returns the lean of the up axis from z in degrees.
double uprightAround(const Axes& axes, const model::Vec3& lengths, model::Box& box) {
    const std::array<double, 3> length{lengths.x, lengths.y, lengths.z};
    std::size_t up = 0;
    for (std::size_t i = 1; i < 3; ++i)
        if (std::abs(axes[i].z) > std::abs(axes[up].z)) up = i;
    std::size_t flat = up == 0 ? 1 : 0;
    for (std::size_t i = 0; i < 3; ++i)
        if (i != up && std::hypot(axes[i].x, axes[i].y) > std::hypot(axes[flat].x, axes[flat].y)) flat = i;
    box.yaw = std::atan2(axes[flat].y, axes[flat].x);
    const model::Vec3 u{std::cos(box.yaw), std::sin(box.yaw), 0}, v{-u.y, u.x, 0}, z{0, 0, 1};
    auto extent = [&](const model::Vec3& d) {
        double sum = 0;
        for (std::size_t i = 0; i < 3; ++i) sum += length[i] * std::abs(dot(axes[i], d));
        return sum;
    };
    box.size = {extent(u), extent(v), extent(z)};
    return std::acos(std::min(1.0, std::abs(axes[up].z))) / model::kDegree;
}

// Doors and windows are the room's anchors, as in Replica; everything else is an object.
bool isOpening(const std::string& category) { return category == "door" || category == "window"; }

model::Node readBox(const Field& field, const std::string& category, model::NodeId localId) {
    model::Node node;
    node.id = localId;
    node.sourceId = static_cast<std::int64_t>(localId);  // the box's place in the room, counted from 1
    node.category = category;
    node.kind = isOpening(category) ? model::NodeKind::Anchor : model::NodeKind::Object;
    node.geometry = isOpening(category) ? model::GeometryKind::Plane : model::GeometryKind::Box;
    Field centroid = field.at("centroid");
    node.box.center = centroid.vec3();
    for (double c : {node.box.center.x, node.box.center.y, node.box.center.z})
        if (std::abs(c) > kMaxCoordinate)
            centroid.fail(fmt::format("{} is more than {} m from the origin", c, kMaxCoordinate));
    Field lengthsField = field.at("axesLengths");
    model::Vec3 lengths = lengthsField.vec3();
    for (double s : {lengths.x, lengths.y, lengths.z})
        if (!(s > 0) || s > kMaxSize)
            lengthsField.fail(fmt::format("length {} is out of range: lengths must be in (0, {}] m", s, kMaxSize));
    double tilt = uprightAround(readAxes(field.at("normalizedAxes")), lengths, node.box);
    if (tilt >= kTiltWorthNoting) node.attributes.push_back({"tilt", fmt::format("{:.1f}", tilt)});
    return node;
}

}  // namespace

namespace {

model::SceneData readRoom(const Field& room, const std::string& name, const std::string& path) {
    model::SceneData scene;
    for (const auto& [written, boxes] : room.at("object_bbox").members()) {
        std::string category = model::categoryName(written);  // "trash bin" -> trash-bin
        if (category.empty()) boxes.fail("empty category name");
        for (std::size_t i = 0; i < boxes.size(); ++i)
            scene.nodes.push_back(readBox(boxes[i], category, scene.nodes.size() + 1));
    }
    if (scene.nodes.empty()) room.at("object_bbox").fail("no boxes: expected at least one");
    // The room's floor area as VSI-Bench measured it (its room size task), on a room node without a
    // box: the layouts have no walls or floor to measure it by (docs/ask.md, "Room size").
    if (auto size = room.find("room_size")) {
        double area = size->number();
        if (!(area > 0) || area > kMaxSize * kMaxSize)
            size->fail(fmt::format("room size {} m^2 is out of range", area));
        model::Node node;
        node.id = scene.nodes.size() + 1;
        node.kind = model::NodeKind::Room;
        node.category = "room";
        node.geometry = model::GeometryKind::None;
        node.attributes.push_back({"area", fmt::format("{:.2f}", area)});
        scene.nodes.push_back(std::move(node));
    }
    detail::finishScene(scene, name, "vsibench:" + path);
    return scene;
}

}  // namespace

std::vector<model::SceneData> readVsiBenchAll(const std::string& path) {
    detail::JsonSource source{path, kVsiBenchHint};
    detail::Json root = detail::parseJsonFile(source);
    Field rooms(root, source);
    std::vector<model::SceneData> scenes;
    for (const auto& [name, room] : rooms.members()) scenes.push_back(readRoom(room, name, path));
    if (scenes.empty()) rooms.fail("no rooms: expected at least one");
    return scenes;
}

model::SceneData readVsiBench(const std::string& path, const std::string& sceneName) {
    detail::JsonSource source{path, kVsiBenchHint};
    detail::Json root = detail::parseJsonFile(source);
    Field rooms(root, source);
    auto members = rooms.members();
    if (members.empty()) rooms.fail("no rooms: expected at least one");
    if (sceneName.empty() && members.size() == 1) return readRoom(members.front().second, members.front().first, path);
    if (sceneName.empty())
        throw Error(ErrorKind::Usage,
                    fmt::format("{} holds {} rooms: name one (the first are {}, {}, {})", path, members.size(),
                                members[0].first, members[1].first, members.size() > 2 ? members[2].first : "..."),
                    std::nullopt, "smql import vsibench FILE --scene ROOM, or --all for every room");
    std::optional<Field> room = rooms.find(sceneName);
    if (!room)
        throw Error(ErrorKind::Input, fmt::format("{}: no room named '{}'", path, sceneName), std::nullopt,
                    fmt::format("the file holds {} rooms, {} the first", members.size(), members.front().first));
    return readRoom(*room, sceneName, path);
}

}  // namespace smql::import
