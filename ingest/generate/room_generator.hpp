// Procedural indoor scenes as SceneData: walls, a door, windows, furniture
// against the walls and in the room, small coloured objects resting on the
// furniture. Deterministic per seed. It feeds `smql demo` and the benchmarks;
// it needs no external data.
#pragma once

#include <cstdint>
#include <string>

#include "engine/model/types.hpp"

namespace smql::generate {

struct RoomOptions {
    std::uint64_t seed = 1;
    // Objects (furniture and small things) to place; the floor area grows with
    // the count so that a large scene stays as dense as a furnished room.
    int objectCount = 30;
    std::string name = "room";
};

model::SceneData generateRoom(const RoomOptions& options);

}  // namespace smql::generate
