// The one translation unit that includes PCL (see pcl_ops.hpp).
#include "ingest/geometry/pcl_ops.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <future>
#include <memory>
#include <thread>
#include <utility>

#include <pcl/PointIndices.h>
#include <pcl/console/print.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/ransac.h>
#include <pcl/sample_consensus/sac_model_parallel_plane.h>
#include <pcl/sample_consensus/sac_model_perpendicular_plane.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>
#include <Eigen/Eigenvalues>

namespace smql::ingest::pcl_ops {

namespace {

// PCL prints to the terminal what it meets on sparse clouds (RANSAC's "Sample points too similar
// or collinear!" is printed as an error, and the fit just draws again): the stages report what
// matters themselves, so PCL prints nothing.
void quietPcl() {
    static const bool quieted = [] {
        pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
        return true;
    }();
    (void)quieted;
}

pcl::PointCloud<pcl::PointXYZ>::Ptr toPcl(const std::vector<model::Vec3>& points) {
    quietPcl();
    auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
    cloud->points.reserve(points.size());
    for (const auto& p : points)
        cloud->points.emplace_back(static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z));
    cloud->width = static_cast<std::uint32_t>(cloud->points.size());
    cloud->height = 1;
    cloud->is_dense = true;
    return cloud;
}

pcl::IndicesPtr toPclIndices(const std::vector<std::size_t>& indices) {
    auto out = std::make_shared<pcl::Indices>();
    out->reserve(indices.size());
    for (auto i : indices) out->push_back(static_cast<pcl::index_t>(i));
    return out;
}

// A second thread that counts one part of each RANSAC hypothesis's points while the caller counts the other: a
// hypothesis's count takes a few microseconds, so the two meet by spinning (a futex's wake-up costs as much as the
// count), and the helper sleeps only once no hypothesis has come for a while (between plane searches). The
// second part goes to whichever of the two claims it first: a helper the system has not run yet (a loaded
// machine, more threads than cores) never holds the caller up, who then counts both parts. Started for one
// plane search and stopped with it; the counts are integers, so the total is the one-thread count.
class SplitCount {
public:
    using Count = std::function<std::size_t(const Eigen::Vector4f&, std::size_t begin, std::size_t end)>;
    SplitCount(std::size_t size, Count count) : size_(size), count_(std::move(count)), helper_([this] { help(); }) {}
    ~SplitCount() {
        stop_.store(true);
        post();
        helper_.join();
    }
    SplitCount(const SplitCount&) = delete;
    SplitCount& operator=(const SplitCount&) = delete;

    std::size_t operator()(const Eigen::Vector4f& plane) {
        plane_ = plane;
        const std::uint64_t ticket = post();
        const std::size_t mine = count_(plane, 0, size_ / 2);
        if (claim(ticket)) return mine + count_(plane, size_ / 2, size_);
        // The helper is counting its part: as long as a count takes, unless the system stops it meanwhile.
        for (int spins = 0; done_.load(std::memory_order_acquire) != ticket; ++spins)
            if (spins < kSpins)
                spin();
            else
                std::this_thread::yield();
        return mine + helperCount_;
    }

private:
    static constexpr int kSpins = 20000;  // about 0.1-0.5 ms
    static void spin() {
#if defined(__x86_64__) || defined(__i386__)
        __builtin_ia32_pause();
#endif
    }
    std::uint64_t post() {
        const std::uint64_t ticket = posted_.fetch_add(1) + 1;
        if (sleeping_.load()) posted_.notify_one();
        return ticket;
    }
    // Whether the second part of hypothesis `ticket` is the claimant's to count (the parts before it are claimed).
    bool claim(std::uint64_t ticket) {
        std::uint64_t before = ticket - 1;
        return claimed_.compare_exchange_strong(before, ticket, std::memory_order_acq_rel);
    }
    void help() {
        std::uint64_t seen = 0;
        while (true) {
            for (int spins = 0; posted_.load(std::memory_order_acquire) == seen; ++spins) {
                if (spins < kSpins) {
                    spin();
                    continue;
                }
                sleeping_.store(true);
                posted_.wait(seen);
                sleeping_.store(false);
                spins = 0;
            }
            seen = posted_.load(std::memory_order_acquire);
            if (stop_.load()) return;
            if (!claim(seen)) continue;  // the caller counted it
            helperCount_ = count_(plane_, size_ / 2, size_);
            done_.store(seen, std::memory_order_release);
        }
    }

    std::size_t size_;
    Count count_;
    Eigen::Vector4f plane_;        // the hypothesis posted: written before posted_, read after it
    std::size_t helperCount_ = 0;  // the helper's part: written before done_, read after it
    std::atomic<std::uint64_t> posted_{0}, claimed_{0}, done_{0};
    std::atomic<bool> sleeping_{false}, stop_{false};
    std::thread helper_;  // last: started once the members above are made
};

// How many of the n points (fewer than 2^32) lie within `limit` of the plane a x + b y + c z + d = 0.
// Vectorised: GCC's -O2 leaves this loop scalar (its cheapest cost model refuses the reduction), so the
// function asks GCC for its full cost model (clang's -O2 vectorises it as it is), and a 32-bit count keeps
// the lanes as wide as the floats; also compiled for AVX2, chosen when the processor has it. The same
// products and sums in the same order a point (no fused multiply-add), so the same count: 67,000 points in
// 6 us instead of 37.
#if !defined(__clang__)
__attribute__((optimize("vect-cost-model=dynamic")))
#endif
__attribute__((target_clones("avx2", "default"))) std::size_t
countNearPlane(float a, float b, float c, float d, float limit, const float* x, const float* y, const float* z,
               std::size_t n) {
    std::uint32_t count = 0;
    for (std::size_t i = 0; i < n; ++i) count += std::abs(a * x[i] + b * y[i] + c * z[i] + d) < limit;
    return count;
}

// A plane model constrained about an axis (PCL's perpendicular or parallel plane) whose RANSAC hypotheses
// count their inliers on a copy of the points laid out coordinate by coordinate, in a loop the compiler
// vectorises: the test PCL's plane model makes (|n . p + d| < threshold, in floats), so the same counts and
// the same plane, without PCL's gather of each point through its index. Counting every point for each of
// 1,000 hypotheses was most of an RGB-D ingest's alignment (docs/benchmarks.md "Ingest"); on a machine with
// two cores or more, each count is split between the caller and a helper thread (SplitCount).
template <typename Constrained>
class CountedContiguously : public Constrained {
public:
    using Cloud = typename Constrained::PointCloudConstPtr;
    CountedContiguously(const Cloud& cloud, const pcl::Indices& indices) : Constrained(cloud, indices) {
        for (auto* axis : {&x_, &y_, &z_}) axis->reserve(indices.size());
        for (auto i : indices) {
            const auto& p = (*cloud)[static_cast<std::size_t>(i)];
            x_.push_back(p.x);
            y_.push_back(p.y);
            z_.push_back(p.z);
        }
        // Below some 30,000 points (3 us a count) the two threads' meeting costs what the split saves (the
        // apartment's alignment, measured: the same time counting on one thread as split from 4,096).
        constexpr std::size_t kSplitFrom = 32768;
        if (x_.size() >= kSplitFrom && std::thread::hardware_concurrency() >= 2)
            split_ = std::make_unique<SplitCount>(
                x_.size(), [this](const Eigen::Vector4f& plane, std::size_t begin, std::size_t end) {
                    return countPart(plane, begin, end);
                });
    }

    std::size_t countWithinDistance(const Eigen::VectorXf& coefficients, double threshold) const override {
        if (!this->isModelValid(coefficients)) return 0;  // as the constrained model counts: none
        const Eigen::Vector4f plane(coefficients[0], coefficients[1], coefficients[2], coefficients[3]);
        limit_ = static_cast<float>(threshold);
        return split_ ? (*split_)(plane) : countPart(plane, 0, x_.size());
    }

private:
    std::size_t countPart(const Eigen::Vector4f& plane, std::size_t begin, std::size_t end) const {
        return countNearPlane(plane[0], plane[1], plane[2], plane[3], limit_, x_.data() + begin, y_.data() + begin,
                              z_.data() + begin, end - begin);
    }

    std::vector<float> x_, y_, z_;
    mutable float limit_ = 0;  // the threshold of the count under way (set before its parts start)
    std::unique_ptr<SplitCount> split_;
};

}  // namespace

std::optional<PlaneFound> segmentPlane(const std::vector<model::Vec3>& points, const std::vector<std::size_t>& indices,
                                       const PlaneSearch& search) {
    if (indices.size() < 3) return std::nullopt;
    auto cloud = toPcl(points);
    const Eigen::Vector3f axis(static_cast<float>(search.axis.x), static_cast<float>(search.axis.y),
                               static_cast<float>(search.axis.z));
    const pcl::Indices all(indices.begin(), indices.end());
    // What SACSegmentation does with the model, which it cannot be given: RANSAC (PCL's generator has a fixed
    // seed, 12345, so runs repeat), then a least-squares refit and its inliers.
    pcl::SampleConsensusModelPlane<pcl::PointXYZ>::Ptr model;
    if (search.constraint == PlaneConstraint::NormalAlongAxis) {
        auto perpendicular =
            std::make_shared<CountedContiguously<pcl::SampleConsensusModelPerpendicularPlane<pcl::PointXYZ>>>(cloud,
                                                                                                              all);
        perpendicular->setAxis(axis);
        perpendicular->setEpsAngle(search.epsAngle);
        model = perpendicular;
    } else {
        auto parallel =
            std::make_shared<CountedContiguously<pcl::SampleConsensusModelParallelPlane<pcl::PointXYZ>>>(cloud, all);
        parallel->setAxis(axis);
        parallel->setEpsAngle(search.epsAngle);
        model = parallel;
    }
    pcl::RandomSampleConsensus<pcl::PointXYZ> ransac(model, search.distance);
    ransac.setMaxIterations(search.maxIterations);
    if (!ransac.computeModel()) return std::nullopt;
    pcl::Indices inliers;
    ransac.getInliers(inliers);
    Eigen::VectorXf coefficients;
    ransac.getModelCoefficients(coefficients);
    if (search.optimise) {
        Eigen::VectorXf refined;
        model->optimizeModelCoefficients(inliers, coefficients, refined);
        coefficients = refined;
        model->selectWithinDistance(coefficients, search.distance, inliers);
    }
    if (inliers.empty() || coefficients.size() != 4) return std::nullopt;

    const double a = coefficients[0], b = coefficients[1], c = coefficients[2], d = coefficients[3];
    const double norm = std::sqrt(a * a + b * b + c * c);
    if (!(norm > 0)) return std::nullopt;
    PlaneFound found;
    found.normal = {a / norm, b / norm, c / norm};
    found.offset = d / norm;
    found.inliers.reserve(inliers.size());
    for (auto i : inliers) found.inliers.push_back(static_cast<std::size_t>(i));
    return found;
}

std::vector<std::vector<std::size_t>> euclideanClusters(const std::vector<model::Vec3>& points,
                                                        const std::vector<std::size_t>& indices, double tolerance,
                                                        std::size_t minPoints, std::size_t maxPoints) {
    std::vector<std::vector<std::size_t>> clusters;
    if (indices.empty()) return clusters;
    auto cloud = toPcl(points);
    auto tree = std::make_shared<pcl::search::KdTree<pcl::PointXYZ>>();
    pcl::EuclideanClusterExtraction<pcl::PointXYZ> extraction;
    extraction.setClusterTolerance(tolerance);
    extraction.setMinClusterSize(static_cast<pcl::uindex_t>(std::max<std::size_t>(minPoints, 1)));
    extraction.setMaxClusterSize(static_cast<pcl::uindex_t>(std::max(maxPoints, minPoints)));
    extraction.setSearchMethod(tree);
    extraction.setInputCloud(cloud);
    extraction.setIndices(toPclIndices(indices));
    std::vector<pcl::PointIndices> found;
    extraction.extract(found);  // PCL returns them largest first
    clusters.reserve(found.size());
    for (const auto& cluster : found) {
        std::vector<std::size_t> members(cluster.indices.begin(), cluster.indices.end());
        std::sort(members.begin(), members.end());
        clusters.push_back(std::move(members));
    }
    return clusters;
}

std::vector<std::size_t> withNeighbours(const std::vector<model::Vec3>& points, double radius, int minNeighbours) {
    std::vector<std::size_t> kept;
    if (points.empty()) return kept;
    auto cloud = toPcl(points);
    pcl::search::KdTree<pcl::PointXYZ> tree;
    tree.setInputCloud(cloud);
    pcl::Indices found;
    std::vector<float> distances;
    for (std::size_t i = 0; i < points.size(); ++i)
        // The point itself is among those found.
        if (tree.radiusSearch(cloud->points[i], radius, found, distances, static_cast<unsigned>(minNeighbours + 1)) >
            minNeighbours)
            kept.push_back(i);
    return kept;
}

std::vector<SurfaceNormal> estimateNormals(const std::vector<model::Vec3>& points, double radius, int minNeighbours) {
    std::vector<SurfaceNormal> normals(points.size(), SurfaceNormal{{0, 0, 0}, 1});
    if (points.empty()) return normals;
    auto cloud = toPcl(points);
    pcl::search::KdTree<pcl::PointXYZ> tree;
    tree.setInputCloud(cloud);
    auto estimate = [&](std::size_t begin, std::size_t end) {
        pcl::Indices neighbours;
        std::vector<float> distances;
        for (std::size_t i = begin; i < end; ++i) {
            int found = tree.radiusSearch(cloud->points[i], radius, neighbours, distances);
            if (found < std::max(minNeighbours, 3)) continue;
            Eigen::Vector3d mean = Eigen::Vector3d::Zero();
            for (auto j : neighbours) mean += Eigen::Vector3d(points[j].x, points[j].y, points[j].z);
            mean /= found;
            Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
            for (auto j : neighbours) {
                Eigen::Vector3d d = Eigen::Vector3d(points[j].x, points[j].y, points[j].z) - mean;
                covariance += d * d.transpose();
            }
            Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
            double total = solver.eigenvalues().sum();
            if (!(total > 0)) continue;
            Eigen::Vector3d n = solver.eigenvectors().col(0);  // smallest eigenvalue first
            normals[i] = {{n.x(), n.y(), n.z()}, solver.eigenvalues()(0) / total};
        }
    };
    // Each point's normal is its own and the tree is only read: the second half on a thread of its own (the
    // alignment's normals, 0.15 s of TUM fr1/rpy's 0.34, while the other core idled).
    const std::size_t half = points.size() / 2;
    auto second = std::async(std::launch::async, estimate, half, points.size());
    estimate(0, half);
    second.get();
    return normals;
}

}  // namespace smql::ingest::pcl_ops
