// Object sources (--objects, IngestOptions::objects): where a capture's
// objects come from. Each source is an ObjectFinder in a file of its own
// (objects_from_masks.cpp, objects_from_detections.cpp,
// objects_from_clusters.cpp; the detector's in objects_from_detections.cpp) and one line in the table of
// object_finder.cpp, which also sets the order `auto` tries them in. The frames stage shows a finder every posed frame
// and takes its tracks; the objects stage turns the tracks into nodes and then lets the finder add objects it finds in
// the aligned structure instead.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "ingest/capture/capture.hpp"
#include "ingest/capture/frame_loader.hpp"
#include "ingest/geometry/walls.hpp"
#include "ingest/pipeline/observations.hpp"
#include "ingest/pipeline/pipeline.hpp"
#include "ingest/pipeline/stage_data.hpp"
#include "ingest/pipeline/stage_runner.hpp"
#include "model/types.hpp"

namespace smql::ingest {

// A frame of the frame pass that has a pose, loaded at the working resolution.
struct PosedFrame {
    std::uint32_t position = 0;  // in Capture::frames
    const CaptureFrame& frame;
    const FrameImages& images;
    const Pose& pose;
};

class ObjectFinder {
public:
    virtual ~ObjectFinder() = default;
    // Every posed frame, in capture order.
    virtual void observe(const PosedFrame& frame) = 0;
    // After the last frame: one track per physical instance the frames showed.
    virtual std::vector<ObjectTrack> takeTracks() = 0;
    // After the last frame: a line for the user on the source's own work (the detector's time per
    // frame), or empty.
    virtual std::string frameNote() const { return {}; }
    // After the tracks became nodes: objects found in the aligned structure
    // cloud rather than in the frames, added to `scene`.
    virtual void addStructureObjects(const AlignedCapture& aligned, const std::vector<WallSegment>& walls,
                                     model::SceneData& scene, StageProgress& progress) = 0;
};

// The finder for options.objects; `auto` takes the first source in the table
// that the capture can feed. Throws smql::Error(Input) when the capture lacks
// what the chosen source needs, or its files (labels, detections) are malformed.
std::unique_ptr<ObjectFinder> makeObjectFinder(const Capture& capture, const IngestOptions& options);

// The sources. `...Usable` says whether the capture has what the source needs;
// `make...` throws smql::Error(Input), naming what is missing, when it has not.
bool masksUsable(const Capture& capture, const IngestOptions& options);
std::unique_ptr<ObjectFinder> makeMaskFinder(const Capture& capture, const IngestOptions& options);
bool detectionsUsable(const Capture& capture, const IngestOptions& options);
std::unique_ptr<ObjectFinder> makeDetectionFinder(const Capture& capture, const IngestOptions& options);
// The detector run on the frames (--objects detect): needs depth and a prepared model.
bool detectorUsable(const Capture& capture, const IngestOptions& options);
std::unique_ptr<ObjectFinder> makeDetectorFinder(const Capture& capture, const IngestOptions& options);
bool clustersUsable(const Capture& capture, const IngestOptions& options);
std::unique_ptr<ObjectFinder> makeClusterFinder(const Capture& capture, const IngestOptions& options);

}  // namespace smql::ingest
