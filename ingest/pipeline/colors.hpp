// Naming an object's colour from its pixels: the dominant colour cluster in
// CIE Lab, then the nearest entry of smql's palette (ingest/synth/palette.hpp).
#pragma once

#include <string>

#include <opencv2/core.hpp>

namespace smql::ingest {

struct ColorEstimate {
    std::string name;  // a palette name
    double share = 0;  // share of the pixels in the dominant cluster
    cv::Vec3f lab;     // the dominant cluster's mean (OpenCV 8-bit Lab scale)
};

// `pixels`: N x 1 CV_8UC3 BGR samples of one object. Two clusters (k-means in
// Lab) separate the object's own colour from shadows and texture; the larger
// names the object. Lightness counts half as much as hue in the distance, so
// a dim red is still red. No samples (an empty Mat: a view thinner than the
// sampling stride) name nothing: an empty name.
ColorEstimate nameColor(const cv::Mat& pixels);

}  // namespace smql::ingest
