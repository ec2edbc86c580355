// `smql synth`: the rendered depth, masks and poses agree with the truth boxes
// (checked by casting rays here, independently of the rasterizer), the files
// parse and agree with each other, and a seed gives byte-identical files.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "ingest/capture/capture.hpp"
#include "ingest/capture/detections.hpp"
#include "ingest/import/importers.hpp"
#include "ingest/synth/palette.hpp"
#include "ingest/synth/render.hpp"
#include "ingest/synth/synth.hpp"
#include "ingest/synth/walk.hpp"
#include "model/error.hpp"
#include "model/geometry.hpp"
#include "scratch_dir.hpp"

namespace fs = std::filesystem;
using namespace smql;
using Json = nlohmann::json;

namespace {

std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

struct V {
    double x = 0, y = 0, z = 0;
};
V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V operator*(double s, V a) { return {s * a.x, s * a.y, s * a.z}; }

V rotate(const ingest::Pose& pose, V p) {
    const auto& r = pose.rotation;
    return {r[0] * p.x + r[1] * p.y + r[2] * p.z, r[3] * p.x + r[4] * p.y + r[5] * p.z,
            r[6] * p.x + r[7] * p.y + r[8] * p.z};
}
V origin(const ingest::Pose& pose) { return {pose.translation.x, pose.translation.y, pose.translation.z}; }

// The camera ray through pixel (u, v): in world coordinates, with camera z = 1 per unit of t.
V rayDirection(const ingest::Intrinsics& K, const ingest::Pose& pose, double u, double v) {
    return rotate(pose, {(u - K.cx) / K.fx, (v - K.cy) / K.fy, 1.0});
}

// Slab test in the box's own frame; the entry parameter when the ray starts outside.
std::optional<double> rayBox(V o, V d, const model::Box& box) {
    double c = std::cos(box.yaw), s = std::sin(box.yaw);
    V rel = o - V{box.center.x, box.center.y, box.center.z};
    double lo[3] = {c * rel.x + s * rel.y, -s * rel.x + c * rel.y, rel.z};
    double ld[3] = {c * d.x + s * d.y, -s * d.x + c * d.y, d.z};
    double half[3] = {box.size.x / 2, box.size.y / 2, box.size.z / 2};
    double enter = -std::numeric_limits<double>::infinity(), exit = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i) {
        if (std::abs(ld[i]) < 1e-15) {
            if (std::abs(lo[i]) > half[i]) return std::nullopt;
            continue;
        }
        double t0 = (-half[i] - lo[i]) / ld[i], t1 = (half[i] - lo[i]) / ld[i];
        if (t0 > t1) std::swap(t0, t1);
        enter = std::max(enter, t0);
        exit = std::min(exit, t1);
    }
    if (enter > exit || enter <= 0) return std::nullopt;
    return enter;
}

struct Hits {
    double first = std::numeric_limits<double>::infinity(), second = std::numeric_limits<double>::infinity();
    model::NodeId id = 0;
};

Hits castRay(const std::vector<synth::Surface>& surfaces, V o, V d) {
    Hits h;
    for (const synth::Surface& s : surfaces) {
        auto t = rayBox(o, d, s.box);
        if (!t) continue;
        if (*t < h.first) {
            h.second = h.first;
            h.first = *t;
            h.id = s.id;
        } else if (*t < h.second) {
            h.second = *t;
        }
    }
    return h;
}

double pointBoxDistance(V p, const model::Box& box) {
    double c = std::cos(box.yaw), s = std::sin(box.yaw);
    V rel = p - V{box.center.x, box.center.y, box.center.z};
    double lx = c * rel.x + s * rel.y, ly = -s * rel.x + c * rel.y;
    double ex = std::max(0.0, std::abs(lx) - box.size.x / 2), ey = std::max(0.0, std::abs(ly) - box.size.y / 2),
           ez = std::max(0.0, std::abs(rel.z) - box.size.z / 2);
    return std::sqrt(ex * ex + ey * ey + ez * ez);
}

// One capture shared by the tests that only read it.
struct Fixture {
    ingest::test::ScratchDir dir;
    synth::SynthOptions options{.seed = 3, .frames = 8, .objects = 24};
    synth::SynthResult result;
    std::vector<synth::Surface> surfaces;
    Fixture() {
        result = synth::writeSynth((dir.path / "capture").string(), options);
        surfaces = synth::surfacesOf(result.scene.truth);
    }
    fs::path file(const std::string& name) const { return (dir.path / "capture") / name; }
    synth::Image image(const std::string& kind, int frame) const {
        return synth::readImage(file(kind + "/" + std::to_string(frame) + ".png").string());
    }
    const model::Node& node(model::NodeId id) const {
        for (const model::Node& n : result.scene.truth.nodes)
            if (n.id == id) return n;
        throw std::runtime_error("no node " + std::to_string(id));
    }
};

const Fixture& fixture() {
    static Fixture f;
    return f;
}

}  // namespace

TEST_CASE("synth: the palette keeps names apart under shading", "[ingest][synth]") {
    for (const synth::NamedColor& c : synth::namedColors()) {
        for (int percent = 78; percent <= 105; ++percent) {
            double s = percent / 100.0;
            INFO(c.name << " x " << s);
            CHECK(synth::nearestColorName(std::min(255.0, c.rgb.r * s), std::min(255.0, c.rgb.g * s),
                                          std::min(255.0, c.rgb.b * s)) == c.name);
        }
        REQUIRE(synth::colorByName(c.name) == c.rgb);
    }
    for (const char* name :
         {"red", "orange", "yellow", "green", "blue", "purple", "pink", "brown", "black", "white", "gray", "grey"})
        CHECK(synth::colorByName(name).has_value());
    CHECK_FALSE(synth::colorByName("taupe").has_value());
}

TEST_CASE("synth: the texture has mean about 1 and the promised contrast", "[ingest][synth]") {
    double sum = 0, lo = 10, hi = 0;
    int n = 0;
    for (int i = 0; i < 200; ++i)
        for (int j = 0; j < 200; ++j) {
            double f = synth::textureFactor({i * 0.0071, j * 0.0053, 1.3}, 17, 0.002);
            sum += f, ++n, lo = std::min(lo, f), hi = std::max(hi, f);
        }
    CHECK(sum / n == Approx(1.0).margin(0.03));
    CHECK(lo >= 0.78 - 1e-9);
    CHECK(hi <= 1.22 + 1e-9);
    CHECK(hi - lo > 0.3);
    // Seen from far away, the fine octaves fade out rather than alias.
    CHECK(synth::textureFactor({0.3, 0.4, 0.5}, 17, 1.0) == 1.0);
}

TEST_CASE("synth: doors and windows are drawn just inside their wall", "[ingest][synth]") {
    const Fixture& f = fixture();
    const auto& nodes = f.result.scene.truth.nodes;
    model::Vec3 floorCenter;
    for (const model::Node& n : nodes)
        if (n.category == "floor") floorCenter = n.box.center;
    int panels = 0;
    REQUIRE(f.surfaces.size() == nodes.size());
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const model::Box& truth = nodes[i].box;
        const model::Box& drawn = f.surfaces[i].box;
        REQUIRE(f.surfaces[i].id == nodes[i].id);
        CHECK(drawn.size == truth.size);
        CHECK(drawn.yaw == truth.yaw);
        if (nodes[i].category != "door" && nodes[i].category != "window") {
            CHECK(drawn.center == truth.center);
            continue;
        }
        ++panels;
        double dx = drawn.center.x - truth.center.x, dy = drawn.center.y - truth.center.y;
        CHECK(std::hypot(dx, dy) == Approx(synth::kPanelOffset).margin(1e-12));
        CHECK(drawn.center.z == truth.center.z);
        // Towards the room's interior.
        CHECK(dx * (floorCenter.x - truth.center.x) + dy * (floorCenter.y - truth.center.y) > 0);
    }
    CHECK(panels >= 2);
}

TEST_CASE("synth: depth at the image centre is the distance to the first box on the ray", "[ingest][synth]") {
    const Fixture& f = fixture();
    const ingest::Intrinsics& K = f.result.intrinsics;
    REQUIRE(f.result.scene.poses.size() == 8);
    for (int frame = 1; frame <= 8; ++frame) {
        const ingest::Pose& pose = f.result.scene.poses[frame - 1];
        synth::Image depth = f.image("depth", frame), instance = f.image("instance", frame);
        REQUIRE(depth.width == 640);
        REQUIRE(depth.height == 480);
        REQUIRE(depth.channels == 1);
        const int u = 320, v = 240;
        Hits hit = castRay(f.surfaces, origin(pose), rayDirection(K, pose, u, v));
        INFO("frame " << frame);
        REQUIRE(std::isfinite(hit.first));
        CHECK(depth.at(u, v) / 1000.0 == Approx(hit.first).margin(0.01));
        CHECK(instance.at(u, v) == hit.id);
    }
}

TEST_CASE("synth: masks and depth agree with rays cast against the boxes", "[ingest][synth]") {
    const Fixture& f = fixture();
    const ingest::Intrinsics& K = f.result.intrinsics;
    int sampled = 0, idMismatch = 0, depthMismatch = 0;
    for (int frame = 1; frame <= 8; frame += 3) {
        const ingest::Pose& pose = f.result.scene.poses[frame - 1];
        synth::Image depth = f.image("depth", frame), instance = f.image("instance", frame);
        for (int v = 3; v < K.height; v += 7) {
            for (int u = 2; u < K.width; u += 7) {
                Hits hit = castRay(f.surfaces, origin(pose), rayDirection(K, pose, u, v));
                if (hit.second - hit.first < 0.002) continue;  // two surfaces meet here: either may win
                ++sampled;
                if (instance.at(u, v) != hit.id) {
                    ++idMismatch;
                    UNSCOPED_INFO("frame " << frame << " pixel " << u << "," << v << ": mask " << instance.at(u, v)
                                           << ", ray " << hit.id);
                }
                double expected = hit.first <= synth::kMaxDepth ? hit.first : 0.0;
                if (std::abs(depth.at(u, v) / 1000.0 - expected) > 0.01) ++depthMismatch;
            }
        }
    }
    CHECK(sampled > 10000);
    CHECK(idMismatch <= sampled / 1000);
    CHECK(depthMismatch <= sampled / 1000);
}

TEST_CASE("synth: depth pixels back-project into their instance's truth box", "[ingest][synth]") {
    const Fixture& f = fixture();
    const ingest::Intrinsics& K = f.result.intrinsics;
    std::map<model::NodeId, const model::Node*> byId;
    for (const model::Node& n : f.result.scene.truth.nodes) byId[n.id] = &n;
    for (int frame = 1; frame <= 8; frame += 2) {
        const ingest::Pose& pose = f.result.scene.poses[frame - 1];
        synth::Image depth = f.image("depth", frame), instance = f.image("instance", frame);
        std::map<model::NodeId, std::pair<int, int>> counts;  // id -> (inside, all)
        for (int v = 0; v < K.height; ++v) {
            for (int u = 0; u < K.width; ++u) {
                model::NodeId id = instance.at(u, v);
                if (id == 0 || depth.at(u, v) == 0) continue;
                REQUIRE(byId.count(id));
                double z = depth.at(u, v) / 1000.0;
                V p = origin(pose) + z * rayDirection(K, pose, u, v);
                auto& [inside, all] = counts[id];
                ++all;
                if (pointBoxDistance(p, byId[id]->box) <= 0.02) ++inside;
            }
        }
        CHECK(counts.size() >= 8);
        for (const auto& [id, c] : counts) {
            INFO("frame " << frame << " instance " << id << " (" << byId[id]->category << "): " << c.first << " of "
                          << c.second << " pixels inside");
            CHECK(c.first > 0.95 * c.second);
        }
    }
}

TEST_CASE("synth: pose.txt gives back the cameras that were rendered", "[ingest][synth]") {
    const Fixture& f = fixture();
    std::ifstream in(f.file("pose.txt"));
    std::string line;
    std::size_t n = 0;
    while (std::getline(in, line)) {
        REQUIRE(n < f.result.scene.poses.size());
        const ingest::Pose& rendered = f.result.scene.poses[n++];
        std::istringstream fields(line);
        double tx, ty, tz, qx, qy, qz, qw;
        REQUIRE(fields >> tx >> ty >> tz >> qx >> qy >> qz >> qw);
        double norm = std::sqrt(qx * qx + qy * qy + qz * qz + qw * qw);
        CHECK(norm == Approx(1.0).margin(1e-8));
        qx /= norm, qy /= norm, qz /= norm, qw /= norm;
        // Camera-to-world rotation of a unit quaternion (x, y, z, w), row-major.
        double R[9] = {1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw),     2 * (qx * qz + qy * qw),
                       2 * (qx * qy + qz * qw),     1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw),
                       2 * (qx * qz - qy * qw),     2 * (qy * qz + qx * qw),     1 - 2 * (qx * qx + qy * qy)};
        for (int i = 0; i < 9; ++i) CHECK(R[i] == Approx(rendered.rotation[i]).margin(1e-9));
        CHECK(tx == Approx(rendered.translation.x).margin(1e-9));
        CHECK(ty == Approx(rendered.translation.y).margin(1e-9));
        CHECK(tz == Approx(rendered.translation.z).margin(1e-9));
        // A person with a phone: about 1.55 m up, looking down a little (+z of the camera), level (+x horizontal-ish).
        CHECK(tz == Approx(1.55).margin(0.05));
        CHECK(R[8] < -std::sin(8.0 * M_PI / 180));
        CHECK(R[8] > -std::sin(22.0 * M_PI / 180));
        CHECK(std::abs(R[6]) < 0.05);
        // OpenCV axes: y points down the world.
        CHECK(R[7] < -0.9);
        // The text written and the parser used by the renderer agree.
        ingest::Pose parsed = synth::parsePoseLine(line);
        CHECK(synth::poseLine(parsed) == line);
    }
    CHECK(n == f.result.scene.poses.size());
}

TEST_CASE("synth: the walk starts at the door and keeps clear of furniture", "[ingest][synth]") {
    const Fixture& f = fixture();
    const auto& truth = f.result.scene.truth;
    const auto& poses = f.result.scene.poses;
    for (const model::Node& n : truth.nodes)
        if (n.category == "door")
            CHECK(std::hypot(poses[0].translation.x - n.box.center.x, poses[0].translation.y - n.box.center.y) < 1.6);
    model::Aabb room{};
    for (const model::Node& n : truth.nodes)
        if (n.category == "floor") room = model::worldAabb(n.box);
    // A longer walk over a bigger room.
    auto walk = synth::planWalk(truth, {.frames = 120, .seed = 3});
    REQUIRE(walk.size() == 120);
    for (const ingest::Pose& pose : walk) {
        V p = origin(pose);
        CHECK(p.x > room.min.x + 0.3);
        CHECK(p.x < room.max.x - 0.3);
        CHECK(p.y > room.min.y + 0.3);
        CHECK(p.y < room.max.y - 0.3);
        for (const model::Node& n : truth.nodes)
            if (n.kind == model::NodeKind::Object) CHECK(pointBoxDistance(p, n.box) > 0.2);
    }
    // Consecutive frames are close (a walk, not a jump cut).
    for (std::size_t i = 1; i < walk.size(); ++i) {
        double step = std::hypot(walk[i].translation.x - walk[i - 1].translation.x,
                                 walk[i].translation.y - walk[i - 1].translation.y);
        CHECK(step < 0.6);
    }
}

TEST_CASE("synth: labels, truth, relations and visibility agree", "[ingest][synth]") {
    const Fixture& f = fixture();
    model::SceneData truth = import::readSceneJson(f.file("truth.json").string());
    CHECK(truth.info.name == "synth-3");
    CHECK(truth.nodes == f.result.scene.truth.nodes);
    std::map<model::NodeId, const model::Node*> byId;
    for (const model::Node& n : truth.nodes) byId[n.id] = &n;
    int objects = 0;
    for (const model::Node& n : truth.nodes) {
        if (n.kind != model::NodeKind::Object) continue;
        ++objects;
        CHECK(n.parent != model::kNoNode);
        REQUIRE(n.attribute("color"));
        CHECK(synth::colorByName(*n.attribute("color")).has_value());
    }
    CHECK(objects == 24);

    Json camera = Json::parse(slurp(f.file("camera.json")));
    CHECK(camera ==
          Json::parse(R"({"width":640,"height":480,"fx":525,"fy":525,"cx":319.5,"cy":239.5,"depth_scale":1000})"));

    Json labels = Json::parse(slurp(f.file("labels.json")));
    std::set<model::NodeId> labelled;
    for (const Json& l : labels.at("instances")) {
        model::NodeId id = l.at("id").get<model::NodeId>();
        REQUIRE(byId.count(id));
        const model::Node& n = *byId[id];
        CHECK(l.at("category") == n.category);
        CHECK(l.at("kind") == std::string(model::toString(n.kind)));
        if (const std::string* color = n.attribute("color"))
            CHECK(l.at("color") == *color);
        else
            CHECK_FALSE(l.contains("color"));
        CHECK(labelled.insert(id).second);
    }
    for (const model::Node& n : truth.nodes)
        CHECK(labelled.count(n.id) == (n.geometry != model::GeometryKind::None ? 1u : 0u));

    Json relations = Json::parse(slurp(f.file("relations.json")));
    int on = 0, near = 0;
    for (const Json& r : relations.at("relationships")) {
        REQUIRE(r.size() == 4);
        model::NodeId s = r[0].get<model::NodeId>(), o = r[1].get<model::NodeId>();
        REQUIRE(byId.count(s));
        REQUIRE(byId.count(o));
        const model::Node &a = *byId[s], &b = *byId[o];
        CHECK(a.kind == model::NodeKind::Object);
        CHECK(b.kind == model::NodeKind::Object);
        std::string predicate = r[3];
        if (predicate == "on") {
            ++on;
            CHECK(r[2] == 30);
            CHECK(model::bottom(a.box) == Approx(model::top(b.box)).margin(1e-9));
            CHECK(model::footprintContains(b.box, {a.box.center.x, a.box.center.y}));
            CHECK(a.parent == b.id);  // the tree the truth carries agrees with how it was built
        } else if (predicate == "near") {
            ++near;
            CHECK(r[2] == 28);
            CHECK(model::distance(a.box, b.box) <= 0.5);
        } else {
            CHECK(predicate == "in");
            CHECK(r[2] == 21);
        }
    }
    CHECK(on > 5);
    CHECK(near > 5);

    Json visibility = Json::parse(slurp(f.file("visibility.json")));
    CHECK(visibility.at("min_pixels") == synth::kMinVisiblePixels);
    CHECK(visibility.at("frames") == 8);
    std::set<model::NodeId> listed;
    int seenObjects = 0;
    for (const Json& v : visibility.at("instances")) {
        model::NodeId id = v.at("id");
        int frames = v.at("frames");
        CHECK(labelled.count(id));
        listed.insert(id);
        CHECK(frames >= 0);
        CHECK(frames <= 8);
        if (byId[id]->kind == model::NodeKind::Object && frames > 0) ++seenObjects;
        if (byId[id]->category == "floor") CHECK(frames == 8);
    }
    CHECK(listed == labelled);
    CHECK(seenObjects > 12);
}

TEST_CASE("synth: visibility counts and object colours match the pixels", "[ingest][synth]") {
    const Fixture& f = fixture();
    std::map<model::NodeId, int> frames;
    std::map<model::NodeId, std::array<double, 4>> colorSums;  // r, g, b, count over frames where seen
    for (int frame = 1; frame <= 8; ++frame) {
        synth::Image color = f.image("color", frame), instance = f.image("instance", frame);
        REQUIRE(color.channels == 3);
        std::map<model::NodeId, std::array<double, 4>> sums;
        for (int v = 0; v < 480; ++v)
            for (int u = 0; u < 640; ++u) {
                auto& s = sums[instance.at(u, v)];
                s[0] += color.at(u, v, 0), s[1] += color.at(u, v, 1), s[2] += color.at(u, v, 2), s[3] += 1;
            }
        for (const auto& [id, s] : sums) {
            if (id == 0 || s[3] < synth::kMinVisiblePixels) continue;
            ++frames[id];
            for (int c = 0; c < 4; ++c) colorSums[id][c] += s[c];
        }
    }
    for (const auto& [id, seen] : f.result.framesSeen) {
        INFO("instance " << id);
        CHECK(frames[id] == seen);
    }
    int checked = 0;
    for (const auto& [id, s] : colorSums) {
        const std::string* color = f.node(id).attribute("color");
        if (!color) continue;
        ++checked;
        INFO("instance " << id << " (" << f.node(id).category << ") mean " << s[0] / s[3] << " " << s[1] / s[3] << " "
                         << s[2] / s[3]);
        CHECK(synth::nearestColorName(s[0] / s[3], s[1] / s[3], s[2] / s[3]) == *color);
    }
    CHECK(checked > 10);
}

TEST_CASE("synth: a seed gives byte-identical files", "[ingest][synth]") {
    ingest::test::ScratchDir dir;
    synth::SynthOptions options{.seed = 5, .frames = 3, .objects = 12};
    synth::writeSynth((dir.path / "a").string(), options);
    synth::writeSynth((dir.path / "b").string(), options);
    std::vector<std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator((dir.path / "a")))
        if (entry.is_regular_file()) files.push_back(fs::relative(entry.path(), (dir.path / "a")).string());
    std::sort(files.begin(), files.end());
    // color, depth and masks per frame; seven files of the capture; the evaluation suite.
    CHECK(files.size() == 3 * 3 + 7 + 1);
    CHECK(std::find(files.begin(), files.end(), "eval-suite.json") != files.end());
    for (const std::string& name : files) {
        INFO(name);
        REQUIRE(fs::exists((dir.path / "b") / name));
        CHECK(slurp((dir.path / "a") / name) == slurp((dir.path / "b") / name));
    }
    options.seed = 6;
    synth::writeSynth((dir.path / "c").string(), options);
    CHECK(slurp((dir.path / "a") / "color/1.png") != slurp((dir.path / "c") / "color/1.png"));
}

TEST_CASE("synth: a non-empty folder is refused unless forced", "[ingest][synth]") {
    ingest::test::ScratchDir dir;
    fs::create_directories((dir.path / "out"));
    std::ofstream((dir.path / "out/notes.txt")) << "mine";
    synth::SynthOptions options{.seed = 2, .frames = 2, .objects = 6};
    try {
        synth::writeSynth((dir.path / "out").string(), options);
        FAIL("no error");
    } catch (const Error& e) {
        CHECK(e.kind() == ErrorKind::Usage);
        CHECK_THAT(e.message(), Catch::Contains("not empty"));
    }
    CHECK_FALSE(fs::exists((dir.path / "out/color")));
    options.force = true;
    synth::writeSynth((dir.path / "out").string(), options);
    CHECK(fs::exists((dir.path / "out/color/2.png")));
    // A forced rewrite with fewer frames leaves no frame of the earlier capture behind; other files stay.
    options.frames = 1;
    synth::writeSynth((dir.path / "out").string(), options);
    CHECK(fs::exists((dir.path / "out/color/1.png")));
    CHECK_FALSE(fs::exists((dir.path / "out/color/2.png")));
    CHECK(slurp((dir.path / "out/notes.txt")) == "mine");
}

TEST_CASE("synth --rgb-only: a photo folder with its camera and detections, the truth beside it", "[ingest][synth]") {
    ingest::test::ScratchDir dir;
    auto result = synth::writeSynth(dir.path.string(), {.seed = 2, .frames = 4, .rgbOnly = true});
    namespace fs = std::filesystem;
    for (const char* absent : {"color", "depth", "instance", "labels.json", "camera.json", "detections.json"})
        CHECK_FALSE(fs::exists(dir.path / absent));
    for (const char* present : {"pose.txt", "truth.json", "visibility.json", "images/camera.json"})
        CHECK(fs::exists(dir.path / present));
    CHECK_FALSE(Json::parse(std::ifstream(dir.path / "images/camera.json")).contains("depth_scale"));

    ingest::Capture capture = ingest::readCapture((dir.path / "images").string());
    CHECK(capture.layout == "images");
    CHECK_FALSE(capture.metric);
    REQUIRE(capture.frames.size() == 4);
    for (const auto& frame : capture.frames) {
        CHECK_FALSE(frame.pose);
        CHECK(frame.depthPath.empty());
    }
    CHECK(capture.intrinsics == result.intrinsics);
    REQUIRE(capture.detectionsPath == (dir.path / "images/detections.json").string());
    auto detections = ingest::readDetections(capture);
    CHECK(std::any_of(detections.begin(), detections.end(), [](const auto& frame) { return !frame.empty(); }));
}
