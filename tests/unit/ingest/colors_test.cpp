// Colour names from an object's pixel samples.
#include <catch2/catch.hpp>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "ingest/pipeline/colors.hpp"

using namespace smql::ingest;

TEST_CASE("nameColor names the dominant colour, and nothing without samples", "[ingest][colors]") {
    cv::Mat red(40, 1, CV_8UC3, cv::Scalar(30, 30, 200));  // BGR
    red.rowRange(0, 8).setTo(cv::Scalar(20, 20, 60));      // a shadow, the smaller cluster
    CHECK(nameColor(red).name == "red");
    // A view thinner than the sampling stride has no samples: no name, and no failure.
    CHECK(nameColor(cv::Mat()).name.empty());
}

TEST_CASE("labOf gives a colour's CIE Lab at OpenCV's 8-bit scale", "[ingest][colors]") {
    // sRGB's white, its middle grey and its red (D65): L* 100, 50.04 and 53.24, a* 0, 0 and 80.09, b* 0, 0
    // and 67.20, at the scale of L * 255/100, a + 128, b + 128.
    auto near = [](cv::Vec3f lab, float l, float a, float b) {
        INFO(lab[0] << " " << lab[1] << " " << lab[2]);
        CHECK(lab[0] == Approx(l * 255 / 100).margin(0.05));
        CHECK(lab[1] == Approx(a + 128).margin(0.05));
        CHECK(lab[2] == Approx(b + 128).margin(0.05));
    };
    near(labOf(255, 255, 255), 100, 0, 0);
    near(labOf(119, 119, 119), 50.04f, 0, 0);
    near(labOf(0, 0, 255), 53.24f, 80.09f, 67.20f);  // blue, green, red
    // Every 17th value of each channel (4,096 colours) against cv::cvtColor's 8-bit COLOR_BGR2Lab, which
    // interpolates between the nodes of its tables and rounds to whole units.
    cv::Mat bgr(16 * 16 * 16, 1, CV_8UC3);
    int row = 0;
    for (int b = 0; b < 256; b += 17)
        for (int g = 0; g < 256; g += 17)
            for (int r = 0; r < 256; r += 17) bgr.at<cv::Vec3b>(row++, 0) = cv::Vec3b(b, g, r);
    cv::Mat lab;
    cv::cvtColor(bgr, lab, cv::COLOR_BGR2Lab);
    float worst = 0;
    for (int i = 0; i < bgr.rows; ++i) {
        const cv::Vec3b c = bgr.at<cv::Vec3b>(i, 0);
        const cv::Vec3f ours = labOf(c[0], c[1], c[2]);
        for (int k = 0; k < 3; ++k)
            worst = std::max(worst, std::abs(ours[k] - static_cast<float>(lab.at<cv::Vec3b>(i, 0)[k])));
    }
    INFO("the largest difference from OpenCV's " << worst);
    CHECK(worst <= 2.5f);
}
