// Object detectors that run here (offline, CPU): NanoDet, trained on COCO's
// 80 classes, and the Open Images SSD of MediaPipe's Objectron, converted to
// ONNX at set-up (scripts/detector/) and run on XNNPACK (network.hpp).
// `--objects detect` feeds their boxes to the same lifting and fusion as
// detections.json (objects_from_detections.cpp); docs/ingest.md "Detector".
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>

#include "ingest/capture/detections.hpp"
#include "ingest/pipeline/network.hpp"

namespace smql::ingest {

// The files of a prepared model: the ONNX graph and its class names, one a line.
struct DetectorFiles {
    std::filesystem::path model;
    std::filesystem::path classes;
};

// The models set-up prepares (scripts/detector/setup.sh), one table: their name, files, role and what
// they know. Detectors find boxes; a segmenter labels every pixel.
enum class ModelRole { Detector, Segmenter };
struct PackagedModel {
    std::string_view name;     // "nanodet"
    std::string_view file;     // "nanodet.onnx", in defaultModelDir()
    std::string_view classes;  // "coco.names", beside it
    ModelRole role;
    std::string_view what;  // "NanoDet, trained on COCO (80 classes)"
};
const std::vector<PackagedModel>& packagedModels();

// Where scripts/detector/setup.sh installs the models (SMQL_MODEL_DIR at build time).
std::filesystem::path defaultModelDir();

// The files of the packaged model `name` in defaultModelDir(); nullopt when it is not installed.
std::optional<DetectorFiles> installedModel(std::string_view name);

// The detector's files: the given ones (--detector, --classes; the class file
// defaults to coco.names beside the model), else the packaged NanoDet's.
// nullopt when the model or the class file is missing.
std::optional<DetectorFiles> findDetectorFiles(const std::string& model = {}, const std::string& classes = {});

class ObjectDetector {
public:
    virtual ~ObjectDetector() = default;
    // The objects in a BGR image: memory categories (memoryCategory), scores,
    // boxes in the image's pixels; after non-maximum suppression, best first.
    // Detections of classes the memory does not keep (people, animals, vehicles) are left out.
    virtual std::vector<Detection> detect(const cv::Mat& bgr) = 0;
    // The models it runs, for the log ("nanodet.onnx + oid_ssd.onnx").
    virtual std::string describe() const = 0;
};

// The NanoDet detector, its graph placed as `placement` says (loadNetwork). Throws
// smql::Error(Input) when the model does not load or its outputs or class file do not have the shapes NanoDet's have.
inline constexpr double kNanoDetMinScore = 0.35;
std::unique_ptr<ObjectDetector> makeNanoDetDetector(const DetectorFiles& files, double minScore = kNanoDetMinScore,
                                                    const GraphPlacement& placement = {});

// An SSD with its boxes decoded in the graph (the Open Images detector, scripts/detector/oid_setup.sh):
// a 1x3x300x300 RGB image in [-1, 1] gives boxes (N x 4: top, left, bottom, right, in shares of the image)
// and class scores (N x classes, sigmoid).
inline constexpr double kSsdMinScore = 0.4;
std::unique_ptr<ObjectDetector> makeSsdDetector(const DetectorFiles& files, double minScore = kSsdMinScore,
                                                const GraphPlacement& placement = {});

// One model's raw boxes (image pixels), scores and class indices (into `categories`) to its detections: those
// scored at least minScore, one per thing per class (non-maximum suppression, and a box nested in a larger one
// of its class is that thing's part), best first.
std::vector<Detection> suppressPerClass(const std::vector<cv::Rect2d>& boxes, const std::vector<float>& scores,
                                        const std::vector<int>& labels, const std::vector<std::string>& categories,
                                        double minScore);

// Every member runs on each image; boxes of different members that overlap by kSameThingIou are one
// detection, the best scored one's box and name, the others' names in Detection::alsoSeenAs.
inline constexpr double kSameThingIou = 0.5;
std::unique_ptr<ObjectDetector> makeDetectorEnsemble(std::vector<std::unique_ptr<ObjectDetector>> members);

// The detector `--objects detect` runs: the model given by --detector (a NanoDet graph), else every
// packaged detector that is installed, each placed as `placement` says. Throws smql::Error(Input) as
// makeNanoDetDetector does.
std::unique_ptr<ObjectDetector> makeDetector(const DetectorFiles& files, bool packaged,
                                             const GraphPlacement& placement = {});

// A model's class name (COCO, Open Images, PASCAL VOC) -> the memory's category ("couch" -> "sofa",
// "Computer monitor" -> "monitor"); empty for classes that are not part of a room's memory.
std::string memoryCategory(std::string_view className);

}  // namespace smql::ingest
