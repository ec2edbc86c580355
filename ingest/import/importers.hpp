// Importers: real layout files -> model::SceneData, and the smql JSON scene
// format that round-trips a SceneData. Importers never touch the database:
// the engine stores the SceneData in one transaction and assigns parents.
//
// Every failure throws smql::Error(ErrorKind::Input) whose message names the
// file and the field (JSON) or line (text); nothing is returned on failure.
// The formats and the mapping rules are documented in docs/formats.md.
#pragma once

#include <string>
#include <vector>

#include "model/types.hpp"

namespace smql::import {

// Each reader names the scene `sceneName`, or by its format's rule when that is empty.
// registry.hpp lists them as import formats; `import::read` dispatches by name.

// Replica's info_semantic.json (objects[] with oriented boxes); by default the folder names the scene.
model::SceneData readReplica(const std::string& path, const std::string& sceneName);

// A SpatialLM layout text (wall_0=Wall(...), door_0=Door(...), bbox_0=Bbox(...)); by default the file's stem.
model::SceneData readSpatialLm(const std::string& path, const std::string& sceneName);

// VSI-Bench's meta-info JSON: many rooms (ScanNet, ARKitScenes) of oriented boxes, keyed by name;
// `sceneName` picks the room (it may be empty only when the file holds one).
model::SceneData readVsiBench(const std::string& path, const std::string& sceneName);
// Every room such a file holds, in its order, each named by its key: one read of the file.
std::vector<model::SceneData> readVsiBenchAll(const std::string& path);

// The smql JSON scene format ({"smql_scene": 1, ...}); by default the name the file gives.
model::SceneData readSceneJson(const std::string& path, const std::string& sceneName = {});

// Pretty JSON in the smql scene format, keys in a fixed order, doubles with
// enough digits that readSceneJson gives back an equal SceneData.
std::string writeSceneJson(const model::SceneData& scene);

// Hydra's Spark-DSG scene graph JSON: its objects and rooms (places, agents and the mesh are
// skipped); by default the scene name smql wrote into it, else the file's stem.
model::SceneData readSparkDsg(const std::string& path, const std::string& sceneName);
// The scene as a Spark-DSG graph: anchors and objects in the object layer, the scene and its rooms in
// the room layer, parents as Hydra's interlayer edges (docs/formats.md, "Spark-DSG").
std::string writeSparkDsg(const model::SceneData& scene);

// The writers of the formats of other tools, for viewing a scene or handing it on: the drawn boxes
// (export_support.hpp: walls, floor, doors, windows, objects), metres, described in docs/formats.md.
// glTF 2.0, binary (.glb) and JSON with the buffer embedded (.gltf): box meshes, y up.
std::string writeGlb(const model::SceneData& scene);
std::string writeGltf(const model::SceneData& scene);
// PLY, binary little endian: the boxes as one triangle mesh with colours per vertex, z up.
std::string writePly(const model::SceneData& scene);
// GeoJSON: the floor plan, one Polygon feature per box's footprint, in the scene's own metres.
std::string writeGeoJson(const model::SceneData& scene);

}  // namespace smql::import
