#include "ingest/pipeline/colors.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <opencv2/core.hpp>

#include "ingest/synth/palette.hpp"

namespace smql::ingest {

cv::Vec3f labOf(std::uint8_t b, std::uint8_t g, std::uint8_t r) {
    // sRGB's transfer curve, undone: each 8-bit value's linear intensity.
    static const std::array<float, 256> linear = [] {
        std::array<float, 256> out{};
        for (int i = 0; i < 256; ++i) {
            const double v = i / 255.0;
            out[static_cast<std::size_t>(i)] =
                static_cast<float>(v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4));
        }
        return out;
    }();
    const float lr = linear[r], lg = linear[g], lb = linear[b];
    // XYZ under D65, relative to the white point (OpenCV's matrix and white).
    const float x = (0.412453f * lr + 0.357580f * lg + 0.180423f * lb) / 0.950456f;
    const float y = 0.212671f * lr + 0.715160f * lg + 0.072169f * lb;
    const float z = (0.019334f * lr + 0.119193f * lg + 0.950227f * lb) / 1.088754f;
    auto f = [](float t) { return t > 0.008856f ? std::cbrt(t) : 7.787f * t + 16.f / 116.f; };
    const float fx = f(x), fy = f(y), fz = f(z);
    return {(116.f * fy - 16.f) * 255.f / 100.f, 500.f * (fx - fy) + 128.f, 200.f * (fy - fz) + 128.f};
}

namespace {

constexpr double kLightnessWeight = 0.5;

std::string nearestPaletteName(const cv::Vec3f& lab) {
    // The palette's colours in Lab, worked out once.
    static const std::vector<cv::Vec3f> paletteLab = [] {
        std::vector<cv::Vec3f> out;
        for (const auto& color : synth::namedColors()) out.push_back(labOf(color.rgb.b, color.rgb.g, color.rgb.r));
        return out;
    }();
    double best = std::numeric_limits<double>::max();
    std::string name;
    for (std::size_t i = 0; i < paletteLab.size(); ++i) {
        const cv::Vec3f& p = paletteLab[i];
        double dl = kLightnessWeight * (lab[0] - p[0]), da = lab[1] - p[1], db = lab[2] - p[2];
        double d = dl * dl + da * da + db * db;
        if (d < best) best = d, name = synth::namedColors()[i].name;
    }
    return name;
}

}  // namespace

ColorEstimate nameColor(const cv::Mat& pixels) {
    ColorEstimate out;
    if (pixels.empty()) return out;
    CV_Assert(pixels.type() == CV_8UC3 && pixels.cols == 1);
    cv::Mat samples(pixels.rows, 3, CV_32F);
    for (int i = 0; i < pixels.rows; ++i) {
        const auto& bgr = pixels.at<cv::Vec3b>(i, 0);
        const cv::Vec3f lab = labOf(bgr[0], bgr[1], bgr[2]);
        for (int c = 0; c < 3; ++c) samples.at<float>(i, c) = lab[c];
    }
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
