#include "ingest/synth/synth.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <thread>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "model/error.hpp"
#include "model/geometry.hpp"
#include "engine/relations/hierarchy.hpp"
#include "engine/relations/predicates.hpp"
#include "ingest/generate/room_generator.hpp"
#include "ingest/import/importers.hpp"
#include "ingest/synth/render.hpp"
#include "ingest/synth/walk.hpp"

namespace smql::synth {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

// The files and folders a capture consists of: what --force replaces.
const char* const kOutputs[] = {"color",         "depth",          "instance",        "pose.txt",
                                "camera.json",   "labels.json",    "truth.json",      "relations.json",
                                "visibility.json", "detections.json"};

constexpr double kNearLabelDistance = 0.5;

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void writeText(const fs::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw Error(ErrorKind::Usage, "cannot write " + path.string(), std::nullopt, "check the folder is writable");
}

void writePng(const fs::path& path, const cv::Mat& image) {
    static const std::vector<int> kParams = {cv::IMWRITE_PNG_COMPRESSION, 1};
    bool ok = false;
    try {
        ok = cv::imwrite(path.string(), image, kParams);
    } catch (const cv::Exception&) {
        ok = false;
    }
    if (!ok) throw Error(ErrorKind::Usage, "cannot write " + path.string(), std::nullopt, "check the folder is writable");
}

void prepareDirectory(const fs::path& dir, bool force) {
    std::error_code ec;
    if (fs::exists(dir, ec)) {
        if (!fs::is_directory(dir, ec))
            throw Error(ErrorKind::Usage, dir.string() + " exists and is not a folder");
        if (!fs::is_empty(dir, ec)) {
            if (!force)
                throw Error(ErrorKind::Usage, dir.string() + " is not empty", std::nullopt,
                            "choose a new folder, or pass --force to replace a capture in it");
            for (const char* name : kOutputs) fs::remove_all(dir / name, ec);
        }
    }
    for (const char* sub : {"color", "depth", "instance"}) {
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
        Json detection = {{"image", image}, {"label", n.category}, {"score", 1},
                          {"bbox", {box.x, box.y, box.width, box.height}}};
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
    out.truth.info.source = "synth:seed=" + std::to_string(options.seed) + ",objects=" + std::to_string(options.objects);
    out.truth.info.nodeCount = out.truth.nodes.size();
    relations::assignParents(out.truth);

    auto node = [&](model::NodeId id) -> const model::Node& { return out.truth.nodes.at(id - 1); };
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
    out.poses = planWalk(out.truth, {.frames = options.frames, .seed = options.seed});
    return out;
}

SynthResult writeSynth(const std::string& directory, const SynthOptions& options) {
    auto start = std::chrono::steady_clock::now();
    SynthResult result;
    result.scene = makeSynthScene(options);
    result.intrinsics = synthIntrinsics();
    const fs::path dir(directory);
    prepareDirectory(dir, options.force);

    const model::SceneData& truth = result.scene.truth;
    Renderer renderer(surfacesOf(truth));
    model::NodeId maxId = 0;
    for (const model::Node& n : truth.nodes)
        if (n.geometry != model::GeometryKind::None) {
            maxId = std::max(maxId, n.id);
            result.framesSeen[n.id] = 0;
        }

    const ingest::Intrinsics& K = result.intrinsics;
    const auto& cameras = result.scene.poses;
    // Frames are independent: two workers render and write them, each frame's files depending
    // only on its pose, so the output does not depend on the scheduling.
    std::vector<std::vector<int>> pixels(cameras.size());
    std::vector<std::vector<Json>> detections(cameras.size());
    std::atomic<std::size_t> next{0};
    std::mutex failureMutex;
    std::exception_ptr failure;
    auto work = [&] {
        try {
            for (std::size_t f = next++; f < cameras.size(); f = next++) {
                RenderedFrame frame = renderer.render(K, cameras[f]);
                cv::Mat color(K.height, K.width, CV_8UC3), depth(K.height, K.width, CV_16UC1),
                    instance(K.height, K.width, CV_16UC1);
                std::vector<int>& counts = pixels[f];
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
                writePng(dir / "color" / name, color);
                writePng(dir / "depth" / name, depth);
                writePng(dir / "instance" / name, instance);
                detections[f] = detectFrame(instance, counts, truth, name);
            }
        } catch (...) {
            std::lock_guard lock(failureMutex);
            if (!failure) failure = std::current_exception();
            next = cameras.size();
        }
    };
    auto framesStart = std::chrono::steady_clock::now();
    {
        std::thread helper(work);
        work();
        helper.join();
    }
    if (failure) std::rethrow_exception(failure);
    result.frameSeconds = secondsSince(framesStart);
    std::string poses;
    for (std::size_t f = 0; f < cameras.size(); ++f) {
        poses += poseLine(cameras[f]) + "\n";
        for (auto& [id, seen] : result.framesSeen)
            if (pixels[f][id] >= kMinVisiblePixels) ++seen;
    }
    writeText(dir / "pose.txt", poses);

    auto number = [](double v) { return v == std::floor(v) ? Json(static_cast<std::int64_t>(v)) : Json(v); };
    Json camera = {{"width", K.width}, {"height", K.height}, {"fx", number(K.fx)}, {"fy", number(K.fy)},
                   {"cx", number(K.cx)}, {"cy", number(K.cy)}, {"depth_scale", 1000}};
    writeText(dir / "camera.json", camera.dump() + "\n");

    std::vector<Json> labels, visibility, relations;
    for (const model::Node& n : truth.nodes) {
        if (n.geometry == model::GeometryKind::None) continue;
        Json label = {{"id", n.id}, {"category", n.category}, {"kind", model::toString(n.kind)}};
        if (const std::string* color = n.attribute("color")) label["color"] = *color;
        labels.push_back(label);
        visibility.push_back({{"id", n.id}, {"frames", result.framesSeen[n.id]}});
    }
    for (const LabelledRelation& r : result.scene.relations)
        relations.push_back(Json::array({r.subject, r.object, r.predicateId, r.predicate}));
    writeText(dir / "labels.json", jsonLines("instances", labels));
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
    writeText(dir / "detections.json", jsonLines("detections", allDetections));
    writeText(dir / "truth.json", import::writeSceneJson(truth) + "\n");
    result.totalSeconds = secondsSince(start);
    return result;
}

Image readImage(const std::string& path) {
    cv::Mat m = cv::imread(path, cv::IMREAD_UNCHANGED);
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
