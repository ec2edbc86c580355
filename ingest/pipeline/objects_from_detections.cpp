// Objects from an open-vocabulary detector's output (--objects detections):
// each frame's detections are lifted with its depth and associated into
// tracks across views (docs/ingest.md, "Objects from detections").
#include <algorithm>

#include <fmt/format.h>

#include "model/error.hpp"
#include "ingest/pipeline/detections.hpp"
#include "ingest/pipeline/geometry_stage.hpp"
#include "ingest/pipeline/object_finder.hpp"

namespace smql::ingest {

namespace {

class DetectionFinder : public ObjectFinder {
public:
    DetectionFinder(const Capture& capture, const IngestOptions& options)
        : capture_(capture), options_(options), detections_(readDetections(capture)) {}

    void observe(const PosedFrame& frame) override {
        const auto& detections = detections_[frame.position];
        const Intrinsics& stored = frame.frame.intrinsics ? *frame.frame.intrinsics : capture_.intrinsics;
        auto seen = observeDetections(frame.images, frame.pose, frame.position, detections, stored.width,
                                      options_.objectStride, options_.minInstancePixels);
        // The most confident detections found tracks first.
        std::stable_sort(seen.begin(), seen.end(), [&](const Observation& a, const Observation& b) {
            return detections[a.instance].score > detections[b.instance].score;
        });
        for (auto& o : seen) {
            const std::string& category = detections[o.instance].category;
            ObjectTrack& track = tracker_.add(std::move(o), category);
            keepLargestEvidence(track.evidence, track.views.back(), frame.images.color, options_.evidenceSize);
        }
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

}  // namespace

bool detectionsUsable(const Capture& capture) { return !capture.detectionsPath.empty() && framesHaveDepth(capture); }

std::unique_ptr<ObjectFinder> makeDetectionFinder(const Capture& capture, const IngestOptions& options) {
    if (!detectionsUsable(capture))
        throw Error(ErrorKind::Input,
                    fmt::format("{}: --objects detections needs detections.json and depth images", capture.path),
                    std::nullopt, "use --objects cluster for captures without detections");
    return std::make_unique<DetectionFinder>(capture, options);
}

}  // namespace smql::ingest
