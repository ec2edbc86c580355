// Objects from 2D detections: an open-vocabulary detector's output
// (--objects detections, detections.json) or the detector run here on the
// frames (--objects detect, detector.hpp). Each frame's detections are lifted
// with its depth, or with the capture's sparse points when it has none, and
// associated into tracks across views; photos with dense points are lifted
// again with the depth those give once the room is aligned (docs/ingest.md,
// "Objects from detections", "Detections without depth" and "Detector").
#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <future>
#include <mutex>
#include <optional>
#include <thread>
#include <unordered_map>
#include <utility>

#include <fmt/format.h>
#include <opencv2/core/utility.hpp>

#include "ingest/capture/detections.hpp"
#include "ingest/capture/frame_loader.hpp"
#include "ingest/geometry/dense_stereo.hpp"
#include "ingest/geometry/pcl_ops.hpp"
#include "ingest/pipeline/detector.hpp"
#include "ingest/pipeline/geometry_stage.hpp"
#include "ingest/pipeline/keyframes.hpp"
#include "ingest/pipeline/object_finder.hpp"
#include "ingest/pipeline/object_fusion.hpp"
#include "ingest/pipeline/objects_from_clusters.hpp"
#include "ingest/pipeline/ray_tracks.hpp"
#include "ingest/pipeline/segmenter.hpp"
#include "model/error.hpp"

namespace smql::ingest {

namespace {

// Whether photos without depth have their things lifted on the dense points' depth: never (no dense points,
// --dense room or off), where the points cover what the detectors saw (--dense auto), or always (--dense on).
enum class DenseLift { Never, WhereCovered, Always };
DenseLift denseLift(const Capture& capture, const IngestOptions& options) {
    if (capture.densePoints.empty()) return DenseLift::Never;
    if (options.dense == DenseUse::All) return DenseLift::Always;
    return options.dense == DenseUse::Auto ? DenseLift::WhereCovered : DenseLift::Never;
}

// Tracks of detections from the frames they are made on: lifted with each frame's depth, or, for
// frames without depth (COLMAP), with the capture's sparse points; the two sources (a detections
// file, the detector) differ only in where a frame's detections come from.
class DetectionLifter : public ObjectFinder {
public:
    DetectionLifter(const Capture& capture, const IngestOptions& options, bool voteLabels)
        : capture_(capture),
          options_(options),
          hasDepth_(framesHaveDepth(capture)),
          lift_(denseLift(capture, options)),
          voteLabels_(voteLabels),
          tracker_(voteLabels) {}

    // A frame's detections are made on a thread of their own while the frames up to the next one looked at are
    // loaded and the earlier ones' views lifted: the models are most of a depth camera's ingest (docs/benchmarks.md
    // "Ingest"). Up to kInFlightPerStream x streams() frames at once, each stream with models of its own (a model
    // is not run from two threads); a frame's thread takes the first stream free, in the order the frames came,
    // so a stream done early (a frame the segmenter skipped) goes on with the next frame instead of waiting for
    // the other stream's turn. The frames are lifted in capture order, so the tracks grow in the order the
    // frames came.
    void observe(const PosedFrame& frame) override {
        if (!looksAt(frame)) return;
        looked_.push_back(frame.position);
        std::optional<Detecting> previous;
        if (detecting_.size() >= kInFlightPerStream * streams()) {
            detecting_.front().detections.wait();  // done with the images it views before they move
            previous.emplace(std::move(detecting_.front()));
            detecting_.pop_front();
        }
        Detecting& next = detecting_.emplace_back(frame);
        try {
            next.detections = std::async(std::launch::async, [this, posed = next.posed(), turn = next_] {
                const FreeStreams::Lease stream = freeStreams_.take(turn, streams());
                return detectionsOf(posed, stream.stream);
            });
        } catch (...) {
            // No thread for it (the system's limit): no frame waits on a turn that never comes, and no
            // future without a thread is waited on.
            detecting_.pop_back();
            throw;
        }
        ++next_;
        if (previous) lift(previous->posed(), previous->detections.get());
    }

    std::vector<ObjectTrack> takeTracks() override {
        for (Detecting& d : detecting_) lift(d.posed(), d.detections.get());
        detecting_.clear();
        detectionsDone();
        auto tracks = tracker_.take();
        if (!hasDepth_) placeOnSparsePoints(tracks);
        return tracks;
    }

    // Photos whose things are not lifted on dense points: how their things were placed, and what places them
    // better. Lifted (--dense on, or auto where the points cover them), they are placed again
    // (fuseOnDenseDepth), which notes what it did.
    std::string frameNote() const override {
        if (hasDepth_ || lift_ == DenseLift::Always || fewPoints_ + uncarved_ == 0) return {};
        return fmt::format(
            "{} detections had too few sparse points on them and {} more were of things whose points did not agree "
            "across views enough to carve a hull; {} of these were placed by their boxes' rays across views "
            "(--dense on lifts the things on the dense points' depth instead)",
            fewPoints_, uncarved_, placedByRays_);
    }

    std::optional<double> pointsCover() const override { return cover_; }

    std::vector<ObjectTrack> fuse(std::vector<ObjectTrack> tracks, const AlignedCapture& aligned,
                                  const std::vector<WallSegment>& walls, StageProgress& progress) override {
        if (!denseFrames_.empty())
            if (auto lifted = fuseOnDenseDepth(aligned, walls, progress)) return std::move(*lifted);
        if (!hasDepth_) return tracks;
        // The frames the detections were made on: what "held in view but not seen" is counted over.
        std::vector<FusionCamera> cameras;
        for (auto position : looked_) {
            const auto& frame = capture_.frames[position];
            cameras.push_back({transformed(*frame.pose, aligned.alignment),
                               frame.intrinsics ? *frame.intrinsics : capture_.intrinsics});
        }
        return fuseViews(std::move(tracks), aligned.alignment, aligned.alignment, walls, cameras, progress);
    }

    // With depth, the large things no model named (a bed, a cabinet, a counter: COCO's, Open Images'
    // and PASCAL's classes lack them) are clusters of the structure left outside every named thing.
    void addStructureObjects(const AlignedCapture& aligned, const std::vector<WallSegment>& walls,
                             model::SceneData& scene, StageProgress& progress) override {
        if (!hasDepth_) return;
        const ClusterCounts counts = addClusterObjects(aligned, walls, scene, kUnnamedThings, capture_);
        const std::size_t added = counts.added;
        if (added > 0)
            progress.note(fmt::format(
                "objects: {} large {} no model named, stored with {} size and colour as 'object'{}{}", added,
                added == 1 ? "thing" : "things", added == 1 ? "its" : "their",
                counts.cabinets > 0
                    ? fmt::format(" ({} right under a sink as 'cabinet', the cabinet it is set in)", counts.cabinets)
                    : "",
                counts.wallCabinets > 0
                    ? fmt::format(" ({} hung on a wall, {:g} m or more above the floor, as 'cabinet', a wall cabinet)",
                                  counts.wallCabinets, kWallCabinetBottom)
                    : ""));
    }

protected:
    struct FrameDetections {
        std::vector<Detection> detections;
        int storedWidth = 0;  // the width of the image the boxes are in
        bool kept = false;    // the models' answers for the frame when the room was placed before (pipeline.cpp)
    };
    // A frame's detections, made with stream `stream`'s models (below streams()); streams never share models.
    virtual FrameDetections detectionsOf(const PosedFrame& frame, std::size_t stream) = 0;
    // How many frames' detections are made at once (each stream on a thread of its own); one by default.
    virtual std::size_t streams() const { return 1; }
    // Every frame looked at has been lifted (takeTracks): the streams' threads are done.
    virtual void detectionsDone() {}
    // The detections of a keyframe lifted on the dense points' depth (fuseOnDenseDepth), once the streams are
    // done; the frame's own by default.
    virtual FrameDetections keyframeDetectionsOf(const PosedFrame& frame) { return detectionsOf(frame, 0); }
    // The keyframes about to be lifted on the dense points' depth, by position: a source whose detections take
    // long makes them here, all at once, before the lift asks for each; nothing by default.
    virtual void answerKeyframes(const std::vector<std::uint32_t>& /*positions*/, StageProgress& /*progress*/) {}
    // Whether the frame's detections are looked at (keyframes); every frame by default.
    virtual bool looksAt(const PosedFrame&) { return true; }
    // Waits for the detections still being made: a source whose detectionsOf uses its own members calls it from
    // its destructor, before they go (the thread may still run when a stage stops on an error).
    void finishDetecting() {
        for (Detecting& d : detecting_) d.detections.wait();
    }
    const Capture& capture() const { return capture_; }
    const IngestOptions& options() const { return options_; }
    bool hasDepth() const { return hasDepth_; }

private:
    // What a thing no model named must be to be kept: at least 0.5 x 0.3 x 0.3 m, seen from 3 frames
    // (a cabinet, a counter, a bed's base; smaller clusters are clutter and the parts detections left),
    // at most 3 m long (longer, a stretch of wall the walls stage did not take).
    static constexpr ClusterObjects kUnnamedThings{
        .minLonger = 0.5, .minShorter = 0.3, .minHeight = 0.3, .maxLonger = 3.0, .minFrames = 3, .outsideKnown = true};
    // A detection's view needs this many sparse points to be placed and associated by them; with
    // fewer, its box's ray places it (placeByRays).
    static constexpr std::size_t kMinSparsePoints = 3;
    // A box holds all of what it frames, so a voxel of the thing projects into every box of it: the
    // hull keeps only voxels inside all of them (F1 0.59 at 0.8, the masks' share, against 0.76 at 1
    // on synth seed 3, docs/ingest.md).
    static constexpr double kBoxHullShare = 1.0;
    // m: dense points this close above the floor, or below it, are the floor's (fuseOnDenseDepth).
    static constexpr double kFloorBand = 0.06;
    // A dense point with fewer than this many others within this many voxels is a speck (a surface's
    // voxel has about 12 within 2).
    static constexpr double kSpeckReach = 2;
    static constexpr int kSpeckNeighbours = 4;

    // A frame's detections lifted into tracks.
    void lift(const PosedFrame& frame, const FrameDetections& found) {
        const std::vector<Detection>& detections = found.detections;
        if (hasDepth_) {
            track(tracker_,
                  observeDetections(frame.images, frame.pose, frame.position, detections, found.storedWidth,
                                    options_.objectStride, options_.minInstancePixels),
                  detections, frame.images.color);
            return;
        }
        auto seen = observeSparse(frame, detections, found.storedWidth);
        mostConfidentFirst(seen, detections);
        std::vector<Observation> placed;
        for (auto& o : seen) {
            if (o.sparse.size() >= kMinSparsePoints) {
                placed.push_back(std::move(o));
                continue;
            }
            const Detection& detection = detections[o.instance - 1];
            o.embedding = detection.embedding;
            EvidenceCrop crop{o.pixels, o.frame, encodeCrop(frame.images.color, o.bounds, options_.evidenceSize)};
            unplaced_.push_back({std::move(o), detection.category, std::move(crop)});
        }
        track(tracker_, std::move(placed), detections, frame.images.color);
        if (lift_ != DenseLift::Never) denseFrames_.push_back(frame.position);
    }

    // The most confident detections found tracks first.
    static void mostConfidentFirst(std::vector<Observation>& seen, const std::vector<Detection>& detections) {
        std::stable_sort(seen.begin(), seen.end(), [&](const Observation& a, const Observation& b) {
            return detections[a.instance - 1].score > detections[b.instance - 1].score;
        });
    }

    // The frame's views into `tracker`, each with its detection's embedding; the largest view of each
    // track keeps its evidence crop.
    void track(DetectionTracker& tracker, std::vector<Observation> seen, const std::vector<Detection>& detections,
               const cv::Mat& color) const {
        mostConfidentFirst(seen, detections);
        for (auto& o : seen) {
            const Detection& detection = detections[o.instance - 1];
            o.embedding = detection.embedding;
            ObjectTrack& made = tracker.add(std::move(o), detection.category, detection.score);
            keepLargestEvidence(made.evidence, made.views.back(), color, options_.evidenceSize);
        }
    }

    // Photos with dense points, once the room is aligned: each frame's depth is what its camera would
    // see of the dense and sparse points (in metres, the aligned frame), so its detections are lifted,
    // segmented from the floor and walls and fused across views as a depth camera's are, with every
    // check of the fusion (duplicates, pieces, tops, names out of place). The tracks the sparse points
    // placed have done their part: they told the floor from a table top.
    // nullopt when the lift is not always asked for (--dense auto) and the points cover less than
    // kDenseCoverToLift of the detections' boxes: then the things stay as the sparse points placed them. Unless
    // the room they placed is not measured: its floor found but not confirmed, or its scale on fewer than two
    // priors, which refuses the memory, and the points cover kDenseCoverToMeasure. The things lifted are then the
    // room's one chance to be measured again (pipeline.cpp), and judged as any: ScanNet's lounge, its 100 frames'
    // points covering 63-65 % in four COLMAP runs, was stored 1.03-1.05x when they were lifted, refused when not.
    std::optional<std::vector<ObjectTrack>> fuseOnDenseDepth(const AlignedCapture& aligned,
                                                             const std::vector<WallSegment>& walls,
                                                             StageProgress& progress) {
        const Alignment& alignment = aligned.alignment;
        std::vector<model::Vec3> all;
        all.reserve(capture_.densePoints.size() + capture_.points.size());
        const double spacing = capture_.denseSpacing * alignment.scale;
        // The floor is left out of the frames' depth: its points, a few centimetres off its plane where
        // the pairs' matches err, would chain the things standing on it into one.
        const double floorBand = alignment.floorFound ? std::max(kFloorBand, 2 * spacing) : -1e9;
        auto add = [&](const SparsePoint& p) {
            if (const model::Vec3 q = alignment.apply(p.position); q.z > floorBand) all.push_back(q);
        };
        std::for_each(capture_.densePoints.begin(), capture_.densePoints.end(), add);
        std::for_each(capture_.points.begin(), capture_.points.end(), add);
        // So are the specks: a wrong match that two pairs agreed on floats alone, and drawn before the
        // camera it hides a square of what stands behind it.
        std::vector<model::Vec3> points;
        for (auto i : pcl_ops::withNeighbours(all, kSpeckReach * spacing, kSpeckNeighbours)) points.push_back(all[i]);
        DetectionTracker tracker(voteLabels_);
        std::vector<FusionCamera> cameras;
        // In metres now, the frames' moves pick the keyframes, as for a depth camera: each view a
        // frame's own errors of depth, the things are fused from views that differ.
        Keyframes keyframes;
        std::vector<std::uint32_t> chosen;
        for (const auto position : denseFrames_)
            if (keyframes.take(transformed(*capture_.frames[position].pose, alignment))) chosen.push_back(position);
        answerKeyframes(chosen, progress);
        double covered = 0, boxed = 0;  // the detections' box pixels with depth, and all of them
        std::size_t kept = 0;           // keyframes whose models' answers were kept from the room placed before
        for (const auto position : chosen) {
            progress.stopIfCancelled();
            const CaptureFrame& frame = capture_.frames[position];
            const Pose pose = transformed(*frame.pose, alignment);
            FrameImages images = loadFrame(capture_, frame, options_.workingWidth);
            images.depth = depthFromPoints(points, pose, images.intrinsics, spacing);
            const FrameDetections found = keyframeDetectionsOf({position, frame, images, pose});
            kept += found.kept;
            for (const auto& detection : found.detections) {
                const cv::Rect box = detectionBounds(detection, images.intrinsics, found.storedWidth);
                covered += box.area() > 0 ? cv::countNonZero(images.depth(box) > 0) : 0;
                boxed += box.area();
            }
            track(tracker,
                  observeDetections(images, pose, position, found.detections, found.storedWidth, options_.objectStride,
                                    options_.minInstancePixels),
                  found.detections, images.color);
            cameras.push_back({pose, frame.intrinsics ? *frame.intrinsics : capture_.intrinsics});
        }
        const double cover = boxed > 0 ? covered / boxed : 0;
        if (boxed > 0) cover_ = cover;
        // (Both are the scale's estimate's: a floor is unconfirmed, and one prior counted, only where no scale was
        // given and the poses are not metric.)
        const bool unmeasured = alignment.floorFound &&
                                (!alignment.floorUnconfirmed.empty() || alignment.scalePriors == 1) &&
                                cover >= kDenseCoverToMeasure;
        const bool underCover =
            lift_ == DenseLift::WhereCovered && cover < kDenseCoverToLift && !aligned.onLiftedThings;
        if (underCover && !unmeasured) {
            progress.note(fmt::format(
                "objects: the dense points cover {:.0f}% of the detections' boxes, under the {:.0f}% that lifts the "
                "things on them (--dense auto): the things stay placed by the sparse points (--dense on lifts them)",
                100 * cover, 100 * kDenseCoverToLift));
            return std::nullopt;
        }
        progress.note(fmt::format(
            "objects: {} keyframes of {} photos lifted again on the depth the dense points give them, which covers "
            "{:.0f}% of the detections' boxes ({} of {} points drawn: the floor's and the specks' left out){}{}",
            cameras.size(), denseFrames_.size(), 100 * cover, points.size(),
            capture_.densePoints.size() + capture_.points.size(),
            kept > 0 ? fmt::format("; the models' answers on {} of them kept from the room placed before", kept)
                     : std::string(),
            underCover ? fmt::format("; under the {:.0f}% that lifts them, lifted for the room the sparse points' "
                                     "things placed is not measured (its floor unconfirmed, or its scale on one "
                                     "prior)",
                                     100 * kDenseCoverToLift)
                       : std::string()));
        // The views are in the aligned frame already.
        return fuseViews(tracker.take(), Alignment{}, alignment, walls, cameras, progress);
    }

    // The views fused as a depth camera's (fuseTracks); `viewFrame` takes their points into the room's
    // aligned frame, whose floor, ceiling and walls `room` gives.
    std::vector<ObjectTrack> fuseViews(std::vector<ObjectTrack> tracks, const Alignment& viewFrame,
                                       const Alignment& room, const std::vector<WallSegment>& walls,
                                       const std::vector<FusionCamera>& cameras, StageProgress& progress) const {
        FusionOptions fusion;
        fusion.voteLabels = voteLabels_;
        if (!hasDepth_) fusion.wallSlack = kPhotosWallSlack;
        return fuseTracks(std::move(tracks), viewFrame, roomSurfaces(room, &walls), cameras, fusion, progress);
    }

    // Frames without depth: the sparse points that fall on each detection, nearest first (as for
    // masks, liftSparsePoints); they stand in for its points until all views are in. Views with too
    // few of them wait for placeByRays.
    std::vector<Observation> observeSparse(const PosedFrame& frame, const std::vector<Detection>& detections,
                                           int storedWidth) {
        FrameImages images = frame.images;
        images.instances = detectionInstances(images.intrinsics, detections, storedWidth);
        auto seen =
            observeInstances(images, frame.pose, frame.position, options_.objectStride, options_.minInstancePixels);
        liftSparsePoints(seen, images, frame.pose, capture_.points, inView_, options_.sparseDepthBand);
        // A detection's own outline (or its box) is its silhouette for carving, whole: where a smaller
        // one was painted over it, the thing still stands behind.
        for (auto& o : seen) {
            o.bounds = detectionBounds(detections[o.instance - 1], images.intrinsics, storedWidth);
            o.outline = detectionOutline(detections[o.instance - 1], images.intrinsics, storedWidth);
        }
        maskViews_.push_back({frame.position, cv::Mat(), images.intrinsics, frame.pose});
        for (auto& o : seen)
            if (o.sparse.size() >= kMinSparsePoints)
                for (auto p : o.sparse) o.points.push_back(capture_.points[p].position);
        return seen;
    }

    // Once every view is in: each track keeps the sparse points that fall on it across its views,
    // then its visual hull (the intersection of its views' outlines) gives its points. A track whose
    // consistent points were too few to carve a hull gives its views back, and they are placed with
    // the views that had too few points of their own, by their boxes' rays (ray_tracks.hpp).
    void placeOnSparsePoints(std::vector<ObjectTrack>& tracks) {
        std::vector<ObjectTrack*> all;
        for (auto& track : tracks) {
            for (auto& v : track.views) v.points.clear();
            all.push_back(&track);
        }
        keepConsistentSparsePoints(all, capture_.points, inView_);
        carveVisualHulls(all, maskViews_, kBoxHullShare);
        fewPoints_ = unplaced_.size();
        std::vector<ObjectTrack> carved;
        for (auto& track : tracks) {
            if (!track.surface.empty()) {
                carved.push_back(std::move(track));
                continue;
            }
            for (auto& v : track.views) {
                EvidenceCrop crop = track.evidence.frame == v.frame ? track.evidence : EvidenceCrop{};
                unplaced_.push_back({std::move(v), track.category, std::move(crop)});
            }
        }
        uncarved_ = unplaced_.size() - fewPoints_;
        placedByRays_ = placeByRays(std::move(unplaced_), maskViews_, carved, options_.minObjectViews);
        tracks = std::move(carved);
    }

    // Frames in flight for each stream: one running, one waiting to take the first stream that is done.
    static constexpr std::size_t kInFlightPerStream = 2;

    // The streams not running a frame's models, handed out to the frames' threads in the frames' order.
    class FreeStreams {
    public:
        struct Lease {
            FreeStreams* owner;
            std::size_t stream;
            Lease(FreeStreams* o, std::size_t s) : owner(o), stream(s) {}
            Lease(const Lease&) = delete;
            Lease& operator=(const Lease&) = delete;
            ~Lease() { owner->give(stream); }
        };
        // Waits for turn `turn` (0, 1, 2 ... as the frames came) and a free stream of `streams`.
        Lease take(std::size_t turn, std::size_t streams) {
            std::unique_lock lock(mutex_);
            if (busy_.empty()) busy_.assign(streams, false);
            auto freeStream = [&] { return std::find(busy_.begin(), busy_.end(), false); };
            changed_.wait(lock, [&] { return turn == serving_ && freeStream() != busy_.end(); });
            const auto stream = static_cast<std::size_t>(freeStream() - busy_.begin());
            busy_[stream] = true;
            ++serving_;
            changed_.notify_all();  // the next turn may find another stream free
            return {this, stream};
        }

    private:
        void give(std::size_t stream) {
            {
                std::lock_guard lock(mutex_);
                busy_[stream] = false;
            }
            changed_.notify_all();
        }
        std::mutex mutex_;
        std::condition_variable changed_;
        std::vector<bool> busy_;   // by stream
        std::size_t serving_ = 0;  // the turn that takes the next free stream
    };

    // A frame looked at whose detections are being made: its own images, as the frames stage loads the next.
    struct Detecting {
        std::uint32_t position;
        const CaptureFrame* frame;
        FrameImages images;
        Pose pose;
        std::future<FrameDetections> detections;
        explicit Detecting(const PosedFrame& posed)
            : position(posed.position), frame(&posed.frame), images(posed.images), pose(posed.pose) {}
        PosedFrame posed() const { return {position, *frame, images, pose}; }
    };

    const Capture& capture_;
    const IngestOptions& options_;
    bool hasDepth_;
    DenseLift lift_;
    bool voteLabels_;
    DetectionTracker tracker_;
    std::vector<std::uint32_t> looked_;       // the frames whose detections were looked at
    std::vector<std::uint32_t> inView_;       // without depth: frames each sparse point projects into
    std::vector<MaskView> maskViews_;         // without depth: each frame's detections, for carving
    std::vector<UnplacedView> unplaced_;      // without depth: views too few sparse points placed
    std::vector<std::uint32_t> denseFrames_;  // with dense points: the frames looked at, for fuseOnDenseDepth
    std::optional<double> cover_;             // ... and the share of the detections' boxes they cover (pointsCover)
    std::size_t fewPoints_ = 0;               // without depth: views with too few sparse points on them,
    std::size_t uncarved_ = 0;                // ... views of tracks whose points carved no hull,
    std::size_t placedByRays_ = 0;            // ... and how many of both their boxes' rays placed
    FreeStreams freeStreams_;
    std::deque<Detecting> detecting_;  // in flight, oldest first (a deque: its elements never move)
    std::size_t next_ = 0;             // frames sent to the streams
};

class DetectionFinder : public DetectionLifter {
public:
    DetectionFinder(const Capture& capture, const IngestOptions& options)
        : DetectionLifter(capture, options, /*voteLabels=*/false), detections_(readDetections(capture)) {}
    ~DetectionFinder() override { finishDetecting(); }

private:
    FrameDetections detectionsOf(const PosedFrame& frame, std::size_t) override {
        const Intrinsics& stored = frame.frame.intrinsics ? *frame.frame.intrinsics : capture().intrinsics;
        return {detections_[frame.position], stored.width};
    }

    std::vector<std::vector<Detection>> detections_;  // per capture frame
};

// OpenCV's thread count is the process's: while any ingest's model streams run (ingests may run side by side in
// one process, through the C API), the count they asked for; the count from before once the last is done.
class OpenCvThreads {
public:
    explicit OpenCvThreads(int threads) {
        std::lock_guard lock(mutex_);
        if (users_++ == 0) {
            before_ = cv::getNumThreads();
            cv::setNumThreads(threads);
        }
    }
    ~OpenCvThreads() {
        std::lock_guard lock(mutex_);
        if (--users_ == 0) cv::setNumThreads(before_);
    }
    OpenCvThreads(const OpenCvThreads&) = delete;
    OpenCvThreads& operator=(const OpenCvThreads&) = delete;

private:
    static inline std::mutex mutex_;
    static inline int users_ = 0;
    static inline int before_ = 0;
};

// The detector sees each frame at the working resolution; its labels are voted across views.
class DetectorFinder : public DetectionLifter {
public:
    DetectorFinder(const Capture& capture, const DetectorFiles& files, const IngestOptions& options)
        : DetectionLifter(capture, options, /*voteLabels=*/true),
          files_(files),
          packaged_(packagedOnFrames(capture, options)),
          packagedOnDense_(options.detectorModel.empty()),
          streams_(std::thread::hardware_concurrency() >= 2 && capture.frames.size() >= 2 ? kStreams : 1),
          coresPerStream_(std::max(1, static_cast<int>(std::thread::hardware_concurrency() / streams_))),
          models_(streams_) {
        // Every stream's models loaded at once, each on a thread of its own: the first keyframe waits for the
        // first stream's anyway, and the second's, loaded when it first ran, took a core from the first's
        // models mid-pass (TUM fr1/rpy 3.35-3.39 -> 2.95-3.19 s, docs/benchmarks.md).
        std::vector<std::future<Models>> loading;
        for (std::size_t s = 1; s < streams_; ++s)
            loading.push_back(std::async(std::launch::async, [this] { return loadModels(); }));
        models_[0] = loadModels();
        for (std::size_t s = 1; s < streams_; ++s) models_[s] = loading[s - 1].get();
        // A stream's models run on its thread and the stream's share of the other cores, a model a stream on
        // each core: through OpenCV's DNN that gave 1.7 times one model's speed where OpenCV's own threads gave
        // 1.5 (NanoDet, the SSD and DeepLab on a TUM frame: 116 -> 99 ms a frame). OpenCV's threads (its image
        // operations, and a graph it runs) are set to that share meanwhile; one core keeps one stream, with
        // OpenCV's threads as they are.
        if (streams_ > 1) threadsPerStream_.emplace(coresPerStream_);
    }
    ~DetectorFinder() override {
        finishDetecting();
        detectionsDone();
    }

    std::string frameNote() const override {
        std::string note = DetectionLifter::frameNote();
        if (milliseconds_.empty() || models_.empty()) return note;
        auto sorted = milliseconds_;
        std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
        const Models& models = models_[0];
        return fmt::format(
            "detector: {}{} on {} keyframes of {}, {} detections, {}median {:.0f} ms a keyframe{}{}",
            models.detector->describe(), models.segmenter ? " + " + models.segmenter->describe() : std::string(),
            milliseconds_.size(), frames_, detections_,
            models.segmenter ? fmt::format("the segmenter on {} (those with a kind it knows), ", segmented_.load())
                             : std::string(),
            sorted[sorted.size() / 2], note.empty() ? "" : "; ", note);
    }

private:
    // Two streams keep two cores busy (each with models of its own, all loaded at the start); more would
    // hold more models in memory for a machine this size. A capture of one frame has one stream, its models
    // on every core: a second set of models would load for no frame (a SUN RGB-D frame, three runs each:
    // 5.5-9.7 -> 7.9-11.0 frames a second, 287 -> 197 MiB at the peak).
    static constexpr std::size_t kStreams = 2;
    struct Models {
        std::unique_ptr<ObjectDetector> detector;
        std::unique_ptr<SemanticSegmenter> segmenter;
    };

    // The packaged models beside NanoDet (the SSD, the segmenter) run when no --detector is given on
    // frames with depth, their own or the dense points' (fuseOnDenseDepth). Without depth, a box is a
    // silhouette that carves a hull (observations.hpp): the SSD's looser boxes carved the dining photos'
    // chairs 1.6 m tall, so the frame pass over photos takes NanoDet's alone, unless their things are
    // always lifted on the dense points (--dense on: the frame pass's things then only tell the floor from
    // a table top, which the ensemble's chairs confirmed in ScanNet's lounge). With --dense auto the frame
    // pass is --dense room's, so a capture the dense points do not cover is placed as room places it.
    static bool packagedOnFrames(const Capture& capture, const IngestOptions& options) {
        return options.detectorModel.empty() &&
               (framesHaveDepth(capture) || denseLift(capture, options) == DenseLift::Always);
    }
    // A stream's graphs run one after another on its thread, so their tensors share one arena: the
    // segmenter's first, the largest, whose buffers the detectors' tensors then fit in (the three planned
    // apart take 76 MB, together 42).
    static Models loadModels(const DetectorFiles& files, bool packaged, int threads) {
        const GraphPlacement placement{threads, std::make_shared<TensorArena>()};
        Models models;
        if (packaged)
            if (auto segmenterFiles = installedModel("deeplab"))
                models.segmenter = makeDeepLabSegmenter(*segmenterFiles, placement);
        models.detector = makeDetector(files, packaged, placement);
        return models;
    }
    Models loadModels() const { return loadModels(files_, packaged_, coresPerStream_); }

    // With depth, the models run on keyframes (keyframes.hpp); without depth, on every frame: COLMAP's
    // captures are few frames far apart, and their poses are in no known unit.
    bool looksAt(const PosedFrame& frame) override {
        ++frames_;
        return !hasDepth() || keyframes_.take(frame.pose);
    }

    std::size_t streams() const override { return streams_; }

    void detectionsDone() override { threadsPerStream_.reset(); }

    FrameDetections detectionsOf(const PosedFrame& frame, std::size_t stream) override {
        Models& models = models_[stream];
        auto start = std::chrono::steady_clock::now();
        auto detections = masked(answer(models, frame.images.color), models);
        const double milliseconds =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        std::lock_guard lock(countMutex_);
        milliseconds_.push_back(milliseconds);
        detections_ += detections.size();
        return {std::move(detections), frame.images.color.cols};
    }

    // Run again rather than kept from the frames pass: a frame's masks are images, and a long walk's would
    // fill the memory. Made for all the keyframes at once (answerKeyframes), and kept for the room placed again
    // (pipeline.cpp), whose keyframes are mostly the same frames: the models' answers depend on the image alone.
    FrameDetections keyframeDetectionsOf(const PosedFrame& frame) override {
        KeptAnswer& kept = keyframeAnswers_.at(frame.position);
        const bool before = kept.lifted;
        kept.lifted = true;
        return {masked(kept.answer, keyframeModels(0)), frame.images.color.cols, before};
    }
    // The keyframes' answers not kept yet, made on the streams as the frame pass's are: a stream's models on
    // one core each. One stream's models on every core (a thread pool) spin while they wait for each other:
    // on a machine busy with another process, or a process held to one core, TUM fr1/rpy's 27 keyframes took
    // 37-42 s, and take 4 on the streams.
    void answerKeyframes(const std::vector<std::uint32_t>& positions, StageProgress& progress) override {
        std::vector<std::uint32_t> missing;
        for (const auto p : positions)
            if (!keyframeAnswers_.contains(p)) missing.push_back(p);
        if (missing.empty()) return;
        std::vector<ModelAnswer> answers(missing.size());
        std::atomic<std::size_t> next = 0;
        auto answerSome = [&](std::size_t stream) {
            Models& models = keyframeModels(stream);
            try {
                for (std::size_t i = next++; i < missing.size(); i = next++) {
                    if (stream == 0) progress.stopIfCancelled();  // the user's check, on the stage's own thread
                    const FrameImages images =
                        loadFrame(capture(), capture().frames[missing[i]], options().workingWidth);
                    answers[i] = answer(models, images.color);
                }
            } catch (...) {
                next = missing.size();  // the other streams stop at their next frame
                throw;
            }
        };
        keyframeModels(0);  // every stream's models loaded before the streams run
        const OpenCvThreads threads(coresPerStream_);
        std::vector<std::future<void>> others;
        for (std::size_t s = 1; s < streams_; ++s) others.push_back(std::async(std::launch::async, answerSome, s));
        std::exception_ptr failed;
        try {
            answerSome(0);
        } catch (...) {
            failed = std::current_exception();
        }
        for (auto& f : others) try {
                f.get();
            } catch (...) {
                if (!failed) failed = std::current_exception();
            }
        if (failed) std::rethrow_exception(failed);
        for (std::size_t i = 0; i < missing.size(); ++i)
            keyframeAnswers_.emplace(missing[i], KeptAnswer{std::move(answers[i])});
    }
    // The models of the lift on the dense points: the frame pass's, or, where those differ (photos whose frame
    // pass ran NanoDet alone), the packaged models, a set for each stream, loaded the first time.
    Models& keyframeModels(std::size_t stream) {
        if (packaged_ == packagedOnDense_) return models_[stream];
        if (denseModels_.empty()) {
            // The frame pass's models are done with: freed before the lift's load (TUM fr1/rpy's photos: 570 ->
            // 515 MB at the peak), and the frame pass's note, read already, says no more (frameNote).
            models_.clear();
            std::vector<std::future<Models>> loading;
            for (std::size_t s = 1; s < streams_; ++s)
                loading.push_back(std::async(std::launch::async,
                                             [this] { return loadModels(files_, packagedOnDense_, coresPerStream_); }));
            denseModels_.push_back(loadModels(files_, packagedOnDense_, coresPerStream_));
            for (auto& l : loading) denseModels_.push_back(l.get());
        }
        return denseModels_[stream];
    }

    // What the models make of an image: the detector's boxes, and the segmenter's labels when it knows the kind
    // of one of them (else its labels would cut nothing): the keyframes of beds, toilets, laptops or nothing
    // skip it. A frame's labels are one image where the masks cut from them are one a detection.
    struct ModelAnswer {
        std::vector<Detection> detections;
        cv::Mat1b labels;  // empty where the segmenter did not run
    };
    ModelAnswer answer(Models& models, const cv::Mat& color) {
        ModelAnswer answer{models.detector->detect(color), {}};
        if (models.segmenter &&
            std::any_of(answer.detections.begin(), answer.detections.end(),
                        [&](const Detection& d) { return segmentable(d, models.segmenter->categories()); })) {
            ++segmented_;
            answer.labels = models.segmenter->segment(color);
        }
        return answer;
    }
    struct KeptAnswer {
        ModelAnswer answer;
        bool lifted = false;  // lifted once already: the room is placed again
    };
    static std::vector<Detection> masked(const ModelAnswer& answer, const Models& models) {
        std::vector<Detection> detections = answer.detections;
        if (!answer.labels.empty())
            for (auto& d : detections) maskBySegments(d, answer.labels, models.segmenter->categories());
        return detections;
    }

    DetectorFiles files_;
    bool packaged_;         // the packaged models beside NanoDet on the frame pass (depth, or photos always lifted)
    bool packagedOnDense_;  // ... on the photos lifted on the dense points' depth (no --detector given)
    std::vector<Models> denseModels_;  // the models of that lift by stream when the frame pass's differ, loaded
                                       // when it first runs
    std::size_t streams_;              // kStreams, or one on a machine with one core
    int coresPerStream_;               // the threads a stream's models and OpenCV's run on
    std::vector<Models> models_;  // by stream, each touched only by its stream's frames, one at a time; none once the
                                  // lift's own are loaded (keyframeModels)
    std::optional<OpenCvThreads> threadsPerStream_;  // while the streams run
    Keyframes keyframes_;
    std::size_t frames_ = 0;            // every frame shown, keyframe or not
    std::mutex countMutex_;             // the streams' threads count below
    std::vector<double> milliseconds_;  // the detector's time on each frame
    std::size_t detections_ = 0;
    std::atomic<std::size_t> segmented_ = 0;                       // frames the segmenter ran on
    std::unordered_map<std::size_t, KeptAnswer> keyframeAnswers_;  // by the keyframe's position in the capture
};

}  // namespace

bool detectionsUsable(const Capture& capture, const IngestOptions&) {
    return !capture.detectionsPath.empty() && hasStructure(capture);
}

std::unique_ptr<ObjectFinder> makeDetectionFinder(const Capture& capture, const IngestOptions& options) {
    if (!detectionsUsable(capture, options))
        throw Error(
            ErrorKind::Input,
            fmt::format("{}: --objects detections needs detections.json, and depth images or 3D points", capture.path),
            std::nullopt,
            "use --objects detect (the detector) or cluster for captures without detections; frames without "
            "depth get 3D points from COLMAP (--geometry colmap)");
    return std::make_unique<DetectionFinder>(capture, options);
}

bool detectorUsable(const Capture& capture, const IngestOptions& options) {
    return hasStructure(capture) && findDetectorFiles(options.detectorModel, options.detectorClasses);
}

std::unique_ptr<ObjectFinder> makeDetectorFinder(const Capture& capture, const IngestOptions& options) {
    if (!hasStructure(capture))
        throw Error(ErrorKind::Input, fmt::format("{}: --objects detect needs depth images or 3D points", capture.path),
                    std::nullopt, "frames without depth get 3D points from COLMAP (--geometry colmap)");
    auto files = findDetectorFiles(options.detectorModel, options.detectorClasses);
    if (!files)
        throw Error(
            ErrorKind::Input,
            options.detectorModel.empty()
                ? fmt::format("no detector model in {} (nanodet.onnx and coco.names)", defaultModelDir().string())
                : fmt::format("{}: the detector model or its class file ({}) is missing", options.detectorModel,
                              options.detectorClasses.empty() ? "coco.names beside it" : options.detectorClasses),
            std::nullopt, "prepare the model with scripts/detector/setup.sh, or give --detector and --classes");
    return std::make_unique<DetectorFinder>(capture, *files, options);
}

extern const ObjectSourceSpec kDetectionsSource{"detections", "detections.json beside the frames", detectionsUsable,
                                                makeDetectionFinder};
extern const ObjectSourceSpec kDetectSource{"detect", "the COCO detector on the frames", detectorUsable,
                                            makeDetectorFinder};

}  // namespace smql::ingest
