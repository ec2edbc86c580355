// What an ingest is asked to do, whoever asks: `smql ingest`'s flags, the C API's smql_ingest
// options and the Python package's keyword arguments are all rows of one option table
// (kIngestOptions in request.cpp), read and checked in one place.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ingest/pipeline/pipeline.hpp"

namespace smql::ingest {

struct IngestRequest {
    std::string capture;                 // the capture folder or file
    std::string scene;                   // the new scene's name (default: the capture's folder name)
    std::string geometry = "auto";       // given | colmap | auto
    std::string objects = "auto";        // a source of SMQL_OBJECT_SOURCES, or auto
    std::string detector;                // --objects detect: the ONNX model (default: the installed one)
    std::string classes;                 // ... and its class names (default: coco.names beside the model)
    double fps = 1.0;                    // frames per second kept from videos and TUM sequences (0: every frame)
    std::string videoFrames;             // where a video's decoded frames go (default: a new temporary folder)
    std::optional<double> scale;         // metres per capture unit, overriding the estimate
    std::optional<double> depthScale;    // depth image units per metre, overriding the capture's
    std::optional<double> cameraHeight;  // m: the cameras' median height above the floor, when known
    std::string camera;                  // fx,fy,cx,cy in pixels of the images as stored
    std::optional<double> fov;           // the horizontal field of view, degrees
    int maxSize = 1024;                  // the long side of the frames COLMAP sees (0: as stored)
    std::string vocabularyTree;          // COLMAP's vocabulary tree, for loop detection
    std::string colmapDir;               // COLMAP's kept work folder; a finished run there is read back
    std::string dense = "auto";          // dense points of pairs of placed photos (no depth): auto | room | on | off
    std::string update;                  // a stored scene of the same place to make the next version of
    bool force = false;                  // store a memory the plausibility checks refuse
};

// One option by name: `name` as the C API and Python spell it (`max_size`); the shell's flag is
// `--max-size`. `set` checks the value and throws smql::Error(Usage) saying what it takes.
struct IngestOption {
    std::string_view name;
    std::string valueName;  // for --help: TEXT, FILE, NUMBER ...; "" for a flag (true or false)
    std::string (*help)();
    void (*set)(IngestRequest& request, const std::string& value);
};

const std::vector<IngestOption>& ingestOptions();
// `--max-size` for max_size.
std::string optionFlag(std::string_view name);
// Sets the option `name`; an unknown name is Error(Usage) with the nearest known ones.
void setIngestOption(IngestRequest& request, std::string_view name, const std::string& value);

// The name the new scene gets: --scene, else the capture's folder (a file's folder for a video).
std::string sceneNameOf(const IngestRequest& request);

struct IngestRun {
    IngestResult result;
    std::size_t frames = 0;  // the capture's frames that were read
};

// Reads the capture and runs the pipeline (ingestCapture says what it throws). Nothing is
// written: the caller stores run.result.scene (Engine::importScene, or Engine::updateScene for
// request.update).
IngestRun runIngest(const IngestRequest& request, ProgressSink& progress, const std::function<bool()>& cancelled = {});

}  // namespace smql::ingest
