#include "ingest/geometry/vertical_lines.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include <Eigen/Eigenvalues>
#include <opencv2/imgproc.hpp>

#include "ingest/capture/frame_loader.hpp"
#include "ingest/geometry/robust.hpp"
#include "model/geometry.hpp"

namespace smql::ingest {

using detail::fromEigen;
using detail::toEigen;

namespace {

// The grid's step over the cone, degrees; the refinement then moves freely.
constexpr double kGridStep = 0.5;
constexpr int kRefinements = 10;

// Tukey's biweight of a segment's plane against a direction: 1 when the plane holds it, falling to 0 at
// `tolerance` (d is the sine of the angle between the two, over the tolerance's sine).
double weightOf(double d) {
    const double inside = 1 - d * d;
    return inside > 0 ? inside * inside : 0;
}

}  // namespace

void addLinePlanes(LinePlanes& planes, const FrameImages& images, const Pose& pose, const LineOptions& options) {
    cv::Mat grey;
    cv::cvtColor(images.color, grey, cv::COLOR_BGR2GRAY);
    std::vector<cv::Vec4f> segments;
    cv::createLineSegmentDetector(cv::LSD_REFINE_STD)->detect(grey, segments);
    const double minLength = options.minLength * std::hypot(grey.cols, grey.rows);
    auto length = [](const cv::Vec4f& s) { return std::hypot(s[2] - s[0], s[3] - s[1]); };
    std::erase_if(segments, [&](const cv::Vec4f& s) { return length(s) < minLength; });
    if (segments.size() > options.maxPerPhoto) {
        std::nth_element(segments.begin(), segments.begin() + static_cast<std::ptrdiff_t>(options.maxPerPhoto),
                         segments.end(), [&](const auto& a, const auto& b) { return length(a) > length(b); });
        segments.resize(options.maxPerPhoto);
    }
    const Intrinsics& k = images.intrinsics;
    auto ray = [&](double u, double v) { return Eigen::Vector3d((u - k.cx) / k.fx, (v - k.cy) / k.fy, 1); };
    const Eigen::Matrix3d rotation = detail::rotationOf(pose);
    const auto photo = static_cast<std::uint32_t>(planes.photos++);
    for (const auto& s : segments) {
        const Eigen::Vector3d normal = ray(s[0], s[1]).cross(ray(s[2], s[3]));
        if (normal.norm() <= 0) continue;
        planes.normals.push_back(fromEigen(rotation * normal.normalized()));
        planes.photo.push_back(photo);
    }
}

std::optional<Vertical> verticalFromLines(const LinePlanes& planes, const model::Vec3& near,
                                          const LineOptions& options) {
    if (planes.normals.size() < options.minSegments) return std::nullopt;
    Eigen::Matrix3Xd normals(3, static_cast<Eigen::Index>(planes.normals.size()));
    for (std::size_t i = 0; i < planes.normals.size(); ++i)
        normals.col(static_cast<Eigen::Index>(i)) = toEigen(planes.normals[i]);
    const Eigen::Vector3d centre = toEigen(near).normalized();
    const double sineTolerance = std::sin(options.tolerance * model::kDegree);
    auto score = [&](const Eigen::Vector3d& u) {
        const Eigen::VectorXd d = (normals.transpose() * u) / sineTolerance;
        return d.unaryExpr(&weightOf).sum();
    };

    // The cone around `near` on a grid: two axes across it, tangents so that the steps are about even.
    const Eigen::Vector3d across =
        centre.cross(std::abs(centre.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY()).normalized();
    const Eigen::Vector3d other = centre.cross(across);
    Eigen::Vector3d best = centre;
    double bestScore = -1, bestAngle = 0;
    for (double a = -options.search; a <= options.search + 1e-9; a += kGridStep)
        for (double b = -options.search; b <= options.search + 1e-9; b += kGridStep) {
            const Eigen::Vector3d u =
                (centre + std::tan(a * model::kDegree) * across + std::tan(b * model::kDegree) * other).normalized();
            const double angle = std::acos(std::clamp(u.dot(centre), -1.0, 1.0)) / model::kDegree;
            if (angle > options.search) continue;
            if (const double s = score(u); s > bestScore) {
                bestScore = s;
                best = u;
                bestAngle = angle;
            }
        }
    if (bestScore <= 0 || bestAngle > options.search - 2 * kGridStep) return std::nullopt;

    // Refined: the direction the supporting planes hold best, each weighted by how well it holds it.
    Eigen::Vector3d up = best;
    for (int i = 0; i < kRefinements; ++i) {
        const Eigen::VectorXd w = ((normals.transpose() * up) / sineTolerance).unaryExpr(&weightOf);
        const Eigen::Matrix3d scatter = normals * w.asDiagonal() * normals.transpose();
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
        Eigen::Vector3d next = solver.eigenvectors().col(0);
        if (next.dot(up) < 0) next = -next;
        up = next;
    }
    if (up.dot(centre) < 0) up = -up;

    Vertical out;
    out.up = fromEigen(up);
    out.degreesFromNear = std::acos(std::clamp(up.dot(centre), -1.0, 1.0)) / model::kDegree;
    std::set<std::uint32_t> photos;
    for (std::size_t i = 0; i < planes.normals.size(); ++i)
        if (std::abs(toEigen(planes.normals[i]).dot(up)) < sineTolerance) {
            ++out.segments;
            photos.insert(planes.photo[i]);
        }
    out.photos = photos.size();
    if (out.segments < options.minSegments || out.photos < options.minPhotos || out.degreesFromNear > options.search)
        return std::nullopt;
    return out;
}

}  // namespace smql::ingest
