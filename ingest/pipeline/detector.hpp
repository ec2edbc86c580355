// An object detector that runs here (offline, CPU): NanoDet, trained on
// COCO's 80 classes, converted to ONNX at set-up (scripts/detector/) and run by
// OpenCV's DNN module. `--objects detect` feeds its boxes to the same lifting
// and association as detections.json (objects_from_detections.cpp);
// docs/ingest.md "Detector".
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>

#include "ingest/capture/detections.hpp"

namespace smql::ingest {

// The files of a prepared detector: the ONNX graph and its class names, one a line.
struct DetectorFiles {
    std::filesystem::path model;
    std::filesystem::path classes;
};

// Where scripts/detector/setup.sh installs the model (SMQL_MODEL_DIR at build time).
std::filesystem::path defaultModelDir();

// The files to use: the given ones (--detector, --classes; the class file
// defaults to coco.names beside the model), else those in defaultModelDir().
// nullopt when the model or the class file is missing.
std::optional<DetectorFiles> findDetectorFiles(const std::string& model = {}, const std::string& classes = {});

class ObjectDetector {
public:
    virtual ~ObjectDetector() = default;
    // The objects in a BGR image: memory categories (memoryCategory), scores,
    // boxes in the image's pixels; after non-maximum suppression, best first.
    // Detections of classes the memory does not keep (people, animals, vehicles) are left out.
    virtual std::vector<Detection> detect(const cv::Mat& bgr) = 0;
};

// The NanoDet detector. Throws smql::Error(Input) when the model does not load
// or its outputs or class file do not have the shapes NanoDet's have.
std::unique_ptr<ObjectDetector> makeNanoDetDetector(const DetectorFiles& files, double minScore = 0.35);

// A COCO class name -> the memory's category ("couch" -> "sofa", "dining
// table" -> "table"); empty for classes that are not part of a room's memory.
std::string memoryCategory(std::string_view cocoName);

}  // namespace smql::ingest
