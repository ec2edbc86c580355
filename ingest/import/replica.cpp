// Replica's info_semantic.json -> SceneData (docs/formats.md, "Replica").
#include <cmath>
#include <filesystem>
#include <unordered_map>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "ingest/import/common.hpp"
#include "ingest/import/importers.hpp"

#include "ingest/import/json_field.hpp"
#include "ingest/import/oriented_box.hpp"
#include "ingest/import/viewpoint.hpp"
#include "model/category.hpp"

namespace smql::import {

namespace {

using detail::Field;
using detail::kMaxCoordinate;
using detail::kMaxSize;
using detail::kQuaternionNormTolerance;

struct ClassMapping {
    model::NodeKind kind;
    model::GeometryKind geometry;
};

ClassMapping mapClass(const std::string& category) {
    using model::GeometryKind;
    using model::NodeKind;
    for (const char* plane : {"wall", "door", "window", "blinds", "floor", "ceiling"})
        if (category == plane) return {NodeKind::Anchor, GeometryKind::Plane};
    for (const char* solid : {"pillar", "beam", "stair"})
        if (category == solid) return {NodeKind::Anchor, GeometryKind::Box};
    return {NodeKind::Object, GeometryKind::Box};
}

void checkCoordinate(const Field& field, const model::Vec3& v, std::string_view what) {
    for (double c : {v.x, v.y, v.z})
        if (std::abs(c) > kMaxCoordinate)
            field.fail(
                fmt::format("{} ({}, {}, {}) is more than {} m from the origin", what, v.x, v.y, v.z, kMaxCoordinate));
}

model::Vec3 readSizes(const Field& field) {
    model::Vec3 sizes = field.vec3();
    for (double s : {sizes.x, sizes.y, sizes.z})
        if (!(s > 0) || s > kMaxSize)
            field.fail(fmt::format("size {} is out of range: sizes must be in (0, {}] m", s, kMaxSize));
    return sizes;
}

Eigen::Matrix3d readRotation(const Field& field) {
    std::vector<double> q = field.numbers(4);  // x, y, z, w
    Eigen::Quaterniond quaternion(q[3], q[0], q[1], q[2]);
    double norm = quaternion.norm();
    if (std::abs(norm - 1) > kQuaternionNormTolerance)
        field.fail(fmt::format("quaternion (x, y, z, w) has norm {:.6g}, expected a unit quaternion", norm));
    return quaternion.normalized().toRotationMatrix();
}

model::Node readObject(const Field& object, model::NodeId localId) {
    model::Node node;
    node.id = localId;
    node.sourceId = object.at("id").integer();

    Field className = object.at("class_name");
    node.category = model::categoryName(className.string());
    if (node.category.empty()) className.fail("empty class name");
    ClassMapping mapping = mapClass(node.category);
    node.kind = mapping.kind;
    node.geometry = mapping.geometry;
    node.hidden = node.category == "undefined";

    Field orientedBox = object.at("oriented_bbox");
    Field abb = orientedBox.at("abb");
    Field orientation = orientedBox.at("orientation");
    Field centerField = abb.at("center");
    model::Vec3 center = centerField.vec3();
    checkCoordinate(centerField, center, "centre");
    model::Vec3 sizes = readSizes(abb.at("sizes"));
    Eigen::Matrix3d rotation = readRotation(orientation.at("rotation"));
    Field translationField = orientation.at("translation");
    model::Vec3 translation = translationField.vec3();
    checkCoordinate(translationField, translation, "translation");

    // abb.center is in the box's frame (habitat-sim's reading of Replica).
    Eigen::Vector3d world = rotation * Eigen::Vector3d(center.x, center.y, center.z) +
                            Eigen::Vector3d(translation.x, translation.y, translation.z);
    node.box = detail::uprightBox({world.x(), world.y(), world.z()}, sizes, rotation);
    checkCoordinate(orientedBox, node.box.center, "world centre");
    return node;
}

}  // namespace

model::SceneData readReplica(const std::string& path, const std::string& sceneName) {
    detail::JsonSource source{path,
                              "expected Replica's info_semantic.json: objects[] with id, class_name and "
                              "oriented_bbox {abb {center, sizes}, orientation {rotation [x, y, z, w], translation}}"};
    detail::Json root = detail::parseJsonFile(source);
    Field objects = Field(root, source).at("objects");
    if (objects.size() == 0) objects.fail("empty: expected at least one object");

    model::SceneData scene;
    std::unordered_map<std::int64_t, std::size_t> indexOfId;
    for (std::size_t i = 0; i < objects.size(); ++i) {
        Field object = objects[i];
        model::Node node = readObject(object, i + 1);
        auto [it, fresh] = indexOfId.emplace(*node.sourceId, i);
        if (!fresh)
            object.at("id").fail(fmt::format("duplicate id {} (also objects[{}].id)", *node.sourceId, it->second));
        scene.nodes.push_back(std::move(node));
    }

    // Replica files are all called info_semantic.json: without a name, the folder names the scene.
    std::string name =
        sceneName.empty() ? std::filesystem::absolute(path).parent_path().filename().string() : sceneName;
    detail::finishScene(scene, name, "replica:" + path);
    return scene;
}

}  // namespace smql::import
