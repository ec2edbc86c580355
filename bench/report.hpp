// The benchmark's report: the machine, the tables and the method, as
// markdown (docs/benchmarks.md and stdout).
#pragma once

#include <string>
#include <vector>

#include "bench/data_set.hpp"
#include "bench/workload.hpp"

namespace smql::bench {

struct MachineInfo {
    std::string cpu;     // model name from /proc/cpuinfo
    unsigned cores = 0;  // what nproc counts
    std::string date;    // UTC, ISO 8601
    std::string build;   // CMake build type and compiler
    std::string sqlite;  // library version
};

MachineInfo machineInfo();

struct DataSetRun {
    DataSet data;
    WorkloadResult result;
};

struct Report {
    MachineInfo machine;
    std::string commandLine;
    WorkloadOptions options;
    std::vector<DataSetRun> runs;  // the small data set first, the large one last
    std::string postgis;           // the server's versions, or why PostGIS did not take part
    double totalSeconds = 0;
};

// The text after this marker in an existing report is hand-written analysis: a rewrite keeps it.
inline constexpr const char* kNotesMarker =
    "<!-- smql_bench keeps everything below this line when it rewrites the file -->";

std::string renderMarkdown(const Report& report);

}  // namespace smql::bench
