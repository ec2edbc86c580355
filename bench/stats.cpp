#include "bench/stats.hpp"

#include <algorithm>
#include <cmath>

namespace smql::bench {

namespace {

double rank(const std::vector<double>& sorted, double q) {
    auto index = static_cast<std::size_t>(std::ceil(q * static_cast<double>(sorted.size())));
    return sorted[std::clamp<std::size_t>(index, 1, sorted.size()) - 1];
}

}  // namespace

Percentiles percentiles(std::vector<double>& samples) {
    Percentiles p;
    if (samples.empty()) return p;
    std::sort(samples.begin(), samples.end());
    p.p50 = rank(samples, 0.50);
    p.p99 = rank(samples, 0.99);
    p.max = samples.back();
    return p;
}

double median(std::vector<double>& samples) { return samples.empty() ? 0.0 : percentiles(samples).p50; }

}  // namespace smql::bench
