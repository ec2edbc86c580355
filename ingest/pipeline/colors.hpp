// Naming an object's colour from its pixels: the dominant colour cluster in
// CIE Lab, then the nearest entry of smql's palette (ingest/synth/palette.hpp).
#pragma once

#include <cstdint>
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

// One sRGB colour in CIE Lab (D65) at OpenCV's 8-bit scale (L * 255/100, a + 128, b + 128), as cv::cvtColor's
// COLOR_BGR2Lab gives it but unrounded. Worked out here because OpenCV builds all its Lab tables in software
// floating point the first time it converts, 90 ms on this machine: most of the objects stage of a capture of
// a frame or a few (one SUN RGB-D frame's took 0.09 s, now 0.01).
cv::Vec3f labOf(std::uint8_t b, std::uint8_t g, std::uint8_t r);

}  // namespace smql::ingest
