// The capture commands of `smql`, built into smql-ingest (docs/ingest.md).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace smql::shell {

struct IngestArguments {
    std::string capture;
    std::string db;
    std::string scene;
    std::string geometry = "auto";  // given | colmap | auto
    std::string objects = "auto";   // masks | detections | cluster | auto
    double fps = 1.0;
    std::optional<double> scale;
    std::string log = "bar";        // bar | quiet | json
    std::string update;             // a scene of the same place to update instead of adding a new one
};

// `smql ingest CAPTURE --db DIR`: capture -> one new scene, in one transaction.
int ingestCommand(const IngestArguments& args);
// `smql check-ingest DIR --truth TRUTH.json`: quality figures against a synthetic capture's truth.
int checkIngestCommand(const std::string& dbDir, const std::string& truthPath, const std::string& sceneName,
                       const std::string& format);
// `smql synth --out DIR [--seed N] [--frames K] [--objects N] [--force]`: a synthetic RGB-D capture
// of a generated room with ground truth (docs/ingest.md, "Synthetic captures").
int synthCommand(const std::string& outDir, std::uint64_t seed, int frames, int objects, bool force);
// `smql demo [--db DIR]`: a generated room captured, ingested into DIR (a new or empty folder) and
// queried, with the answers and their timings.
int demoCommand(const std::string& dbDir);

}  // namespace smql::shell
