// How close an ingested scene is to the ground truth of a synthetic capture
// (`smql check-ingest`): anchors and objects matched one to one, then
// precision / recall / F1, colour accuracy and parent accuracy on the matches.
#pragma once

#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "model/types.hpp"

namespace smql::ingest {

struct MatchCounts {
    int truth = 0;      // truth nodes that count (seen in the capture)
    int predicted = 0;  // ingested nodes
    int matched = 0;
    double precision() const { return predicted ? double(matched) / predicted : 0.0; }
    double recall() const { return truth ? double(matched) / truth : 0.0; }
    double f1() const {
        double p = precision(), r = recall();
        return p + r > 0 ? 2 * p * r / (p + r) : 0.0;
    }
};

// An object on one side that found no match on the other: what it is, where, and how close the
// nearest object of its category on the other side came.
struct UnmatchedObject {
    bool inTruth = true;  // a truth object the ingest missed; false: an ingested object the truth lacks
    std::string category;
    model::Box box;
    double bestIou = 0;   // with any object of its category on the other side
    double nearest = -1;  // centre distance to the nearest of them (m); -1 when there is none
};

struct QualityReport {
    MatchCounts anchors;  // walls, doors and windows
    MatchCounts objects;  // same category and 3D IoU >= the threshold
    int colorChecked = 0, colorCorrect = 0;
    int parentChecked = 0, parentCorrect = 0;
    double meanCenterError = 0;              // metres, over matched objects
    std::vector<UnmatchedObject> unmatched;  // truth objects first
    double colorAccuracy() const { return colorChecked ? double(colorCorrect) / colorChecked : 0.0; }
    double parentAccuracy() const { return parentChecked ? double(parentCorrect) / parentChecked : 0.0; }
};

struct QualityOptions {
    double objectIou = 0.25;
    // Truth nodes (local ids) the capture shows; empty = all of them.
    std::set<model::NodeId> visible;
};

// Both scenes in the same frame (the truth's). Node ids are each scene's own.
QualityReport compareToTruth(const model::SceneData& ingested, const model::SceneData& truth,
                             const QualityOptions& options = {});

// The objects of two scenes of one place paired one to one: same category,
// 3D IoU >= minIou, best pairs first. Pairs of (reference id, other id).
std::vector<std::pair<model::NodeId, model::NodeId>> matchObjects(const model::SceneData& reference,
                                                                  const model::SceneData& other, double minIou);

// 3D intersection over union of two upright boxes.
double boxIou(const model::Box& a, const model::Box& b);

// An ingested scene mapped into the truth frame by the similarity (Umeyama)
// that best carries its camera centres onto the true ones: how scale-free
// (COLMAP) runs are compared with the truth. `scale` is that similarity's
// scale: 1 when the ingest got the metric scale right.
struct CameraRegistration {
    model::SceneData mapped;
    double scale = 1;
    double residual = 0;  // mean camera distance after the mapping (m)
};
// Pairs of (camera centre in the ingested scene, true camera centre); at least 3.
CameraRegistration registerByCameras(const model::SceneData& ingested,
                                     const std::vector<std::pair<model::Vec3, model::Vec3>>& cameras);

// The ingested scene brought back into the capture's frame (undoing the
// alignment stored on the scene), where a synthetic capture's truth lives.
model::SceneData inCaptureFrame(const model::SceneData& ingested);

// `smql check-ingest`: a stored scene against the truth.json of its synthetic capture. Into the
// truth's frame through the true camera poses beside the truth (pose.txt, as smql synth writes
// it) when the scene keeps its cameras as frame nodes, which also measures the metric scale of
// scale-free (COLMAP) runs; else by undoing the scene's stored alignment. visibility.json beside
// the truth, when there, says which truth nodes the capture shows at all.
struct TruthCheck {
    QualityReport report;
    QualityOptions options;
    std::optional<CameraRegistration> registration;
    std::size_t cameras = 0;  // camera pairs the registration used
};
TruthCheck checkAgainstTruth(const model::SceneData& stored, const std::string& truthPath);

// The figures of a check by name (anchors_f1, objects_recall, scale_error ...), for programs.
std::vector<std::pair<std::string, double>> truthCheckFigures(const TruthCheck& check);

}  // namespace smql::ingest
