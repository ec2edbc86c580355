#include "ingest/pipeline/quality.hpp"
#include "ingest/capture/detections.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <unordered_map>

#include <Eigen/Geometry>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "ingest/capture/capture.hpp"
#include "ingest/import/importers.hpp"
#include "ingest/synth/walk.hpp"
#include "model/error.hpp"
#include "model/geometry.hpp"

namespace smql::ingest {

using model::Box;
using model::Node;
using model::NodeId;

namespace {

bool isStructural(const Node& n) {
    return n.kind == model::NodeKind::Anchor && (n.category == "wall" || isOpening(n.category));
}

bool counts(const Node& n) { return !n.hidden && n.geometry != model::GeometryKind::None; }

// Plane segments are compared as slabs 0.3 m thick: where exactly a wall's
// thin box sits within its thickness is not what the check is about.
Box slab(const Box& b) {
    Box out = b;
    if (out.size.x < out.size.y)
        out.size.x = std::max(out.size.x, 0.3);
    else
        out.size.y = std::max(out.size.y, 0.3);
    return out;
}

double overlapOfSmaller(const Box& a, const Box& b) {
    double inter = model::footprintOverlap(a, b) * model::verticalOverlap(a, b);
    double smaller = std::min(model::volume(a), model::volume(b));
    return smaller > 0 ? inter / smaller : 0.0;
}

// Greedy one-to-one matching, best score first; returns truth id -> ingested id.
template <class Score>
std::unordered_map<NodeId, NodeId> match(const std::vector<const Node*>& truth,
                                         const std::vector<const Node*>& ingested, double threshold, Score score) {
    std::vector<std::tuple<double, NodeId, NodeId>> pairs;
    for (const Node* t : truth)
        for (const Node* i : ingested) {
            if (t->category != i->category) continue;
            double s = score(*t, *i);
            if (s >= threshold) pairs.emplace_back(s, t->id, i->id);
        }
    std::sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) { return std::get<0>(a) > std::get<0>(b); });
    std::unordered_map<NodeId, NodeId> out;
    std::set<NodeId> used;
    for (const auto& [s, t, i] : pairs) {
        if (out.contains(t) || used.contains(i)) continue;
        out.emplace(t, i);
        used.insert(i);
    }
    return out;
}

}  // namespace

double boxIou(const Box& a, const Box& b) {
    double inter = model::footprintOverlap(a, b) * model::verticalOverlap(a, b);
    double uni = model::volume(a) + model::volume(b) - inter;
    return uni > 0 ? inter / uni : 0.0;
}

QualityReport compareToTruth(const model::SceneData& ingested, const model::SceneData& truth,
                             const QualityOptions& options) {
    auto seen = [&](const Node& n) { return options.visible.empty() || options.visible.contains(n.id); };
    std::vector<const Node*> truthAnchors, truthObjects, gotAnchors, gotObjects;
    for (const Node& n : truth.nodes) {
        if (!counts(n) || !seen(n)) continue;
        if (isStructural(n)) truthAnchors.push_back(&n);
        if (n.kind == model::NodeKind::Object) truthObjects.push_back(&n);
    }
    for (const Node& n : ingested.nodes) {
        if (!counts(n)) continue;
        if (isStructural(n)) gotAnchors.push_back(&n);
        if (n.kind == model::NodeKind::Object) gotObjects.push_back(&n);
    }

    QualityReport report;
    auto anchorMatch = match(truthAnchors, gotAnchors, 0.5,
                             [](const Node& t, const Node& i) { return overlapOfSmaller(slab(t.box), slab(i.box)); });
    auto objectMatch = match(truthObjects, gotObjects, options.objectIou,
                             [](const Node& t, const Node& i) { return boxIou(t.box, i.box); });
    report.anchors = {static_cast<int>(truthAnchors.size()), static_cast<int>(gotAnchors.size()),
                      static_cast<int>(anchorMatch.size())};
    report.objects = {static_cast<int>(truthObjects.size()), static_cast<int>(gotObjects.size()),
                      static_cast<int>(objectMatch.size())};

    std::unordered_map<NodeId, const Node*> truthById, gotById;
    for (const Node& n : truth.nodes) truthById.emplace(n.id, &n);
    for (const Node& n : ingested.nodes) gotById.emplace(n.id, &n);
    std::unordered_map<NodeId, NodeId> truthToGot = objectMatch;
    truthToGot.insert(anchorMatch.begin(), anchorMatch.end());

    double centerError = 0;
    for (const auto& [t, i] : objectMatch) {
        const Node& tn = *truthById.at(t);
        const Node& in = *gotById.at(i);
        centerError += model::centerDistance(tn.box, in.box);
        if (const std::string* want = tn.attribute("color")) {
            ++report.colorChecked;
            const std::string* got = in.attribute("color");
            report.colorCorrect += got && *got == *want;
        }
        // The parent is right when the ingested parent is the match of the truth parent
        // (the scene root matches the scene root).
        ++report.parentChecked;
        if (tn.parent == model::kNoNode) {
            report.parentCorrect += in.parent == model::kNoNode;
        } else if (auto m = truthToGot.find(tn.parent); m != truthToGot.end()) {
            report.parentCorrect += in.parent == m->second;
        }
    }
    report.meanCenterError = objectMatch.empty() ? 0.0 : centerError / objectMatch.size();

    std::set<NodeId> gotMatched;
    for (const auto& [t, i] : objectMatch) gotMatched.insert(i);
    auto unmatched = [&](const Node& n, bool inTruth, const std::vector<const Node*>& others) {
        UnmatchedObject u{inTruth, n.category, n.box};
        for (const Node* o : others) {
            if (o->category != n.category) continue;
            u.bestIou = std::max(u.bestIou, boxIou(n.box, o->box));
            double d = model::centerDistance(n.box, o->box);
            if (u.nearest < 0 || d < u.nearest) u.nearest = d;
        }
        report.unmatched.push_back(std::move(u));
    };
    for (const Node* t : truthObjects)
        if (!objectMatch.contains(t->id)) unmatched(*t, true, gotObjects);
    for (const Node* i : gotObjects)
        if (!gotMatched.contains(i->id)) unmatched(*i, false, truthObjects);
    return report;
}

std::vector<std::pair<NodeId, NodeId>> matchObjects(const model::SceneData& reference, const model::SceneData& other,
                                                    double minIou) {
    std::vector<const Node*> a, b;
    for (const Node& n : reference.nodes)
        if (n.kind == model::NodeKind::Object && counts(n)) a.push_back(&n);
    for (const Node& n : other.nodes)
        if (n.kind == model::NodeKind::Object && counts(n)) b.push_back(&n);
    auto pairs = match(a, b, minIou, [](const Node& x, const Node& y) { return boxIou(x.box, y.box); });
    return {pairs.begin(), pairs.end()};
}

CameraRegistration registerByCameras(const model::SceneData& ingested,
                                     const std::vector<std::pair<model::Vec3, model::Vec3>>& cameras) {
    const auto n = static_cast<Eigen::Index>(cameras.size());
    Eigen::Matrix3Xd from(3, n), to(3, n);
    for (Eigen::Index k = 0; k < n; ++k) {
        const auto& [a, b] = cameras[static_cast<std::size_t>(k)];
        from.col(k) << a.x, a.y, a.z;
        to.col(k) << b.x, b.y, b.z;
    }
    Eigen::Matrix4d T = Eigen::umeyama(from, to, true);
    CameraRegistration out;
    out.scale = T.block<3, 1>(0, 0).norm();
    Eigen::Matrix3d R = T.block<3, 3>(0, 0) / out.scale;
    Eigen::Vector3d shift = T.block<3, 1>(0, 3);
    for (Eigen::Index k = 0; k < n; ++k) out.residual += ((out.scale * R * from.col(k) + shift) - to.col(k)).norm();
    out.residual /= std::max<Eigen::Index>(n, 1);
    // Both frames are z-up, so the rotation is a turn about z.
    double yaw = std::atan2(R(1, 0), R(0, 0));
    out.mapped = ingested;
    for (auto& node : out.mapped.nodes) {
        Eigen::Vector3d m =
            out.scale * R * Eigen::Vector3d(node.box.center.x, node.box.center.y, node.box.center.z) + shift;
        node.box.center = {m.x(), m.y(), m.z()};
        node.box.size = {node.box.size.x * out.scale, node.box.size.y * out.scale, node.box.size.z * out.scale};
        node.box.yaw += yaw;
    }
    return out;
}

model::SceneData inCaptureFrame(const model::SceneData& ingested) {
    // alignment: aligned = A * capture, A = [s R | t]; undo it for centres and yaws.
    const auto& a = ingested.info.alignment;
    double s = std::cbrt(a[0] * (a[5] * a[10] - a[6] * a[9]) - a[1] * (a[4] * a[10] - a[6] * a[8]) +
                         a[2] * (a[4] * a[9] - a[5] * a[8]));
    if (!(s > 0)) s = 1;
    model::SceneData out = ingested;
    double yawOffset = std::atan2(a[4], a[0]);  // the alignment's turn about z
    for (auto& n : out.nodes) {
        model::Vec3 c = n.box.center;
        double px = c.x - a[3], py = c.y - a[7], pz = c.z - a[11];
        // R^T (p - t) / s
        n.box.center = {(a[0] * px + a[4] * py + a[8] * pz) / (s * s), (a[1] * px + a[5] * py + a[9] * pz) / (s * s),
                        (a[2] * px + a[6] * py + a[10] * pz) / (s * s)};
        n.box.size = {n.box.size.x / s, n.box.size.y / s, n.box.size.z / s};
        n.box.yaw -= yawOffset;
    }
    return out;
}

namespace {

// The true camera centres of pose.txt paired with the scene's frame nodes. A stored frame is the
// capture's n-th (its "frame" attribute, from 0); which pose line is the n-th frame's is decided as
// the rgbd layout decides it, from the frames' numbered images beside pose.txt (color/ and depth/,
// or the images/ of a colour-only copy), so a capture missing a frame is paired right. Without
// images there, line n is frame n. A frame node whose attribute is no position is not paired.
std::vector<std::pair<model::Vec3, model::Vec3>> cameraPairs(const model::SceneData& stored,
                                                             const std::filesystem::path& folder) {
    namespace fs = std::filesystem;
    std::vector<std::pair<model::Vec3, model::Vec3>> cameras;
    const fs::path poseFile = folder / "pose.txt";
    if (!fs::exists(poseFile)) return cameras;
    const fs::path colour = fs::is_directory(folder / "color") ? folder / "color" : folder / "images";
    std::vector<Pose> poses;
    if (fs::is_directory(colour)) {
        poses = posesInFrameOrder(poseFile.string(), colour.string(), (folder / "depth").string());
    } else {
        std::ifstream in(poseFile);
        for (std::string line; std::getline(in, line);)
            if (!line.empty()) poses.push_back(synth::parsePoseLine(line));
    }
    for (const auto& n : stored.nodes) {
        const std::string* frame = n.attribute("frame");
        std::size_t position = 0;
        if (n.kind != model::NodeKind::Frame || !frame) continue;
        const auto [end, error] = std::from_chars(frame->data(), frame->data() + frame->size(), position);
        if (error != std::errc() || end != frame->data() + frame->size()) continue;
        if (position < poses.size()) cameras.push_back({n.box.center, poses[position].translation});
    }
    return cameras;
}

std::set<model::NodeId> visibleNodes(const std::filesystem::path& visibility) {
    std::set<model::NodeId> visible;
    if (!std::filesystem::exists(visibility)) return visible;
    std::ifstream in(visibility);
    try {
        auto j = nlohmann::json::parse(in);
        for (const auto& entry : j.at("instances"))
            if (entry.at("frames").get<int>() > 0) visible.insert(entry.at("id").get<model::NodeId>());
    } catch (const nlohmann::json::exception& e) {
        throw Error(ErrorKind::Input, fmt::format("{}: {}", visibility.string(), e.what()), std::nullopt,
                    "visibility.json holds {\"instances\": [{\"id\": 1, \"frames\": 12}]}");
    }
    return visible;
}

}  // namespace

TruthCheck checkAgainstTruth(const model::SceneData& stored, const std::string& truthPath) {
    const model::SceneData truth = import::readSceneJson(truthPath);
    const std::filesystem::path folder = std::filesystem::path(truthPath).parent_path();
    TruthCheck check;
    auto cameras = cameraPairs(stored, folder);
    check.cameras = cameras.size();
    if (cameras.size() >= 3) check.registration = registerByCameras(stored, cameras);
    model::SceneData ingested = check.registration ? check.registration->mapped : inCaptureFrame(stored);
    check.options.visible = visibleNodes(folder / "visibility.json");
    check.report = compareToTruth(ingested, truth, check.options);
    return check;
}

std::vector<std::pair<std::string, double>> truthCheckFigures(const TruthCheck& check) {
    const QualityReport& r = check.report;
    std::vector<std::pair<std::string, double>> figures = {
        {"anchors_f1", r.anchors.f1()},
        {"anchors_precision", r.anchors.precision()},
        {"anchors_recall", r.anchors.recall()},
        {"objects_f1", r.objects.f1()},
        {"objects_precision", r.objects.precision()},
        {"objects_recall", r.objects.recall()},
        {"color_accuracy", r.colorAccuracy()},
        {"parent_accuracy", r.parentAccuracy()},
        {"mean_center_error_m", r.meanCenterError},
    };
    if (check.registration) figures.emplace_back("scale_error", std::abs(check.registration->scale - 1));
    return figures;
}

}  // namespace smql::ingest
