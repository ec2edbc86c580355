#include "ingest/geometry/dense_stereo.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <set>
#include <unordered_map>
#include <utility>

#include <Eigen/Core>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "ingest/capture/frame_loader.hpp"
#include "ingest/geometry/robust.hpp"
#include "model/geometry.hpp"

namespace smql::ingest {

namespace {

using detail::rotationOf;
using detail::toEigen;

using model::kDegree;

// A placed frame: its camera in the capture's frame and the depths at which it sees the capture's
// sparse points (5th, 50th and 95th percentiles), which bound the disparities searched.
struct View {
    std::size_t frame = 0;
    Eigen::Matrix3d rotation;  // camera-to-world
    Eigen::Vector3d centre;
    double nearDepth = 0, medianDepth = 0, farDepth = 0;
};

// Where a point of the capture lies in the photo of a camera (rotation camera-to-world, centre) with
// intrinsics k: its pixel (x, y) and depth (z), when it lies in front of the camera and inside the photo.
std::optional<Eigen::Vector3d> inPhoto(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& centre,
                                       const Intrinsics& k, const model::Vec3& point) {
    const Eigen::Vector3d p = rotation.transpose() * (toEigen(point) - centre);
    if (p.z() <= 0) return std::nullopt;
    const double u = k.fx * p.x() / p.z() + k.cx, v = k.fy * p.y() / p.z() + k.cy;
    if (!(u >= 0 && v >= 0 && u < k.width && v < k.height)) return std::nullopt;
    return Eigen::Vector3d{u, v, p.z()};
}

std::optional<View> viewOf(const Capture& capture, std::size_t index, const DenseOptions& options) {
    const CaptureFrame& frame = capture.frames[index];
    if (!frame.pose) return std::nullopt;
    const Intrinsics& k = frame.intrinsics ? *frame.intrinsics : capture.intrinsics;
    View view{index, rotationOf(*frame.pose), toEigen(frame.pose->translation)};
    std::vector<double> depths;
    for (const auto& point : capture.points)
        if (const auto seen = inPhoto(view.rotation, view.centre, k, point.position)) depths.push_back(seen->z());
    if (depths.size() < options.minSparsePoints) return std::nullopt;
    std::sort(depths.begin(), depths.end());
    auto at = [&](double fraction) { return depths[static_cast<std::size_t>(fraction * double(depths.size() - 1))]; };
    view.nearDepth = at(0.05);
    view.medianDepth = at(0.5);
    view.farDepth = at(0.95);
    return view;
}

// The neighbour to match `a` with: the baseline nearest the sought share of a's depth, the axes
// nearest parallel, the step most to the side (moving along the optical axis gives little
// disparity). A neighbour to the side is rectified and matched by SGBM; when every frame that
// qualifies lies ahead or behind (a walk forward), the nearest to the side is swept instead.
// nullopt when no frame qualifies.
struct Neighbour {
    std::size_t view = 0;
    bool sideways = true;
};

std::optional<Neighbour> neighbourOf(const std::vector<View>& views, std::size_t a, const DenseOptions& options) {
    std::optional<Neighbour> best;
    double bestScore = 0;
    for (std::size_t b = 0; b < views.size(); ++b) {
        if (b == a) continue;
        const Eigen::Vector3d step = views[b].centre - views[a].centre;
        const double ratio = step.norm() / views[a].medianDepth;
        const double angle =
            std::acos(std::clamp(views[a].rotation.col(2).dot(views[b].rotation.col(2)), -1.0, 1.0)) / kDegree;
        if (ratio < options.minBaselineRatio || ratio > options.maxBaselineRatio || angle > options.maxAxisAngle)
            continue;
        const double along = std::abs(step.normalized().dot(views[a].rotation.col(2)));
        const bool sideways = along <= options.maxForwardShare;
        // Any neighbour to the side before any ahead or behind.
        const double score = std::abs(std::log(ratio / options.baselineRatio)) + angle / options.maxAxisAngle +
                             2 * along + (sideways ? 0 : 10);
        if (!best || score < bestScore) {
            best = Neighbour{b, sideways};
            bestScore = score;
        }
    }
    return best;
}

cv::Matx33d cameraMatrix(const Intrinsics& k) { return {k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1}; }

struct Rectified {
    cv::Mat r1, r2, p1, p2, q;
};

// b's camera from a's: x_b = r x_a + t (OpenCV's R and T of a pair).
struct RelativePose {
    Eigen::Matrix3d r;
    Eigen::Vector3d t;
};

RelativePose relativePose(const View& a, const View& b) {
    return {b.rotation.transpose() * a.rotation, b.rotation.transpose() * (a.centre - b.centre)};
}

Rectified rectify(const View& a, const Intrinsics& ka, const View& b, const Intrinsics& kb) {
    const RelativePose pose = relativePose(a, b);
    cv::Matx33d rotation;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) rotation(i, j) = pose.r(i, j);
    Rectified out;
    cv::stereoRectify(cameraMatrix(ka), cv::noArray(), cameraMatrix(kb), cv::noArray(), cv::Size(ka.width, ka.height),
                      rotation, cv::Vec3d(pose.t.x(), pose.t.y(), pose.t.z()), out.r1, out.r2, out.p1, out.p2, out.q,
                      cv::CALIB_ZERO_DISPARITY, -1);
    return out;
}

struct PairPoints {
    std::vector<Eigen::Vector3d> positions;
    std::vector<std::array<std::uint8_t, 3>> colours;  // RGB
};

// The left image's disparities, at every pixel: SGBM leaves the left border as wide as the search
// range without any, so both images are widened there (black) and the border cut off again.
cv::Mat disparityOf(cv::StereoSGBM& matcher, const cv::Mat& left, const cv::Mat& right) {
    const int border = matcher.getMinDisparity() + matcher.getNumDisparities();
    cv::Mat wideLeft, wideRight, fixedPoint, disparity;
    cv::copyMakeBorder(left, wideLeft, 0, 0, border, 0, cv::BORDER_CONSTANT, 0);
    cv::copyMakeBorder(right, wideRight, 0, 0, border, 0, cv::BORDER_CONSTANT, 0);
    matcher.compute(wideLeft, wideRight, fixedPoint);
    fixedPoint(cv::Rect(border, 0, left.cols, left.rows))
        .convertTo(disparity, CV_32F, 1.0 / static_cast<double>(cv::StereoMatcher::DISP_SCALE));
    return disparity;
}

// The right image's disparities (a pixel x of the right image matches x + d of the left): the pair
// mirrored, the right image on the left, matched alike and mirrored back.
cv::Mat rightDisparity(cv::StereoSGBM& matcher, const cv::Mat& left, const cv::Mat& right) {
    cv::Mat mirroredLeft, mirroredRight, out;
    cv::flip(right, mirroredLeft, 1);
    cv::flip(left, mirroredRight, 1);
    cv::flip(disparityOf(matcher, mirroredLeft, mirroredRight), out, 1);
    return out;
}

// The left-right check: a left pixel keeps its disparity d only where the right pixel it matches, x - d,
// lies in the image and matches it back within `tolerance`. Semi-global matching gives the background
// beside a near thing, which the right image does not see, the thing's disparity (it carries the
// smoothest), and the right image, which sees other background there, disagrees: without the check a
// lounge chair's depth spread over the floor beside it, alike in every pair looking that way.
void keepConsistent(cv::Mat& left, const cv::Mat& right, int minDisparity, double tolerance) {
    for (int y = 0; y < left.rows; ++y) {
        auto* d = left.ptr<float>(y);
        const auto* back = right.ptr<float>(y);
        for (int x = 0; x < left.cols; ++x) {
            const long match = std::lround(x - d[x]);
            if (match < 0 || match >= left.cols || !(std::abs(back[match] - d[x]) <= tolerance))
                d[x] = static_cast<float>(minDisparity - 1);  // below the range searched: no point
        }
    }
}

// Semi-global matching of the pair rectified with a on the left; each matched pixel (every
// pixelStride-th) within a's depth range, in the capture's frame.
PairPoints matchRectified(const View& a, const FrameImages& ia, const FrameImages& ib, const Rectified& rect,
                          const DenseOptions& options) {
    PairPoints out;
    const cv::Size size(ia.color.cols, ia.color.rows);
    const double focal = rect.p1.at<double>(0, 0);
    const double baseline = std::abs(rect.p2.at<double>(0, 3) / rect.p2.at<double>(0, 0));
    const int minDisparity = static_cast<int>(std::floor(focal * baseline / (2 * a.farDepth)));
    const double maxDisparity = focal * baseline / (0.5 * a.nearDepth);
    const int disparities =
        std::clamp(16 * static_cast<int>(std::ceil((maxDisparity - minDisparity) / 16)), 16, options.maxDisparities);

    cv::Mat mapAx, mapAy, mapBx, mapBy, grayA, grayB, leftGray, rightGray, left;
    cv::initUndistortRectifyMap(cameraMatrix(ia.intrinsics), cv::noArray(), rect.r1, rect.p1, size, CV_32FC1, mapAx,
                                mapAy);
    cv::initUndistortRectifyMap(cameraMatrix(ib.intrinsics), cv::noArray(), rect.r2, rect.p2, size, CV_32FC1, mapBx,
                                mapBy);
    cv::cvtColor(ia.color, grayA, cv::COLOR_BGR2GRAY);
    cv::cvtColor(ib.color, grayB, cv::COLOR_BGR2GRAY);
    cv::remap(grayA, leftGray, mapAx, mapAy, cv::INTER_LINEAR);
    cv::remap(grayB, rightGray, mapBx, mapBy, cv::INTER_LINEAR);
    cv::remap(ia.color, left, mapAx, mapAy, cv::INTER_LINEAR);

    constexpr int kBlock = 5;
    auto matcher = cv::StereoSGBM::create(minDisparity, disparities, kBlock, 8 * kBlock * kBlock, 32 * kBlock * kBlock,
                                          1, 0, 10, 100, 2, cv::StereoSGBM::MODE_SGBM_3WAY);
    cv::Mat disparity = disparityOf(*matcher, leftGray, rightGray), xyz;
    keepConsistent(disparity, rightDisparity(*matcher, leftGray, rightGray), minDisparity, options.leftRightTolerance);
    cv::reprojectImageTo3D(disparity, xyz, rect.q);

    Eigen::Matrix3d unrectify;  // rectified camera -> a's camera
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) unrectify(i, j) = rect.r1.at<double>(j, i);
    for (int y = 0; y < disparity.rows; y += options.pixelStride) {
        const auto* d = disparity.ptr<float>(y);
        const auto* p = xyz.ptr<cv::Vec3f>(y);
        const auto* c = left.ptr<cv::Vec3b>(y);
        for (int x = 0; x < disparity.cols; x += options.pixelStride) {
            if (!(d[x] > static_cast<float>(minDisparity))) continue;
            const Eigen::Vector3d camera = unrectify * Eigen::Vector3d(p[x][0], p[x][1], p[x][2]);
            if (camera.z() < 0.5 * a.nearDepth || camera.z() > 2 * a.farDepth) continue;
            out.positions.push_back(a.rotation * camera + a.centre);
            out.colours.push_back({c[x][2], c[x][1], c[x][0]});
        }
    }
    return out;
}

// The pair rectified and matched: OpenCV rectifies it with the first camera on the left, where
// disparities are positive, so b goes first when it lies to a's left.
PairPoints matchPair(const View& a, const FrameImages& ia, const View& b, const FrameImages& ib,
                     const DenseOptions& options) {
    const Rectified rect = rectify(a, ia.intrinsics, b, ib.intrinsics);
    if (rect.p2.at<double>(0, 3) > 0)
        return matchRectified(b, ib, ia, rectify(b, ib.intrinsics, a, ia.intrinsics), options);
    return matchRectified(a, ia, ib, rect, options);
}

cv::Mat grayFloat(const cv::Mat& colour) {
    cv::Mat gray, out;
    cv::cvtColor(colour, gray, cv::COLOR_BGR2GRAY);
    gray.convertTo(out, CV_32F);
    return out;
}

cv::Mat boxMean(const cv::Mat& image, int window) {
    cv::Mat out;
    cv::boxFilter(image, out, CV_32F, cv::Size(window, window));
    return out;
}

// Plane sweep of b against a, for a pair that rectification cannot serve (b ahead of or behind a):
// for each of `sweepPlanes` depths, evenly spaced in inverse depth over a's range, b is warped
// onto a through the plane at that depth, facing a, and compared window by window (zero-mean
// normalised cross-correlation). A pixel takes the depth that matches best when the match is
// close (correlation sweepCorrelation or more), the window has texture, the depths apart from it
// match clearly worse, and the range moves it far enough in b to tell depths apart (near the
// point b walks towards, depth does not show).
PairPoints sweepPair(const View& a, const FrameImages& ia, const View& b, const FrameImages& ib,
                     const DenseOptions& options) {
    PairPoints out;
    const cv::Size size(ia.color.cols, ia.color.rows);
    const RelativePose pose = relativePose(a, b);
    const cv::Matx33d ka = cameraMatrix(ia.intrinsics), kb = cameraMatrix(ib.intrinsics), kaInverse = ka.inv();
    auto homography = [&](double depth) {  // a's pixel -> b's pixel through the plane z = depth of a
        cv::Matx33d m;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) m(i, j) = pose.r(i, j) + (j == 2 ? pose.t(i) / depth : 0);
        return kb * m * kaInverse;
    };
    const int window = options.sweepWindow, planes = options.sweepPlanes;
    const double nearInverse = 1 / (0.5 * a.nearDepth), farInverse = 1 / (2 * a.farDepth);
    auto inverseDepth = [&](double m) { return farInverse + (nearInverse - farInverse) * m / (planes - 1); };

    const cv::Mat left = grayFloat(ia.color), right = grayFloat(ib.color);
    const cv::Mat meanA = boxMean(left, window), varA = boxMean(left.mul(left), window) - meanA.mul(meanA);
    const cv::Mat ones(size, CV_32F, cv::Scalar(1));
    std::vector<cv::Mat> costs(static_cast<std::size_t>(planes));
    for (int m = 0; m < planes; ++m) {
        const cv::Matx33d h = homography(1 / inverseDepth(m));
        cv::Mat warped, seen;  // seen: 1 where b covers a's pixel
        cv::warpPerspective(right, warped, h, size, cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_CONSTANT, 0);
        cv::warpPerspective(ones, seen, h, size, cv::INTER_NEAREST | cv::WARP_INVERSE_MAP, cv::BORDER_CONSTANT, 0);
        const cv::Mat meanB = boxMean(warped, window);
        const cv::Mat varB = boxMean(warped.mul(warped), window) - meanB.mul(meanB);
        const cv::Mat covariance = boxMean(left.mul(warped), window) - meanA.mul(meanB);
        cv::Mat denominator;
        cv::sqrt(cv::max(varA.mul(varB), 1e-6), denominator);
        cv::Mat cost = 1 - covariance / denominator;
        cost.setTo(std::numeric_limits<float>::quiet_NaN(), boxMean(seen, window) < 0.999);  // a window b leaves
        costs[static_cast<std::size_t>(m)] = cost;
    }

    const cv::Matx33d nearH = homography(0.5 * a.nearDepth), farH = homography(2 * a.farDepth);
    const double minTexture = options.sweepTexture * options.sweepTexture;
    for (int y = 0; y < size.height; y += options.pixelStride) {
        for (int x = 0; x < size.width; x += options.pixelStride) {
            if (!(varA.at<float>(y, x) >= minTexture)) continue;
            const cv::Vec3d p(x, y, 1), pn = nearH * p, pf = farH * p;
            if (pn[2] <= 0 || pf[2] <= 0 ||
                std::hypot(pn[0] / pn[2] - pf[0] / pf[2], pn[1] / pn[2] - pf[1] / pf[2]) < options.sweepParallax)
                continue;
            auto cost = [&](int m) { return costs[static_cast<std::size_t>(m)].at<float>(y, x); };
            int best = -1;
            float bestCost = 0;
            for (int m = 0; m < planes; ++m)
                if (const float c = cost(m); c == c && (best < 0 || c < bestCost)) {  // c == c: not NaN
                    best = m;
                    bestCost = c;
                }
            if (best <= 0 || best >= planes - 1 || bestCost > 1 - options.sweepCorrelation) continue;
            bool unique = true;
            for (int m = 0; m < planes && unique; ++m)
                unique = std::abs(m - best) < 3 || !(cost(m) < bestCost + options.sweepMargin);
            if (!unique) continue;
            // The minimum between the planes: a parabola through the best and its two neighbours.
            const double before = cost(best - 1), after = cost(best + 1);
            const double curvature = before - 2 * bestCost + after;
            const double shift = curvature > 0 ? std::clamp(0.5 * (before - after) / curvature, -0.5, 0.5) : 0;
            const double depth = 1 / inverseDepth(best + shift);
            const Eigen::Vector3d camera((x - ia.intrinsics.cx) * depth / ia.intrinsics.fx,
                                         (y - ia.intrinsics.cy) * depth / ia.intrinsics.fy, depth);
            out.positions.push_back(a.rotation * camera + a.centre);
            const auto& c = ia.color.at<cv::Vec3b>(y, x);
            out.colours.push_back({c[2], c[1], c[0]});
        }
    }
    return out;
}

// Points gathered per voxel, and how many pairs gave them (pairs come one after another, so a pair
// other than the last one to give a point here is a new one).
struct Cell {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    std::array<double, 3> colour{};
    std::size_t count = 0;
    std::size_t lastPair = 0;
    std::size_t pairs = 0;
};

std::int64_t voxelKey(const Eigen::Vector3d& p, double voxel) {
    constexpr std::int64_t kBits = 21, kOffset = std::int64_t{1} << (kBits - 1), kMask = (std::int64_t{1} << kBits) - 1;
    auto index = [&](double v) { return (static_cast<std::int64_t>(std::floor(v / voxel)) + kOffset) & kMask; };
    return (index(p.x()) << (2 * kBits)) | (index(p.y()) << kBits) | index(p.z());
}

// One pair's points against the capture's sparse points, which COLMAP saw in several frames: those the
// pair's first frame sees where the pair put a point (its points drawn as that frame's depth), and how many
// lie within a tenth of that depth.
void checkAgainstSparse(DensePoints& pair, const Capture& capture, const View& view) {
    constexpr double kTolerance = 0.1;
    const CaptureFrame& frame = capture.frames[view.frame];
    const Intrinsics& k = frame.intrinsics ? *frame.intrinsics : capture.intrinsics;
    std::vector<model::Vec3> positions;
    for (const auto& p : pair.points) positions.push_back(p.position);
    const cv::Mat depth = depthFromPoints(positions, *frame.pose, k, pair.voxel);
    for (const auto& point : capture.points) {
        const auto seen = inPhoto(view.rotation, view.centre, k, point.position);
        if (!seen) continue;
        // The pixel depthFromPoints draws a point at.
        const int x = static_cast<int>(std::min<long>(std::lround(seen->x()), depth.cols - 1));
        const int y = static_cast<int>(std::min<long>(std::lround(seen->y()), depth.rows - 1));
        const float z = depth.at<float>(y, x);
        if (z <= 0) continue;
        ++pair.sparseJudged;
        if (std::abs(seen->z() / z - 1) <= kTolerance) ++pair.sparseAgree;
    }
}

}  // namespace

DensePoints densePoints(const Capture& capture, const DenseOptions& options, const DenseProgress& progress) {
    DensePoints out;
    std::vector<View> views;
    for (std::size_t i = 0; i < capture.frames.size(); ++i)
        if (auto view = viewOf(capture, i, options)) views.push_back(*view);
    if (views.size() < 2) return out;
    std::vector<double> depths;
    for (const auto& v : views) depths.push_back(v.medianDepth);
    out.voxel = options.voxelShare * detail::median(depths);

    std::unordered_map<std::int64_t, Cell> cells;
    std::set<std::pair<std::size_t, std::size_t>> matched;
    std::size_t firstOfPair = 0;
    for (std::size_t a = 0; a < views.size(); ++a) {
        if (progress) progress(views[a].frame);
        auto b = neighbourOf(views, a, options);
        if (!b || !matched.insert(std::minmax(a, b->view)).second) continue;
        FrameImages ia = loadFrame(capture, capture.frames[views[a].frame], options.stereoWidth);
        FrameImages ib = loadFrame(capture, capture.frames[views[b->view].frame], options.stereoWidth);
        if (ia.color.size() != ib.color.size()) continue;
        PairPoints points;
        if (!b->sideways) {
            points = sweepPair(views[a], ia, views[b->view], ib, options);
            ++out.swept;
        } else {
            points = matchPair(views[a], ia, views[b->view], ib, options);
        }
        const std::size_t pair = out.pairs++;
        firstOfPair = a;
        out.matched += points.positions.size();
        for (std::size_t i = 0; i < points.positions.size(); ++i) {
            Cell& cell = cells[voxelKey(points.positions[i], out.voxel)];
            cell.sum += points.positions[i];
            for (int k = 0; k < 3; ++k) cell.colour[k] += points.colours[i][k];
            if (cell.count++ == 0 || cell.lastPair != pair) ++cell.pairs;
            cell.lastPair = pair;
        }
    }
    // A single pair has no second pair to agree with: its points are checked against the capture's sparse
    // points instead (below), beside SGBM's own checks (left to right, unique, in patches). Two or three of TUM's
    // office photos make one pair, and were refused for want of a floor among COLMAP's 95-450 points; on the
    // pair's points, with a second prior of the scale to check them (plausibility.cpp), they were stored
    // 0.92-0.99 times the true distances (docs/ingest.md, "Dense points from placed photos").
    out.agreeing = out.pairs == 1 ? 1 : options.minPairs;
    // In voxel order, so that a run gives its points in the same order every time.
    std::vector<std::int64_t> agreed;
    for (const auto& [key, cell] : cells)
        if (cell.pairs >= out.agreeing) agreed.push_back(key);
    std::sort(agreed.begin(), agreed.end());
    for (auto key : agreed) {
        const Cell& cell = cells.at(key);
        const Eigen::Vector3d p = cell.sum / static_cast<double>(cell.count);
        SparsePoint point{{p.x(), p.y(), p.z()}};
        for (int k = 0; k < 3; ++k)
            point.color[k] = static_cast<std::uint8_t>(std::lround(cell.colour[k] / static_cast<double>(cell.count)));
        out.points.push_back(point);
    }
    if (out.agreeing == 1 && !out.points.empty()) {
        checkAgainstSparse(out, capture, views[firstOfPair]);
        out.pairDropped =
            out.sparseJudged < options.minSparseJudged ||
            static_cast<double>(out.sparseAgree) < options.minSparseAgreement * static_cast<double>(out.sparseJudged);
        if (out.pairDropped) out.points.clear();
    }
    return out;
}

cv::Mat depthFromPoints(const std::vector<model::Vec3>& points, const Pose& pose, const Intrinsics& k, double spacing) {
    // A point nearer than this many voxels to the camera covers no more than this square: a speck
    // before the lens does not hide the frame.
    constexpr int kMaxHalfSide = 8;
    cv::Mat1f depth = cv::Mat1f::zeros(k.height, k.width);
    const Eigen::Matrix3d toCamera = rotationOf(pose).transpose();
    const Eigen::Vector3d centre = toEigen(pose.translation);
    for (const auto& point : points) {
        const Eigen::Vector3d p = toCamera * (toEigen(point) - centre);
        if (p.z() <= 0) continue;
        const double u = k.fx * p.x() / p.z() + k.cx, v = k.fy * p.y() / p.z() + k.cy;
        const int half = std::min(kMaxHalfSide, static_cast<int>(std::ceil(0.5 * k.fx * spacing / p.z() - 0.5)));
        // Off the image by more than its square (tested before rounding: a point grazing the camera's
        // plane lands arbitrarily far out).
        if (!(u > -half - 1 && v > -half - 1 && u < k.width + half && v < k.height + half)) continue;
        const long column = std::lround(u), row = std::lround(v);
        const auto z = static_cast<float>(p.z());
        for (long y = std::max(0L, row - half); y <= std::min<long>(k.height - 1, row + half); ++y) {
            auto* line = depth.ptr<float>(static_cast<int>(y));
            for (long x = std::max(0L, column - half); x <= std::min<long>(k.width - 1, column + half); ++x)
                if (line[x] == 0 || z < line[x]) line[x] = z;
        }
    }
    return depth;
}

}  // namespace smql::ingest
