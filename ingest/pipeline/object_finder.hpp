// Object sources (--objects, IngestOptions::objects): where a capture's objects come from. Each
// source is an ObjectFinder and its ObjectSourceSpec in a file of its own (objects_from_masks.cpp,
// objects_from_detections.cpp, objects_from_clusters.cpp; the detector's in
// objects_from_detections.cpp) and one line in the table of object_finder.cpp, which also sets the
// order `auto` tries them in. The frames stage shows a finder every posed frame
// and takes its tracks; the objects stage turns the tracks into nodes and then lets the finder add objects it finds in
// the aligned structure instead.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ingest/capture/capture.hpp"
#include "ingest/capture/frame_loader.hpp"
#include "ingest/capture/observations.hpp"
#include "ingest/geometry/walls.hpp"
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
    // Once the room is aligned: the tracks again, their views fused anew now that the floor and the
    // walls are known (ObjectTrack::fused); by default as they are.
    virtual std::vector<ObjectTrack> fuse(std::vector<ObjectTrack> tracks, const AlignedCapture& aligned,
                                          const std::vector<WallSegment>& walls, StageProgress& progress) {
        (void)aligned, (void)walls, (void)progress;
        return tracks;
    }
    // Once the things were fused (fuse): the share of the detections' boxes that the dense points of photos
    // without depth cover, where the finder measured it; nullopt for captures it did not (depth, no dense
    // points, no detection). Few points under what the detectors saw is why such a room cannot be measured
    // (plausibility.hpp: thinPointsFinding).
    virtual std::optional<double> pointsCover() const { return std::nullopt; }
    // After the tracks became nodes: objects found in the aligned structure
    // cloud rather than in the frames, added to `scene`.
    virtual void addStructureObjects(const AlignedCapture& aligned, const std::vector<WallSegment>& walls,
                                     model::SceneData& scene, StageProgress& progress) = 0;
};

// An object source: its name (--objects NAME), what it is for the help text, whether the capture has
// what it needs, and its finder (which throws smql::Error(Input), naming what is missing, when it
// has not). The sources are one table (object_finder.cpp, SMQL_OBJECT_SOURCES); each source's file
// defines its ObjectSourceSpec, named k<Name>Source.
struct ObjectSourceSpec {
    std::string_view name;
    std::string_view does;  // "detections.json beside the frames"
    bool (*usable)(const Capture& capture, const IngestOptions& options);
    std::unique_ptr<ObjectFinder> (*make)(const Capture& capture, const IngestOptions& options);
};
// Every source, in the order `auto` tries them: the most specific evidence first.
const std::vector<const ObjectSourceSpec*>& objectSources();
// The names --objects takes: every source's, and "auto".
std::vector<std::string> objectSourceNames();
// "masks (the instance masks), ... or auto (default: ...)": for --help.
std::string objectSourcesHelp();

// The finder for options.objects; `auto` takes the first source in the table that the capture can
// feed. Throws smql::Error(Usage) for a name no source has, and smql::Error(Input) when the capture
// lacks what the chosen source needs, or its files (labels, detections) are malformed.
std::unique_ptr<ObjectFinder> makeObjectFinder(const Capture& capture, const IngestOptions& options);

}  // namespace smql::ingest
