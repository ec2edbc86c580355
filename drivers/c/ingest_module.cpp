// libsmql_ingest.so (ingest_module.hpp): smql_ingest's work, run in the ingest library.
#include "ingest_module.hpp"

#include <nlohmann/json.hpp>

#include "ingest/pipeline/plausibility.hpp"
#include "ingest/pipeline/quality.hpp"
#include "ingest/pipeline/request.hpp"
#include "module_call.hpp"

namespace smql::capi {

namespace {

// The options' JSON object, row by row through the option table (numbers as their text).
ingest::IngestRequest requestOf(const IngestCall& call) {
    ingest::IngestRequest request;
    request.capture = call.capture;
    if (call.options.empty()) return request;
    nlohmann::json options;
    try {
        options = nlohmann::json::parse(call.options);
    } catch (const nlohmann::json::exception& e) {
        throw Error(ErrorKind::Usage, std::string("smql_ingest: the options are not JSON: ") + e.what(), std::nullopt,
                    R"(options are a JSON object, {"scene": "kitchen", "objects": "cluster"}, or NULL)");
    }
    if (!options.is_object())
        throw Error(ErrorKind::Usage, "smql_ingest: the options are not a JSON object", std::nullopt,
                    R"(options are a JSON object, {"scene": "kitchen", "objects": "cluster"}, or NULL)");
    for (const auto& [name, value] : options.items()) {
        if (!value.is_string() && !value.is_number() && !value.is_boolean())
            throw Error(ErrorKind::Usage,
                        "smql_ingest: option '" + name + "' is neither text, a number nor true/false");
        ingest::setIngestOption(request, name, value.is_string() ? value.get<std::string>() : value.dump());
    }
    return request;
}

// Progress as the C API's events; a stop asked for by the callback or by smql_interrupt is kept,
// so that the pipeline, which asks between frames, stops at its next question.
class CallbackProgress : public ingest::ProgressSink {
public:
    explicit CallbackProgress(const IngestCall& call) : call_(call) {}

    void stageStarted(const std::string& stage, std::size_t steps) override {
        stage_ = stage, steps_ = steps;
        send({SMQL_PROGRESS_STAGE_STARTED, stage_.c_str(), 0, steps, 0.0, ""});
    }
    void advanced(std::size_t done) override { send({SMQL_PROGRESS_ADVANCED, stage_.c_str(), done, steps_, 0.0, ""}); }
    void stageFinished(const std::string& stage, double seconds, const std::string& summary) override {
        send({SMQL_PROGRESS_STAGE_FINISHED, stage.c_str(), steps_, steps_, seconds, summary.c_str()});
    }
    void note(const std::string& text) override { send({SMQL_PROGRESS_NOTE, "", 0, 0, 0.0, text.c_str()}); }

    bool stopped() const { return stopped_ || (call_.interrupted && call_.interrupted->load()); }

private:
    void send(const smql_progress& event) {
        if (call_.progress && !stopped_ && call_.progress(event)) stopped_ = true;
    }

    const IngestCall& call_;
    std::string stage_;
    std::size_t steps_ = 0;
    bool stopped_ = false;
};

}  // namespace

}  // namespace smql::capi

extern "C" SMQL_API void smql_ingest_module_read(smql::capi::IngestCall& call) noexcept {
    smql::capi::guarded(call, "the ingest", smql::ErrorKind::Input, [&] {
        auto request = smql::capi::requestOf(call);
        call.sceneName = smql::ingest::sceneNameOf(request);
        call.update = request.update;
    });
}

extern "C" SMQL_API void smql_ingest_module_run(smql::capi::IngestCall& call) noexcept {
    smql::capi::guarded(call, "the ingest", smql::ErrorKind::Input, [&] {
        smql::capi::CallbackProgress progress(call);
        try {
            auto run = smql::ingest::runIngest(smql::capi::requestOf(call), progress,
                                               [&progress] { return progress.stopped(); });
            call.scene = std::move(run.result.scene);
            call.frames = run.frames;
        } catch (const smql::Error&) {
            if (!progress.stopped()) throw;
            throw smql::Error(smql::ErrorKind::Interrupted, "the ingest was stopped; nothing was written");
        }
    });
}

extern "C" SMQL_API void smql_ingest_module_check(smql::capi::CheckCall& call) noexcept {
    smql::capi::guarded(call, "the ingest", smql::ErrorKind::Input, [&] {
        if (!call.truth.empty()) {
            call.figures = smql::ingest::truthCheckFigures(smql::ingest::checkAgainstTruth(call.stored, call.truth));
            return;
        }
        // No truth: does the stored scene look like a room (plausibility.hpp)?
        const auto report = smql::ingest::checkPlausibility(call.stored, {.stored = true});
        auto add = [&](const char* name, const std::optional<double>& value) {
            if (value) call.figures.emplace_back(name, *value);
        };
        add("camera_height_m", report.cameraHeight);
        add("ceiling_height_m", report.ceilingHeight);
        add("size_ratio", report.sizeRatio);
        call.figures.emplace_back("named_things", static_cast<double>(report.namedThings));
        call.figures.emplace_back("warnings", static_cast<double>(report.findings.size()));
        call.figures.emplace_back("objects_flagged", static_cast<double>(report.objects.size()));
        call.figures.emplace_back("refused", report.refused() ? 1.0 : 0.0);
        for (const auto& o : report.objects) call.warnings.push_back(smql::ingest::objectWarning(o));
    });
}
