// Procedural indoor scenes as SceneData: walls, a door, windows, furniture
// against the walls and in the room, small coloured objects resting on the
// furniture. Deterministic per seed. It feeds `smql demo` and the benchmarks;
// it needs no external data.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "model/types.hpp"

namespace smql::generate {

struct RoomOptions {
    std::uint64_t seed = 1;
    // Objects (furniture and small things) to place; the floor area grows with
    // the count so that a large scene stays as dense as a furnished room.
    int objectCount = 30;
    std::string name = "room";
};

model::SceneData generateRoom(const RoomOptions& options);

// What the generator put on what: each small thing with the furniture piece it
// was placed on (local ids). `smql synth` turns these into on/in labels.
struct Support {
    model::NodeId object = model::kNoNode;
    model::NodeId supporter = model::kNoNode;
};

struct GeneratedRoom {
    model::SceneData scene;  // exactly what generateRoom returns for the same options
    std::vector<Support> supports;
};

GeneratedRoom generateRoomWithSupports(const RoomOptions& options);

}  // namespace smql::generate
