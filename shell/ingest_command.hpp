// The capture commands of `smql`, built into smql-ingest (docs/ingest.md).
#pragma once

#include <string>

#include "ingest/pipeline/request.hpp"
#include "ingest/synth/synth.hpp"

namespace smql::shell {

struct IngestArguments {
    ingest::IngestRequest request;  // the capture and the options of ingest::ingestOptions()
    std::string db;
    std::string log = "bar";  // bar | quiet | json
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
