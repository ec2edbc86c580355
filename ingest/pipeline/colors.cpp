#include "ingest/pipeline/colors.hpp"

#include <limits>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "ingest/synth/palette.hpp"

namespace smql::ingest {

namespace {

constexpr double kLightnessWeight = 0.5;

cv::Vec3f toLab(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    cv::Mat bgr(1, 1, CV_8UC3, cv::Scalar(b, g, r)), lab;
    cv::cvtColor(bgr, lab, cv::COLOR_BGR2Lab);
    auto v = lab.at<cv::Vec3b>(0, 0);
    return {float(v[0]), float(v[1]), float(v[2])};
}

std::string nearestPaletteName(const cv::Vec3f& lab) {
    double best = std::numeric_limits<double>::max();
    std::string name;
    for (const auto& color : synth::namedColors()) {
        cv::Vec3f p = toLab(color.rgb.r, color.rgb.g, color.rgb.b);
        double dl = kLightnessWeight * (lab[0] - p[0]), da = lab[1] - p[1], db = lab[2] - p[2];
        double d = dl * dl + da * da + db * db;
        if (d < best) best = d, name = color.name;
    }
    return name;
}

}  // namespace

ColorEstimate nameColor(const cv::Mat& pixels) {
    ColorEstimate out;
    if (pixels.empty()) return out;
    CV_Assert(pixels.type() == CV_8UC3 && pixels.cols == 1);
    cv::Mat lab;
    cv::cvtColor(pixels, lab, cv::COLOR_BGR2Lab);
    cv::Mat samples;
    lab.reshape(1, lab.rows).convertTo(samples, CV_32F);
    int k = samples.rows >= 20 ? 2 : 1;
    cv::Mat labels, centers;
    // Deterministic: fixed attempts and OpenCV's seeded RNG (theRNG is reset for repeatability).
    cv::theRNG().state = 0x5eed;
    cv::kmeans(samples, k, labels, cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 20, 0.5), 3,
               cv::KMEANS_PP_CENTERS, centers);
    std::vector<int> counts(k, 0);
    for (int i = 0; i < labels.rows; ++i) ++counts[labels.at<int>(i)];
    int dominant = std::max_element(counts.begin(), counts.end()) - counts.begin();
    out.lab = {centers.at<float>(dominant, 0), centers.at<float>(dominant, 1), centers.at<float>(dominant, 2)};
    out.share = double(counts[dominant]) / labels.rows;
    out.name = nearestPaletteName(out.lab);
    return out;
}

}  // namespace smql::ingest
