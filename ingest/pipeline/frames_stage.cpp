#include "ingest/pipeline/frames_stage.hpp"

#include <string>

#include <fmt/format.h>

#include "ingest/capture/frame_loader.hpp"
#include "ingest/geometry/point_cloud.hpp"
#include "ingest/pipeline/geometry_stage.hpp"
#include "model/error.hpp"
#include "model/presentation.hpp"

namespace smql::ingest {

namespace {

// Structure points gathered before the next down-sampling: bounds memory on long captures.
constexpr std::size_t kPendingStructurePoints = 400000;
// Frames whose depth is kept small for the check of the views against each other, spread over
// the capture.
constexpr std::size_t kSketchedFrames = 60;
// Photos without depth whose straight edges are found, spread over the capture: the vertical ones are
// measured against the floor and level a room whose floor is seen little or not at all (vertical_lines.hpp);
// more photos see no new edges of the room.
constexpr std::size_t kLinedPhotos = 60;

DepthSketch sketchOf(const FrameImages& images, const Pose& pose) {
    const cv::Mat depth = images.depth.isContinuous() ? images.depth : images.depth.clone();
    DepthView view;
    view.width = depth.cols;
    view.height = depth.rows;
    view.metres = depth.ptr<float>(0);
    view.intrinsics = images.intrinsics;
    return sketchDepth(view, pose);
}

// One note for the frames without a pose, however many (COLMAP leaves out tens of a long walk's), naming the
// first of them.
std::string unposedNote(const std::vector<std::string>& frames) {
    return frames.size() == 1 ? fmt::format("frame {} has no camera pose (not registered): skipped", frames.front())
                              : fmt::format("{} frames have no camera pose (not registered): skipped: {}",
                                            frames.size(), model::listFirst(frames, 12));
}

}  // namespace

FramePass FramesStage::run(StageProgress& progress) {
    FramePass pass;
    PointCloud pending;
    std::vector<DepthSketch> sketches;
    std::vector<std::string> unposed;  // the numbers of the frames COLMAP did not register
    const std::size_t sketchEvery = capture.frames.size() / kSketchedFrames + 1;
    const std::size_t lineEvery = capture.frames.size() / kLinedPhotos + 1;
    for (std::size_t i = 0; i < capture.frames.size(); ++i) {
        progress.stopIfCancelled();
        const auto& frame = capture.frames[i];
        if (!frame.pose) {
            unposed.push_back(std::to_string(frame.index));
            progress.advanced(i + 1);
            continue;
        }
        auto position = static_cast<std::uint32_t>(i);
        FrameImages images = loadFrame(capture, frame, options.workingWidth);
        const Pose& pose = *frame.pose;
        pass.cameras.push_back({position, pose});
        append(pending, backProject(images, pose, position, options.structureStride));
        if (!images.depth.empty() && i % sketchEvery == 0) sketches.push_back(sketchOf(images, pose));
        if (images.depth.empty() && i % lineEvery == 0) addLinePlanes(pass.lines, images, pose);
        if (pending.size() > kPendingStructurePoints) {
            append(pass.structure, voxelDownsample(pending, options.structureVoxel));
            pending = PointCloud{};
        }
        finder.observe({position, frame, images, pose});
        progress.advanced(i + 1);
    }
    if (!unposed.empty()) progress.note(unposedNote(unposed));
    append(pass.structure, pending);
    pass.structure = voxelDownsample(pass.structure, options.structureVoxel);
    bool hasDepth = framesHaveDepth(capture);
    // Depth images that hold no reading (all zero, or every pixel out of range) would give an empty
    // scene that looks like a success.
    if (hasDepth && pass.structure.empty())
        throw Error(ErrorKind::Input,
                    fmt::format("{}: no depth reading in any frame: every depth image is empty (0 = no reading) "
                                "or farther than {:g} m",
                                capture.path, kMaxDepthReading),
                    std::nullopt,
                    "check the depth images and the depth scale (depth units per metre: 1000 for millimetres, "
                    "5000 for TUM)");
    if (!hasDepth) {
        // The capture's sparse points (COLMAP) are the structure: already sparse, in the capture's units.
        for (const auto& p : capture.points) pass.structure.push(p.position, p.color, 0);
    }
    // Then the dense points, which only photos without depth have (the dense stage).
    pass.measuredPoints = pass.structure.size();
    for (const auto& p : capture.densePoints) pass.structure.push(p.position, p.color, 0);
    pass.viewAgreement = compareViews(sketches);
    if (pass.viewAgreement.tested())
        progress.note(fmt::format("depth: the views agree at {:.0f}% of {} points seen from two frames ({} pairs)",
                                  100 * pass.viewAgreement.share(),
                                  pass.viewAgreement.agree + pass.viewAgreement.conflict, pass.viewAgreement.pairs));
    pass.tracks = finder.takeTracks();
    if (auto note = finder.frameNote(); !note.empty()) progress.note(note);
    return pass;
}

std::string FramesStage::summary(const FramePass& pass) const {
    return fmt::format("{} frames, {} structure points, {} instances", capture.frames.size(), pass.structure.size(),
                       pass.tracks.size());
}

}  // namespace smql::ingest
