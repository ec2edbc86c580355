#include "ingest/pipeline/stage_runner.hpp"

#include "model/error.hpp"

namespace smql::ingest {

StageProgress::StageProgress(ProgressSink& sink, std::vector<std::string>& notes, std::function<bool()> cancelled)
    : sink_(sink), notes_(notes), cancelled_(std::move(cancelled)) {}

void StageProgress::advanced(std::size_t done) { sink_.advanced(done); }

void StageProgress::note(const std::string& text) {
    notes_.push_back(text);
    sink_.note(text);
}

void StageProgress::stopIfCancelled() const {
    if (cancelled_ && cancelled_()) throw Error(ErrorKind::Usage, "cancelled; nothing was written");
}

StageRunner::StageRunner(ProgressSink& sink, IngestResult& result, std::function<bool()> cancelled)
    : sink_(sink), timings_(result.stages), progress_(sink, result.notes, std::move(cancelled)) {}

void StageRunner::finished(const std::string& name, std::chrono::steady_clock::time_point start, std::string summary) {
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    sink_.stageFinished(name, seconds, summary);
    timings_.push_back({name, seconds, std::move(summary)});
}

}  // namespace smql::ingest
