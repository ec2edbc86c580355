// The GeoJSON writer: a FeatureCollection of one footprint Polygon per drawn box, rings closed and
// counter-clockwise (RFC 7946), properties naming the node.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "exported_scenes.hpp"
#include "ingest/import/export_support.hpp"
#include "ingest/import/importers.hpp"
#include "model/geometry.hpp"

using namespace smql;
using Catch::Detail::Approx;
using Json = nlohmann::json;

namespace {

// Twice the signed area (shoelace): positive for a counter-clockwise ring.
double ringArea(const Json& ring) {
    double twice = 0;
    for (std::size_t i = 0; i + 1 < ring.size(); ++i)
        twice += ring[i][0].get<double>() * ring[i + 1][1].get<double>() -
                 ring[i + 1][0].get<double>() * ring[i][1].get<double>();
    return twice / 2;
}

}  // namespace

TEST_CASE("geojson: the Replica room's floor plan", "[import][geojson]") {
    model::SceneData scene = import::test::replicaScene();
    Json plan = Json::parse(import::writeGeoJson(scene));
    CHECK(plan.at("type") == "FeatureCollection");
    CHECK(plan.at("name") == "replica-room0");
    CHECK_FALSE(plan.contains("crs"));

    std::vector<std::string> paths = model::nodePaths(scene);
    std::size_t next = 0;
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
        const model::Node& n = scene.nodes[i];
        if (!import::detail::isDrawn(n)) continue;
        REQUIRE(next < plan.at("features").size());
        const Json& feature = plan.at("features")[next++];
        INFO(model::nodeLabel(n));
        CHECK(feature.at("type") == "Feature");
        CHECK(feature.at("id") == n.id);
        CHECK(feature.at("geometry").at("type") == "Polygon");
        const Json& ring = feature.at("geometry").at("coordinates").at(0);
        REQUIRE(ring.size() == 5);
        CHECK(ring.front() == ring.back());
        CHECK(ringArea(ring) == Approx(model::footprintArea(n.box)));
        CHECK(ring[0][0].get<double>() == Approx(model::footprint(n.box)[0].x));

        const Json& properties = feature.at("properties");
        CHECK(properties.at("id") == n.id);
        CHECK(properties.at("category") == n.category);
        CHECK(properties.at("kind") == model::toString(n.kind));
        CHECK(properties.at("path") == paths[i]);
        CHECK(properties.at("z_min").get<double>() == Approx(model::bottom(n.box)));
        CHECK(properties.at("z_max").get<double>() == Approx(model::top(n.box)));
        CHECK(properties.at("attributes").is_object());
    }
    CHECK(next == 79);
    CHECK(plan.at("features").size() == 79);
}

TEST_CASE("geojson: attributes and paths of nested nodes", "[import][geojson]") {
    Json plan = Json::parse(import::writeGeoJson(import::test::roomsScene()));
    REQUIRE(plan.at("features").size() == 4);  // wall, table, mug, chair
    const Json& mug = plan.at("features")[2].at("properties");
    CHECK(mug.at("path") == "flat / kitchen#1 / wall#3 / table#4 / mug#5");
    CHECK(mug.at("z_min").get<double>() == Approx(0.75));
    const Json& chair = plan.at("features")[3].at("properties");
    CHECK(chair.at("attributes") == Json{{"color", "red"}, {"material", "wood"}});
}
