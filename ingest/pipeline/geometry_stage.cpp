#include "ingest/pipeline/geometry_stage.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "ingest/geometry/colmap_runner.hpp"
#include "model/error.hpp"

namespace smql::ingest {

bool usesColmap(const Capture& capture, GeometrySource geometry) {
    bool hasPoses = framesHavePoses(capture);
    if (geometry == GeometrySource::Given && !hasPoses)
        throw Error(ErrorKind::Input, fmt::format("{}: some frames have no camera pose", capture.path), std::nullopt,
                    "ingest needs camera poses: pose.txt (rgbd), groundtruth.txt (TUM), transforms.json or a COLMAP "
                    "model; or let COLMAP find them (--geometry colmap)");
    // Poses without depth or points (transforms.json of photos) need COLMAP's points, triangulated with them.
    return geometry == GeometrySource::Colmap ||
           (geometry == GeometrySource::Auto && (!hasPoses || !hasStructure(capture)));
}

Reconstruction ColmapStage::run(StageProgress& progress) {
    Reconstruction out;
    out.capture = input;
    bool hadDepth = false;
    for (auto& f : out.capture.frames) {
        hadDepth = hadDepth || !f.depthPath.empty();
        f.depthPath.clear();
    }
    if (hadDepth)
        progress.note(framesHavePoses(out.capture)
                          ? "--geometry colmap: depth images are ignored; COLMAP triangulates with the given poses"
                          : "--geometry colmap: depth images are ignored (COLMAP's poses are up to scale)");
    ColmapRun run = runColmap(out.capture, options,
                              {.notes = [&](const std::string& note) { progress.note(note); },
                               .stop = [&] { progress.stopIfCancelled(); },
                               .progress = [&](std::size_t frames) { progress.advanced(frames); }});
    progress.advanced(steps());
    out.registered = run.registered;
    out.points = run.points;
    return out;
}

std::string ColmapStage::summary(const Reconstruction& reconstruction) const {
    return fmt::format("{} of {} frames registered, {} points", reconstruction.registered,
                       reconstruction.capture.frames.size(), reconstruction.points);
}

bool needsDensePoints(const Capture& capture, const IngestOptions& options) {
    return options.dense != DenseUse::Off && !framesHaveDepth(capture) && !capture.points.empty() &&
           std::count_if(capture.frames.begin(), capture.frames.end(),
                         [](const auto& f) { return f.pose.has_value(); }) >= 2;
}

namespace {

// Which of the pairs' points were kept, and why: where pairs agree, or one pair's judged by the sparse points.
std::string keptNote(const DensePoints& dense, const DenseOptions& options) {
    if (dense.pairDropped)
        return fmt::format(
            "none kept: with no second pair to agree with, {} of the {} sparse points its first frame sees where "
            "it put a point lie within a tenth of its depth, where it needs {:.0f}% of at least {}",
            dense.sparseAgree, dense.sparseJudged, 100 * options.minSparseAgreement, options.minSparseJudged);
    if (dense.agreeing == 1 && dense.sparseJudged > 0)
        return fmt::format(
            "{} of them kept with no second pair to agree with, as {} of the {} sparse points its first frame "
            "sees where it put a point lie within a tenth of its depth",
            dense.points.size(), dense.sparseAgree, dense.sparseJudged);
    return fmt::format("{} of them where {} or more pairs agree", dense.points.size(), dense.agreeing);
}

}  // namespace

Reconstruction DenseStage::run(StageProgress& progress) {
    Reconstruction out;
    out.capture = input;
    out.registered = static_cast<std::size_t>(
        std::count_if(input.frames.begin(), input.frames.end(), [](const auto& f) { return f.pose.has_value(); }));
    out.dense = densePoints(input, options, [&](std::size_t done) {
        progress.stopIfCancelled();
        progress.advanced(done);
    });
    out.capture.densePoints = out.dense.points;
    out.capture.denseSpacing = out.dense.voxel;
    out.points = input.points.size();
    progress.note(
        fmt::format("dense: {} pair{} of frames matched, {} points, {} (a {:.3g}-unit voxel); {} sparse "
                    "points beside them",
                    out.dense.pairs, out.dense.pairs == 1 ? "" : "s", out.dense.matched, keptNote(out.dense, options),
                    out.dense.voxel, input.points.size()));
    return out;
}

std::string DenseStage::summary(const Reconstruction& reconstruction) const {
    return fmt::format("{} pair{}, {} dense points", reconstruction.dense.pairs,
                       reconstruction.dense.pairs == 1 ? "" : "s", reconstruction.dense.points.size());
}

void requirePosesAndStructure(const Capture& capture) {
    if (std::none_of(capture.frames.begin(), capture.frames.end(), [](const auto& f) { return f.pose.has_value(); }))
        throw Error(
            ErrorKind::Input, fmt::format("{}: no frame has a camera pose", capture.path), std::nullopt,
            "ingest needs camera poses: pose.txt (rgbd), groundtruth.txt (TUM), transforms.json or a COLMAP model");
    if (!hasStructure(capture))
        throw Error(ErrorKind::Input,
                    fmt::format("{}: the frames have no depth and the capture no 3D points", capture.path),
                    std::nullopt, "give depth images, or a COLMAP model with points3D (or --geometry colmap)");
}

bool framesHaveDepth(const Capture& capture) {
    return std::all_of(capture.frames.begin(), capture.frames.end(),
                       [](const auto& f) { return !f.depthPath.empty(); });
}

bool hasStructure(const Capture& capture) { return framesHaveDepth(capture) || !capture.points.empty(); }

bool framesHavePoses(const Capture& capture) {
    return std::all_of(capture.frames.begin(), capture.frames.end(), [](const auto& f) { return f.pose.has_value(); });
}

}  // namespace smql::ingest
