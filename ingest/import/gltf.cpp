// glTF 2.0, binary (.glb) or JSON with the buffer inside (.gltf) (docs/formats.md, "glTF"): the
// drawn boxes as meshes coloured by category, one glTF node per smql node in smql's tree.
#define TINYGLTF_IMPLEMENTATION
#include "ingest/import/tiny_gltf_config.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>

#include "ingest/import/export_support.hpp"
#include "ingest/import/importers.hpp"

namespace smql::import {

namespace {

using detail::kBoxTriangles;

constexpr int kIndexAccessor = 0;  // the 36 indices every box shares
constexpr std::size_t kIndicesBytes = kBoxTriangles.size() * 3 * sizeof(std::uint16_t);
constexpr std::size_t kBoxPositionBytes = 8 * 3 * sizeof(float);

// glTF is y-up, smql z-up, both right-handed in metres: (x, y, z) -> (x, z, -y), a quarter turn
// about x, baked into the positions so that every reader sees the room upright.
std::array<float, 3> toGltf(const model::Vec3& v) {
    return {static_cast<float>(v.x), static_cast<float>(v.z), static_cast<float>(-v.y)};
}

// glTF's colour factors are linear; the category colours are sRGB, as PLY and images hold them.
double linearChannel(std::uint8_t srgb) {
    double c = srgb / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

tinygltf::Value text(const std::string& value) { return tinygltf::Value(value); }

class GltfBuilder {
public:
    explicit GltfBuilder(const model::SceneData& scene) : scene_(scene), palette_(scene.nodes) {}

    tinygltf::Model build() {
        model_.asset.generator = "smql";
        tinygltf::Scene gltfScene;
        gltfScene.name = scene_.info.name;
        gltfScene.nodes = {0};
        model_.scenes.push_back(std::move(gltfScene));
        model_.defaultScene = 0;
        model_.accessors.emplace_back();  // the shared indices' accessor, filled by addBuffer
        addNodes();
        addBuffer();
        return std::move(model_);
    }

private:
    // Node 0 is the scene; smql's node i is glTF node i + 1, under its parent's glTF node.
    void addNodes() {
        tinygltf::Node root;
        root.name = scene_.info.name;
        root.extras = tinygltf::Value(tinygltf::Value::Object{{"scene", text(scene_.info.name)}});
        model_.nodes.push_back(std::move(root));
        std::map<model::NodeId, int> gltfIndexOf;
        for (std::size_t i = 0; i < scene_.nodes.size(); ++i)
            gltfIndexOf.emplace(scene_.nodes[i].id, static_cast<int>(i) + 1);

        std::vector<std::string> paths = model::nodePaths(scene_);
        for (std::size_t i = 0; i < scene_.nodes.size(); ++i) {
            const model::Node& node = scene_.nodes[i];
            tinygltf::Node gltfNode;
            gltfNode.name = model::nodeLabel(node);
            gltfNode.extras = extras(node, paths[i]);
            if (detail::isDrawn(node)) gltfNode.mesh = boxMesh(node);
            model_.nodes.push_back(std::move(gltfNode));
        }
        for (std::size_t i = 0; i < scene_.nodes.size(); ++i) {
            auto parent = gltfIndexOf.find(scene_.nodes[i].parent);
            int parentIndex = parent == gltfIndexOf.end() ? 0 : parent->second;
            model_.nodes[static_cast<std::size_t>(parentIndex)].children.push_back(static_cast<int>(i) + 1);
        }
    }

    static tinygltf::Value extras(const model::Node& node, const std::string& path) {
        tinygltf::Value::Object out{
            {"id", tinygltf::Value(static_cast<int>(node.id))},
            {"category", text(node.category)},
            {"kind", text(std::string(model::toString(node.kind)))},
            {"path", text(path)},
        };
        // Only when there are some: tinygltf writes an empty object as null.
        if (!node.attributes.empty()) {
            tinygltf::Value::Object attributes;
            for (const model::Attribute& a : node.attributes) attributes.emplace(a.name, text(a.value));
            out.emplace("attributes", tinygltf::Value(std::move(attributes)));
        }
        return tinygltf::Value(std::move(out));
    }

    // The box's eight corners as an accessor of its own; the triangles are the shared indices.
    int boxMesh(const model::Node& node) {
        std::array<float, 3> low{}, high{};
        std::array<model::Vec3, 8> corners = detail::boxCorners(node.box);
        for (std::size_t c = 0; c < corners.size(); ++c) {
            std::array<float, 3> p = toGltf(corners[c]);
            for (std::size_t axis = 0; axis < 3; ++axis) {
                low[axis] = c == 0 ? p[axis] : std::min(low[axis], p[axis]);
                high[axis] = c == 0 ? p[axis] : std::max(high[axis], p[axis]);
            }
            const auto* bytes = reinterpret_cast<const unsigned char*>(p.data());
            positions_.insert(positions_.end(), bytes, bytes + sizeof p);
        }
        tinygltf::Accessor accessor;
        accessor.bufferView = 1;
        accessor.byteOffset = positions_.size() - kBoxPositionBytes;
        accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
        accessor.count = corners.size();
        accessor.type = TINYGLTF_TYPE_VEC3;
        accessor.minValues = {low[0], low[1], low[2]};
        accessor.maxValues = {high[0], high[1], high[2]};
        model_.accessors.push_back(std::move(accessor));

        tinygltf::Primitive primitive;
        primitive.attributes["POSITION"] = static_cast<int>(model_.accessors.size()) - 1;
        primitive.indices = kIndexAccessor;
        primitive.material = material(node.category);
        primitive.mode = TINYGLTF_MODE_TRIANGLES;
        tinygltf::Mesh mesh;
        mesh.name = model::nodeLabel(node);
        mesh.primitives.push_back(std::move(primitive));
        model_.meshes.push_back(std::move(mesh));
        return static_cast<int>(model_.meshes.size()) - 1;
    }

    int material(const std::string& category) {
        auto [it, fresh] = materialOf_.emplace(category, static_cast<int>(model_.materials.size()));
        if (!fresh) return it->second;
        model::Rgb colour = palette_(category);
        tinygltf::Material m;
        m.name = category;
        m.pbrMetallicRoughness.baseColorFactor = {linearChannel(colour.r), linearChannel(colour.g),
                                                  linearChannel(colour.b), 1.0};
        m.pbrMetallicRoughness.metallicFactor = 0.0;
        model_.materials.push_back(std::move(m));
        return it->second;
    }

    // One buffer: the shared indices (view 0), then every box's corners (view 1).
    void addBuffer() {
        if (positions_.empty()) {
            model_.accessors.clear();  // a scene without boxes has no geometry at all
            return;
        }
        tinygltf::Buffer buffer;
        for (const auto& triangle : kBoxTriangles)
            for (std::uint16_t corner : triangle) {
                unsigned char bytes[sizeof corner];
                std::memcpy(bytes, &corner, sizeof corner);
                buffer.data.insert(buffer.data.end(), bytes, bytes + sizeof corner);
            }
        buffer.data.insert(buffer.data.end(), positions_.begin(), positions_.end());
        model_.buffers.push_back(std::move(buffer));

        tinygltf::BufferView indexView;
        indexView.buffer = 0;
        indexView.byteLength = kIndicesBytes;
        indexView.target = TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER;
        tinygltf::BufferView positionView;
        positionView.buffer = 0;
        positionView.byteOffset = kIndicesBytes;
        positionView.byteLength = positions_.size();
        positionView.byteStride = 3 * sizeof(float);  // required, as every box's accessor shares the view
        positionView.target = TINYGLTF_TARGET_ARRAY_BUFFER;
        model_.bufferViews = {indexView, positionView};

        tinygltf::Accessor& index = model_.accessors[kIndexAccessor];
        index.bufferView = 0;
        index.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
        index.count = kBoxTriangles.size() * 3;
        index.type = TINYGLTF_TYPE_SCALAR;
    }

    const model::SceneData& scene_;
    const model::Palette palette_;
    tinygltf::Model model_;
    std::vector<unsigned char> positions_;
    std::map<std::string, int> materialOf_;
};

std::string gltfBytes(const model::SceneData& scene, bool binary) {
    tinygltf::Model model = GltfBuilder(scene).build();
    tinygltf::TinyGLTF writer;
    std::ostringstream out;
    // Writing to memory cannot fail: the stream is a string.
    writer.WriteGltfSceneToStream(&model, out, /*prettyPrint=*/!binary, /*writeBinary=*/binary);
    return out.str();
}

}  // namespace

std::string writeGlb(const model::SceneData& scene) { return gltfBytes(scene, true); }

std::string writeGltf(const model::SceneData& scene) { return gltfBytes(scene, false); }

}  // namespace smql::import
