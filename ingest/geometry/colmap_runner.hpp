// Structure from motion for captures without poses: runs Debian's `colmap`
// command on the CPU (feature_extractor, a matcher, mapper) as a subprocess,
// then copies the largest model's camera poses and sparse points into the
// capture (docs/ingest.md, "--geometry colmap").
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ingest/capture/capture.hpp"

namespace smql::ingest {

struct ColmapOptions {
    std::string command = "colmap";  // looked up on PATH
    int maxImageSize = 1024;         // frames with a longer side are scaled down to it for COLMAP (0: as stored)
    int exhaustiveUpTo = 60;         // unordered photo sets up to this many frames: exhaustive_matcher
    int exhaustiveOrderedUpTo = 40;  // frames in capture order (a short video) up to this many: the same
    int sequentialOverlap = 5;       // COLMAP's overlap: each frame is matched with the overlap - 1 after it
    // Captures up to this many frames: SIFT starts an octave below the image (COLMAP's default, the frame
    // doubled for its finest features); longer ones start at the frame's own size, which halves the
    // extraction and leaves each frame's many neighbours enough features to be placed.
    int fineFeaturesUpTo = 100;
    std::string vocabularyTree;  // COLMAP vocabulary tree (vocab_tree_*.bin) for loop detection; empty: none
    // Without a tree, captures of up to `everyPairUpTo` frames close their loops by matching every pair of
    // frames here (sift_matching.hpp, a few seconds for 100 frames) and verifying the pairs with `loopMatches`
    // matches or more that are among the `loopsPerFrame` with the most of either frame; longer ones by matching
    // `loopFrames` frames spread through the capture all against all.
    int everyPairUpTo = 400;
    int loopMatches = 30;
    int loopsPerFrame = 10;
    int loopFrames = 20;
    int minMatches = 15;             // verified matches that make two frames overlap (COLMAP's mapper default)
    int threads = -1;                // cores for extraction and matching (-1: all); COLMAP's random steps take one
    bool keepWorkDirectory = false;  // keep the work folder (images, database, models, colmap.log) after a success too
    // A work folder of one's own, always kept (empty: a new one under /tmp). When it holds the finished run of
    // the same frames with the same options, COLMAP does not run again: its model is read back.
    std::string workDirectory;
};

struct ColmapRun {
    std::string workDirectory;   // /tmp/smql-colmap-XXXXXX
    std::string logPath;         // every command's output
    std::string matcher;         // exhaustive_matcher or sequential_matcher (then matches_importer closes loops)
    std::size_t cameras = 0;     // COLMAP cameras: one per image size (and per known camera of that size)
    std::size_t registered = 0;  // frames that got a pose
    std::size_t points = 0;      // sparse points
    std::size_t models = 0;      // models the mapper wrote (the largest is used)
    bool reused = false;         // the work folder held this run already: no COLMAP step ran
    // Each COLMAP command run and its wall-clock seconds (a step run once per camera, summed), in order.
    std::vector<std::pair<std::string, double>> steps;
    std::vector<std::string> notes;
};

// Receives each of the run's notes as it is made (they are also in ColmapRun::notes).
using ColmapNotes = std::function<void(const std::string&)>;

// What a run says, and is asked, as it goes (each may be empty):
// - `notes`: each note as it is made;
// - `stop`: asked every 50 ms while a COLMAP command runs, and once it has ended; it throws to stop the run (the
//   user's Ctrl-C: StageProgress::stopIfCancelled), the command stopped first and a work folder of the run's own
//   removed;
// - `progress`: how many of the capture's frames the running command has done, as its log counts them (the
//   files extracted, the images or blocks matched, the images registered), each time the count grows.
struct ColmapWatch {
    ColmapNotes notes{};
    std::function<void()> stop{};
    std::function<void(std::size_t)> progress{};
};

// A COLMAP model read back, and the folder it was read from.
struct ColmapModel {
    std::filesystem::path folder;
    Capture capture;
};

// Runs COLMAP's model_merger on two model folders, writing the result to the third.
using ColmapMerger =
    std::function<void(const std::filesystem::path&, const std::filesystem::path&, const std::filesystem::path&)>;
// The model in a folder, when it holds one that reads.
using ColmapModelReader = std::function<std::optional<Capture>(const std::filesystem::path&)>;

// COLMAP's mapper starts a new model where it can add no frame to the one it grows, and a later model
// may place again frames an earlier one holds: two models that share frames are one place seen twice,
// in two frames of reference. The largest of `models` takes in, one at a time, every other that shares
// at least three frames (by image path) with it: `merge` aligns the two by the frames they share (COLMAP
// fits a similarity to three frames at a time and keeps it when the other's points reproject into the
// shared frames) and writes the joined model to `output`/1, 2 ... (one folder per attempt), kept when
// `read` finds more frames in it than before; a model refused is tried again only once it shares more
// frames. `joins` receives one line per join ("97 and 50 frames sharing 20"). Nothing when `models` is
// empty.
std::optional<ColmapModel> joinColmapModels(std::vector<ColmapModel> models, const std::filesystem::path& output,
                                            const ColmapMerger& merge, const ColmapModelReader& read,
                                            std::vector<std::string>& joins);

// Fills every registered frame's pose and intrinsics (in the frame's own
// pixels: COLMAP sees the frames scaled down to maxImageSize) and the
// capture's points (replacing any it had); frames COLMAP did not register, and
// frames whose image is missing, keep no pose. Sets metric = false. Throws
// smql::Error(Input) when `colmap` is missing (naming how to install it) or a
// step fails or no model comes out (naming the step, what the database shows:
// photos with features, photos that overlap, and what to do); the notes made
// until then have reached `watch.notes`. While a COLMAP command runs, and when it has ended, `watch.stop` may stop
// the run: a terminal's Ctrl-C, which reaches COLMAP too, is then the user's, not COLMAP's failure.
ColmapRun runColmap(Capture& capture, const ColmapOptions& options = {}, ColmapWatch watch = {});

}  // namespace smql::ingest
