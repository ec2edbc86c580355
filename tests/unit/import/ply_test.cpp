// The PLY writer, read back as a PLY reader reads it: the header, then 8 coloured vertices and 12
// triangles a box, wound so that every box encloses a positive volume.
#include <algorithm>
#include <bit>
#include <cstring>
#include <sstream>

#include <catch2/catch.hpp>

#include "exported_scenes.hpp"
#include "ingest/import/export_support.hpp"
#include "ingest/import/importers.hpp"
#include "model/geometry.hpp"

using namespace smql;
using Catch::Detail::Approx;

namespace {

struct Vertex {
    model::Vec3 position;
    model::Rgb colour;
};

struct PlyMesh {
    std::vector<std::string> headerLines;
    std::vector<Vertex> vertices;
    std::vector<std::array<std::uint32_t, 3>> faces;
};

std::uint32_t littleEndian(const std::string& bytes, std::size_t& at) {
    std::uint32_t value = 0;
    for (int i = 0; i < 4; ++i) value |= std::uint32_t(static_cast<unsigned char>(bytes.at(at++))) << (8 * i);
    return value;
}

PlyMesh parsePly(const std::string& bytes) {
    PlyMesh mesh;
    std::size_t end = bytes.find("end_header\n");
    REQUIRE(end != std::string::npos);
    std::istringstream header(bytes.substr(0, end));
    for (std::string line; std::getline(header, line);) mesh.headerLines.push_back(line);
    std::size_t vertexCount = 0, faceCount = 0;
    for (const std::string& line : mesh.headerLines) {
        if (line.rfind("element vertex ", 0) == 0) vertexCount = std::stoul(line.substr(15));
        if (line.rfind("element face ", 0) == 0) faceCount = std::stoul(line.substr(13));
    }
    std::size_t at = end + std::strlen("end_header\n");
    for (std::size_t v = 0; v < vertexCount; ++v) {
        Vertex vertex;
        vertex.position.x = std::bit_cast<float>(littleEndian(bytes, at));
        vertex.position.y = std::bit_cast<float>(littleEndian(bytes, at));
        vertex.position.z = std::bit_cast<float>(littleEndian(bytes, at));
        vertex.colour = {static_cast<std::uint8_t>(bytes.at(at)), static_cast<std::uint8_t>(bytes.at(at + 1)),
                         static_cast<std::uint8_t>(bytes.at(at + 2))};
        at += 3;
        mesh.vertices.push_back(vertex);
    }
    for (std::size_t f = 0; f < faceCount; ++f) {
        REQUIRE(bytes.at(at++) == 3);
        mesh.faces.push_back({littleEndian(bytes, at), littleEndian(bytes, at), littleEndian(bytes, at)});
    }
    CHECK(at == bytes.size());
    return mesh;
}

// The volume a closed triangle mesh encloses (divergence theorem), the sum of the tetrahedra from
// the box's centre to its triangles: each positive when its triangle is counter-clockwise seen from
// outside, so that every face must be wound outward for the sum to be the box's volume. Measured
// from the centre also keeps the float coordinates' rounding far from the origin small.
double signedVolume(const PlyMesh& mesh, std::size_t firstFace, std::size_t faceCount, const model::Vec3& centre) {
    auto corner = [&](std::size_t f, int k) {
        const model::Vec3& p = mesh.vertices.at(mesh.faces[f][k]).position;
        return model::Vec3{p.x - centre.x, p.y - centre.y, p.z - centre.z};
    };
    double volume = 0;
    for (std::size_t f = firstFace; f < firstFace + faceCount; ++f) {
        model::Vec3 a = corner(f, 0), b = corner(f, 1), c = corner(f, 2);
        double tetrahedron =
            (a.x * (b.y * c.z - b.z * c.y) - a.y * (b.x * c.z - b.z * c.x) + a.z * (b.x * c.y - b.y * c.x)) / 6;
        CHECK(tetrahedron > 0);
        volume += tetrahedron;
    }
    return volume;
}

}  // namespace

TEST_CASE("ply: the Replica room's boxes as one coloured triangle mesh", "[import][ply]") {
    model::SceneData scene = import::test::replicaScene();
    std::vector<const model::Node*> boxes;
    for (const model::Node& n : scene.nodes)
        if (import::detail::isDrawn(n)) boxes.push_back(&n);
    REQUIRE(boxes.size() == 79);

    PlyMesh mesh = parsePly(import::writePly(scene));
    CHECK(mesh.headerLines.at(0) == "ply");
    CHECK(mesh.headerLines.at(1) == "format binary_little_endian 1.0");
    CHECK(mesh.headerLines.at(2) == "comment smql scene replica-room0: 79 boxes, metres, z up");
    CHECK(mesh.headerLines.at(3) == "comment box 0 " + model::nodeLabel(*boxes[0]));
    REQUIRE(mesh.vertices.size() == 8 * boxes.size());
    REQUIRE(mesh.faces.size() == 12 * boxes.size());

    for (std::size_t k = 0; k < boxes.size(); ++k) {
        const model::Node& n = *boxes[k];
        INFO(model::nodeLabel(n));
        std::array<model::Vec3, 8> corners = import::detail::boxCorners(n.box);
        for (std::size_t c = 0; c < 8; ++c) {
            const Vertex& v = mesh.vertices[8 * k + c];
            CHECK(v.position.x == Approx(corners[c].x).margin(1e-5));
            CHECK(v.position.y == Approx(corners[c].y).margin(1e-5));
            CHECK(v.position.z == Approx(corners[c].z).margin(1e-5));
            CHECK(v.colour == model::Palette(scene.nodes)(n.category));
        }
        for (std::size_t f = 12 * k; f < 12 * (k + 1); ++f)
            for (std::uint32_t index : mesh.faces[f]) CHECK((index >= 8 * k && index < 8 * (k + 1)));
        CHECK(signedVolume(mesh, 12 * k, 12, n.box.center) == Approx(model::volume(n.box)).epsilon(1e-3));
    }
}

TEST_CASE("ply: a scene without boxes is a valid empty mesh", "[import][ply]") {
    model::SceneData scene = import::test::roomsScene();
    scene.nodes.resize(2);
    PlyMesh mesh = parsePly(import::writePly(scene));
    CHECK(mesh.vertices.empty());
    CHECK(mesh.faces.empty());
    CHECK(std::count(mesh.headerLines.begin(), mesh.headerLines.end(), "element vertex 0") == 1);
}
