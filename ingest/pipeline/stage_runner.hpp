// Runs the ingest's stages one after the other. Timing, progress reports and
// cancellation live here, once, so a stage only does its work: it is a type
// with a name, a number of steps, a run over its inputs (held by the stage)
// that returns its output, and a one-line summary of that output.
#pragma once

#include <chrono>
#include <concepts>
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "ingest/pipeline/pipeline.hpp"

namespace smql::ingest {

// What a running stage may tell the user: how far it is, and notes on what it
// assumed or skipped. It also stops the work when the user asks to.
class StageProgress {
public:
    StageProgress(ProgressSink& sink, std::vector<std::string>& notes, std::function<bool()> cancelled);
    void advanced(std::size_t done);
    void note(const std::string& text);
    // Throws Error(Usage, "cancelled; nothing was written") once the user has asked to stop.
    void stopIfCancelled() const;

private:
    ProgressSink& sink_;
    std::vector<std::string>& notes_;
    std::function<bool()> cancelled_;
};

template <typename S>
using StageOutput = decltype(std::declval<S&>().run(std::declval<StageProgress&>()));

// A stage whose output is added to the scene in place (relations) has no
// output of its own: its summary then takes no argument. Two concepts joined by
// ||, so the summary(output) form is only checked when there is an output.
template <typename S>
concept SummarisedInPlace = std::is_void_v<StageOutput<S>> && requires(S& stage) {
    { stage.summary() } -> std::convertible_to<std::string>;
};
template <typename S>
concept SummarisedOutput = !std::is_void_v<StageOutput<S>> && requires(S & stage, const StageOutput<S>& output) {
    { stage.summary(output) } -> std::convertible_to<std::string>;
};

template <typename S>
concept IngestStage = requires(S& stage, StageProgress& progress) {
    { S::kName } -> std::convertible_to<std::string_view>;
    { stage.steps() } -> std::convertible_to<std::size_t>;
    stage.run(progress);
}
&&(SummarisedInPlace<S> || SummarisedOutput<S>);

class StageRunner {
public:
    // Notes and timings go to `result` as well as to the sink.
    StageRunner(ProgressSink& sink, IngestResult& result, std::function<bool()> cancelled);

    void note(const std::string& text) { progress_.note(text); }

    // Checks for cancellation, reports the stage started, runs it, and reports
    // and records its time and summary.
    template <typename S, typename Stage = std::remove_cvref_t<S>>
    requires IngestStage<Stage> StageOutput<Stage> run(S&& stage) {
        progress_.stopIfCancelled();
        const std::string name(Stage::kName);
        sink_.stageStarted(name, stage.steps());
        auto start = std::chrono::steady_clock::now();
        if constexpr (std::is_void_v<StageOutput<Stage>>) {
            stage.run(progress_);
            finished(name, start, stage.summary());
        } else {
            StageOutput<Stage> output = stage.run(progress_);
            finished(name, start, stage.summary(output));
            return output;
        }
    }

private:
    void finished(const std::string& name, std::chrono::steady_clock::time_point start, std::string summary);

    ProgressSink& sink_;
    std::vector<StageTiming>& timings_;
    StageProgress progress_;
};

}  // namespace smql::ingest
