// segmentPlane against PCL's own SACSegmentation on a real cloud: segmentPlane counts each RANSAC hypothesis's
// inliers in its own loop (pcl_ops.cpp), which must rank the hypotheses as PCL's plane model does. This is the
// one test unit that includes PCL.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include <pcl/ModelCoefficients.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/method_types.h>
#include <pcl/sample_consensus/model_types.h>
#include <pcl/segmentation/sac_segmentation.h>

#include "dining_cloud.hpp"
#include "ingest/geometry/alignment.hpp"
#include "ingest/geometry/pcl_ops.hpp"

using namespace smql;
using namespace smql::ingest;
using namespace smql::ingest::test;

TEST_CASE("rgbd-dining: segmentPlane keeps the plane PCL's SACSegmentation keeps, point for point",
          "[ingest][geometry][real]") {
    // The real dining cloud: the floor (perpendicular to up) and the strongest wall (parallel to it), each with
    // the same inliers and coefficients as PCL's RANSAC with the same seed, iterations and refit.
    const Dining dining = loadDining(1, 0.02);
    REQUIRE(dining.cloud.size() >= 40000);
    const Alignment depth = alignCapture(dining.cloud, dining.cameras, AlignOptions{});
    REQUIRE(depth.floorFound);
    std::vector<std::size_t> all(dining.cloud.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
    pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
    for (const auto& p : dining.cloud.points)
        cloud->push_back({static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)});
    for (auto constraint : {pcl_ops::PlaneConstraint::NormalAlongAxis, pcl_ops::PlaneConstraint::NormalAcrossAxis}) {
        pcl_ops::PlaneSearch search;
        search.axis = depth.up;
        search.constraint = constraint;
        search.epsAngle = 10 * std::numbers::pi / 180;
        const auto ours = pcl_ops::segmentPlane(dining.cloud.points, all, search);

        pcl::SACSegmentation<pcl::PointXYZ> segmentation;
        segmentation.setModelType(constraint == pcl_ops::PlaneConstraint::NormalAlongAxis
                                      ? pcl::SACMODEL_PERPENDICULAR_PLANE
                                      : pcl::SACMODEL_PARALLEL_PLANE);
        segmentation.setMethodType(pcl::SAC_RANSAC);
        segmentation.setAxis(Eigen::Vector3f(static_cast<float>(search.axis.x), static_cast<float>(search.axis.y),
                                             static_cast<float>(search.axis.z)));
        segmentation.setEpsAngle(search.epsAngle);
        segmentation.setDistanceThreshold(search.distance);
        segmentation.setMaxIterations(search.maxIterations);
        segmentation.setOptimizeCoefficients(true);
        segmentation.setInputCloud(cloud);
        pcl::PointIndices inliers;
        pcl::ModelCoefficients coefficients;
        segmentation.segment(inliers, coefficients);

        REQUIRE(ours);
        REQUIRE(coefficients.values.size() == 4);
        CHECK(ours->inliers.size() > 2000);
        CHECK(ours->inliers == std::vector<std::size_t>(inliers.indices.begin(), inliers.indices.end()));
        const double norm = std::hypot(coefficients.values[0], coefficients.values[1], coefficients.values[2]);
        CHECK(ours->normal.x == Approx(coefficients.values[0] / norm).margin(1e-6));
        CHECK(ours->normal.y == Approx(coefficients.values[1] / norm).margin(1e-6));
        CHECK(ours->normal.z == Approx(coefficients.values[2] / norm).margin(1e-6));
        CHECK(ours->offset == Approx(coefficients.values[3] / norm).margin(1e-6));
    }
}
