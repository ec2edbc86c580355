// Objects from 2D detections: an open-vocabulary detector's output
// (--objects detections, detections.json) or the detector run here on the
// frames (--objects detect, detector.hpp). Each frame's detections are lifted
// with its depth and associated into tracks across views (docs/ingest.md,
// "Objects from detections" and "Detector").
#include <algorithm>
#include <chrono>

#include <fmt/format.h>

#include "ingest/pipeline/detections.hpp"
#include "ingest/pipeline/detector.hpp"
#include "ingest/pipeline/geometry_stage.hpp"
#include "ingest/pipeline/object_finder.hpp"
#include "model/error.hpp"

namespace smql::ingest {

namespace {

// The frame's detections, lifted and associated, the most confident first.
// `storedWidth` is the width of the image the detections were made on.
void trackDetections(const PosedFrame& frame, const std::vector<Detection>& detections, int storedWidth,
                     const IngestOptions& options, DetectionTracker& tracker) {
    auto seen = observeDetections(frame.images, frame.pose, frame.position, detections, storedWidth,
                                  options.objectStride, options.minInstancePixels);
    // The most confident detections found tracks first.
    std::stable_sort(seen.begin(), seen.end(), [&](const Observation& a, const Observation& b) {
        return detections[a.instance].score > detections[b.instance].score;
    });
    for (auto& o : seen) {
        const Detection& detection = detections[o.instance];
        o.embedding = detection.embedding;
        ObjectTrack& track = tracker.add(std::move(o), detection.category, detection.score);
        keepLargestEvidence(track.evidence, track.views.back(), frame.images.color, options.evidenceSize);
    }
}

class DetectionFinder : public ObjectFinder {
public:
    DetectionFinder(const Capture& capture, const IngestOptions& options)
        : capture_(capture), options_(options), detections_(readDetections(capture)) {}

    void observe(const PosedFrame& frame) override {
        const Intrinsics& stored = frame.frame.intrinsics ? *frame.frame.intrinsics : capture_.intrinsics;
        trackDetections(frame, detections_[frame.position], stored.width, options_, tracker_);
    }

    std::vector<ObjectTrack> takeTracks() override { return tracker_.take(); }

    void addStructureObjects(const AlignedCapture&, const std::vector<WallSegment>&, model::SceneData&,
                             StageProgress&) override {}

private:
    const Capture& capture_;
    const IngestOptions& options_;
    std::vector<std::vector<Detection>> detections_;  // per capture frame
    DetectionTracker tracker_;
};

// The detector sees each frame at the working resolution; its labels are voted across views.
class DetectorFinder : public ObjectFinder {
public:
    DetectorFinder(const DetectorFiles& files, const IngestOptions& options)
        : files_(files), options_(options), detector_(makeNanoDetDetector(files)), tracker_(/*voteLabels=*/true) {}

    void observe(const PosedFrame& frame) override {
        auto start = std::chrono::steady_clock::now();
        auto detections = detector_->detect(frame.images.color);
        milliseconds_.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        detections_ += detections.size();
        trackDetections(frame, detections, frame.images.color.cols, options_, tracker_);
    }

    std::vector<ObjectTrack> takeTracks() override { return tracker_.take(); }

    std::string frameNote() const override {
        if (milliseconds_.empty()) return {};
        auto sorted = milliseconds_;
        std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
        return fmt::format("detector: {} on {} frames, {} detections, median {:.0f} ms per frame",
                           files_.model.filename().string(), milliseconds_.size(), detections_,
                           sorted[sorted.size() / 2]);
    }

    void addStructureObjects(const AlignedCapture&, const std::vector<WallSegment>&, model::SceneData&,
                             StageProgress&) override {}

private:
    DetectorFiles files_;
    const IngestOptions& options_;
    std::unique_ptr<ObjectDetector> detector_;
    DetectionTracker tracker_;
    std::vector<double> milliseconds_;  // the detector's time on each frame
    std::size_t detections_ = 0;
};

}  // namespace

bool detectionsUsable(const Capture& capture, const IngestOptions&) {
    return !capture.detectionsPath.empty() && framesHaveDepth(capture);
}

std::unique_ptr<ObjectFinder> makeDetectionFinder(const Capture& capture, const IngestOptions& options) {
    if (!detectionsUsable(capture, options))
        throw Error(ErrorKind::Input,
                    fmt::format("{}: --objects detections needs detections.json and depth images", capture.path),
                    std::nullopt, "use --objects detect (the detector) or cluster for captures without detections");
    return std::make_unique<DetectionFinder>(capture, options);
}

bool detectorUsable(const Capture& capture, const IngestOptions& options) {
    return framesHaveDepth(capture) && findDetectorFiles(options.detectorModel, options.detectorClasses);
}

std::unique_ptr<ObjectFinder> makeDetectorFinder(const Capture& capture, const IngestOptions& options) {
    if (!framesHaveDepth(capture))
        throw Error(ErrorKind::Input, fmt::format("{}: --objects detect needs depth images", capture.path),
                    std::nullopt, "use --objects cluster for captures without depth");
    auto files = findDetectorFiles(options.detectorModel, options.detectorClasses);
    if (!files)
        throw Error(
            ErrorKind::Input,
            options.detectorModel.empty()
                ? fmt::format("no detector model in {} (nanodet.onnx and coco.names)", defaultModelDir().string())
                : fmt::format("{}: the detector model or its class file ({}) is missing", options.detectorModel,
                              options.detectorClasses.empty() ? "coco.names beside it" : options.detectorClasses),
            std::nullopt, "prepare the model with scripts/detector/setup.sh, or give --detector and --classes");
    return std::make_unique<DetectorFinder>(*files, options);
}

}  // namespace smql::ingest
