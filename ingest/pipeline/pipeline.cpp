#include "ingest/pipeline/pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "model/error.hpp"
#include "model/geometry.hpp"
#include "model/points.hpp"

#include "ingest/pipeline/align_stage.hpp"
#include "ingest/pipeline/anchors_stage.hpp"
#include "ingest/pipeline/frames_stage.hpp"
#include "ingest/pipeline/geometry_stage.hpp"
#include "ingest/pipeline/object_finder.hpp"
#include "ingest/pipeline/objects_stage.hpp"
#include "ingest/pipeline/openings_stage.hpp"
#include "ingest/pipeline/plausibility.hpp"
#include "ingest/pipeline/relations_stage.hpp"
#include "ingest/pipeline/stage_runner.hpp"

namespace smql::ingest {

namespace {

// Name, origin and frame of the scene; its default viewpoint is the first
// camera, at its height, facing where it looked.
model::SceneInfo sceneInfo(const Capture& capture, const IngestOptions& options, const FramePass& frames,
                           const AlignedCapture& aligned) {
    model::SceneInfo info;
    info.name = options.sceneName;
    info.source = fmt::format("{}:{}", capture.layout, capture.path);
    info.alignment = aligned.alignment.transform;
    info.scale = aligned.alignment.scale;
    Pose first = transformed(frames.cameras.front().pose, aligned.alignment);
    const auto& R = first.rotation;
    info.viewpoint = {first.translation, std::atan2(R[5], R[2])};  // the camera's +z axis in the floor plane
    info.viewpointNote = "the first camera of the capture, facing where it looked";
    return info;
}

// The structure cloud as the memory keeps it, on the scene's node: the points viewers draw under
// the boxes (`smql export ply --points`, the view).
model::Blob pointsBlob(const AlignedCapture& aligned, const IngestOptions& options) {
    model::ScenePoints points;
    points.positions = aligned.cloud.points;
    points.colours.reserve(aligned.cloud.size());
    for (const auto& [r, g, b] : aligned.cloud.colors) points.colours.push_back({r, g, b});
    return {
        model::kNoNode, std::string(model::kPointsBlobName), std::string(model::kPointsMediaType),
        model::pointsPly(points, fmt::format("smql points of scene {}: one a {:g} m voxel, metres, z up, floor at 0",
                                             options.sceneName, options.structureVoxel))};
}

// The plausibility checks: each failure a note with its fix; a refusal ends the ingest unless
// --force, so that no wrong memory is stored with exit status 0. Photos without depth whose points cover
// under half of what the detectors saw are refused for it (thinPointsFinding), and where they cover far less,
// that is the cause beneath whatever else refuses their room: a floor unconfirmed, priors that part.
// The things flagged (report.objects) are listed by whoever writes the memory, by its ids (objectWarning).
void checkRoom(const IngestResult& result, const Capture& capture, const IngestOptions& options,
               const FramePass& frames, const Alignment& alignment, const DensePoints* dense,
               std::optional<double> pointsCover, StageRunner& runner) {
    const bool depth = framesHaveDepth(capture) && !options.scale;
    const ScaleSource source{.depth = depth,
                             .depthScale = capture.depthScale,
                             .given = options.scale.has_value(),
                             .cameraHeight = capture.metric ? std::nullopt : options.cameraHeight,
                             .metric = capture.metric && !depth && !options.scale,
                             .onePairDepth = dense && dense->agreeing == 1 && !dense->points.empty()};
    std::vector<double> cameraHeights;
    for (const auto& [frame, centre] : result.cameraCentres) cameraHeights.push_back(centre.z);
    PlausibilityReport report = checkPlausibility(result.scene, source, std::move(cameraHeights));
    if (auto views = viewAgreementFinding(frames.viewAgreement))
        report.findings.insert(report.findings.begin(), std::move(*views));
    auto aligned = alignmentFindings(alignment, source);
    report.findings.insert(report.findings.begin(), aligned.begin(), aligned.end());
    // The points' finding comes last: another refusal keeps its own reason, the points named beneath it only where
    // far too few (kThinCover); ten of TUM's desk frames, 25-38 %, are refused for the desk top that fills them.
    // Beneath a refusal whose fix gives --scale (the floor's), the points' fix does not give it again.
    const bool measured = !depth && dense && pointsCover;
    const auto leading =
        std::find_if(report.findings.begin(), report.findings.end(), [](const auto& f) { return f.refuse; });
    const bool beneath = measured && *pointsCover < kThinCover && leading != report.findings.end();
    const auto thin =
        measured ? thinPointsFinding({.photos = frames.cameras.size(),
                                      .sparse = capture.points.size(),
                                      .dense = dense->points.size(),
                                      .cover = *pointsCover,
                                      .scaled = source.scaled(),
                                      .scaleOffered = beneath && leading->fix.find("--scale") != std::string::npos})
                 : std::nullopt;
    if (thin) report.findings.push_back(*thin);
    const PlausibilityFinding* refusal = nullptr;
    for (const auto& f : report.findings) {
        runner.note(fmt::format("{} {}: {}; {}", f.refuse ? "implausible" : "warning:", f.check, f.what, f.fix));
        if (f.refuse && !refusal) refusal = &f;
    }
    if (!refusal || options.force) return;
    // beneath: the points cover under kThinCover < kCoverToStore, so their finding is made.
    throw Error(
        ErrorKind::Input,
        fmt::format("the memory would be wrong: {}{}", refusal->what, beneath ? "; beneath it, " + thin->what : ""),
        std::nullopt,
        fmt::format("{}{}; --force stores the memory anyway", beneath ? thin->fix + "; or " : "", refusal->fix));
}

}  // namespace

IngestResult ingestCapture(const Capture& input, const IngestOptions& options, ProgressSink& progress,
                           const std::function<bool()>& cancelled) {
    IngestResult result;
    StageRunner runner(progress, result, cancelled);
    for (const auto& n : input.notes) runner.note(n);

    std::optional<Reconstruction> reconstruction;
    if (usesColmap(input, options.geometry)) reconstruction = runner.run(ColmapStage{input, options.colmap});
    if (needsDensePoints(reconstruction ? reconstruction->capture : input, options))
        reconstruction = runner.run(DenseStage{reconstruction ? reconstruction->capture : input, options.denseOptions});
    const Capture& capture = reconstruction ? reconstruction->capture : input;
    requirePosesAndStructure(capture);
    auto finder = makeObjectFinder(capture, options);

    FramePass frames = runner.run(FramesStage{capture, options, *finder});
    // A memory without one placed camera holds nothing the capture saw: never stored, --force or not.
    if (frames.cameras.empty())
        throw Error(ErrorKind::Input,
                    fmt::format("{}: no frame was placed, so there is nothing to store", capture.path), std::nullopt,
                    "the frames need camera poses (pose.txt, groundtruth.txt, transforms.json) or enough overlap "
                    "for COLMAP to place them");
    AlignedCapture aligned = runner.run(AlignStage{capture, options, frames});
    // Photos without depth whose things the objects stage lifts on the dense points: the alignment measured
    // the floor and the scale on the things the sparse points placed (hulls carved around few points, or their
    // boxes' rays), which the lift then places again, as the memory stores them. So the alignment is measured
    // once more on the things as stored, their heights leading the scale (AlignOptions::thingsOnDepth), and the
    // room is placed again on it. TUM's office photos: their hulls' heights said 1.15x the true scale, the
    // things lifted 0.97-1.01x; ScanNet's lounge, 100 frames: its floor, half the points, was unconfirmed for
    // its chairs' hulls reached below it, and the cameras' assumed height alone said 1.19x; the chairs lifted
    // stand on the floor and say 1.05x.
    const bool mayMeasureAgain =
        !framesHaveDepth(capture) && !options.scale && !capture.metric && !capture.densePoints.empty();

    model::SceneData& scene = result.scene;
    std::vector<WallSegment> walls;
    std::vector<TrackedNode> tracked;
    auto placeRoom = [&](std::vector<ObjectTrack> tracks) {
        result.cameraCentres.clear();
        for (std::size_t c = 0; c < frames.cameras.size(); ++c)
            result.cameraCentres.push_back({frames.cameras[c].frame, aligned.cameraCentres[c]});
        scene = model::SceneData{};
        scene.info = sceneInfo(capture, options, frames, aligned);
        scene.blobs.push_back(pointsBlob(aligned, options));
        walls = runner.run(AnchorsStage{aligned, scene});
        tracked = runner.run(ObjectsStage{capture, options, std::move(tracks), aligned, walls, *finder, scene});
    };
    placeRoom(std::move(frames.tracks));
    if (mayMeasureAgain) {
        const auto things = thingsAsStored(scene, tracked, aligned.alignment);
        if (const auto named =
                std::count_if(things.begin(), things.end(), [](const NamedThing& t) { return t.measures; });
            named > 0) {
            runner.note(fmt::format("align: measured again on the {} named things lifted on the dense points", named));
            aligned = runner.run(AlignStage{capture, options, frames, &things});
            // No frame tracks: the finder lifts the things again, whatever the keyframes of the new placement
            // cover (AlignedCapture::onLiftedThings), and the lift replaces them.
            placeRoom({});
        }
    }
    runner.run(OpeningsStage{aligned, result.cameraCentres, walls, framesHaveDepth(capture), scene});
    runner.run(RelationsStage{capture, options, frames, aligned, tracked, scene});
    checkRoom(result, capture, options, frames, aligned.alignment, reconstruction ? &reconstruction->dense : nullptr,
              finder->pointsCover(), runner);
    return result;
}

}  // namespace smql::ingest
