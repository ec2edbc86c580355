// What flows from one ingest stage to the next (ingest/pipeline/pipeline.cpp
// runs them in this order; docs/ingest.md, "Stages"):
//
//   Capture --colmap--> Reconstruction (only without poses)
//           --dense--> Reconstruction (only without depth)
//           --frames--> FramePass --align--> AlignedCapture
//           --anchors--> walls --objects--> TrackedNodes --relations--> the scene
//
// The anchors, objects and relations stages also add their nodes and edges to
// the model::SceneData being built, so node ids follow the stage order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "ingest/capture/capture.hpp"
#include "ingest/capture/observations.hpp"
#include "ingest/geometry/alignment.hpp"
#include "ingest/geometry/dense_stereo.hpp"
#include "ingest/geometry/point_cloud.hpp"
#include "ingest/geometry/vertical_lines.hpp"
#include "ingest/geometry/view_consistency.hpp"
#include "model/types.hpp"

namespace smql::ingest {

// The capture again, with COLMAP's poses and sparse points instead of its own
// poses and depth.
struct Reconstruction {
    Capture capture;
    std::size_t registered = 0;  // frames that got a pose
    std::size_t points = 0;
    DensePoints dense;  // the dense stage's points (also capture.densePoints), when it ran
};

struct Camera {
    std::uint32_t frame = 0;  // position in Capture::frames
    Pose pose;                // camera-to-world, capture frame
};

// The one pass over the frames: everything later stages need, so the frames
// are read once and memory stays flat.
struct FramePass {
    PointCloud structure;  // down-sampled, capture frame
    // The structure's leading points that the capture measured (depth readings, COLMAP's features);
    // the dense points follow them.
    std::size_t measuredPoints = 0;
    std::vector<Camera> cameras;      // the frames that had a pose, in capture order
    std::vector<ObjectTrack> tracks;  // from the object source
    ViewAgreement viewAgreement;      // the depth images against each other (frames with depth)
    LinePlanes lines;                 // the straight edges of photos without depth, against their floor
};

struct AlignedCapture {
    Alignment alignment;
    PointCloud cloud;                        // the structure cloud in the aligned frame
    std::vector<model::Vec3> cameraCentres;  // of FramePass::cameras, aligned frame
    // Measured again on the things lifted on the dense points and stored (pipeline.cpp): the objects stage
    // lifts them again, whatever the keyframes taken at the new scale cover (ScanNet's lounge: 65 % at the
    // first scale, 63 % at the second, whose things the sparse points alone would place).
    bool onLiftedThings = false;
};

// A node the objects stage made from a track (an object, a door, a window),
// with the views it was seen in: what view-local relations and image-level
// descriptions are made from.
struct TrackedNode {
    model::NodeId node = model::kNoNode;
    std::vector<Observation> views;
    bool fused = false;  // its box was fitted to its views' points fused in the aligned frame (ObjectTrack::fused)
};

}  // namespace smql::ingest
