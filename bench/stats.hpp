// Latency samples and their percentiles, and a monotonic stopwatch.
#pragma once

#include <chrono>
#include <cstddef>
#include <vector>

namespace smql::bench {

using Clock = std::chrono::steady_clock;

inline double microsecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::micro>(Clock::now() - start).count();
}

struct Percentiles {
    double p50 = 0;
    double p99 = 0;
    double max = 0;
    // Over rounds (overRounds in workload.cpp): the lowest and highest round p50, the noise band.
    double p50Low = 0;
    double p50High = 0;
};

// Nearest-rank percentiles of `samples` (which it sorts).
Percentiles percentiles(std::vector<double>& samples);

// The median of `samples` (which it sorts); 0 when empty.
double median(std::vector<double>& samples);

}  // namespace smql::bench
