// Objects from an open-vocabulary detector's output (detections.json,
// COCO-results style; docs/formats.md "detections.json"): reading and
// checking the file, lifting each detection of a frame into an Observation,
// and associating observations across views, since detections carry no
// identity from one frame to the next.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "ingest/capture/capture.hpp"
#include "ingest/capture/frame_loader.hpp"
#include "ingest/capture/observations.hpp"

namespace smql::ingest {

// Detections under this score are ignored: open-vocabulary detectors emit many
// low-confidence guesses that would become phantom objects.
inline constexpr double kMinDetectionScore = 0.3;
// Pixels whose depth is farther than this from the median depth inside the
// mask are left out of a view's points (Observation::points, what views are
// associated by before the floor is known): a box also covers the background.
inline constexpr double kDetectionDepthBand = 0.25;  // m
// A pixel inside several detections' masks belongs to the smallest whose
// median depth it lies at most this far behind (a mug on a table, a chair in
// front of a sofa), else to the next larger: a smaller thing stands in front.
inline constexpr double kOwnedBehind = 0.3;  // m
// A view's region (Observation::region) keeps about this many of its pixels,
// on a regular grid.
inline constexpr int kRegionPoints = 3000;

struct Detection {
    std::string category;
    double score = 0;
    cv::Rect2d box;                                  // pixels of the stored image
    std::vector<std::vector<cv::Point2d>> polygons;  // COCO polygons, pixels of the stored image
    cv::Mat1b mask;  // its own mask (stored image size): a COCO RLE mask decoded, or the segmenter's (segmenter.hpp)
    // Neither polygons nor a mask: the box is the mask.
    std::vector<float> embedding;  // the detector's vector for what it saw; empty when it gave none
    // What other models called the same box (the detectors' ensemble, detector.hpp): name and score.
    std::vector<std::pair<std::string, double>> alsoSeenAs;
};

// Reads capture.detectionsPath; the result has one list per capture frame (by
// position). Throws smql::Error(Input) "<file>: detections[i].field: ..." on
// missing fields, wrong types, non-finite numbers, boxes outside the image,
// images the capture does not have, RLE masks that do not decode to the image's size,
// and embeddings that model::embeddingProblem refuses or that differ in length.
std::vector<std::vector<Detection>> readDetections(const Capture& capture);

// Lifts the frame's detections (score >= kMinDetectionScore) into observations
// with the frame's depth; Observation::instance is 1 + the detection's position
// in `detections` (0 is no instance, as in masks). `storedWidth` is the width
// of the image the detections were made on. Each pixel goes to one detection
// (kOwnedBehind); its points within kDetectionDepthBand of the median depth
// are the view's points, all of them (sub-sampled) its region.
std::vector<Observation> observeDetections(const FrameImages& images, const Pose& pose, std::uint32_t frame,
                                           const std::vector<Detection>& detections, int storedWidth, int stride,
                                           int minPixels);

// Frames without depth: the frame's detections (score >= kMinDetectionScore)
// painted into an instance image at the working resolution (intrinsics `K`;
// CV_16U) with the value 1 + their position, the larger first so that a
// smaller thing in front of a larger one keeps its pixels.
cv::Mat detectionInstances(const Intrinsics& K, const std::vector<Detection>& detections, int storedWidth);

// The detection's whole box in the pixels of the working resolution
// (intrinsics `K`), clipped to the image.
cv::Rect detectionBounds(const Detection& detection, const Intrinsics& K, int storedWidth);

// What a detection of `category` becomes: structure is geometry's job, and doors and windows become
// anchors like labelled masks (Anchor); everything else an object.
model::NodeKind detectionKind(const std::string& category);
// Doors and windows: anchors that are openings in a wall (a plane segment in it).
bool isOpening(const std::string& category);

// The detection's own outline (polygons or RLE mask) at the working
// resolution, cropped to detectionBounds; empty when the box is all it gives.
cv::Mat1b detectionOutline(const Detection& detection, const Intrinsics& K, int storedWidth);

// Greedy association of observations into tracks (docs/ingest.md, "Objects
// from detections"): an observation joins the track of its category, not yet
// seen in its frame, whose 3D bounds overlap the observation's by IoU >= 0.1
// or whose centroid lies within max(0.3 m, half the track's largest extent) of
// the observation's; else it starts a new track.
//
// With `voteLabels` (a closed-set detector, whose label for one thing may
// change from view to view) an observation also joins a track of another
// category whose bounds it overlaps by IoU >= kRelabelIou, and a track's
// category is the one with the largest sum of scores over its views: one bad
// view does not rename a sofa.
inline constexpr double kRelabelIou = 0.3;

class DetectionTracker {
public:
    explicit DetectionTracker(bool voteLabels = false) : voteLabels_(voteLabels) {}
    // Returns the track the observation joined (to update its evidence).
    ObjectTrack& add(Observation observation, const std::string& category, double score = 1);
    // The tracks, after merging those the rule joins that never share a frame (order independence).
    std::vector<ObjectTrack> take();
    std::size_t size() const { return tracks_.size(); }

private:
    struct Extent {
        model::Vec3 lo{1e18, 1e18, 1e18}, hi{-1e18, -1e18, -1e18}, sum{0, 0, 0};
        std::size_t count = 0;
        std::set<std::uint32_t> frames;
        std::map<std::string, double> votes;  // category -> sum of the scores of its views
    };
    static void relabel(ObjectTrack& track, const Extent& extent);
    static std::optional<std::pair<double, double>> fit(const Extent& track, const Extent& observation);
    static void merge(Extent& into, const Extent& from);
    bool voteLabels_;
    std::vector<ObjectTrack> tracks_;
    std::vector<Extent> extents_;
};

}  // namespace smql::ingest
