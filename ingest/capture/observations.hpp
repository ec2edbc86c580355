// What one frame says about one instance: its lifted 3D points (capture
// frame), colour samples, where it was in the image, and an evidence crop.
#pragma once

#include <algorithm>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "ingest/capture/frame_loader.hpp"
#include "model/types.hpp"

namespace smql::ingest {

// A pixel of a view's region lifted into the capture frame, with its colour: single precision, as a
// capture holds thousands of them for each detection until the objects stage fuses them.
struct RegionPoint {
    float x = 0, y = 0, z = 0;
    cv::Vec3b bgr;
    std::uint16_t column = 0, row = 0;  // its place on the region's grid (pixel / stride)
    model::Vec3 position() const { return {x, y, z}; }
};

struct Observation {
    std::uint32_t frame = 0;
    std::uint16_t instance = 0;
    std::vector<model::Vec3> points;    // capture frame
    cv::Mat colors;                     // N x 1 CV_8UC3 BGR samples
    int pixels = 0;                     // mask area in the frame
    cv::Rect bounds;                    // mask bounding box
    cv::Mat1b outline;                  // detections: their own outline inside `bounds` (empty: the box)
    double centreX = 0;                 // mask centroid, as a share of the image width (0 left, 1 right)
    std::vector<std::uint32_t> sparse;  // indices of Capture::points on the mask (frames without depth)
    std::vector<float> embedding;       // an external model's vector for this view (detections.json); may be empty
    // Detections with depth: every pixel the detection owns in its frame (its mask, else its box, less
    // what a smaller detection in front owns), sub-sampled to about kRegionPoints; the objects stage
    // finds the thing among them once the floor and the walls are known (view_segment.hpp).
    std::vector<RegionPoint> region;
    double regionPitch = 0;  // m: the region's grid step at the detection's median depth
    std::string label;       // detections: what this view was detected as, and how sure the detector was
    double score = 1;
    std::vector<std::pair<std::string, double>> alsoSeenAs;  // ... and what other models called it
};

struct EvidenceCrop {
    int pixels = 0;  // mask area of the view it came from (the largest wins)
    std::uint32_t frame = 0;
    std::string jpeg;
};

// Everything the frame pass gathers about one physical instance, whichever
// source found it (a mask id, or detections associated across views): the
// object stage builds nodes from these alone (the node's embedding from its
// views' embeddings).
struct ObjectTrack {
    std::string category;
    model::NodeKind kind = model::NodeKind::Object;  // Anchor: walls, floor, ceiling, door, window
    std::string material;
    std::vector<Observation> views;
    EvidenceCrop evidence;
    // Where the views' points became a visual hull (carveVisualHulls): the sparse points it was carved
    // around, which lie on the thing's surfaces (the hull of boxes reaches above a thing's top).
    std::vector<model::Vec3> surface;
    // The points are a visual hull carved without depth (carveVisualHulls, placeByRays): seen from a
    // narrow range of directions it stays long along the view.
    bool carved = false;
    // Fused from its views once the room is aligned (detections with depth, instance_map.hpp): the
    // thing's points in the aligned frame, their colours (N x 1 CV_8UC3 BGR), and the box fitted to
    // them, which the objects stage takes instead of fitting one to the views' points.
    std::vector<model::Vec3> fused;
    cv::Mat fusedColors;
    std::optional<model::Box> fusedBox;
    // Where fusion did not keep the detectors' name though it suits the box (object_fusion.hpp: FusedThing), that
    // name and why, else "": `category` is then what the thing is stored as, and the name is kept as detected_as.
    std::string detectedAs;
    std::string renamedWhy;
};

// Lifts every instance of one frame with enough pixels. `stride` samples the
// mask; pixels without depth give colour samples but no points.
std::vector<Observation> observeInstances(const FrameImages& images, const Pose& pose, std::uint32_t frame, int stride,
                                          int minPixels);

// Frames without depth (COLMAP captures): every sparse point whose projection
// falls on an instance's mask pixel joins that instance's observation (its
// index goes to Observation::sparse). Points seen through the instance are
// dropped: only those within `depthBand` (a share of the median depth of the
// instance's points) of its nearest points are kept. `inView` counts, per
// point, the frames it projects into (for the cross-view vote in
// keepConsistentSparsePoints).
void liftSparsePoints(std::vector<Observation>& observations, const FrameImages& images, const Pose& pose,
                      const std::vector<SparsePoint>& points, std::vector<std::uint32_t>& inView,
                      double depthBand = 0.25);

// Keeps in each view only the sparse points that fall on the same instance in
// at least `minVotes` frames and in at least `minShare` of the frames that see
// them (rejecting background points at mask edges), and fills
// Observation::points with them.
void keepConsistentSparsePoints(std::vector<ObjectTrack*>& tracks, const std::vector<SparsePoint>& points,
                                const std::vector<std::uint32_t>& inView, int minVotes = 2, double minShare = 0.5);

// One frame's instance mask kept (down-sampled) for carving, with its camera;
// or, for boxes, just the camera: each view's box (Observation::bounds) is its
// silhouette.
struct MaskView {
    std::uint32_t frame = 0;
    cv::Mat instances;      // CV_16U; empty: the views' boxes are their silhouettes
    Intrinsics intrinsics;  // scaled to `instances`, or the frame's (working resolution)
    Pose pose;
};

// The frame's instance image (working resolution, intrinsics `K`) at 1/4
// resolution, enough to carve hulls with.
MaskView maskView(std::uint32_t frame, const cv::Mat& instances, const Intrinsics& K, const Pose& pose);

// An axis-aligned region of the capture frame to carve a hull in.
struct HullRegion {
    model::Vec3 lo, hi;
    bool holds(const model::Vec3& p) const {
        return lo.x <= p.x && p.x <= hi.x && lo.y <= p.y && p.y <= hi.y && lo.z <= p.z && p.z <= hi.z;
    }
    // The smallest region that holds both.
    HullRegion united(const HullRegion& other) const {
        return {{std::min(lo.x, other.lo.x), std::min(lo.y, other.lo.y), std::min(lo.z, other.lo.z)},
                {std::max(hi.x, other.hi.x), std::max(hi.y, other.hi.y), std::max(hi.z, other.hi.z)}};
    }
};

// The visual hull of `views` inside `region`: the centres of a grid x grid x
// grid lattice that project onto the view's silhouette (its mask value in the
// frame's MaskView, or its box where the MaskView keeps no mask) in at least `minShare` of the views whose
// image shows them, and in at least two.
std::vector<model::Vec3> carveRegion(const HullRegion& region, const std::vector<Observation>& views,
                                     const std::vector<MaskView>& masks, double minShare, int grid = 28);

// Whether a hull's projection spans at least kMinFill of the box's width and
// height in the view's image (`bounds` at the camera's resolution): so it does
// in every view of one thing (more, where something in front cut the box
// short); a view of another thing leaves much of its box empty.
inline constexpr double kMinFill = 0.6;
bool hullFillsBox(const std::vector<model::Vec3>& hull, const cv::Rect& bounds, const MaskView& camera);

// Sparse points see only the textured faces an object shows the cameras: a
// box around them is often flat. Each track with enough sparse points is
// replaced by its visual hull: the voxels of a region around its points
// (grown by its largest side) carved by carveRegion. The hull's voxel
// centres become the track's points (in its first view), and the sparse
// points it was carved around its surface.
void carveVisualHulls(std::vector<ObjectTrack*>& tracks, const std::vector<MaskView>& masks, double minShare = 0.8,
                      int grid = 28);

// Where a capture-frame point falls in an image with camera-to-world `pose` and intrinsics `K`, in
// pixels (pixel centres at whole numbers), with its depth along the camera's axis as z: nothing when it
// is behind the camera. Inline, as the two below: carving calls them for every voxel in every view.
inline std::optional<cv::Point3d> projectToCamera(const model::Vec3& p, const Pose& pose, const Intrinsics& K) {
    const auto& R = pose.rotation;
    const auto& t = pose.translation;
    double dx = p.x - t.x, dy = p.y - t.y, dz = p.z - t.z;
    // camera = R^T (p - t)
    double x = R[0] * dx + R[3] * dy + R[6] * dz, y = R[1] * dx + R[4] * dy + R[7] * dz,
           z = R[2] * dx + R[5] * dy + R[8] * dz;
    if (!(z > 1e-6)) return std::nullopt;
    return cv::Point3d(K.fx * x / z + K.cx, K.fy * y / z + K.cy, z);
}
// The same without the depth: nothing when it falls outside the image either.
inline std::optional<cv::Point2d> projectToImage(const model::Vec3& p, const Pose& pose, const Intrinsics& K) {
    auto at = projectToCamera(p, pose, K);
    // Within the image: nearest a pixel centre 0 .. size - 1.
    if (!at || !(at->x >= -0.5 && at->y >= -0.5 && at->x < K.width - 0.5 && at->y < K.height - 0.5))
        return std::nullopt;
    return cv::Point2d(at->x, at->y);
}

// A JPEG of the instance's bounding box (padded 10%), longest side `size`.
std::string encodeCrop(const cv::Mat& color, const cv::Rect& bounds, int size);

// Replaces `evidence` with a crop of `view` (from `color`, its frame's image)
// when the view shows more of the instance than the one it came from.
void keepLargestEvidence(EvidenceCrop& evidence, const Observation& view, const cv::Mat& color, int size);

}  // namespace smql::ingest
