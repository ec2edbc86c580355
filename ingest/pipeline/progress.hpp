// A ProgressSink that reports nothing: for `--quiet`, tests and embedding programs.
#pragma once

#include "ingest/pipeline/pipeline.hpp"

namespace smql::ingest {

class SilentProgress : public ProgressSink {
public:
    void stageStarted(const std::string&, std::size_t) override {}
    void advanced(std::size_t) override {}
    void stageFinished(const std::string&, double, const std::string&) override {}
    void note(const std::string&) override {}
};

}  // namespace smql::ingest
