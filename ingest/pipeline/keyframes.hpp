// Keyframes: the frames the detectors look at. A camera that barely moved shows the things it showed
// a moment ago; the models (about 0.1 s a frame together, docs/ingest.md "Detector") run again only
// once the camera has moved or turned enough for a new view, and the other frames give geometry alone.
#pragma once

#include <optional>

#include "ingest/capture/capture.hpp"

namespace smql::ingest {

struct KeyframeRule {
    double move = 0.25;  // m the camera's centre moved since the last keyframe ...
    double turn = 15;    // ... or degrees its view direction turned
};

class Keyframes {
public:
    explicit Keyframes(KeyframeRule rule = {}) : rule_(rule) {}
    // Whether the frame with this camera-to-world pose is a keyframe; the first always is.
    bool take(const Pose& pose);

private:
    KeyframeRule rule_;
    std::optional<Pose> last_;
};

}  // namespace smql::ingest
