#include "ingest/pipeline/scene_nodes.hpp"

#include "model/geometry.hpp"

namespace smql::ingest {

model::Node& addNode(model::SceneData& scene, model::NodeKind kind, std::string category, model::GeometryKind geometry,
                     const model::Box& box) {
    model::Node n;
    n.id = scene.nodes.size() + 1;
    n.kind = kind;
    n.category = std::move(category);
    n.geometry = geometry;
    n.box = box;
    scene.nodes.push_back(std::move(n));
    return scene.nodes.back();
}

const model::Node& nodeById(const model::SceneData& scene, model::NodeId id) { return scene.nodes[id - 1]; }

std::string sizeWord(const model::Box& box) {
    double v = model::volume(box);
    return v < 0.01 ? "small" : v < 0.3 ? "medium" : "large";
}

}  // namespace smql::ingest
