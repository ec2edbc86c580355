// Colour names from an object's pixel samples.
#include <catch2/catch.hpp>

#include <opencv2/core.hpp>

#include "ingest/pipeline/colors.hpp"

using namespace smql::ingest;

TEST_CASE("nameColor names the dominant colour, and nothing without samples", "[ingest][colors]") {
    cv::Mat red(40, 1, CV_8UC3, cv::Scalar(30, 30, 200));  // BGR
    red.rowRange(0, 8).setTo(cv::Scalar(20, 20, 60));      // a shadow, the smaller cluster
    CHECK(nameColor(red).name == "red");
    // A view thinner than the sampling stride has no samples: no name, and no failure.
    CHECK(nameColor(cv::Mat()).name.empty());
}
