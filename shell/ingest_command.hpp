// The ingest sub-commands of `smql` (docs/ingest.md).
#pragma once

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
// `smql export evidence '#id' DIR --db DB`: writes a node's evidence crops into DIR.
int exportEvidenceCommand(const std::string& dbDir, const std::string& node, const std::string& outDir);

}  // namespace smql::shell
