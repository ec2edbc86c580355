// Dense points for photos without depth: semi-global matching (OpenCV's
// StereoSGBM) between each placed frame and a neighbour that sees the same
// things from a little to the side, on the pair rectified from their poses;
// a plane sweep when the only neighbour lies ahead or behind (a walk forward).
// COLMAP's sparse points come from texture; a floor, a wall or a table's side
// hold few, and the floor is what gives such a capture its up and its scale
// (docs/ingest.md, "Dense points from placed photos"). A point is kept only
// where two or more pairs agree on it, so one pair's mismatches do not count;
// when the placed frames make one pair only (two or three photos), its points
// have no second pair to agree with, and are checked against the sparse points.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include <opencv2/core.hpp>

#include "ingest/capture/capture.hpp"

namespace smql::ingest {

struct DenseOptions {
    int stereoWidth = 320;           // pairs are matched at this width (frames scaled down, the camera with them)
    double baselineRatio = 0.12;     // the neighbour sought: this far to the side, as a share of the scene's depth
    double minBaselineRatio = 0.03;  // ... no closer (too little parallax to measure depth)
    double maxBaselineRatio = 0.4;   // ... and no farther (too little of the same view)
    double maxAxisAngle = 30;        // degrees between the two cameras' optical axes
    // A step along the optical axis more than this share of its length: the pair is not rectified (the
    // epipole lies in the picture, as when walking forward) but swept with planes.
    double maxForwardShare = 0.7;
    int sweepPlanes = 64;              // depths tried, evenly spaced in inverse depth
    int sweepWindow = 7;               // pixels a side of the windows compared
    double sweepCorrelation = 0.8;     // the best depth's window correlation, at least
    double sweepMargin = 0.1;          // depths 3 planes or more from the best match worse by this much
    double sweepTexture = 3;           // grey levels of standard deviation a window needs
    double sweepParallax = 3;          // pixels the depth range moves a pixel in the other frame, at least
    int maxDisparities = 192;          // the disparity range searched, at stereoWidth
    double leftRightTolerance = 1;     // pixels: each image's disparities agree with the other's this well
    int pixelStride = 2;               // every n-th pixel of a pair's disparity map becomes a point
    double voxelShare = 0.02;          // points agree within a voxel this share of the capture's median depth
    std::size_t minPairs = 2;          // ... when this many pairs put a point in it (1 when one pair is matched)
    std::size_t minSparsePoints = 20;  // a frame that sees fewer of the capture's points has no depth range
    // One pair alone keeps its points when this share of the capture's sparse points in its first frame, where
    // it put a point, lie within a tenth of its depth, and that many were judged at least. Real pairs with true
    // poses: ScanNet's lounge 82-91 % (their points 57-87 % within a tenth of the depth camera's), TUM fr1/rpy's
    // and the dining photos' 6-41 % (1-40 %).
    double minSparseAgreement = 2.0 / 3;
    std::size_t minSparseJudged = 10;
};

struct DensePoints {
    std::vector<SparsePoint> points;  // one a voxel that pairs agree on, capture frame and units
    std::size_t pairs = 0;            // pairs matched
    std::size_t swept = 0;            // ... of them swept with planes (the neighbour ahead or behind)
    std::size_t matched = 0;          // points all pairs gave before they were checked against each other
    std::size_t agreeing = 0;         // pairs a kept point's voxel has points of: minPairs, or 1 with one pair
    // One pair alone: the sparse points its first frame sees where the pair put a point, and how many of them
    // lie within a tenth of the pair's depth (COLMAP's points, seen in several frames, are its second opinion);
    // its points are dropped when too few agree.
    std::size_t sparseJudged = 0, sparseAgree = 0;
    bool pairDropped = false;
    double voxel = 0;  // the voxel's side, capture units
};

// Receives the frames done so far (of capture.frames.size()).
using DenseProgress = std::function<void(std::size_t)>;

// The dense points of the capture's placed frames (those with a pose), using its
// sparse points (capture.points) for each frame's depth range. Frames' images
// are read with loadFrame. Empty when fewer than two frames are placed.
DensePoints densePoints(const Capture& capture, const DenseOptions& options = {}, const DenseProgress& progress = {});

// The depth image the camera at `pose` would take of `points` (CV_32F, the points' units, 0 where none
// lies): each point a square `spacing` wide (the dense points' voxel), the nearest in front. Photos
// without depth get their frames' depth this way once the room is aligned, so that their detections
// are lifted, segmented and fused as a depth camera's are (objects_from_detections.cpp).
cv::Mat depthFromPoints(const std::vector<model::Vec3>& points, const Pose& pose, const Intrinsics& k, double spacing);

}  // namespace smql::ingest
