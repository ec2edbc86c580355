// Capture -> metric memory (docs/ingest.md): frames, geometry, metric
// alignment, anchors, objects, attributes, openings, relations, two-layer descriptions.
// The result is one SceneData that the engine stores in one transaction.
// pipeline.cpp runs the stages (*_stage.hpp, stage_data.hpp) in order.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "ingest/capture/capture.hpp"
#include "ingest/geometry/colmap_runner.hpp"
#include "ingest/geometry/dense_stereo.hpp"
#include "model/types.hpp"

namespace smql::ingest {

enum class GeometrySource { Given, Colmap, Auto };

// What the dense points of photos without depth (dense_stereo.hpp) are used for: none made (Off); the
// room's surfaces, so the floor, its up and the scale, the walls and openings (Room); those and the
// things, each photo's detections lifted on the depth the points give it (All); those and the things
// where the points cover what the detectors saw, else the room's alone (Auto: kDenseCoverToLift).
enum class DenseUse { Off, Room, All, Auto };
// Auto lifts the things on the dense points when those cover at least this share of the detections'
// boxes, pixel by pixel, in the photos the things are lifted from: 0.73-0.87 in cluttered real rooms' photos
// (TUM's office and desk, 7-Scenes' kitchen; ScanNet's lounge 0.65), 0.42 in a bathroom's, 0.03 in five dining
// photos a wide step apart and 0.44-0.59 in generated walks, whose flat colours stereo cannot match
// (docs/ingest.md, "Dense points from placed photos").
inline constexpr double kDenseCoverToLift = 0.65;
// ... and at least this share where the room the sparse points' things placed is not measured (its floor
// unconfirmed, or its scale on one prior): the lifted things are then its one chance to be measured again. Below
// half, most of a thing's box has no depth and its lift is a fragment: the five dining photos' (3 %) lifted
// "chair" and "fridge" stood on the floor and stored them 1.7x too large.
inline constexpr double kDenseCoverToMeasure = 0.5;

struct IngestOptions {
    std::string sceneName;
    GeometrySource geometry = GeometrySource::Auto;
    // Where the objects come from: a source of the table in object_finder.cpp by name ("masks",
    // "detections", "detect", "cluster"), or "auto", the first the capture can feed.
    std::string objects = "auto";
    std::string detectorModel;           // --detector: the ONNX model (default: defaultModelDir()/nanodet.onnx)
    std::string detectorClasses;         // --classes: its class names (default: coco.names beside the model)
    std::optional<double> scale;         // metres per capture unit, overriding the alignment's estimate
    std::optional<double> cameraHeight;  // m: the cameras' median height above the floor, when known
    bool force = false;                  // keep a memory the plausibility checks refuse (plausibility.hpp)
    int workingWidth = 640;
    int structureStride = 4;          // every n-th pixel of each frame feeds the structure cloud
    double structureVoxel = 0.05;     // m
    int objectStride = 2;             // every n-th pixel of an instance mask is lifted
    double objectVoxel = 0.01;        // m
    int minInstancePixels = 150;      // smaller mask fragments in a frame are ignored
    int minObjectViews = 1;           // an instance needs this many views to become an object
    int descriptionAgreement = 2;     // views that must agree before a scene-level phrase is promoted
    double agreementShare = 0.6;      // ... and the share of its views they must be
    int evidenceSize = 160;           // longest side of an evidence crop (pixels)
    ColmapOptions colmap;             // --geometry colmap (and auto for captures without poses)
    DenseUse dense = DenseUse::Auto;  // photos without depth: what dense points from pairs of placed frames place
    DenseOptions denseOptions;
    double sparseDepthBand = 0.25;  // sparse points lifted onto a mask: within this share of the median depth
};

// Progress of a long ingest, stage by stage. Implementations print a bar, JSON
// lines or nothing (shell/ingest_command.cpp).
class ProgressSink {
public:
    virtual ~ProgressSink() = default;
    // The capture's frames, once it is read: what a stage's rate (frames a second) is counted in.
    virtual void captureRead(std::size_t frames) { (void)frames; }
    virtual void stageStarted(const std::string& stage, std::size_t steps) = 0;
    virtual void advanced(std::size_t done) = 0;
    virtual void stageFinished(const std::string& stage, double seconds, const std::string& summary) = 0;
    virtual void note(const std::string& text) = 0;
};

struct StageTiming {
    std::string stage;
    double seconds = 0;
    std::string summary;
};

struct IngestResult {
    model::SceneData scene;
    std::vector<StageTiming> stages;
    std::vector<std::string> notes;
    // Every frame that had a pose: (position in the capture, camera centre in
    // the aligned frame, metres). For checking COLMAP runs against truth poses.
    std::vector<std::pair<std::size_t, model::Vec3>> cameraCentres;
};

// Throws smql::Error(Input) for captures the chosen sources cannot handle
// (naming what to try instead). A `cancelled` callback returning true stops
// the work between frames with Error(Usage, "cancelled").
IngestResult ingestCapture(const Capture& capture, const IngestOptions& options, ProgressSink& progress,
                           const std::function<bool()>& cancelled = {});

}  // namespace smql::ingest
