// The import registry: every format by name, the scene's default name per format, and an unknown
// format as a usage error that names the known ones.
#include <catch2/catch.hpp>

#include "import_support.hpp"
#include "ingest/import/importers.hpp"
#include "ingest/import/registry.hpp"
#include "model/error.hpp"

using namespace smql;
using import::test::TempDir;

namespace {
constexpr const char* kLayout = "wall_0=Wall(0,0,0,4,0,0,2.5,0)\nbbox_0=Bbox(sofa,1,2.5,0.45,0,2.0,0.9,0.9)\n";
}

TEST_CASE("the registry reads every format it lists, naming scenes by each format's rule") {
    TempDir dir;
    std::string layout = dir.write("kitchen.txt", kLayout);
    auto byDefault = import::read("spatiallm", layout);
    CHECK(byDefault.info.name == "kitchen");
    CHECK(import::read("spatiallm", layout, "mine").info.name == "mine");

    std::string replica = std::string(SMQL_SHARED_DATA) + "/replica-room0/info_semantic.json";
    CHECK(import::read("replica", replica).info.name == "replica-room0");

    // smql JSON keeps the name inside the file unless one is given.
    std::string json = dir.write("exported.json", import::writeSceneJson(byDefault));
    CHECK(import::read("json", json).info.name == "kitchen");
    CHECK(import::read("json", json, "renamed").info.name == "renamed");

    std::vector<std::string> listed;
    for (const auto& f : import::formats())
        if (f.read) listed.emplace_back(f.name);
    CHECK(listed == import::readableFormats());
    CHECK(import::writableFormats() == std::vector<std::string>{"json", "spark-dsg", "glb", "gltf", "ply", "geojson"});
    CHECK(import::readableFormats() ==
          std::vector<std::string>{"replica", "spatiallm", "json", "vsibench", "spark-dsg"});
    CHECK(import::read("json", dir.write("again.json", import::write("json", byDefault))).info.name == "kitchen");
    CHECK_THROWS_WITH(import::write("jsn", byDefault), "unknown export format 'jsn'");
    // A format smql only writes is no import format: the did-you-mean stays among the readable ones.
    CHECK_THROWS_WITH(import::read("glb", layout), "unknown import format 'glb'");
    CHECK(import::findFormat("replica") != nullptr);
}

TEST_CASE("an unknown import format is a usage error naming the formats") {
    TempDir dir;
    std::string layout = dir.write("kitchen.txt", kLayout);
    try {
        import::read("spatialml", layout);
        FAIL("expected an error");
    } catch (const Error& e) {
        CHECK(e.kind() == ErrorKind::Usage);
        CHECK(e.message() == "unknown import format 'spatialml'");
        CHECK(e.hint() == "did you mean spatiallm?");
    }
    CHECK_THROWS_AS(import::read("", layout), Error);
}
