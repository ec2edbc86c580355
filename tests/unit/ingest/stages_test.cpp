// The ingest's stage runner (timing, progress and cancellation in one place),
// cancellation of a whole ingest between frames and between stages, and the
// anchors stage's floor and the objects stage's carved hulls.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include "ingest/capture/capture.hpp"
#include "ingest/geometry/clusters.hpp"
#include "ingest/pipeline/align_stage.hpp"
#include "ingest/pipeline/anchors_stage.hpp"
#include "ingest/pipeline/frames_stage.hpp"
#include "ingest/pipeline/keyframes.hpp"
#include "ingest/pipeline/object_finder.hpp"
#include "ingest/pipeline/objects_stage.hpp"
#include "ingest/pipeline/pipeline.hpp"
#include "ingest/pipeline/progress.hpp"
#include "ingest/pipeline/request.hpp"
#include "ingest/pipeline/stage_runner.hpp"
#include "ingest/synth/synth.hpp"
#include "model/category.hpp"
#include "model/error.hpp"
#include "model/geometry.hpp"
#include "scratch_dir.hpp"

using namespace smql;
using namespace smql::ingest;
using smql::ingest::test::ScratchDir;

namespace {

// Every event a sink gets, as one line each.
class RecordingSink : public ProgressSink {
public:
    std::vector<std::string> events;
    void stageStarted(const std::string& stage, std::size_t steps) override {
        events.push_back("started " + stage + " " + std::to_string(steps));
    }
    void advanced(std::size_t done) override { events.push_back("advanced " + std::to_string(done)); }
    void stageFinished(const std::string& stage, double seconds, const std::string& summary) override {
        CHECK(seconds >= 0);
        events.push_back("finished " + stage + ": " + summary);
    }
    void note(const std::string& text) override { events.push_back("note " + text); }
};

struct CountStage {
    static constexpr std::string_view kName = "count";
    int upTo;
    std::size_t steps() const { return static_cast<std::size_t>(upTo); }
    std::vector<int> run(StageProgress& progress) {
        std::vector<int> out;
        for (int i = 1; i <= upTo; ++i) {
            out.push_back(i);
            progress.advanced(static_cast<std::size_t>(i));
        }
        progress.note("counted");
        return out;
    }
    std::string summary(const std::vector<int>& out) const { return std::to_string(out.size()) + " numbers"; }
};

// A stage that changes something in place, as the relations stage changes the scene.
struct SumStage {
    static constexpr std::string_view kName = "sum";
    const std::vector<int>& numbers;
    int& total;
    std::size_t steps() const { return 1; }
    void run(StageProgress&) {
        for (int n : numbers) total += n;
    }
    std::string summary() const { return "total " + std::to_string(total); }
};

// A finder that was shown no frame and finds nothing in the structure: the objects stage's tracks are given.
class GivenTracks : public ObjectFinder {
public:
    void observe(const PosedFrame&) override {}
    std::vector<ObjectTrack> takeTracks() override { return {}; }
    void addStructureObjects(const AlignedCapture&, const std::vector<WallSegment>&, model::SceneData&,
                             StageProgress&) override {}
};

}  // namespace

TEST_CASE("the stage runner reports, times and records each stage, and passes outputs on") {
    RecordingSink sink;
    IngestResult result;
    StageRunner runner(sink, result, {});
    runner.note("before any stage");
    auto numbers = runner.run(CountStage{3});
    int total = 0;
    runner.run(SumStage{numbers, total});

    CHECK(numbers == std::vector<int>{1, 2, 3});
    CHECK(total == 6);
    CHECK(sink.events == std::vector<std::string>{
                             "note before any stage", "started count 3", "advanced 1", "advanced 2", "advanced 3",
                             "note counted", "finished count: 3 numbers", "started sum 1", "finished sum: total 6"});
    REQUIRE(result.stages.size() == 2);
    CHECK(result.stages[0].stage == "count");
    CHECK(result.stages[0].summary == "3 numbers");
    CHECK(result.stages[1].stage == "sum");
    CHECK(result.stages[1].summary == "total 6");
    CHECK(result.notes == std::vector<std::string>{"before any stage", "counted"});
}

TEST_CASE("the stage runner stops between stages once cancelled") {
    RecordingSink sink;
    IngestResult result;
    bool cancel = false;
    StageRunner runner(sink, result, [&] { return cancel; });
    auto numbers = runner.run(CountStage{2});
    cancel = true;
    int total = 0;
    try {
        runner.run(SumStage{numbers, total});
        FAIL("a cancelled runner ran the next stage");
    } catch (const Error& e) {
        CHECK(e.kind() == ErrorKind::Usage);
        CHECK(e.message() == "cancelled; nothing was written");
    }
    CHECK(total == 0);
    CHECK(result.stages.size() == 1);
    CHECK(sink.events.back() == "finished count: 2 numbers");
}

TEST_CASE("an ingest cancelled during the frame pass stops before the next frame") {
    ScratchDir dir;
    auto capturePath = (dir.path / "capture").string();
    synth::writeSynth(capturePath, {.seed = 2, .frames = 6});
    Capture capture = readCapture(capturePath);
    RecordingSink sink;
    int asked = 0;
    // Asked once before the frames stage, then before each frame: stop before the third frame.
    auto cancelled = [&] { return ++asked > 3; };
    try {
        ingestCapture(capture, IngestOptions{}, sink, cancelled);
        FAIL("the ingest was not cancelled");
    } catch (const Error& e) {
        CHECK(e.kind() == ErrorKind::Usage);
        CHECK(e.message() == "cancelled; nothing was written");
    }
    CHECK(sink.events == std::vector<std::string>{"started frames 6", "advanced 1", "advanced 2"});
}

TEST_CASE("the floor spans the room, not the stray points far outside it") {
    AlignedCapture aligned;
    aligned.alignment.floorFound = true;
    // A 4 x 5 m floor every 5 cm, and five strays 20 m away (sparse points seen through a window).
    for (double x = 0; x <= 4; x += 0.05)
        for (double y = 0; y <= 5; y += 0.05) aligned.cloud.push({x, y, 0}, {0, 0, 0}, 0);
    for (int k = 0; k < 5; ++k) aligned.cloud.push({24.0 + k, -20.0, 0.5}, {0, 0, 0}, 0);
    model::SceneData scene;
    RecordingSink sink;
    std::vector<std::string> notes;
    StageProgress progress(sink, notes, [] { return false; });
    AnchorsStage{aligned, scene}.run(progress);
    auto floor = std::find_if(scene.nodes.begin(), scene.nodes.end(),
                              [](const model::Node& n) { return n.category == "floor"; });
    REQUIRE(floor != scene.nodes.end());
    CHECK(floor->box.size.x == Approx(4).margin(0.1));
    CHECK(floor->box.size.y == Approx(5).margin(0.1));
    CHECK(floor->box.center.x == Approx(2).margin(0.1));
}

// --fps keeps that many frames a second of a video or a TUM sequence; 0 keeps every frame, as
// docs/formats.md says, and a negative rate is refused naming the option.
TEST_CASE("ingest options: --fps 0 keeps every frame, a negative rate is refused") {
    IngestRequest request;
    setIngestOption(request, "fps", "0");
    CHECK(request.fps == 0);
    setIngestOption(request, "fps", "2.5");
    CHECK(request.fps == 2.5);
    try {
        setIngestOption(request, "fps", "-1");
        FAIL("a negative --fps was taken");
    } catch (const Error& e) {
        CHECK(e.kind() == ErrorKind::Usage);
        CHECK(std::string(e.what()).find("--fps") != std::string::npos);
    }
}

// --dense auto|room|on|off: photos without depth place their room on dense points, and their things where the
// points cover them, unless told otherwise (docs/ingest.md, "Dense points from placed photos"); another value is
// refused naming the ones it takes.
TEST_CASE("ingest options: --dense is auto unless asked otherwise, and takes auto, room, on or off") {
    IngestRequest request;
    CHECK(request.dense == "auto");
    CHECK(IngestOptions{}.dense == DenseUse::Auto);
    for (const char* value : {"on", "off", "room", "auto"}) {
        setIngestOption(request, "dense", value);
        CHECK(request.dense == value);
    }
    try {
        setIngestOption(request, "dense", "yes");
        FAIL("--dense yes was taken");
    } catch (const Error& e) {
        CHECK(e.kind() == ErrorKind::Usage);
        CHECK_THAT(std::string(e.hint()), Catch::Contains("auto, room, on or off"));
    }
}

// --camera-height METRES: the cameras' height above the floor when known, above 0 and at most 5 (150 is in
// centimetres); with --scale, which also says what the scale is, the ingest is refused before any work.
TEST_CASE("ingest options: --camera-height takes metres, and not beside --scale") {
    IngestRequest request;
    CHECK_FALSE(request.cameraHeight);
    setIngestOption(request, "camera_height", "1.33");
    REQUIRE(request.cameraHeight);
    CHECK(*request.cameraHeight == 1.33);
    for (const char* value : {"0", "-1.2", "tall", "150"}) {
        INFO(value);
        try {
            setIngestOption(request, "camera_height", value);
            FAIL("--camera-height " << value << " was taken");
        } catch (const Error& e) {
            CHECK(e.kind() == ErrorKind::Usage);
            CHECK_THAT(std::string(e.what()), Catch::Contains("--camera-height"));
        }
    }
    request.capture = "no-such-capture";
    request.scale = 0.5;
    SilentProgress silent;
    try {
        runIngest(request, silent);
        FAIL("--scale and --camera-height were both taken");
    } catch (const Error& e) {
        CHECK(e.kind() == ErrorKind::Usage);
        CHECK_THAT(std::string(e.what()), Catch::Contains("--scale and --camera-height"));
    }
}

// The detectors look at a frame when the camera has moved 0.25 m or turned 15 degrees since the last
// one they looked at: a camera standing still, or turning a little, shows nothing new.
TEST_CASE("keyframes: the first frame, then one for every 0.25 m moved or 15 degrees turned") {
    auto pose = [](double x, double yawDegrees) {
        const double a = yawDegrees * M_PI / 180;
        Pose p;
        // The camera looks along +z, turned about the y axis (image down) by `yaw`.
        p.rotation = {std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a)};
        p.translation = {x, 0, 0};
        return p;
    };
    Keyframes keyframes;
    CHECK(keyframes.take(pose(0, 0)));
    CHECK_FALSE(keyframes.take(pose(0.1, 5)));
    CHECK_FALSE(keyframes.take(pose(0.2, 10)));
    CHECK(keyframes.take(pose(0.3, 10)));  // 0.3 m from the first
    CHECK_FALSE(keyframes.take(pose(0.3, 20)));
    CHECK(keyframes.take(pose(0.3, 26)));  // 16 degrees from the last keyframe
    int taken = 0;
    for (int i = 0; i < 100; ++i) taken += keyframes.take(pose(0.3, 26));  // standing still
    CHECK(taken == 0);
}

// Frames COLMAP did not place (tens in a long walk) are one note naming the first of them, not a note each.
TEST_CASE("the frames stage names the frames without a pose in one note") {
    Capture capture = readCapture(std::string(SMQL_SHARED_DATA) + "/rgbd-dining");
    REQUIRE(capture.frames.size() == 5);
    IngestOptions options;
    options.objects = "cluster";
    auto finder = makeObjectFinder(capture, options);
    RecordingSink sink;
    std::vector<std::string> notes;
    StageProgress progress(sink, notes, [] { return false; });

    capture.frames[3].pose.reset();
    FramePass one = FramesStage{capture, options, *finder}.run(progress);
    CHECK(one.cameras.size() == 4);
    CHECK(std::count(notes.begin(), notes.end(), "frame 3 has no camera pose (not registered): skipped") == 1);

    notes.clear();
    capture.frames[0].pose.reset();
    capture.frames[1].pose.reset();
    FramePass two = FramesStage{capture, options, *finder}.run(progress);
    CHECK(two.cameras.size() == 2);
    const auto said = [&](std::string_view text) { return std::find(notes.begin(), notes.end(), text) != notes.end(); };
    CHECK(said("3 frames have no camera pose (not registered): skipped: 0, 1, 3"));
    CHECK(std::none_of(notes.begin(), notes.end(), [](const std::string& n) { return n.rfind("frame ", 0) == 0; }));
}

// A table's hull carved from views that all look down reaches up to the top of its boxes: the space over
// the table projects into the table's outline in every view. The shape below is 7-Scenes' red kitchen
// table as 100 of its photos give it (docs/ingest.md, "Detections without depth"): its sparse points on
// the top at 0.73-0.77 m, a few on what stands there up to 1.03 m, the hull carved up to 1.56 m.
TEST_CASE(
    "the objects stage merges a hull carved without depth, or a chair pushed in, that lies mostly inside a larger one "
    "of its kind, and what holds a sink on its pedestal into the sink") {
    auto trackOf = [](const std::string& category, bool carved, std::uint32_t frame) {
        ObjectTrack track;
        track.category = category;
        track.carved = carved;
        Observation view;
        view.frame = frame;
        track.views.push_back(view);
        return track;
    };
    auto boxOf = [](double x, double y, double side) { return model::Box{{x, y, side / 2}, {side, side, side}, 0}; };
    const cv::Mat white(1, 1, CV_8UC3, cv::Scalar(255, 255, 255));
    // A toilet carved twice from views of the same frames, a "table" hull inside a "desk" (one kind), a chair
    // inside the larger toilet's hull (another kind), and a toilet fused on depth inside it (not carved).
    std::vector<ObjectTrack> tracks{trackOf("toilet", true, 1),  trackOf("toilet", true, 2), trackOf("chair", true, 3),
                                    trackOf("toilet", false, 4), trackOf("desk", true, 5),   trackOf("table", true, 6)};
    std::vector<PlacedTrack> placed{{0, white, boxOf(0, 0, 1.0)},    {1, white, boxOf(0.1, 0, 0.6)},
                                    {2, white, boxOf(-0.1, 0, 0.5)}, {3, white, boxOf(0, 0.1, 0.5)},
                                    {4, white, boxOf(5, 5, 1.2)},    {5, white, boxOf(5.3, 5, 0.7)}};
    CHECK(mergeStoredTwice(placed, tracks) == 2);
    std::vector<std::size_t> kept;
    for (const auto& p : placed) kept.push_back(p.track);
    CHECK(kept == std::vector<std::size_t>{0, 2, 3, 4});
    REQUIRE(tracks[0].views.size() == 2);
    CHECK(tracks[0].views[1].frame == 2);
    CHECK(placed[0].colors.rows == 2);
    CHECK(placed[0].box.size.x == 1.0);  // the larger's box stays
    CHECK(tracks[4].views.size() == 2);
    // Side by side, the smaller's half outside the larger: two things.
    std::vector<ObjectTrack> apart{trackOf("chair", true, 1), trackOf("chair", true, 1)};
    std::vector<PlacedTrack> sideBySide{{0, white, boxOf(0, 0, 0.6)}, {1, white, boxOf(0.35, 0, 0.5)}};
    CHECK(mergeStoredTwice(sideBySide, apart) == 0);
    CHECK(sideBySide.size() == 2);
    // Two pieces of one chair's back, measured on depth and pushed in at a table (the dining frames'): one chair, its
    // box taking in both; a pushed-in chair and one that was not are left apart.
    auto chairAt = [](double y, double width) { return model::Box{{0.62, y, 0.49}, {0.33, width, 0.98}, 0}; };
    std::vector<ObjectTrack> pieces{trackOf("chair", false, 1), trackOf("chair", false, 2), trackOf("chair", false, 3)};
    std::vector<PlacedTrack> pushed{{0, white, chairAt(1.16, 0.39), false, true},
                                    {1, white, chairAt(0.98, 0.32), false, true},
                                    {2, white, chairAt(1.30, 0.39), false, false}};
    CHECK(mergeStoredTwice(pushed, pieces) == 1);
    REQUIRE(pushed.size() == 2);
    CHECK(pushed[0].track == 0);
    CHECK(pushed[0].box.size.y == Approx(1.355 - 0.82));
    CHECK(pushed[0].box.center.y == Approx((1.355 + 0.82) / 2));
    CHECK(pushed[0].box.size.x == Approx(0.33));
    CHECK(pieces[0].views.size() == 2);
    // ScanNet's apartment from every third frame: its sink on its pedestal, 0.76 x 0.38 x 0.88 m from the floor, and
    // the pedestal seen apart, stored unnamed (a doubted "table", 0.54 x 0.36 x 0.28 m, turned 29 degrees): one thing,
    // the sink. Not so a bin stored as what it is, nor the unnamed thing under a sink hung off the floor.
    const model::Box sinkBox{{8.42, 0.51, 0.44}, {0.76, 0.38, 0.88}, std::numbers::pi / 2};
    const model::Box pedestal{{8.40, 0.67, 0.14}, {0.54, 0.36, 0.28}, -0.51};
    std::vector<ObjectTrack> bathroom{
        trackOf("sink", false, 1), trackOf(std::string(model::kUnnamedCategory), false, 2), trackOf("bin", false, 3)};
    std::vector<PlacedTrack> sinkAndPedestal{{0, white, sinkBox}, {1, white, pedestal}, {2, white, pedestal}};
    CHECK(mergeStoredTwice(sinkAndPedestal, bathroom) == 1);
    REQUIRE(sinkAndPedestal.size() == 2);
    CHECK(sinkAndPedestal[1].track == 2);
    CHECK(bathroom[0].views.size() == 2);
    model::Box hung = sinkBox;
    hung.center.z = 0.8, hung.size.z = 0.16;
    std::vector<PlacedTrack> hungSink{{0, white, hung}, {1, white, {{8.42, 0.51, 0.75}, {0.3, 0.2, 0.06}, 0}}};
    CHECK(mergeStoredTwice(hungSink, bathroom) == 0);
}

TEST_CASE("a sink on a pedestal reaches the floor; one on a vanity or hung on a wall does not") {
    // A basin fitted to its bowl, 0.60 x 0.45 m, its rim 0.88 m up, against a wall at x = 0.55 (facing -x).
    const model::Box basin{{0.3, 0, 0.8}, {0.45, 0.6, 0.16}, 0};
    WallSegment wall;
    wall.normal = {-1, 0, 0}, wall.offset = 0.55, wall.along0 = -2, wall.along1 = 2, wall.z1 = 2.5;
    const std::vector<WallSegment> walls{wall};
    // Whether a column is found under the basin among the room's points and those of a block from (x0, y0, z0) to
    // (x1, y1, z1), the `others` things' boxes left out.
    auto onPedestal = [&](double x0, double x1, double y0, double y1, double z0, double z1,
                          const std::vector<model::Box>& others) {
        PointCloud cloud;
        // The wall behind, from the floor up: its own points, never the sink's.
        for (double y = -0.6; y <= 0.6; y += 0.05)
            for (double z = 0; z <= 1.2; z += 0.05) cloud.push({0.55, y, z}, {0, 0, 0}, 0);
        for (double x = x0; x <= x1 + 1e-9; x += 0.04)
            for (double y = y0; y <= y1 + 1e-9; y += 0.04)
                for (double z = z0; z <= z1 + 1e-9; z += 0.05) cloud.push({x, y, z}, {0, 0, 0}, 0);
        return !pedestalUnder(basin, cloud, nonStructuralPoints(cloud, walls), others).empty();
    };
    // ScanNet's apartment's pedestal: a column about 0.2 m across from the floor to the bowl.
    CHECK(onPedestal(0.2, 0.4, -0.1, 0.1, 0, 0.7, {}));
    // A vanity's front, as wide as the basin or wider, its cabinet not stored apart: its points fill the footprint.
    CHECK_FALSE(onPedestal(0.1, 0.1, -0.32, 0.32, 0, 0.7, {}));
    // A bin standing under it, a thing of its own: its points are the bin's.
    const model::Box bin{{0.3, 0, 0.35}, {0.3, 0.3, 0.7}, 0};
    CHECK_FALSE(onPedestal(0.2, 0.4, -0.1, 0.1, 0, 0.7, {bin}));
    // A sink hung on the wall: its drain, from the bowl into the wall 0.45 m over the floor.
    CHECK_FALSE(onPedestal(0.3, 0.35, -0.02, 0.02, 0.45, 0.7, {}));
    // Nothing under it but the wall.
    CHECK_FALSE(onPedestal(0, -1, 0, -1, 0, -1, {}));
}

TEST_CASE(
    "a thing held up by a column no model named stands on a table; a chair or a thing on a stored table does not") {
    // ScanNet's bathroom: towels stored as a 0.34 x 0.32 x 0.18 m "toy", its bottom 0.49 m up, on a tripod stand whose
    // column is 0.01-0.15 m across. ScanNet's apartment from every second frame: a sink's bowl fitted 0.46 x 0.22 m
    // (its basin is 0.67 m long) over its pedestal, 0.30 m across, wider than half the bowl. Books on a shelf no model
    // named, the shelf's points filling their footprint.
    const cv::Mat white(1, 1, CV_8UC3, cv::Scalar(255, 255, 255));
    PointCloud cloud;
    auto column = [&](double x, double y, double half, double z1) {
        for (double dx = -half; dx <= half + 1e-9; dx += 0.02)
            for (double dy = -half; dy <= half + 1e-9; dy += 0.02)
                for (double z = 0; z <= z1 + 1e-9; z += 0.03) cloud.push({x + dx, y + dy, z}, {90, 60, 40}, 0);
    };
    column(0, 0, 0.04, 0.48);
    column(2, 0, 0.15, 0.72);
    column(4, 0, 0.04, 0.48);
    column(6, 0, 0.18, 0.82);
    auto trackOf = [](const std::string& category) {
        ObjectTrack track;
        track.category = category;
        return track;
    };
    std::vector<ObjectTrack> tracks{trackOf("toy"), trackOf("sink"), trackOf("chair"), trackOf("book")};
    // The sink's fused points: its basin, 0.67 x 0.45 m along the walls (ScanNet's box), from its bowl up to its rim.
    for (double x = 2 - 0.225; x <= 2 + 0.225 + 1e-9; x += 0.025)
        for (double y = -0.335; y <= 0.335 + 1e-9; y += 0.025)
            for (double z = 0.73; z <= 0.89 + 1e-9; z += 0.04) tracks[1].fused.push_back({x, y, z});
    std::vector<PlacedTrack> placed{{0, white, {{0, 0, 0.58}, {0.34, 0.32, 0.18}, 0}},
                                    {1, white, {{2, 0, 0.81}, {0.46, 0.22, 0.16}, -std::numbers::pi / 4}},
                                    {2, white, {{4, 0, 0.7}, {0.5, 0.5, 0.4}, 0}},
                                    {3, white, {{6, 0, 0.93}, {0.21, 0.16, 0.2}, 0}}};
    const Pedestals found = standOnPedestals(placed, tracks, cloud, {});
    // The towels stay where they were, on a stand from the floor up to them, as wide as they are. The shelf under the
    // books fills their footprint: no stand there (0.3 m is narrow under a sink's bowl alone).
    REQUIRE(found.stands.size() == 1);
    CHECK(found.stands[0].box.center.x == Approx(0));
    CHECK(found.stands[0].box.size.x == Approx(0.34));
    CHECK(model::bottom(found.stands[0].box) == Approx(0).margin(1e-9));
    CHECK(model::top(found.stands[0].box) == Approx(0.49));
    CHECK_FALSE(found.stands[0].points.empty());
    CHECK(placed[0].box.center.z == Approx(0.58));
    // The sink is one thing with its pedestal: its box reaches the floor, and no stand is added under it. With no
    // counter around its bowl, its rim is its own edge: the basin is all its points, square to the walls, where the
    // bowl was fitted short of it and turned 45 degrees (the apartment from every second frame).
    CHECK(found.sinks == 1);
    CHECK(model::bottom(placed[1].box) == Approx(0).margin(1e-9));
    CHECK(model::top(placed[1].box) == Approx(0.89));
    CHECK(std::max(placed[1].box.size.x, placed[1].box.size.y) == Approx(0.67).margin(0.05));
    CHECK(std::min(placed[1].box.size.x, placed[1].box.size.y) == Approx(0.45).margin(0.05));
    CHECK(std::fmod(std::abs(placed[1].box.yaw), std::numbers::pi / 2) == Approx(0).margin(1e-9));
    // A chair's box holds its own legs: a floating "chair" is something else, judged by its name (renameFloating).
    CHECK(model::bottom(placed[2].box) == Approx(0.5));

    // The towels on a stored table: the column's points are the table's, and no stand is added.
    std::vector<PlacedTrack> onTable{{0, white, {{0, 0, 0.58}, {0.34, 0.32, 0.18}, 0}},
                                     {2, white, {{0, 0, 0.245}, {0.5, 0.5, 0.49}, 0}}};
    const std::vector<ObjectTrack> towelsAndTable{trackOf("toy"), trackOf("sink"), trackOf("table")};
    CHECK(standOnPedestals(onTable, towelsAndTable, cloud, {}).stands.empty());
}

TEST_CASE("chairs seen by their backs alone: pushed in at a table, facing away from the cameras at none") {
    const cv::Mat white(1, 1, CV_8UC3, cv::Scalar(255, 255, 255));
    auto trackOf = [](const std::string& category) {
        ObjectTrack track;
        track.category = category;
        return track;
    };
    std::vector<ObjectTrack> tracks{trackOf("table"), trackOf("chair"), trackOf("chair"),
                                    trackOf("chair"), trackOf("chair"), trackOf("chair")};
    // A table along y; a back 0.17 m deep beyond its +x side; a back 0.17 m deep 2 m from it, its thin side along x,
    // seen from cameras at x = -1 (so from behind, the chair facing +x); a chair seen whole, 0.5 m deep; the dining
    // frames' wingback armchair seen from behind, a 0.74 x 0.36 m slab 1.21 m tall; and a 1.46 x 0.69 m "chair",
    // wider than any chair is.
    const model::Vec3 cameras{-1, 0, 1.4};
    std::vector<PlacedTrack> placed{{0, white, {{0, 0, 0.37}, {1.0, 1.8, 0.75}, 0}, false, false, cameras},
                                    {1, white, {{0.7, 0.2, 0.49}, {0.17, 0.5, 0.98}, 0.3}, false, false, cameras},
                                    {2, white, {{2.5, 0, 0.49}, {0.17, 0.51, 0.98}, M_PI}, false, false, cameras},
                                    {3, white, {{2.5, 2.0, 0.45}, {0.5, 0.55, 0.9}, 0.2}, false, false, cameras},
                                    {4, white, {{2.5, -2.0, 0.6}, {0.36, 0.74, 1.21}, 0}, false, false, cameras},
                                    {5, white, {{2.5, 4.0, 0.34}, {0.69, 1.46, 0.67}, 0}, false, false, cameras}};
    CHECK(seatChairs(placed, tracks) == std::pair<std::size_t, std::size_t>{1, 2});
    // Pushed in: square to the table's +x side, facing it (-x), 0.33 deep towards it from its back.
    CHECK(placed[1].pushedIn);
    CHECK(std::cos(placed[1].box.yaw) == Approx(-1).margin(1e-9));
    CHECK(placed[1].box.size.x == Approx(0.33));
    CHECK(placed[1].box.center.x == Approx(0.7 - 0.08));
    // Seen from behind: facing away from the cameras (+x), its seat ahead of the back, as deep as 0.65 of its width.
    CHECK_FALSE(placed[2].pushedIn);
    CHECK(std::cos(placed[2].box.yaw) == Approx(1).margin(1e-9));
    CHECK(placed[2].box.size.x == Approx(0.65 * 0.51));
    CHECK(placed[2].box.size.y == Approx(0.51));
    CHECK(placed[2].box.center.x == Approx(2.5 + (0.65 * 0.51 - 0.17) / 2));
    // Seen whole: left as it was.
    CHECK(placed[3].box.yaw == 0.2);
    CHECK(placed[3].box.size.x == 0.5);
    // The wingback: deeper than the shallowest chairs, yet half as deep as a chair 0.74 m wide is; it reaches 0.65 of
    // its width (0.48 m), facing away from the cameras.
    CHECK(std::cos(placed[4].box.yaw) == Approx(1).margin(1e-9));
    CHECK(placed[4].box.size.x == Approx(0.65 * 0.74));
    CHECK(placed[4].box.size.y == Approx(0.74));
    CHECK(placed[4].box.center.x == Approx(2.5 + (0.65 * 0.74 - 0.36) / 2));
    // Wider than any chair: no chair's back alone, left as it was.
    CHECK(placed[5].box.size.x == 0.69);
    CHECK(placed[5].box.size.y == 1.46);
}

TEST_CASE("the objects stage holds a carved hull's top, and a table's footprint, to where its surfaces were seen") {
    auto hullOf = [](double length, double width, double height) {
        std::vector<model::Vec3> hull;
        for (double x = 0; x <= length; x += 0.05)
            for (double y = 0; y <= width; y += 0.05)
                for (double z = 0; z <= height; z += 0.05) hull.push_back({x, y, z});
        return hull;
    };
    auto heightOf = [](const std::vector<model::Vec3>& points) {
        auto [low, high] =
            std::minmax_element(points.begin(), points.end(), [](const auto& a, const auto& b) { return a.z < b.z; });
        return high->z - low->z;
    };
    std::vector<model::Vec3> cameras;
    for (int i = 0; i < 10; ++i) cameras.push_back({0.2 * i, -2.0, 1.45});  // along one side, looking across

    const auto table = hullOf(2.0, 1.0, 1.55);
    std::vector<model::Vec3> top;
    for (int i = 0; i < 950; ++i) top.push_back({0.1 + 0.002 * i, 0.1 + 0.0008 * i, 0.73 + 0.04 * (i % 11) / 10.0});
    for (int i = 0; i < 50; ++i) top.push_back({0.5 + 0.01 * i, 0.5, 0.80 + 0.23 * i / 49.0});  // a bowl, a bottle
    const auto held = holdToSurface(table, top, cameras, false);
    CHECK(heightOf(held) >= 0.75);
    CHECK(heightOf(held) <= 0.90);  // was 1.55
    CHECK(std::any_of(held.begin(), held.end(), [](const auto& p) { return p.x > 1.95 && p.y > 0.95; }));

    // A chair whose points reach the top of its back keeps its height.
    const auto chair = hullOf(0.5, 0.5, 0.95);
    std::vector<model::Vec3> seatAndBack;
    for (int i = 0; i < 200; ++i) seatAndBack.push_back({0.05 + 0.002 * i, 0.1, 0.45});
    for (int i = 0; i < 200; ++i) seatAndBack.push_back({0.05 + 0.002 * i, 0.45, 0.45 + 0.45 * i / 199.0});
    CHECK(heightOf(holdToSurface(chair, seatAndBack, cameras, false)) == heightOf(chair));

    // The views along the table could not carve away the chairs on both its sides: its hull is 1.8 m wide
    // where its top, which its points show, is 0.8 m. A table is widest at its top.
    const auto withChairs = hullOf(2.1, 1.8, 0.85);
    std::vector<model::Vec3> onTop;
    for (const auto& p : top) onTop.push_back({p.x, p.y + 0.5, p.z});
    for (int i = 0; i < 100; ++i) onTop.push_back({0.2 + 0.016 * i, 0.25, 0.45});  // the seats, under its top band
    const auto footprint = holdToSurface(withChairs, onTop, cameras, true);
    auto [west, east] =
        std::minmax_element(footprint.begin(), footprint.end(), [](const auto& a, const auto& b) { return a.x < b.x; });
    auto [south, north] =
        std::minmax_element(footprint.begin(), footprint.end(), [](const auto& a, const auto& b) { return a.y < b.y; });
    CHECK(north->y - south->y <= 1.2);  // was 1.8
    CHECK(north->y - south->y >= 0.8);
    CHECK(east->x - west->x >= 1.8);
    CHECK(heightOf(footprint) >= 0.8);
}

TEST_CASE("a floor placed a table's height under a table top bounds the table's hull below and above") {
    // Photos of a desk whose floor never shows (TUM's desk frames): the floor is placed 0.75 m under the desk's
    // top, and the desk's hull, carved from views that all look down, reached 0.13 m under it and, with the
    // monitors' points among its surface's, 0.24 m over its top.
    Capture capture;
    for (int f = 0; f < 4; ++f) {
        CaptureFrame frame;
        frame.index = f;
        Pose pose;
        pose.translation = {0.4 * f, -1.5, 1.5};
        frame.pose = pose;
        capture.frames.push_back(frame);
    }
    ObjectTrack desk;
    desk.category = "table";
    desk.carved = true;
    for (std::uint32_t f = 0; f < 4; ++f) {
        Observation view;
        view.frame = f;
        desk.views.push_back(view);
    }
    for (double x = 0; x <= 1.6; x += 0.05)
        for (double y = 0; y <= 0.8; y += 0.05) {
            for (double z = -0.15; z <= 1.2; z += 0.05) desk.views.front().points.push_back({x, y, z});
            desk.surface.push_back({x, y, 0.74 + 0.02 * std::fmod(x * 7, 1.0)});
        }
    for (double z = 0.8; z <= 1.2; z += 0.01) desk.surface.push_back({0.8, 0.6, z});  // a monitor on it
    AlignedCapture aligned;
    aligned.alignment.tableTopHeight = 0.75;
    IngestOptions options;
    GivenTracks finder;
    model::SceneData scene;
    RecordingSink sink;
    std::vector<std::string> notes;
    StageProgress progress(sink, notes, [] { return false; });
    std::vector<WallSegment> walls;
    ObjectsStage{capture, options, {desk}, aligned, walls, finder, scene}.run(progress);
    auto table = std::find_if(scene.nodes.begin(), scene.nodes.end(),
                              [](const model::Node& n) { return n.category == "table"; });
    REQUIRE(table != scene.nodes.end());
    CHECK(table->box.center.z - table->box.size.z / 2 >= -0.03);  // was -0.15
    CHECK(table->box.center.z + table->box.size.z / 2 <= 0.8);    // was 1.2
    CHECK(table->box.center.z + table->box.size.z / 2 >= 0.75);
}

TEST_CASE("a table's footprint is held in the frame its top shows, not its hull's") {
    // The red kitchen's table as photos (one of five COLMAP runs): its hull, reaching past the table along the
    // views, had its box turned 25 degrees from the top's edges, and the footprint cut in that frame came out
    // 1.86 x 1.41 m where the top is 2.1 x 1.0 m.
    const double yaw = 40 * std::numbers::pi / 180;
    auto turned = [](double angle, double u, double v, double z) {
        return model::Vec3{std::cos(angle) * u - std::sin(angle) * v, std::sin(angle) * u + std::cos(angle) * v, z};
    };
    std::vector<model::Vec3> hull, top;
    for (double u = -1.05; u <= 1.05; u += 0.05)
        for (double v = -0.5; v <= 0.5; v += 0.05) {
            for (double z = 0; z <= 0.85; z += 0.05) hull.push_back(turned(yaw, u, v, z));
            top.push_back(turned(yaw, u, v, 0.8 + 0.02 * std::fmod(std::abs(u * 7), 1.0)));
        }
    const double off = 15 * std::numbers::pi / 180;  // what the views did not carve, turned from the table
    for (double u = -1.3; u <= 1.3; u += 0.05)
        for (double v = -0.8; v <= 0.8; v += 0.05)
            for (double z = 0; z <= 0.85; z += 0.05) hull.push_back(turned(off, u, v, z));
    std::vector<model::Vec3> cameras;
    for (int i = 0; i < 10; ++i) cameras.push_back(turned(yaw, -2.5, -2.0 + 0.4 * i, 1.45));
    const model::Box box = uprightBox(holdToSurface(hull, top, cameras, true));
    CHECK(box.size.x == Approx(2.1).margin(0.2));
    CHECK(box.size.y == Approx(1.0).margin(0.2));
    CHECK(std::remainder(box.yaw - yaw, std::numbers::pi / 2) == Approx(0).margin(5 * std::numbers::pi / 180));
}

TEST_CASE("the things as stored, for the alignment measured again: a name not kept comes back measuring nothing") {
    // ScanNet's bathroom's 296 frames without depth: fusion stored its toilets as "object" among three "fridges";
    // measured again, the toilets must still doubt the fridges beside them (scale_priors.hpp), not vanish.
    model::SceneData scene;
    auto add = [&](model::NodeId id, const char* category, model::Vec3 centre, std::vector<model::Attribute> attrs) {
        model::Node node;
        node.id = id;
        node.category = category;
        node.box.center = centre;
        node.box.size = {0.5, 0.5, 1.0};
        node.attributes = std::move(attrs);
        scene.nodes.push_back(node);
    };
    add(1, "fridge", {0, 0, 0.5}, {});
    add(2, "object", {1, 0, 0.5}, {{"detected_as", "toilet"}});
    add(3, "object", {2, 0, 0.5}, {});  // no model named it: nothing to say
    add(4, "chair", {3, 0, 0.5}, {});
    std::vector<TrackedNode> tracked;
    for (model::NodeId id : {1, 2, 3, 4}) tracked.push_back({id, {}, /*fused=*/id != 4});
    Alignment alignment;
    alignment.scale = 0.5;  // metres per capture unit: the things come back twice as large, in capture units
    alignment.transform = {0.5, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 0.5, 0};
    const std::vector<NamedThing> things = thingsAsStored(scene, tracked, alignment);
    REQUIRE(things.size() == 2);  // the chair's box was not fused on its views' points
    CHECK(things[0].category == "fridge");
    CHECK(things[0].measures);
    CHECK(things[1].category == "toilet");
    CHECK_FALSE(things[1].measures);
    REQUIRE(things[0].points.size() == 27);
    const auto [low, high] = std::minmax_element(things[0].points.begin(), things[0].points.end(),
                                                 [](const auto& a, const auto& b) { return a.z < b.z; });
    CHECK(low->z == Approx(0.0));
    CHECK(high->z == Approx(2.0));
}
