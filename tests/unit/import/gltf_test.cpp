// The glTF writer, read back with tinygltf's loader: nodes in smql's tree with their extras, one box
// mesh per drawn node in y-up coordinates, one material per category.
#include <cmath>
#include <cstring>
#include <map>
#include <set>

#include <catch2/catch.hpp>

#include "exported_scenes.hpp"
#include "ingest/import/export_support.hpp"
#include "ingest/import/importers.hpp"
#include "ingest/import/tiny_gltf_config.hpp"
#include "model/geometry.hpp"

using namespace smql;
using Catch::Detail::Approx;
using import::test::replicaScene;
using import::test::roomsScene;

namespace {

tinygltf::Model loadGlb(const std::string& bytes) {
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string error, warning;
    bool loaded =
        loader.LoadBinaryFromMemory(&model, &error, &warning, reinterpret_cast<const unsigned char*>(bytes.data()),
                                    static_cast<unsigned int>(bytes.size()));
    INFO("error: " << error << "\nwarning: " << warning);
    REQUIRE(loaded);
    CHECK(warning.empty());
    return model;
}

// The accessor's eight positions, turned back from glTF's y up to smql's z up.
std::vector<model::Vec3> cornersOf(const tinygltf::Model& model, int accessorIndex) {
    const tinygltf::Accessor& accessor = model.accessors.at(static_cast<std::size_t>(accessorIndex));
    const tinygltf::BufferView& view = model.bufferViews.at(static_cast<std::size_t>(accessor.bufferView));
    const unsigned char* data = model.buffers.at(0).data.data() + view.byteOffset + accessor.byteOffset;
    std::vector<model::Vec3> corners;
    for (std::size_t i = 0; i < accessor.count; ++i) {
        float p[3];
        std::memcpy(p, data + i * sizeof p, sizeof p);
        corners.push_back({p[0], -p[2], p[1]});
    }
    return corners;
}

}  // namespace

TEST_CASE("glb: the Replica room as smql's tree of nodes with box meshes", "[import][gltf]") {
    model::SceneData scene = replicaScene();
    tinygltf::Model model = loadGlb(import::writeGlb(scene));

    REQUIRE(model.nodes.size() == scene.nodes.size() + 1);
    REQUIRE(model.scenes.size() == 1);
    CHECK(model.scenes[0].nodes == std::vector<int>{0});
    CHECK(model.nodes[0].name == "replica-room0");

    std::map<int, int> parentOf;  // glTF node -> its parent node
    for (std::size_t i = 0; i < model.nodes.size(); ++i)
        for (int child : model.nodes[i].children) CHECK(parentOf.emplace(child, static_cast<int>(i)).second);
    std::size_t drawn = 0, nested = 0;
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
        const model::Node& n = scene.nodes[i];
        const tinygltf::Node& g = model.nodes[i + 1];
        CHECK(g.name == n.category + "#" + std::to_string(n.id));
        CHECK(parentOf.at(static_cast<int>(i) + 1) == static_cast<int>(n.parent));  // smql id k is glTF node k
        nested += n.parent != model::kNoNode;
        CHECK(g.extras.Get("id").Get<int>() == static_cast<int>(n.id));
        CHECK(g.extras.Get("category").Get<std::string>() == n.category);
        CHECK(g.extras.Get("kind").Get<std::string>() == model::toString(n.kind));
        CHECK(g.extras.Has("attributes") == !n.attributes.empty());
        CHECK((g.mesh >= 0) == import::detail::isDrawn(n));
        if (g.mesh < 0) continue;
        ++drawn;
        const tinygltf::Primitive& primitive = model.meshes.at(static_cast<std::size_t>(g.mesh)).primitives.at(0);
        CHECK(model.materials.at(static_cast<std::size_t>(primitive.material)).name == n.category);
        CHECK(model.accessors.at(static_cast<std::size_t>(primitive.indices)).count == 36);
        std::vector<model::Vec3> corners = cornersOf(model, primitive.attributes.at("POSITION"));
        std::array<model::Vec3, 8> expected = import::detail::boxCorners(n.box);
        REQUIRE(corners.size() == 8);
        for (std::size_t c = 0; c < 8; ++c) {
            CHECK(corners[c].x == Approx(expected[c].x).margin(1e-5));
            CHECK(corners[c].y == Approx(expected[c].y).margin(1e-5));
            CHECK(corners[c].z == Approx(expected[c].z).margin(1e-5));
        }
    }
    CHECK(drawn == 79);  // 92 nodes less 12 hidden `undefined` parts and the ceiling
    CHECK(nested > 0);
    CHECK(model.meshes.size() == drawn);

    // One material per category, coloured as the category's colour (linear in glTF).
    std::set<std::string> categories;
    for (const model::Node& n : scene.nodes)
        if (import::detail::isDrawn(n)) categories.insert(n.category);
    CHECK(model.materials.size() == categories.size());
    for (const tinygltf::Material& m : model.materials) {
        INFO(m.name);
        CHECK(categories.count(m.name) == 1);
        double red = model::Palette(scene.nodes)(m.name).r / 255.0;
        double linear = red <= 0.04045 ? red / 12.92 : std::pow((red + 0.055) / 1.055, 2.4);
        CHECK(m.pbrMetallicRoughness.baseColorFactor.at(0) == Approx(linear));
    }
}

TEST_CASE("glb: extras hold the node's path from the scene down and its attributes", "[import][gltf]") {
    model::SceneData scene = roomsScene();
    tinygltf::Model model = loadGlb(import::writeGlb(scene));
    const tinygltf::Node& mug = model.nodes.at(5);
    CHECK(mug.name == "mug#5");
    CHECK(mug.extras.Get("path").Get<std::string>() == "flat / kitchen#1 / wall#3 / table#4 / mug#5");
    const tinygltf::Node& chair = model.nodes.at(8);
    CHECK(chair.extras.Get("attributes").Get("color").Get<std::string>() == "red");
    CHECK(chair.extras.Get("attributes").Get("material").Get<std::string>() == "wood");
    // Rooms, the hidden part and the ceiling are nodes of the tree without a mesh.
    for (int undrawn : {1, 2, 6, 7}) CHECK(model.nodes.at(static_cast<std::size_t>(undrawn)).mesh == -1);
    CHECK(model.meshes.size() == 4);
    // The wall stands from 0 to 2.5 m: glTF's y.
    const tinygltf::Accessor& wall = model.accessors.at(static_cast<std::size_t>(
        model.meshes.at(static_cast<std::size_t>(model.nodes.at(3).mesh)).primitives.at(0).attributes.at("POSITION")));
    CHECK(wall.minValues.at(1) == Approx(0.0));
    CHECK(wall.maxValues.at(1) == Approx(2.5));
}

TEST_CASE("gltf: the same asset as JSON with the buffer inside", "[import][gltf]") {
    model::SceneData scene = roomsScene();
    std::string text = import::writeGltf(scene);
    CHECK_THAT(text, Catch::Contains("\"uri\": \"data:application/octet-stream;base64,"));
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string error, warning;
    REQUIRE(
        loader.LoadASCIIFromString(&model, &error, &warning, text.data(), static_cast<unsigned int>(text.size()), ""));
    CHECK(model.nodes.size() == scene.nodes.size() + 1);
    CHECK(model.meshes.size() == 4);
}

TEST_CASE("glb: a scene without boxes is a tree of nodes and no geometry", "[import][gltf]") {
    model::SceneData scene = roomsScene();
    scene.nodes.resize(2);  // the two rooms
    tinygltf::Model model = loadGlb(import::writeGlb(scene));
    CHECK(model.nodes.size() == 3);
    CHECK(model.meshes.empty());
    CHECK(model.accessors.empty());
    CHECK(model.buffers.empty());
}
