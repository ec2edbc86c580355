#include "ingest/synth/synth.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <random>
#include <set>
#include <thread>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "ingest/capture/media.hpp"
#include "ingest/generate/room_generator.hpp"
#include "ingest/import/importers.hpp"
#include "ingest/synth/render.hpp"
#include "ingest/synth/walk.hpp"
#include "model/error.hpp"
#include "model/geometry.hpp"
#include "relations/hierarchy.hpp"
#include "relations/predicates.hpp"

namespace smql::synth {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

// The files and folders a capture consists of: what --force replaces.
const char* const kOutputs[] = {"color",          "depth",           "instance",        "images",
                                "pose.txt",       "camera.json",     "labels.json",     "truth.json",
                                "relations.json", "visibility.json", "detections.json", "changes.json",
                                "eval-suite.json"};

// How many small things --changes moves, takes away and puts down.
constexpr int kChangesEach = 2;

constexpr double kNearLabelDistance = 0.5;

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void writeText(const fs::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    out.close();
    if (!out)
        throw Error(ErrorKind::Usage, "cannot write " + path.string(), std::nullopt, "check the folder is writable");
}

void writePng(const fs::path& path, const cv::Mat& image) {
    static const std::vector<int> kParams = {cv::IMWRITE_PNG_COMPRESSION, 1};
    bool ok = false;
    try {
        ok = ingest::media::write(path.string(), image, kParams);
    } catch (const cv::Exception&) {
        ok = false;
    }
    if (!ok)
        throw Error(ErrorKind::Usage, "cannot write " + path.string(), std::nullopt, "check the folder is writable");
}

void prepareDirectory(const fs::path& dir, bool force, bool rgbOnly) {
    std::error_code ec;
    if (fs::exists(dir, ec)) {
        if (!fs::is_directory(dir, ec)) throw Error(ErrorKind::Usage, dir.string() + " exists and is not a folder");
        if (!fs::is_empty(dir, ec)) {
            if (!force)
                throw Error(ErrorKind::Usage, dir.string() + " is not empty", std::nullopt,
                            "choose a new folder, or pass --force to replace a capture in it");
            for (const char* name : kOutputs) fs::remove_all(dir / name, ec);
        }
    }
    const std::vector<const char*> folders =
        rgbOnly ? std::vector<const char*>{"images"} : std::vector<const char*>{"color", "depth", "instance"};
    for (const char* sub : folders) {
        fs::create_directories(dir / sub, ec);
        if (ec) throw Error(ErrorKind::Usage, "cannot create " + (dir / sub).string() + ": " + ec.message());
    }
}

// What a perfect detector would report for one frame: every visible object, door
// and window (walls, floor and ceiling are structure, not detections) with its
// mask's box and outline, in id order so the file is deterministic.
std::vector<Json> detectFrame(const cv::Mat& instance, const std::vector<int>& counts, const model::SceneData& truth,
                              const std::string& image) {
    std::vector<Json> out;
    for (std::size_t id = 1; id < counts.size(); ++id) {
        if (counts[id] < kMinVisiblePixels || id > truth.nodes.size()) continue;
        const model::Node& n = truth.nodes[id - 1];
        bool opening = n.category == "door" || n.category == "window";
        if (n.kind != model::NodeKind::Object && !opening) continue;
        cv::Mat mask = instance == static_cast<int>(id);
        cv::Rect box = cv::boundingRect(mask);
        std::vector<std::vector<cv::Point>> contours;
        cv::findContours(mask, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
        Json detection = {
            {"image", image}, {"label", n.category}, {"score", 1}, {"bbox", {box.x, box.y, box.width, box.height}}};
        auto largest = std::max_element(contours.begin(), contours.end(), [](const auto& a, const auto& b) {
            return cv::contourArea(a) < cv::contourArea(b);
        });
        if (largest != contours.end()) {
            std::vector<cv::Point> polygon;
            cv::approxPolyDP(*largest, polygon, 1.0, true);
            if (polygon.size() >= 3) {
                Json flat = Json::array();
                for (const auto& p : polygon) flat.push_back(p.x), flat.push_back(p.y);
                detection["segmentation"] = Json::array({flat});
            }
        }
        out.push_back(std::move(detection));
    }
    return out;
}

std::string jsonLines(const std::string& key, const std::vector<Json>& entries, const Json& head = Json::object()) {
    std::string out = "{";
    for (const auto& [k, v] : head.items()) out += "\n  " + Json(k).dump() + ": " + v.dump() + ",";
    out += "\n  " + Json(key).dump() + ": [";
    for (std::size_t i = 0; i < entries.size(); ++i) out += (i ? ",\n    " : "\n    ") + entries[i].dump();
    out += entries.empty() ? "]\n}\n" : "\n  ]\n}\n";
    return out;
}

}  // namespace

ingest::Intrinsics synthIntrinsics() { return {640, 480, 525.0, 525.0, 319.5, 239.5}; }

namespace {

// Moves, removes and adds small things (what the generator placed on furniture), each resting on
// a piece of furniture's top, deterministically from `seed`. Furniture stays, so the walk is the same.
std::vector<model::ObjectChange> tidyUp(model::SceneData& truth, std::vector<generate::Support>& supports,
                                        std::uint64_t seed) {
    std::mt19937_64 rng(seed * 7919 + 17);
    auto pick = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
    auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
    auto byId = [&](model::NodeId id) -> model::Node& {
        return *std::find_if(truth.nodes.begin(), truth.nodes.end(), [&](const model::Node& n) { return n.id == id; });
    };
    std::vector<model::NodeId> furniture;
    for (const auto& s : supports)
        if (std::find(furniture.begin(), furniture.end(), s.supporter) == furniture.end())
            furniture.push_back(s.supporter);
    if (supports.size() < 2 * kChangesEach || furniture.size() < 2)
        throw Error(ErrorKind::Usage, "--changes needs a room with more small things: give it more --objects");

    // A spot on top of a piece of furniture, away from the things already there and a metre from any
    // thing of the same kind, so that which thing went where is never ambiguous.
    auto spotOn = [&](model::NodeId supporter, const model::Node& thing) -> std::optional<model::Box> {
        const model::Box& size = thing.box;
        const model::Box& top = byId(supporter).box;
        for (int attempt = 0; attempt < 20; ++attempt) {
            double lx = uniform(-0.4, 0.4) * top.size.x, ly = uniform(-0.3, 0.3) * top.size.y;
            model::Box placed = size;
            placed.center = {top.center.x + std::cos(top.yaw) * lx - std::sin(top.yaw) * ly,
                             top.center.y + std::sin(top.yaw) * lx + std::cos(top.yaw) * ly,
                             model::top(top) + size.size.z / 2};
            bool clear = std::none_of(truth.nodes.begin(), truth.nodes.end(), [&](const model::Node& n) {
                if (n.kind != model::NodeKind::Object || n.id == supporter || n.id == thing.id) return false;
                return model::distance(n.box, placed) < (n.category == thing.category ? 1.0 : 0.1);
            });
            if (clear) return placed;
        }
        return std::nullopt;
    };

    std::vector<model::ObjectChange> changes;
    std::vector<std::size_t> order(supports.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), rng);
    std::set<model::NodeId> removed;
    // Each change is of a kind of thing no other change touches: two cushions that swapped
    // places look the same as two that stayed.
    std::set<std::string> changedKinds;
    // Moved: the first few things that find a place on another piece of furniture.
    std::size_t next = 0;
    for (int moved = 0; moved < kChangesEach && next < order.size(); ++next) {
        generate::Support& s = supports[order[next]];
        model::NodeId to = furniture[pick(furniture.size())];
        if (to == s.supporter)
            to = furniture[(std::find(furniture.begin(), furniture.end(), to) - furniture.begin() + 1) %
                           furniture.size()];
        model::Node& thing = byId(s.object);
        if (changedKinds.count(thing.category)) continue;
        auto spot = spotOn(to, thing);
        if (!spot) continue;
        changedKinds.insert(thing.category);
        changes.push_back({model::ChangeKind::Moved, thing.category, thing.id, thing.id, thing.box, *spot});
        thing.box = *spot;
        thing.parent = model::kNoNode;  // found anew: it rests on other furniture now
        s.supporter = to;
        ++moved;
    }
    // Removed: the next few.
    for (int taken = 0; taken < kChangesEach && next < order.size(); ++next) {
        const model::Node& thing = byId(supports[order[next]].object);
        if (!changedKinds.insert(thing.category).second) continue;
        ++taken;
        changes.push_back({model::ChangeKind::Missing, thing.category, thing.id, model::kNoNode, thing.box, {}});
        removed.insert(thing.id);
    }
    // Added: copies of things still there (same kind, size and colour), put on other furniture.
    model::NodeId nextId = 0;
    for (const auto& n : truth.nodes) nextId = std::max(nextId, n.id);
    for (int added = 0, attempts = 0; added < kChangesEach && attempts < 50; ++attempts) {
        const generate::Support& model = supports[pick(supports.size())];
        if (removed.count(model.object)) continue;
        model::NodeId on = furniture[pick(furniture.size())];
        model::Node copy = byId(model.object);
        if (changedKinds.count(copy.category)) continue;
        auto spot = spotOn(on, copy);
        if (!spot) continue;
        changedKinds.insert(copy.category);
        copy.id = ++nextId;
        copy.box = *spot;
        copy.parent = model::kNoNode;
        copy.sourceId.reset();
        changes.push_back({model::ChangeKind::Added, copy.category, model::kNoNode, copy.id, {}, copy.box});
        truth.nodes.push_back(std::move(copy));
        supports.push_back({nextId, on});
        ++added;
    }
    std::erase_if(truth.nodes, [&](const model::Node& n) { return removed.count(n.id) > 0; });
    std::erase_if(supports, [&](const generate::Support& s) { return removed.count(s.object) > 0; });

    // Local ids run from 1 to the node count (truth.json is an smql scene file): renumber, and say
    // `after` in the new numbers.
    std::map<model::NodeId, model::NodeId> renumbered;
    for (std::size_t i = 0; i < truth.nodes.size(); ++i) renumbered.emplace(truth.nodes[i].id, i + 1);
    auto newId = [&](model::NodeId id) { return id == model::kNoNode ? id : renumbered.at(id); };
    for (auto& n : truth.nodes) {
        n.id = newId(n.id);
        n.parent = newId(n.parent);
    }
    std::erase_if(truth.relations, [&](const model::Relation& r) {
        return !renumbered.count(r.subject) || !renumbered.count(r.object);
    });
    for (auto& r : truth.relations) {
        r.subject = newId(r.subject);
        r.object = newId(r.object);
        r.frame = renumbered.count(r.frame) ? newId(r.frame) : model::kNoNode;
    }
    for (auto& s : supports) s = {newId(s.object), newId(s.supporter)};
    for (auto& c : changes) c.after = newId(c.after);
    return changes;
}

}  // namespace

SynthScene makeSynthScene(const SynthOptions& options) {
    if (options.frames < 1) throw Error(ErrorKind::Usage, "--frames must be at least 1");
    if (options.objects < 1) throw Error(ErrorKind::Usage, "--objects must be at least 1");
    if (options.objects > 5000) throw Error(ErrorKind::Usage, "--objects must be at most 5000");
    std::string name = "synth-" + std::to_string(options.seed);
    generate::GeneratedRoom room =
        generate::generateRoomWithSupports({.seed = options.seed, .objectCount = options.objects, .name = name});
    SynthScene out;
    out.truth = std::move(room.scene);
    out.truth.info.name = name;
    // Fixed times keep the files reproducible; the room after --changes is a day later.
    out.truth.info.captureTime = options.changes ? "2026-11-21T10:00:00Z" : "2026-11-20T10:00:00Z";
    out.truth.info.source =
        "synth:seed=" + std::to_string(options.seed) + ",objects=" + std::to_string(options.objects);
    relations::assignParents(out.truth);
    // The walk is planned in the room as it was, so a capture with --changes walks the same path.
    out.poses = planWalk(out.truth, {.frames = options.frames, .seed = options.seed});
    if (options.changes) {
        out.changes = tidyUp(out.truth, room.supports, options.seed);
        relations::assignParents(out.truth);
    }
    out.truth.info.nodeCount = out.truth.nodes.size();

    std::map<model::NodeId, const model::Node*> byId;
    for (const auto& n : out.truth.nodes) byId.emplace(n.id, &n);
    auto node = [&](model::NodeId id) -> const model::Node& { return *byId.at(id); };
    // on / in: what the generator put where.
    std::set<std::pair<model::NodeId, model::NodeId>> supported;
    for (const generate::Support& s : room.supports) {
        bool holder = relations::affordanceOf(node(s.supporter).category) == relations::Affordance::Holder;
        out.relations.push_back({s.object, s.supporter, holder ? 21 : 30, holder ? "in" : "on"});
        supported.insert({s.object, s.supporter});
    }
    // near: objects whose boxes are within 0.5 m, both directions (as ReplicaSSG lists them).
    const auto& nodes = out.truth.nodes;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        if (nodes[i].kind != model::NodeKind::Object || nodes[i].geometry == model::GeometryKind::None) continue;
        for (std::size_t j = i + 1; j < nodes.size(); ++j) {
            if (nodes[j].kind != model::NodeKind::Object || nodes[j].geometry == model::GeometryKind::None) continue;
            if (model::distance(nodes[i].box, nodes[j].box) > kNearLabelDistance) continue;
            out.relations.push_back({nodes[i].id, nodes[j].id, 28, "near"});
            out.relations.push_back({nodes[j].id, nodes[i].id, 28, "near"});
        }
    }
    return out;
}

namespace {

// What rendering the walk gives besides the files: per frame the pixels of each node (by id) and the
// detections of its masks.
struct RenderedWalk {
    std::vector<std::vector<int>> pixels;
    std::vector<std::vector<Json>> detections;
};

// Renders and writes every frame (colour, and depth and instance masks unless RGB-only). Frames are
// independent: two workers render and write them, each frame's files depending only on its pose,
// so the output does not depend on the scheduling.
RenderedWalk renderWalk(const SynthResult& result, const SynthOptions& options, const fs::path& dir,
                        const fs::path& capture, model::NodeId maxId) {
    const model::SceneData& truth = result.scene.truth;
    const Renderer renderer(surfacesOf(truth));
    const ingest::Intrinsics& K = result.intrinsics;
    const auto& cameras = result.scene.poses;
    RenderedWalk walk{std::vector<std::vector<int>>(cameras.size()), std::vector<std::vector<Json>>(cameras.size())};
    std::atomic<std::size_t> next{0};
    std::mutex failureMutex;
    std::exception_ptr failure;
    auto work = [&] {
        try {
            for (std::size_t f = next++; f < cameras.size(); f = next++) {
                RenderedFrame frame = renderer.render(K, cameras[f]);
                cv::Mat color(K.height, K.width, CV_8UC3), depth(K.height, K.width, CV_16UC1),
                    instance(K.height, K.width, CV_16UC1);
                std::vector<int>& counts = walk.pixels[f];
                counts.assign(maxId + 1, 0);
                for (int v = 0; v < K.height; ++v) {
                    auto* c = color.ptr<std::uint8_t>(v);
                    auto* d = depth.ptr<std::uint16_t>(v);
                    auto* m = instance.ptr<std::uint16_t>(v);
                    for (int u = 0; u < K.width; ++u) {
                        std::size_t i = static_cast<std::size_t>(v) * K.width + u;
                        c[u * 3 + 0] = frame.rgb[i * 3 + 2];  // OpenCV writes BGR
                        c[u * 3 + 1] = frame.rgb[i * 3 + 1];
                        c[u * 3 + 2] = frame.rgb[i * 3 + 0];
                        double z = frame.depth[i];
                        d[u] = z > 0 && z <= kMaxDepth ? static_cast<std::uint16_t>(std::lround(z * 1000)) : 0;
                        m[u] = frame.instance[i];
                        if (frame.instance[i] <= maxId) ++counts[frame.instance[i]];
                    }
                }
                std::string name = std::to_string(f + 1) + ".png";
                if (options.rgbOnly) {
                    writePng(capture / name, color);
                } else {
                    writePng(dir / "color" / name, color);
                    writePng(dir / "depth" / name, depth);
                    writePng(dir / "instance" / name, instance);
                }
                walk.detections[f] = detectFrame(instance, counts, truth, name);
            }
        } catch (...) {
            std::lock_guard lock(failureMutex);
            if (!failure) failure = std::current_exception();
            next = cameras.size();
        }
    };
    {
        std::thread helper(work);
        work();
        helper.join();
    }
    if (failure) std::rethrow_exception(failure);
    return walk;
}

// The truth beside the frames: labels of the masks, how many frames saw each node, the labelled
// relations, the detections and truth.json.
void writeTruth(const SynthResult& result, const SynthOptions& options, const fs::path& dir, const fs::path& capture,
                std::vector<std::vector<Json>> detections) {
    const model::SceneData& truth = result.scene.truth;
    std::vector<Json> labels, visibility, relations;
    for (const model::Node& n : truth.nodes) {
        if (n.geometry == model::GeometryKind::None) continue;
        Json label = {{"id", n.id}, {"category", n.category}, {"kind", model::toString(n.kind)}};
        if (const std::string* color = n.attribute("color")) label["color"] = *color;
        labels.push_back(label);
        visibility.push_back({{"id", n.id}, {"frames", result.framesSeen.at(n.id)}});
    }
    for (const LabelledRelation& r : result.scene.relations)
        relations.push_back(Json::array({r.subject, r.object, r.predicateId, r.predicate}));
    if (!options.rgbOnly) writeText(dir / "labels.json", jsonLines("instances", labels));  // the masks' names
    writeText(dir / "visibility.json",
              jsonLines("instances", visibility,
                        {{"min_pixels", kMinVisiblePixels}, {"frames", static_cast<int>(result.scene.poses.size())}}));
    writeText(dir / "relations.json",
              jsonLines("relationships", relations,
                        {{"scene", truth.info.name},
                         {"format", "[subject_id, object_id, predicate_id, predicate]; ids are truth.json node ids"}}));
    std::vector<Json> allDetections;
    for (auto& frameDetections : detections)
        for (auto& d : frameDetections) allDetections.push_back(std::move(d));
    writeText(capture / "detections.json", jsonLines("detections", allDetections));
    writeText(dir / "truth.json", import::writeSceneJson(truth) + "\n");
}

// The evaluation suite (docs/eval.md): truth ids of what the walk saw; answers come from truth.json
// when `smql eval` runs.
void writeEvalSuite(const SynthResult& result, const fs::path& dir) {
    const model::SceneData& truth = result.scene.truth;
    std::vector<model::NodeId> things, anchors, doors;
    for (const model::Node& n : truth.nodes) {
        if (n.geometry == model::GeometryKind::None || result.framesSeen.at(n.id) == 0) continue;
        if (n.kind == model::NodeKind::Object) things.push_back(n.id);
        bool upright = n.category == "wall" || n.category == "door" || n.category == "window";
        if (n.kind == model::NodeKind::Anchor && upright) anchors.push_back(n.id);
        if (n.kind == model::NodeKind::Anchor && n.category == "door") doors.push_back(n.id);
    }
    Json suite = {{"smql_eval", 1},
                  {"scene", truth.info.name},
                  {"truth", "truth.json"},
                  {"relative_position", Json::array()},
                  {"guidance", Json::array()},
                  {"retrieval", Json::array()}};
    for (model::NodeId thing : things) {
        for (model::NodeId anchor : anchors)
            suite["relative_position"].push_back({{"subject", thing}, {"anchor", anchor}});
        for (model::NodeId door : doors) suite["guidance"].push_back({{"from", door}, {"to", thing}});
        suite["retrieval"].push_back({{"object", thing}});
    }
    writeText(dir / "eval-suite.json", suite.dump(1) + "\n");
}

// --changes: what changed from the room without them, in truth ids.
void writeChanges(const SynthResult& result, const fs::path& dir) {
    auto centre = [](const model::Box& b) { return Json::array({b.center.x, b.center.y, b.center.z}); };
    std::vector<Json> changes;
    for (const auto& c : result.scene.changes) {
        Json change = {{"change", model::toString(c.kind)}, {"category", c.category}};
        if (c.before != model::kNoNode) change["before_id"] = c.before;
        if (c.after != model::kNoNode) change["after_id"] = c.after;
        if (c.kind != model::ChangeKind::Added) change["from"] = centre(c.from);
        if (c.kind != model::ChangeKind::Missing) change["to"] = centre(c.to);
        if (c.after != model::kNoNode) change["frames_seen"] = result.framesSeen.at(c.after);
        changes.push_back(change);
    }
    writeText(dir / "changes.json",
              jsonLines("changes", changes,
                        {{"scene", result.scene.truth.info.name},
                         {"format",
                          "ids are truth.json ids: before_id of the capture without --changes, after_id of this one; "
                          "from/to are box centres in metres"}}));
}

}  // namespace

SynthResult writeSynth(const std::string& directory, const SynthOptions& options) {
    auto start = std::chrono::steady_clock::now();
    SynthResult result;
    result.scene = makeSynthScene(options);
    result.intrinsics = synthIntrinsics();
    const fs::path dir(directory);
    prepareDirectory(dir, options.force, options.rgbOnly);
    // Where the capture's own files go: the photos' folder, or beside the frame folders.
    const fs::path capture = options.rgbOnly ? dir / "images" : dir;

    model::NodeId maxId = 0;
    for (const model::Node& n : result.scene.truth.nodes)
        if (n.geometry != model::GeometryKind::None) {
            maxId = std::max(maxId, n.id);
            result.framesSeen[n.id] = 0;
        }
    auto framesStart = std::chrono::steady_clock::now();
    RenderedWalk walk = renderWalk(result, options, dir, capture, maxId);
    result.frameSeconds = secondsSince(framesStart);

    const auto& cameras = result.scene.poses;
    std::string poses;
    for (std::size_t f = 0; f < cameras.size(); ++f) {
        poses += poseLine(cameras[f]) + "\n";
        for (auto& [id, seen] : result.framesSeen)
            if (walk.pixels[f][id] >= kMinVisiblePixels) ++seen;
    }
    writeText(dir / "pose.txt", poses);
    const ingest::Intrinsics& K = result.intrinsics;
    auto number = [](double v) { return v == std::floor(v) ? Json(static_cast<std::int64_t>(v)) : Json(v); };
    Json camera = {{"width", K.width},   {"height", K.height}, {"fx", number(K.fx)},
                   {"fy", number(K.fy)}, {"cx", number(K.cx)}, {"cy", number(K.cy)}};
    if (!options.rgbOnly) camera["depth_scale"] = 1000;
    writeText(capture / "camera.json", camera.dump() + "\n");

    writeTruth(result, options, dir, capture, std::move(walk.detections));
    writeEvalSuite(result, dir);
    if (options.changes) writeChanges(result, dir);
    result.totalSeconds = secondsSince(start);
    return result;
}

Image readImage(const std::string& path) {
    cv::Mat m = ingest::media::read(path, cv::IMREAD_UNCHANGED);
    if (m.empty()) throw Error(ErrorKind::Input, "cannot read image " + path);
    Image image;
    image.width = m.cols;
    image.height = m.rows;
    image.channels = m.channels();
    image.data.resize(static_cast<std::size_t>(m.cols) * m.rows * m.channels());
    std::size_t k = 0;
    for (int v = 0; v < m.rows; ++v) {
        for (int u = 0; u < m.cols; ++u) {
            for (int c = 0; c < m.channels(); ++c) {
                // Colour comes back as R, G, B (OpenCV stores B, G, R).
                int channel = m.channels() >= 3 && c < 3 ? 2 - c : c;
                if (m.depth() == CV_16U)
                    image.data[k++] = m.ptr<std::uint16_t>(v)[u * m.channels() + channel];
                else if (m.depth() == CV_8U)
                    image.data[k++] = m.ptr<std::uint8_t>(v)[u * m.channels() + channel];
                else
                    throw Error(ErrorKind::Input, "unsupported pixel type in " + path);
            }
        }
    }
    return image;
}

}  // namespace smql::synth
