// Scenes for the writers' tests: the Replica room as the engine stores it (with the parents the
// import gives), and a small scene with rooms, nested objects and attributes.
#pragma once

#include "import_support.hpp"
#include "ingest/import/registry.hpp"
#include "relations/hierarchy.hpp"

namespace smql::import::test {

// Replica room 0 with its objects below their supports and anchors, as `smql import` stores it.
inline model::SceneData replicaScene() {
    model::SceneData scene = import::read("replica", replicaPath());
    relations::assignParents(scene);
    return scene;
}

inline model::Node sceneNode(model::NodeId id, model::NodeKind kind, model::NodeId parent, std::string category,
                             model::Box box) {
    model::Node n;
    n.id = id;
    n.kind = kind;
    n.parent = parent;
    n.category = std::move(category);
    n.box = box;
    n.geometry = kind == model::NodeKind::Room ? model::GeometryKind::None : model::GeometryKind::Box;
    return n;
}

// Two rooms; a wall and a table in the first, a mug on the table, a hidden part and a ceiling
// (neither drawn), a chair with attributes in the second.
inline model::SceneData roomsScene() {
    using model::NodeKind;
    model::SceneData scene;
    scene.info.name = "flat";
    scene.nodes = {
        sceneNode(1, NodeKind::Room, 0, "kitchen", {}),
        sceneNode(2, NodeKind::Room, 0, "living room", {}),
        sceneNode(3, NodeKind::Anchor, 1, "wall", {{2, 0, 1.25}, {4, 0.1, 2.5}, 0}),
        sceneNode(4, NodeKind::Object, 3, "table", {{2, 1, 0.375}, {1.2, 0.8, 0.75}, 0.5}),
        sceneNode(5, NodeKind::Object, 4, "mug", {{2.1, 1, 0.8}, {0.08, 0.08, 0.1}, -1.0}),
        sceneNode(6, NodeKind::Object, 1, "undefined", {{1, 1, 1}, {0.2, 0.2, 0.2}, 0}),
        sceneNode(7, NodeKind::Anchor, 0, "ceiling", {{2, 2, 2.55}, {6, 6, 0.1}, 0}),
        sceneNode(8, NodeKind::Object, 2, "chair", {{6, 2, 0.45}, {0.5, 0.5, 0.9}, 3.0}),
    };
    scene.nodes[2].geometry = model::GeometryKind::Plane;
    scene.nodes[5].hidden = true;
    scene.nodes[7].attributes = {{"color", "red"}, {"material", "wood"}};
    scene.nodes[7].sourceId = 70;
    return scene;
}

}  // namespace smql::import::test
