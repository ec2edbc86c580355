// What one frame says about one instance: its lifted 3D points (capture
// frame), colour samples, where it was in the image, and an evidence crop.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "engine/model/types.hpp"
#include "ingest/capture/frame_loader.hpp"

namespace smql::ingest {

struct Observation {
    std::uint32_t frame = 0;
    std::uint16_t instance = 0;
    std::vector<model::Vec3> points;  // capture frame
    cv::Mat colors;                   // N x 1 CV_8UC3 BGR samples
    int pixels = 0;                   // mask area in the frame
    cv::Rect bounds;                  // mask bounding box
    double centreX = 0;               // mask centroid, as a share of the image width (0 left, 1 right)
};

struct EvidenceCrop {
    int pixels = 0;  // mask area of the view it came from (the largest wins)
    std::uint32_t frame = 0;
    std::string jpeg;
};

// Everything the frame pass gathers about one physical instance, whichever
// source found it (a mask id, or detections associated across views): the
// object stage builds nodes from these alone.
struct ObjectTrack {
    std::string category;
    model::NodeKind kind = model::NodeKind::Object;  // Anchor: walls, floor, ceiling, door, window
    std::string material;
    std::vector<Observation> views;
    EvidenceCrop evidence;
};

// Lifts every instance of one frame with enough pixels. `stride` samples the
// mask; pixels without depth give colour samples but no points.
std::vector<Observation> observeInstances(const FrameImages& images, const Pose& pose, std::uint32_t frame,
                                          int stride, int minPixels);

// A JPEG of the instance's bounding box (padded 10%), longest side `size`.
std::string encodeCrop(const cv::Mat& color, const cv::Rect& bounds, int size);

}  // namespace smql::ingest
