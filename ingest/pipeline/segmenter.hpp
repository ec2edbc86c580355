// The semantic segmenter that runs here (offline, CPU): DeepLab v3 (MobileNetV2) trained on PASCAL VOC,
// converted to ONNX at set-up (scripts/detector/setup.sh) and run on XNNPACK (network.hpp). It names
// every pixel of a frame; `--objects detect` cuts each detection of a kind it knows (chairs, sofas,
// tables, tvs, plants, bottles) to the pixels it names so, which keeps a table's box apart from the
// chairs in it (docs/ingest.md, "Detector").
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "ingest/capture/detections.hpp"
#include "ingest/pipeline/detector.hpp"

namespace smql::ingest {

class SemanticSegmenter {
public:
    virtual ~SemanticSegmenter() = default;
    // Each pixel's class (an index into categories()) for a BGR image, at the image's size.
    virtual cv::Mat1b segment(const cv::Mat& bgr) = 0;
    // The memory's category of each class ("" for the background and what a room's memory does not keep).
    virtual const std::vector<std::string>& categories() const = 0;
    virtual std::string describe() const = 0;
};

// DeepLab's graph: "image", 1x3x385x513 RGB in [-1, 1], gives "logits_lowres", 1 x classes x 25 x 33.
// Its graph is placed as `placement` says (loadNetwork). Throws smql::Error(Input) when the model does not load
// or its outputs do not have that shape.
std::unique_ptr<SemanticSegmenter> makeDeepLabSegmenter(const DetectorFiles& files,
                                                        const GraphPlacement& placement = {});

// A detection's mask from the segmenter's labels: the pixels of its box whose class is the
// detection's kind. Left as it is (the box) when the segmenter does not know the kind, or names it
// on fewer than kMinMaskShare of the box's pixels (it missed the thing).
inline constexpr double kMinMaskShare = 0.15;
void maskBySegments(Detection& detection, const cv::Mat1b& labels, const std::vector<std::string>& categories);
// Whether the segmenter knows the detection's kind, so that maskBySegments may cut it: a frame none of whose
// detections it knows is left as its boxes with or without the segmenter's labels.
bool segmentable(const Detection& detection, const std::vector<std::string>& categories);

}  // namespace smql::ingest
