// Loads one frame's images at the working resolution. Internal to ingest/:
// OpenCV types are fine here and never leave the ingest library.
#pragma once

#include <opencv2/core.hpp>

#include "ingest/capture/capture.hpp"

namespace smql::ingest {

struct FrameImages {
    cv::Mat color;          // CV_8UC3, BGR
    cv::Mat depth;          // CV_32F metres, 0 = no reading; empty without depth
    cv::Mat instances;      // CV_16U instance ids, 0 = none; empty without masks
    Intrinsics intrinsics;  // scaled to these images; a pinhole: the lens's distortion undone
};

// Reads the frame's files, undoes the lens's distortion when the camera has one,
// scales them down to at most `workingWidth` pixels wide (nearest neighbour for
// depth and masks, area averaging for colour) and converts depth to metres. Throws smql::Error(Input) naming the file
// when an image is unreadable or depth / masks do not match the colour image's size.
FrameImages loadFrame(const Capture& capture, const CaptureFrame& frame, int workingWidth);

// The image the pinhole camera of the same intrinsics takes: each pixel read from where `camera`'s lens put
// it (`interpolation`: cv::INTER_LINEAR for colour, cv::INTER_NEAREST for depth and masks, whose values must not
// blend). Pixels the lens did not see are 0: no reading, no instance. `image` is at `camera`'s size.
cv::Mat undistorted(const cv::Mat& image, const Intrinsics& camera, int interpolation);

}  // namespace smql::ingest
