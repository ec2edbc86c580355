#include "ingest/pipeline/pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <numeric>
#include <set>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>
#include <nlohmann/json.hpp>

#include "engine/error.hpp"
#include "engine/model/geometry.hpp"
#include "engine/relations/hierarchy.hpp"
#include "engine/relations/predicates.hpp"
#include "ingest/capture/frame_loader.hpp"
#include "ingest/geometry/alignment.hpp"
#include "ingest/geometry/clusters.hpp"
#include "ingest/geometry/point_cloud.hpp"
#include "ingest/geometry/walls.hpp"
#include "ingest/pipeline/colors.hpp"
#include "ingest/pipeline/detections.hpp"
#include "ingest/pipeline/observations.hpp"

namespace smql::ingest {

using model::Node;
using model::NodeId;
using model::NodeKind;

namespace {

struct InstanceLabel {
    std::string category;
    NodeKind kind = NodeKind::Object;
    std::string material;
};

// labels.json beside instance masks: {"instances": [{"id", "category", "kind", ...}]}.
// Colour in a labels file is ground truth for checking, never read here: ingest names colours from pixels.
std::map<std::uint16_t, InstanceLabel> readLabels(const std::string& path) {
    std::ifstream in(path);
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        throw Error(ErrorKind::Input, fmt::format("{}: not valid JSON ({})", path, e.what()));
    }
    std::map<std::uint16_t, InstanceLabel> out;
    if (!j.contains("instances") || !j["instances"].is_array())
        throw Error(ErrorKind::Input, fmt::format("{}: instances: expected an array", path), std::nullopt,
                    "labels.json holds {\"instances\": [{\"id\": 1, \"category\": \"mug\", \"kind\": \"object\"}]}");
    for (std::size_t i = 0; i < j["instances"].size(); ++i) {
        const auto& e = j["instances"][i];
        if (!e.is_object() || !e.contains("id") || !e["id"].is_number_unsigned() || !e.contains("category") ||
            !e["category"].is_string())
            throw Error(ErrorKind::Input, fmt::format("{}: instances[{}]: needs an id (1..65535) and a category", path, i));
        auto id = e["id"].get<std::uint64_t>();
        if (id == 0 || id > 65535)
            throw Error(ErrorKind::Input, fmt::format("{}: instances[{}].id: {} is not a 16-bit mask value", path, i, id));
        InstanceLabel label;
        label.category = e["category"].get<std::string>();
        if (e.contains("kind") && e["kind"] == "anchor") label.kind = NodeKind::Anchor;
        if (e.contains("material") && e["material"].is_string()) label.material = e["material"].get<std::string>();
        out.emplace(static_cast<std::uint16_t>(id), std::move(label));
    }
    return out;
}

class Stage {
public:
    Stage(ProgressSink& sink, std::vector<StageTiming>& timings, std::string name, std::size_t steps)
        : sink_(sink), timings_(timings), name_(std::move(name)), start_(std::chrono::steady_clock::now()) {
        sink_.stageStarted(name_, steps);
    }
    void finish(std::string summary) {
        double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        sink_.stageFinished(name_, seconds, summary);
        timings_.push_back({name_, seconds, std::move(summary)});
    }

private:
    ProgressSink& sink_;
    std::vector<StageTiming>& timings_;
    std::string name_;
    std::chrono::steady_clock::time_point start_;
};

std::string sizeWord(const model::Box& b) {
    double v = model::volume(b);
    return v < 0.01 ? "small" : v < 0.3 ? "medium" : "large";
}

// "left of", "in front of"
std::string words(relations::Predicate p) {
    std::string w(relations::toString(p));
    std::replace(w.begin(), w.end(), '_', ' ');
    return w;
}

}  // namespace

IngestResult ingestCapture(const Capture& input, const IngestOptions& options, ProgressSink& progress,
                           const std::function<bool()>& cancelled) {
    IngestResult result;
    auto note = [&](const std::string& text) {
        result.notes.push_back(text);
        progress.note(text);
    };
    for (const auto& n : input.notes) note(n);

    bool hasPoses = std::all_of(input.frames.begin(), input.frames.end(), [](const auto& f) { return f.pose.has_value(); });
    bool useColmap = options.geometry == GeometrySource::Colmap || (options.geometry == GeometrySource::Auto && !hasPoses);
    if (options.geometry == GeometrySource::Given && !hasPoses)
        throw Error(ErrorKind::Input, fmt::format("{}: some frames have no camera pose", input.path), std::nullopt,
                    "ingest needs camera poses: pose.txt (rgbd), groundtruth.txt (TUM), transforms.json or a COLMAP "
                    "model; or let COLMAP find them (--geometry colmap)");
    // ---- COLMAP: poses and sparse points from the colour frames alone.
    std::optional<Capture> reconstructed;
    if (useColmap) {
        Stage stage(progress, result.stages, "colmap", 1);
        reconstructed = input;
        bool hadDepth = false;
        for (auto& f : reconstructed->frames) {
            hadDepth = hadDepth || !f.depthPath.empty();
            f.depthPath.clear();
        }
        if (hadDepth) note("--geometry colmap: depth images are ignored (COLMAP's poses are up to scale)");
        ColmapRun run = runColmap(*reconstructed, options.colmap);
        for (const auto& n : run.notes) note(n);
        progress.advanced(1);
        stage.finish(fmt::format("{} of {} frames registered, {} points", run.registered,
                                 reconstructed->frames.size(), run.points));
    }
    const Capture& capture = reconstructed ? *reconstructed : input;
    std::size_t posed = std::count_if(capture.frames.begin(), capture.frames.end(), [](const auto& f) { return f.pose.has_value(); });
    if (posed == 0)
        throw Error(ErrorKind::Input, fmt::format("{}: no frame has a camera pose", capture.path), std::nullopt,
                    "ingest needs camera poses: pose.txt (rgbd), groundtruth.txt (TUM), transforms.json or a COLMAP model");
    bool hasDepth = std::all_of(capture.frames.begin(), capture.frames.end(), [](const auto& f) { return !f.depthPath.empty(); });
    if (!hasDepth && capture.points.empty())
        throw Error(ErrorKind::Input, fmt::format("{}: the frames have no depth and the capture no 3D points", capture.path),
                    std::nullopt, "give depth images, or a COLMAP model with points3D (or --geometry colmap)");
    bool hasMasks = !capture.labelsPath.empty() &&
                    std::all_of(capture.frames.begin(), capture.frames.end(), [](const auto& f) { return !f.instancePath.empty(); });
    bool hasDetections = !capture.detectionsPath.empty() && hasDepth;
    ObjectSource objects = options.objects;
    if (objects == ObjectSource::Auto)
        objects = hasMasks ? ObjectSource::Masks : hasDetections ? ObjectSource::Detections : ObjectSource::Cluster;
    if (objects == ObjectSource::Masks && !hasMasks)
        throw Error(ErrorKind::Input, fmt::format("{}: --objects masks needs instance/ masks and labels.json", capture.path),
                    std::nullopt, "use --objects cluster for captures without masks");
    if (objects == ObjectSource::Detections && !hasDetections)
        throw Error(ErrorKind::Input,
                    fmt::format("{}: --objects detections needs detections.json and depth images", capture.path),
                    std::nullopt, "use --objects cluster for captures without detections");
    auto labels = objects == ObjectSource::Masks ? readLabels(capture.labelsPath) : std::map<std::uint16_t, InstanceLabel>{};
    auto detections = objects == ObjectSource::Detections ? readDetections(capture) : std::vector<std::vector<Detection>>{};

    // ---- Frames: one pass; each frame feeds the structure cloud and the instance tracks.
    // Masks give tracks by their ids; detections are associated into tracks across views.
    PointCloud structure;
    std::map<std::uint16_t, ObjectTrack> instanceTracks;
    DetectionTracker tracker;
    std::vector<ObjectTrack> tracks;
    std::vector<Pose> cameras;
    std::vector<std::size_t> cameraFrames;  // capture position of each camera
    std::vector<std::uint32_t> inView;      // sparse points: frames each one projects into
    std::vector<MaskView> maskViews;        // frames without depth: masks for carving
    {
        Stage stage(progress, result.stages, "frames", capture.frames.size());
        PointCloud pending;
        for (std::size_t i = 0; i < capture.frames.size(); ++i) {
            if (cancelled && cancelled()) throw Error(ErrorKind::Usage, "cancelled; nothing was written");
            const auto& frame = capture.frames[i];
            if (!frame.pose) {
                note(fmt::format("frame {} has no camera pose (not registered): skipped", frame.index));
                progress.advanced(i + 1);
                continue;
            }
            FrameImages images = loadFrame(capture, frame, options.workingWidth);
            const Pose& pose = *frame.pose;
            cameras.push_back(pose);
            cameraFrames.push_back(i);
            append(pending, backProject(images, pose, static_cast<std::uint32_t>(i), options.structureStride));
            // Down-sample as we go so memory stays flat over long captures.
            if (pending.size() > 400000) {
                append(structure, voxelDownsample(pending, options.structureVoxel));
                pending = PointCloud{};
            }
            auto keepEvidence = [&](ObjectTrack& track, const Observation& o) {
                if (o.pixels > track.evidence.pixels)
                    track.evidence = {o.pixels, static_cast<std::uint32_t>(i),
                                      encodeCrop(images.color, o.bounds, options.evidenceSize)};
            };
            if (objects == ObjectSource::Masks) {
                auto seen = observeInstances(images, pose, static_cast<std::uint32_t>(i), options.objectStride,
                                             options.minInstancePixels);
                if (!hasDepth) {
                    liftSparsePoints(seen, images, pose, capture.points, inView, options.sparseDepthBand);
                    MaskView m;
                    m.frame = static_cast<std::uint32_t>(i);
                    cv::resize(images.instances, m.instances, cv::Size(), 0.25, 0.25, cv::INTER_NEAREST);
                    double sx = double(m.instances.cols) / images.instances.cols, sy = double(m.instances.rows) / images.instances.rows;
                    const auto& K = images.intrinsics;
                    m.intrinsics = {m.instances.cols, m.instances.rows, K.fx * sx, K.fy * sy, (K.cx + 0.5) * sx - 0.5,
                                    (K.cy + 0.5) * sy - 0.5};
                    m.pose = pose;
                    maskViews.push_back(std::move(m));
                }
                for (auto& o : seen) {
                    auto& track = instanceTracks[o.instance];
                    keepEvidence(track, o);
                    track.views.push_back(std::move(o));
                }
            } else if (objects == ObjectSource::Detections) {
                const Intrinsics& stored = frame.intrinsics ? *frame.intrinsics : capture.intrinsics;
                auto seen = observeDetections(images, pose, static_cast<std::uint32_t>(i), detections[i], stored.width,
                                              options.objectStride, options.minInstancePixels);
                // The most confident detections found tracks first.
                std::stable_sort(seen.begin(), seen.end(), [&](const Observation& a, const Observation& b) {
                    return detections[i][a.instance].score > detections[i][b.instance].score;
                });
                for (auto& o : seen) {
                    const std::string& category = detections[i][o.instance].category;
                    ObjectTrack& track = tracker.add(std::move(o), category);
                    keepEvidence(track, track.views.back());
                }
            }
            progress.advanced(i + 1);
        }
        append(structure, pending);
        structure = voxelDownsample(structure, options.structureVoxel);
        // Depth images that hold no reading (all zero, or every pixel out of
        // range) would give an empty scene that looks like a success.
        if (hasDepth && structure.size() == 0)
            throw Error(ErrorKind::Input,
                        fmt::format("{}: no depth reading in any frame: every depth image is empty (0 = no reading) "
                                    "or farther than {:g} m",
                                    capture.path, kMaxDepthReading),
                        std::nullopt,
                        "check the depth images and the depth scale (depth units per metre: 1000 for millimetres, "
                        "5000 for TUM)");
        if (!hasDepth) {
            // The capture's sparse points (COLMAP) are the structure: already sparse, in the capture's units.
            for (const auto& p : capture.points) structure.push(p.position, p.color, 0);
        }
        if (objects == ObjectSource::Masks) {
            if (!hasDepth) {
                std::vector<ObjectTrack*> all;
                for (auto& [instance, track] : instanceTracks) all.push_back(&track);
                keepConsistentSparsePoints(all, capture.points, inView);
                carveVisualHulls(all, maskViews);
            }
            for (auto& [instance, track] : instanceTracks) {
                auto label = labels.find(instance);
                if (label == labels.end()) continue;  // an unlabelled mask value
                track.category = label->second.category;
                track.kind = label->second.kind;
                track.material = label->second.material;
                tracks.push_back(std::move(track));
            }
        } else {
            tracks = tracker.take();
        }
        stage.finish(fmt::format("{} frames, {} structure points, {} instances", capture.frames.size(), structure.size(),
                                 tracks.size()));
    }

    // ---- Metric alignment.
    Alignment alignment;
    {
        Stage stage(progress, result.stages, "align", 1);
        AlignOptions align;
        align.metric = capture.metric;
        align.scale = options.scale;
        alignment = alignCapture(structure, cameras, align);
        for (const auto& n : alignment.notes) note(n);
        if (!alignment.floorFound) note("no floor plane found: the frame is levelled by the cameras' up direction");
        stage.finish(fmt::format("floor {}, heading {:.1f} deg, scale {:.3f}", alignment.floorFound ? "found" : "not found",
                                 alignment.heading * 180 / M_PI, alignment.scale));
    }
    PointCloud aligned = transformed(structure, alignment);
    for (std::size_t c = 0; c < cameras.size(); ++c)
        result.cameraCentres.push_back({cameraFrames[c], alignment.apply(cameras[c].translation)});

    model::SceneData& scene = result.scene;
    scene.info.name = options.sceneName;
    scene.info.source = fmt::format("{}:{}", capture.layout, capture.path);
    scene.info.alignment = alignment.transform;
    scene.info.scale = alignment.scale;
    auto addNode = [&](NodeKind kind, std::string category, model::GeometryKind g, model::Box box) -> Node& {
        Node n;
        n.id = scene.nodes.size() + 1;
        n.kind = kind;
        n.category = std::move(category);
        n.geometry = g;
        n.box = box;
        scene.nodes.push_back(std::move(n));
        return scene.nodes.back();
    };

    // ---- Anchors: floor, ceiling, walls from geometry; doors and windows from labelled masks.
    std::vector<WallSegment> walls;
    {
        Stage stage(progress, result.stages, "anchors", 1);
        double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
        for (const auto& p : aligned.points) x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
        if (alignment.floorFound && !aligned.empty()) {
            Node& floor = addNode(NodeKind::Anchor, "floor", model::GeometryKind::Plane,
                                  {{(x0 + x1) / 2, (y0 + y1) / 2, -0.01}, {x1 - x0, y1 - y0, 0.02}, 0});
            floor.confidence = 1.0f;
        }
        if (alignment.ceilingHeight)
            addNode(NodeKind::Anchor, "ceiling", model::GeometryKind::Plane,
                    {{(x0 + x1) / 2, (y0 + y1) / 2, *alignment.ceilingHeight + 0.01}, {x1 - x0, y1 - y0, 0.02}, 0});
        std::vector<model::Vec3> cameraPositions;
        for (const auto& c : cameras) cameraPositions.push_back(alignment.apply(c.translation));
        walls = findWalls(aligned, cameraPositions);
        for (const auto& w : walls) {
            Node& wall = addNode(NodeKind::Anchor, "wall", model::GeometryKind::Plane, w.box());
            wall.confidence = static_cast<float>(w.confidence);
            wall.attributes.push_back({"views", std::to_string(w.frames)});
        }
        stage.finish(fmt::format("{} walls{}{}", walls.size(), alignment.floorFound ? ", floor" : "",
                                 alignment.ceilingHeight ? ", ceiling" : ""));
    }

    // ---- Objects (and labelled doors/windows) from the instance tracks, or clusters.
    std::map<std::size_t, NodeId> trackNode;  // position in tracks -> its node
    {
        Stage stage(progress, result.stages, "objects", tracks.size());
        std::size_t done = 0;
        for (std::size_t t = 0; t < tracks.size(); ++t) {
            auto& track = tracks[t];
            progress.advanced(++done);
            const auto& category = track.category;
            bool opening = category == "door" || category == "window";
            if (track.kind == NodeKind::Anchor && !opening) continue;  // walls, floor, ceiling: geometry's job
            if (static_cast<int>(track.views.size()) < options.minObjectViews) continue;

            PointCloud cloud;
            for (const auto& v : track.views)
                for (const auto& p : v.points) cloud.push(alignment.apply(p), {0, 0, 0}, v.frame);
            if (cloud.size() < 10) continue;
            cloud = voxelDownsample(cloud, options.objectVoxel);
            model::Box box = uprightBox(cloud.points);
            if (opening && !walls.empty()) {
                // A door or window lies in its wall: take the nearest wall's direction and a thin depth.
                const WallSegment* nearest = &walls.front();
                for (const auto& w : walls)
                    if (std::abs(w.signedDistance(box.center)) < std::abs(nearest->signedDistance(box.center))) nearest = &w;
                model::Vec3 d = nearest->direction();
                box.yaw = std::atan2(d.y, d.x);
                double along0 = 1e9, along1 = -1e9;
                for (const auto& p : cloud.points) {
                    double a = p.x * d.x + p.y * d.y;
                    along0 = std::min(along0, a), along1 = std::max(along1, a);
                }
                box.size = {along1 - along0, 0.05, box.size.z};
            }
            cv::Mat colors;
            for (const auto& v : track.views) colors.push_back(v.colors);
            Node& node = addNode(opening ? NodeKind::Anchor : NodeKind::Object, category,
                                 opening ? model::GeometryKind::Plane : model::GeometryKind::Box, box);
            if (!opening) {
                auto color = nameColor(colors);
                node.attributes.push_back({"color", color.name});
                node.attributes.push_back({"size", sizeWord(box)});
                if (!track.material.empty()) node.attributes.push_back({"material", track.material});
            }
            auto [first, last] = std::minmax_element(track.views.begin(), track.views.end(),
                                                     [](const auto& a, const auto& b) { return a.frame < b.frame; });
            node.attributes.push_back({"first_seen", std::to_string(capture.frames[first->frame].index)});
            node.attributes.push_back({"last_seen", std::to_string(capture.frames[last->frame].index)});
            node.attributes.push_back({"views", std::to_string(track.views.size())});
            node.confidence = static_cast<float>(std::min(1.0, 0.5 + 0.1 * track.views.size()));
            std::sort(node.attributes.begin(), node.attributes.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
            if (!track.evidence.jpeg.empty())
                scene.blobs.push_back({node.id, fmt::format("evidence-frame{}.jpg", capture.frames[track.evidence.frame].index),
                                       "image/jpeg", std::move(track.evidence.jpeg)});
            trackNode.emplace(t, node.id);
        }
        if (objects == ObjectSource::Cluster) {
            StructureOptions structureOptions;
            structureOptions.ceilingHeight = alignment.ceilingHeight;
            auto rest = nonStructuralPoints(aligned, walls, structureOptions);
            auto clusters = euclideanClusters(aligned, rest, 0.08, 30, 200000);
            for (const auto& cluster : clusters) {
                std::vector<model::Vec3> points;
                cv::Mat colors;
                for (auto i : cluster) {
                    points.push_back(aligned.points[i]);
                    const auto& c = aligned.colors[i];
                    colors.push_back(cv::Vec3b(c[2], c[1], c[0]));
                }
                model::Box box = uprightBox(points);
                if (box.size.x < 0.05 || box.size.y < 0.03 || box.size.z < 0.03) continue;  // specks
                Node& node = addNode(NodeKind::Object, "object", model::GeometryKind::Box, box);
                node.attributes.push_back({"color", nameColor(colors).name});
                node.attributes.push_back({"size", sizeWord(box)});
                node.attributes.push_back({"points", std::to_string(cluster.size())});
                node.confidence = 0.5f;
            }
            note(fmt::format("objects by 3D clustering (no masks): {} clusters, category 'object'", clusters.size()));
        }
        std::size_t count = std::count_if(scene.nodes.begin(), scene.nodes.end(), [](const Node& n) { return n.kind == NodeKind::Object; });
        stage.finish(fmt::format("{} objects", count));
    }

    // ---- Default viewpoint: the first camera, at its height, facing where it looked.
    {
        Pose first = transformed(cameras.front(), alignment);
        const auto& R = first.rotation;
        scene.info.viewpoint = {first.translation, std::atan2(R[5], R[2])};  // the camera's +z axis in the floor plane
        scene.info.viewpointNote = "the first camera of the capture, facing where it looked";
    }

    // ---- Parents, relations and two-layer descriptions.
    {
        Stage stage(progress, result.stages, "relations", 1);
        relations::Thresholds thresholds;
        relations::assignParents(scene, thresholds);

        // Vertical relations hold in the aligned frame: evaluate once, allocentric.
        std::vector<const Node*> things;
        for (const auto& n : scene.nodes)
            if (n.kind == NodeKind::Object) things.push_back(&n);
        relations::Frame none;
        for (const Node* a : things)
            for (const Node* b : things) {
                if (a == b) continue;
                for (auto p : {relations::Predicate::On, relations::Predicate::In}) {
                    double score = relations::evaluate(p, *a, *b, thresholds, none);
                    if (score > 0) scene.relations.push_back({a->id, b->id, p, static_cast<float>(score), 1, 0});
                }
            }

        // Lateral relations are view-local: left/right in each frame's image where both
        // instances are seen; promoted to allocentric when enough views agree.
        std::map<std::pair<NodeId, NodeId>, std::pair<int, int>> votes;  // (a, b) -> (left votes, views together)
        std::map<std::uint32_t, std::vector<std::pair<NodeId, double>>> byFrame;
        for (std::size_t t = 0; t < tracks.size(); ++t) {
            const auto& track = tracks[t];
            auto node = trackNode.find(t);
            if (node == trackNode.end()) continue;
            for (const auto& v : track.views) byFrame[v.frame].push_back({node->second, v.centreX});
        }
        // Each frame that saw objects is a frame node (its camera centre as a small box): the
        // view-local relations point at it.
        std::map<std::uint32_t, NodeId> frameNode;
        for (std::size_t c = 0; c < cameras.size(); ++c) {
            auto position = static_cast<std::uint32_t>(cameraFrames[c]);
            if (!byFrame.contains(position)) continue;
            model::Vec3 centre = alignment.apply(cameras[c].translation);
            Node& f = addNode(NodeKind::Frame, "frame", model::GeometryKind::Box, {centre, {0.05, 0.05, 0.05}, 0});
            f.text = capture.frames[position].colorPath;
            f.attributes = {{"frame", std::to_string(capture.frames[position].index)}};
            frameNode.emplace(position, f.id);
        }
        for (const auto& [frame, seen] : byFrame)
            for (const auto& [a, ax] : seen)
                for (const auto& [b, bx] : seen) {
                    if (a >= b) continue;
                    auto& vote = votes[{a, b}];
                    ++vote.second;
                    // As seen in this frame: left of / right of in the image, by at least 5% of its width.
                    std::optional<relations::Predicate> local;
                    if (ax < bx - 0.05) ++vote.first, local = relations::Predicate::LeftOf;
                    else if (ax > bx + 0.05) --vote.first, local = relations::Predicate::RightOf;
                    if (local)
                        scene.relations.push_back({a, b, *local, 1.0f, 1, frameNode.at(frame)});
                }
        std::map<NodeId, std::vector<std::string>> lateralPhrases;
        auto nodeById = [&](NodeId id) -> const Node& { return scene.nodes[id - 1]; };
        for (const auto& [pair, vote] : votes) {
            auto [a, b] = pair;
            int agree = std::abs(vote.first);
            if (vote.second < options.descriptionAgreement || agree < options.agreementShare * vote.second) continue;
            auto p = vote.first > 0 ? relations::Predicate::LeftOf : relations::Predicate::RightOf;
            scene.relations.push_back({a, b, p, static_cast<float>(double(agree) / vote.second),
                                       static_cast<std::uint32_t>(agree), 0});
            lateralPhrases[a].push_back(fmt::format("{} the {}", words(p), nodeById(b).category));
        }

        // Each view names the colour it sees; the scene-level phrase uses a colour only when
        // enough views agree on it.
        std::map<NodeId, std::vector<std::pair<std::uint32_t, std::string>>> viewColors;
        for (std::size_t t = 0; t < tracks.size(); ++t) {
            const auto& track = tracks[t];
            auto node = trackNode.find(t);
            if (node == trackNode.end() || nodeById(node->second).kind != NodeKind::Object) continue;
            for (const auto& v : track.views) viewColors[node->second].push_back({v.frame, nameColor(v.colors).name});
        }
        auto agreedColor = [&](NodeId id) -> std::optional<std::string> {
            std::map<std::string, int> counts;
            for (const auto& [frame, name] : viewColors[id]) ++counts[name];
            if (counts.empty()) return std::nullopt;
            auto best = std::max_element(counts.begin(), counts.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
            int views = static_cast<int>(viewColors[id].size());
            if (best->second < std::min(options.descriptionAgreement, views) || best->second < options.agreementShare * views)
                return std::nullopt;
            return best->first;
        };

        // Layer 2: the scene-level phrase, from what holds allocentrically (support) and what enough
        // views agree on (colour, lateral order). It is the object's text, the default answer.
        std::size_t objectCount = scene.nodes.size();
        for (std::size_t i = 0; i < objectCount; ++i) {
            Node& n = scene.nodes[i];
            if (n.kind != NodeKind::Object) continue;
            std::string support;
            for (const auto& r : scene.relations)
                if (r.subject == n.id && (r.type == model::RelationType::On || r.type == model::RelationType::In)) {
                    support = fmt::format(" {} the {}", model::toString(r.type), nodeById(r.object).category);
                    break;
                }
            auto color = viewColors.empty() ? (n.attribute("color") ? std::optional<std::string>(*n.attribute("color")) : std::nullopt)
                                            : agreedColor(n.id);
            std::string head = (color ? *color + " " : std::string()) + n.category;
            std::string scenePhrase = head + support;
            if (auto it = lateralPhrases.find(n.id); it != lateralPhrases.end()) scenePhrase += ", " + it->second.front();
            n.text = scenePhrase;
        }
        // Layer 1: a phrase per object per view, as description nodes below each object.
        for (const auto& [id, views] : viewColors) {
            std::string category = nodeById(id).category;
            for (const auto& [frame, colorName] : views) {
                Node& d = addNode(NodeKind::Description, "description", model::GeometryKind::None, {});
                d.parent = id;
                d.text = fmt::format("{} {}, seen in frame {}", colorName, category, capture.frames[frame].index);
                d.attributes = {{"frame", std::to_string(capture.frames[frame].index)}, {"layer", "image"}};
            }
        }
        stage.finish(fmt::format("{} relations", scene.relations.size()));
    }
    return result;
}

}  // namespace smql::ingest
