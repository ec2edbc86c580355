// Small robust statistics shared by the geometry and the stages. Internal to smql_ingest.
#pragma once

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "ingest/capture/capture.hpp"
#include "model/types.hpp"

namespace smql::ingest::detail {

inline Eigen::Vector3d toEigen(const model::Vec3& v) { return {v.x, v.y, v.z}; }
inline model::Vec3 fromEigen(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
// A pose's camera-to-world rotation.
inline Eigen::Matrix3d rotationOf(const Pose& pose) {
    return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(pose.rotation.data());
}

// The `fraction`-quantile (0..1) of the values, by linear interpolation; 0 when empty.
inline double quantile(std::vector<double> values, double fraction) {
    if (values.empty()) return 0;
    double at = std::clamp(fraction, 0.0, 1.0) * static_cast<double>(values.size() - 1);
    auto low = static_cast<std::size_t>(std::floor(at));
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(low), values.end());
    double lowValue = values[low];
    if (low + 1 >= values.size()) return lowValue;
    double highValue = *std::min_element(values.begin() + static_cast<std::ptrdiff_t>(low) + 1, values.end());
    return lowValue + (at - static_cast<double>(low)) * (highValue - lowValue);
}

inline double median(std::vector<double> values) { return quantile(std::move(values), 0.5); }

// quantile(values, high) - quantile(values, low), the same number, partitioning one copy of the values:
// the high quantile's partition leaves the low quantile's values in front of it.
inline double quantileSpread(std::vector<double> values, double low, double high) {
    const auto n = values.size();
    if (n == 0) return 0;
    const double atLow = std::clamp(low, 0.0, 1.0) * static_cast<double>(n - 1);
    const double atHigh = std::clamp(high, 0.0, 1.0) * static_cast<double>(n - 1);
    const auto lo = static_cast<std::size_t>(std::floor(atLow)), hi = static_cast<std::size_t>(std::floor(atHigh));
    if (lo + 1 >= hi || hi + 1 >= n) return quantile(values, high) - quantile(values, low);
    const auto begin = values.begin();
    std::nth_element(begin, begin + static_cast<std::ptrdiff_t>(hi), values.end());
    const double hiValue = values[hi];
    const double hiNext = *std::min_element(begin + static_cast<std::ptrdiff_t>(hi) + 1, values.end());
    std::nth_element(begin, begin + static_cast<std::ptrdiff_t>(lo), begin + static_cast<std::ptrdiff_t>(hi));
    const double loValue = values[lo];
    const double loNext =
        *std::min_element(begin + static_cast<std::ptrdiff_t>(lo) + 1, begin + static_cast<std::ptrdiff_t>(hi));
    return (hiValue + (atHigh - static_cast<double>(hi)) * (hiNext - hiValue)) -
           (loValue + (atLow - static_cast<double>(lo)) * (loNext - loValue));
}

// The range of the values without outliers. The 2% and 98% quantiles mark the
// bulk; values farther than `slack` x (bulk span) beyond either mark are
// outliers; the range spans the remaining values. Unlike plain percentiles
// this keeps the true extent of densely sampled surfaces (a 2-98% cut alone
// would shrink a uniformly sampled 4 m wall by 16 cm).
inline std::pair<double, double> robustRange(std::vector<double> values, double lowFraction = 0.02,
                                             double highFraction = 0.98, double slack = 0.1) {
    if (values.empty()) return {0, 0};
    std::sort(values.begin(), values.end());
    auto at = [&](double f) {
        double pos = f * static_cast<double>(values.size() - 1);
        auto lo = static_cast<std::size_t>(std::floor(pos));
        auto hi = std::min(lo + 1, values.size() - 1);
        return values[lo] + (pos - static_cast<double>(lo)) * (values[hi] - values[lo]);
    };
    double low = at(lowFraction), high = at(highFraction);
    double margin = slack * (high - low);
    auto first = std::lower_bound(values.begin(), values.end(), low - margin);
    auto last = std::upper_bound(values.begin(), values.end(), high + margin);
    assert(first < last);
    return {*first, *(last - 1)};
}

}  // namespace smql::ingest::detail
