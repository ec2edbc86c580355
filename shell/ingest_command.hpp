// The capture commands of `smql`, built into smql-ingest (docs/ingest.md).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "ingest/synth/synth.hpp"

namespace smql::shell {

struct IngestArguments {
    std::string capture;
    std::string db;
    std::string scene;
    std::string geometry = "auto";  // given | colmap | auto
    std::string objects = "auto";   // masks | detections | detect | cluster | auto
    std::string detector;           // --objects detect: the ONNX model (default: the installed one)
    std::string classes;            // ... and its class names (default: coco.names beside the model)
    double fps = 1.0;
    std::optional<double> scale;
    std::string camera;          // --camera fx,fy,cx,cy (pixels of the images as stored)
    std::optional<double> fov;   // --fov DEG, horizontal
    int maxSize = 1024;          // --max-size: long side of the frames COLMAP sees (0: as stored)
    std::string vocabularyTree;  // --vocab-tree: COLMAP's vocabulary tree, for loop detection
    std::string colmapDir;       // --colmap-dir: COLMAP's kept work folder, its finished run read back
    std::string log = "bar";     // bar | quiet | json
    std::string update;          // a scene of the same place to update instead of adding a new one
};

// `smql ingest CAPTURE --db DIR`: capture -> one new scene, in one transaction.
int ingestCommand(const IngestArguments& args);
// `smql check-ingest DIR --truth TRUTH.json`: quality figures against a synthetic capture's truth.
int checkIngestCommand(const std::string& dbDir, const std::string& truthPath, const std::string& sceneName,
                       const std::string& format, bool misses = false);
// `smql synth --out DIR [--seed N] [--frames K] [--objects N] [--force] [--changes]`: a synthetic
// RGB-D capture of a generated room with ground truth (docs/ingest.md, "Synthetic captures").
int synthCommand(const synth::SynthOptions& options, const std::string& outDir);
// `smql demo [--db DIR]`: a generated room captured, ingested into DIR (a new or empty folder) and
// queried, with the answers and their timings.
int demoCommand(const std::string& dbDir);

}  // namespace smql::shell
