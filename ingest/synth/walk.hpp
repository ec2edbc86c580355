// The egocentric walk of `smql synth`: a person holding a phone starts just
// inside the door and walks a loop about 1 m inside the walls, looking into
// the room a little ahead of where they walk, pitched down, with a small
// height bob, yaw sway and roll. Deterministic per seed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ingest/capture/capture.hpp"
#include "model/types.hpp"

namespace smql::synth {

struct WalkOptions {
    int frames = 60;
    std::uint64_t seed = 1;
    double eyeHeight = 1.55;  // metres above the floor
    double wallInset = 1.0;   // the loop's distance from the walls (less in small rooms)
    double clearance = 0.4;   // the camera keeps this far from every object box
};

// One pose per frame (camera-to-world, OpenCV camera axes), evenly spaced
// along the loop. The room is the floor's box (else the boxes' extent); the
// start is the loop point nearest the door (else the middle of the first side).
std::vector<ingest::Pose> planWalk(const model::SceneData& scene, const WalkOptions& options);

// Pose <-> `tx ty tz qx qy qz qw` (the TUM / rgbd-dining line). poseLine
// writes 9 decimals; parsePoseLine normalises the quaternion.
std::string poseLine(const ingest::Pose& pose);
ingest::Pose parsePoseLine(const std::string& line);

}  // namespace smql::synth
