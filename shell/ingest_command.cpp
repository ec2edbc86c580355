// `smql ingest` and `smql check-ingest`.
#include "shell/ingest_command.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <filesystem>
#include <iostream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "engine/engine.hpp"
#include "ingest/pipeline/pipeline.hpp"
#include "ingest/pipeline/plausibility.hpp"
#include "ingest/pipeline/progress.hpp"
#include "ingest/pipeline/quality.hpp"
#include "model/error.hpp"

namespace smql::shell {

namespace fs = std::filesystem;

namespace {

std::atomic<bool> interrupted{false};

// A stage's rate: the capture's frames over its time, "85 frames/s"; empty before the capture is read,
// and for a stage of under 10 ms, whose rate says nothing.
std::string rate(std::size_t frames, double seconds) {
    return frames > 0 && seconds >= 0.01 ? fmt::format("{:.0f} frames/s", static_cast<double>(frames) / seconds) : "";
}

// A bar with the stage's name on a terminal; one line per stage otherwise. The bar is redrawn in
// place with \r, so it must stay shorter than the terminal: a line that wraps scrolls at every step.
class TerminalProgress : public ingest::ProgressSink {
public:
    explicit TerminalProgress(bool tty) : tty_(tty) {}
    void stageStarted(const std::string& stage, std::size_t steps) override { stage_ = stage, steps_ = steps; }
    void advanced(std::size_t done) override {
        if (!tty_ || steps_ <= 1) return;
        std::string counts = fmt::format(" {}/{}", done, steps_);
        std::string name = fmt::format("{:<10}", stage_);
        // name, " [", bar, "]", counts, and one column spare so the cursor never wraps.
        int room = static_cast<int>(terminalColumns()) - static_cast<int>(name.size() + counts.size()) - 4;
        int width = std::min(30, room);
        std::string line = width >= 5 ? fmt::format("{} [{}{}]{}", name, std::string(width * done / steps_, '#'),
                                                    std::string(width - width * done / steps_, ' '), counts)
                                      : (name + counts).substr(0, std::max<std::size_t>(terminalColumns(), 2) - 1);
        std::cerr << "\r" << line << "\033[K" << std::flush;
    }
    void captureRead(std::size_t frames) override { frames_ = frames; }
    void stageFinished(const std::string& stage, double seconds, const std::string& summary) override {
        if (tty_) std::cerr << "\r\033[K";
        std::cerr << fmt::format("{:<10} {:7.2f} s {:>15}  {}\n", stage, seconds, rate(frames_, seconds), summary);
    }
    void note(const std::string& text) override {
        if (tty_) std::cerr << "\r\033[K";
        std::cerr << "note: " << text << "\n";
    }

private:
    static std::size_t terminalColumns() {
        winsize size{};
        return ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0 ? size.ws_col : 80;
    }

    bool tty_;
    std::string stage_;
    std::size_t steps_ = 0;
    std::size_t frames_ = 0;
};

// One JSON object per line on standard error, for scripts. A stage's progress is told at each tenth of its steps
// it reaches (a COLMAP command's count, which starts again with each command, too), so that a script sees a long
// stage move without a line per frame.
class JsonProgress : public ingest::ProgressSink {
public:
    void stageStarted(const std::string& stage, std::size_t steps) override {
        stage_ = stage, steps_ = steps, tenth_ = 0;
        emit({{"event", "stage_started"}, {"stage", stage}, {"steps", steps}});
    }
    void advanced(std::size_t done) override {
        const std::size_t tenth = steps_ > 0 ? 10 * std::min(done, steps_) / steps_ : 0;
        if (tenth == tenth_) return;
        tenth_ = tenth;
        emit({{"event", "stage_progress"}, {"stage", stage_}, {"done", done}, {"steps", steps_}});
    }
    void captureRead(std::size_t frames) override { frames_ = frames; }
    void stageFinished(const std::string& stage, double seconds, const std::string& summary) override {
        nlohmann::json event{{"event", "stage_finished"}, {"stage", stage}, {"seconds", seconds}, {"summary", summary}};
        if (frames_ > 0 && seconds > 0) event["frames_per_second"] = static_cast<double>(frames_) / seconds;
        emit(event);
    }
    void note(const std::string& text) override { emit({{"event", "note"}, {"text", text}}); }

private:
    static void emit(const nlohmann::json& j) { std::cerr << j.dump() << "\n"; }
    std::size_t frames_ = 0;
    std::string stage_;
    std::size_t steps_ = 0;
    std::size_t tenth_ = 0;  // of the stage's steps, last told
};

int ingestInto(const IngestArguments& args) {
    auto start = std::chrono::steady_clock::now();
    const ingest::IngestRequest& request = args.request;
    // The scene's name is checked before the work starts, not after minutes of it.
    Engine::open(args.db)->checkIngestTarget(ingest::sceneNameOf(request), request.update);

    std::unique_ptr<ingest::ProgressSink> progress;
    if (args.log == "json")
        progress = std::make_unique<JsonProgress>();
    else if (args.log == "quiet")
        progress = std::make_unique<ingest::SilentProgress>();
    else
        progress = std::make_unique<TerminalProgress>(isatty(STDERR_FILENO));

    // Ctrl-C stops between frames; nothing has been written then, and the database stays as it was.
    auto previous = std::signal(SIGINT, [](int) { interrupted = true; });
    ingest::IngestRun run;
    try {
        run = ingest::runIngest(request, *progress, [] { return interrupted.load(); });
    } catch (...) {
        std::signal(SIGINT, previous);
        throw;
    }
    std::signal(SIGINT, previous);

    // The scene's stamps (capture time, first and last seen) are the engine's, as for an import.
    auto writeStart = std::chrono::steady_clock::now();
    auto engine = Engine::open(args.db);
    auto writeSeconds = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - writeStart).count();
    };
    // The things the checks flagged, by the ids they are stored under (the ingest's own are not those).
    auto listFlagged = [&](const std::string& scene) {
        for (const auto& finding : ingest::objectFindings(engine->readScene(scene)))
            progress->note(ingest::objectWarning(finding));
    };
    if (!request.update.empty()) {
        auto update = engine->updateScene(request.update, run.result.scene);
        progress->stageFinished(
            "write", writeSeconds(),
            fmt::format("scene '{}' updated: version {} is in its history", update.scene, update.version));
        listFlagged(update.scene);
        if (args.log != "quiet") {
            std::cout << update.summary() << "\n";
            if (const auto warning = update.warning()) std::cerr << "warning: " << *warning << "\n";
        }
        return 0;
    }
    engine->importScene(run.result.scene);
    progress->stageFinished("write", writeSeconds(), fmt::format("one transaction into {}", args.db));
    listFlagged(run.result.scene.info.name);

    double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::size_t objects = 0, anchors = 0;
    for (const auto& n : run.result.scene.nodes)
        objects += n.kind == model::NodeKind::Object, anchors += n.kind == model::NodeKind::Anchor;
    // Frames that got no pose (COLMAP did not place them) did not make the memory: say how many did.
    const std::size_t placed = run.result.cameraCentres.size();
    const std::string frames = placed < run.frames ? fmt::format("{} frames ({} placed)", run.frames, placed)
                                                   : fmt::format("{} frames", run.frames);
    if (args.log != "quiet")
        std::cout << fmt::format(
            "ingested '{}' into scene '{}': {}, {} anchors, {} objects in {:.1f} s ({:.1f} "
            "frames/s)\n",
            request.capture, run.result.scene.info.name, frames, anchors, objects, total,
            run.frames / std::max(total, 1e-9));
    return 0;
}

}  // namespace

int ingestCommand(const IngestArguments& args) {
    // A database this ingest creates is removed again when the ingest fails: no empty database is
    // left behind.
    const bool creates = !fs::exists(args.db);
    try {
        return ingestInto(args);
    } catch (...) {
        std::error_code ignored;
        if (creates) fs::remove_all(args.db, ignored);
        throw;
    }
}

namespace {

// check-ingest without a truth: the plausibility checks of a stored scene. Exit status 1 when one
// of them would have refused the ingest.
int checkPlausibilityCommand(Engine& engine, const std::string& sceneName, const std::string& format) {
    const model::SceneData scene = engine.readScene(sceneName);
    const auto report = ingest::checkPlausibility(scene, {.stored = true});
    auto figure = [](const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
    if (format == "json") {
        nlohmann::json findings = nlohmann::json::array();
        for (const auto& f : report.findings)
            findings.push_back({{"check", f.check}, {"refuse", f.refuse}, {"what", f.what}, {"fix", f.fix}});
        nlohmann::json objects = nlohmann::json::array();
        for (const auto& o : report.objects)
            objects.push_back({{"node", o.node}, {"problem", o.problem}, {"what", o.what}});
        std::cout << nlohmann::json{{"scene", scene.info.name},
                                    {"camera_height_m", figure(report.cameraHeight)},
                                    {"ceiling_height_m", figure(report.ceilingHeight)},
                                    {"size_ratio", figure(report.sizeRatio)},
                                    {"named_things", report.namedThings},
                                    {"findings", findings},
                                    {"objects", objects}}
                         .dump(2)
                  << "\n";
        return report.refused() ? 1 : 0;
    }
    auto shown = [](const std::optional<double>& v, const char* unit) {
        return v ? fmt::format("{:.2f}{}", *v, unit) : std::string("not measured");
    };
    std::cout << fmt::format("scene '{}'\n", scene.info.name);
    std::cout << fmt::format("cameras  {} above the floor\n", shown(report.cameraHeight, " m"));
    std::cout << fmt::format("ceiling  {} above the floor\n", shown(report.ceilingHeight, " m"));
    std::cout << fmt::format("sizes    {} of their kinds' largest, over {} named things\n",
                             shown(report.sizeRatio, "x"), report.namedThings);
    for (const auto& f : report.findings)
        std::cout << fmt::format("{} {}: {}\n  fix: {}\n", f.refuse ? "IMPLAUSIBLE" : "warning", f.check, f.what,
                                 f.fix);
    for (const auto& o : report.objects) std::cout << fmt::format("  {}: {}\n", o.problem, o.what);
    if (report.findings.empty())
        std::cout << (report.measured() ? "looks like a room: every check passed\n"
                                        : "nothing could be checked: no floor, no ceiling and too few named things of "
                                          "known size\n");
    return report.refused() ? 1 : 0;
}

}  // namespace

int checkIngestCommand(const std::string& dbDir, const std::string& truthPath, const std::string& sceneName,
                       const std::string& format, bool misses) {
    auto engine = Engine::open(dbDir, /*readOnly=*/true);
    if (truthPath.empty()) return checkPlausibilityCommand(*engine, sceneName, format);
    const ingest::TruthCheck check = ingest::checkAgainstTruth(engine->exportScene(sceneName), truthPath);
    const ingest::QualityReport& r = check.report;
    const auto& registration = check.registration;
    const auto& options = check.options;
    if (format == "json") {
        nlohmann::json j = {
            {"anchors",
             {{"truth", r.anchors.truth},
              {"ingested", r.anchors.predicted},
              {"matched", r.anchors.matched},
              {"precision", r.anchors.precision()},
              {"recall", r.anchors.recall()},
              {"f1", r.anchors.f1()}}},
            {"objects",
             {{"truth", r.objects.truth},
              {"ingested", r.objects.predicted},
              {"matched", r.objects.matched},
              {"precision", r.objects.precision()},
              {"recall", r.objects.recall()},
              {"f1", r.objects.f1()}}},
            {"color_accuracy", r.colorAccuracy()},
            {"scale_error", registration ? nlohmann::json(std::abs(registration->scale - 1)) : nlohmann::json(nullptr)},
            {"parent_accuracy", r.parentAccuracy()},
            {"mean_center_error_m", r.meanCenterError}};
        if (misses) {
            j["unmatched_objects"] = nlohmann::json::array();
            for (const auto& u : r.unmatched)
                j["unmatched_objects"].push_back(
                    {{"side", u.inTruth ? "truth" : "ingested"},
                     {"category", u.category},
                     {"center", {u.box.center.x, u.box.center.y, u.box.center.z}},
                     {"size", {u.box.size.x, u.box.size.y, u.box.size.z}},
                     {"best_iou", u.bestIou},
                     {"nearest_m", u.nearest < 0 ? nlohmann::json(nullptr) : nlohmann::json(u.nearest)}});
        }
        std::cout << j.dump(2) << "\n";
        return 0;
    }
    std::cout << fmt::format(
        "anchors  F1 {:.2f}  (precision {:.2f}, recall {:.2f}; {} matched of {} true, {} ingested)\n", r.anchors.f1(),
        r.anchors.precision(), r.anchors.recall(), r.anchors.matched, r.anchors.truth, r.anchors.predicted);
    std::cout << fmt::format(
        "objects  F1 {:.2f}  (precision {:.2f}, recall {:.2f}; {} matched of {} true, {} ingested; 3D IoU >= {})\n",
        r.objects.f1(), r.objects.precision(), r.objects.recall(), r.objects.matched, r.objects.truth,
        r.objects.predicted, options.objectIou);
    std::cout << fmt::format("color    accuracy {:.2f}  ({} of {})\n", r.colorAccuracy(), r.colorCorrect,
                             r.colorChecked);
    std::cout << fmt::format("parent   accuracy {:.2f}  ({} of {})\n", r.parentAccuracy(), r.parentCorrect,
                             r.parentChecked);
    std::cout << fmt::format("centres  mean error {:.3f} m over matched objects\n", r.meanCenterError);
    if (registration)
        std::cout << fmt::format(
            "scale    off by {:.1f}% (similarity from {} cameras to the true poses, residual {:.3f} m)\n",
            100 * std::abs(registration->scale - 1), check.cameras, registration->residual);
    if (misses)
        for (const auto& u : r.unmatched)
            std::cout << fmt::format(
                "{:<8} {:<12} at ({:.2f}, {:.2f}, {:.2f}) size {:.2f} x {:.2f} x {:.2f}  best IoU {:.2f}{}\n",
                u.inTruth ? "missed" : "extra", u.category, u.box.center.x, u.box.center.y, u.box.center.z,
                u.box.size.x, u.box.size.y, u.box.size.z, u.bestIou,
                u.nearest < 0 ? std::string(", none of its category")
                              : fmt::format(", nearest of its category {:.2f} m away", u.nearest));
    return 0;
}

}  // namespace smql::shell
