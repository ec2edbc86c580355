// Importers: real layout files -> model::SceneData, and the smql JSON scene
// format that round-trips a SceneData. Importers never touch the database:
// the engine stores the SceneData in one transaction and assigns parents.
//
// Every failure throws smql::Error(ErrorKind::Input) whose message names the
// file and the field (JSON) or line (text); nothing is returned on failure.
// The formats and the mapping rules are documented in docs/formats.md.
#pragma once

#include <string>

#include "engine/model/types.hpp"

namespace smql::import {

// Replica's info_semantic.json (objects[] with oriented boxes).
model::SceneData readReplica(const std::string& path, const std::string& sceneName);

// A SpatialLM layout text (wall_0=Wall(...), door_0=Door(...), bbox_0=Bbox(...)).
model::SceneData readSpatialLm(const std::string& path, const std::string& sceneName);

// The smql JSON scene format ({"smql_scene": 1, ...}); the scene name comes from the file.
model::SceneData readSceneJson(const std::string& path);

// Pretty JSON in the smql scene format, keys in a fixed order, doubles with
// enough digits that readSceneJson gives back an equal SceneData.
std::string writeSceneJson(const model::SceneData& scene);

}  // namespace smql::import
