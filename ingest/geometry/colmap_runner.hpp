// Structure from motion for captures without poses: runs Debian's `colmap`
// command on the CPU (feature_extractor, a matcher, mapper) as a subprocess,
// then copies the largest model's camera poses and sparse points into the
// capture (docs/ingest.md, "--geometry colmap").
#pragma once

#include <string>
#include <vector>

#include "ingest/capture/capture.hpp"

namespace smql::ingest {

struct ColmapOptions {
    std::string command = "colmap";  // looked up on PATH
    int exhaustiveUpTo = 60;         // exhaustive_matcher up to this many frames, sequential_matcher above
    int threads = -1;                // COLMAP's num_threads (-1: all cores)
    bool keepWorkDirectory = false;  // keep the work folder (images, database, models, colmap.log) after a success too
};

struct ColmapRun {
    std::string workDirectory;   // /tmp/smql-colmap-XXXXXX
    std::string logPath;         // every command's output
    std::size_t registered = 0;  // frames that got a pose
    std::size_t points = 0;      // sparse points
    std::size_t models = 0;      // models the mapper wrote (the largest is used)
    std::vector<std::string> notes;
};

// Fills every registered frame's pose and the capture's points (replacing any
// it had); frames COLMAP did not register keep no pose. Sets metric = false.
// Throws smql::Error(Input) when `colmap` is missing (naming how to install
// it) or a step fails or no model comes out (naming the step and the log).
ColmapRun runColmap(Capture& capture, const ColmapOptions& options = {});

}  // namespace smql::ingest
