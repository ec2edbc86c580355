// Statements end to end through the public API: parse, bind, plan and run
// against a small database (one SpatialLM room: walls, a door, a window and a
// few objects), then format the answers as a table, CSV and JSON.
//
// SET and USE SCENE change the engine's state for the statements after them;
// an input that may hold either (any "set" or "use" in it, in any case) gets
// a freshly opened engine after it, so that no input runs in a state another
// one left and a crash found reproduces from its input alone. Opening an
// engine per input would be deterministic too, at a tenth of the speed.
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <memory>

#include "engine/engine.hpp"
#include "engine/format.hpp"
#include "fuzz/fuzz_support.hpp"
#include "ingest/import/importers.hpp"
#include "model/error.hpp"

using namespace smql;

namespace {

constexpr const char* kRoom = R"(wall_0=Wall(0,0,0,4,0,0,2.5,0)
wall_1=Wall(4,0,0,4,3,0,2.5,0.1)
wall_2=Wall(4,3,0,0,3,0,2.5,0)
wall_3=Wall(0,3,0,0,0,0,2.5,0)
door_0=Door(wall_0,1,0,1.0,0.9,2.0)
window_0=Window(wall_1,4,1.5,1.4,1.2,1.0)
bbox_0=Bbox(table,2,1.5,0.4,0.5,1.6,0.9,0.8)
bbox_1=Bbox(sofa,1,2.5,0.45,-0.25,2.0,0.9,0.9)
bbox_2=Bbox(mug,2.1,1.4,0.85,0,0.1,0.1,0.1)
bbox_3=Bbox(cushion,0.8,2.5,0.95,0,0.4,0.4,0.15)
bbox_4=Bbox(chair,2.9,1.5,0.45,1.2,0.5,0.5,0.9)
bbox_5=Bbox(lamp,3.6,2.6,0.8,0,0.3,0.3,1.6)
)";

struct Database {
    fuzz::Scratch scratch;
    std::string directory = scratch.path("db").string();

    Database() {
        auto engine = Engine::open(directory);
        engine->importScene(import::readSpatialLm(scratch.write("room.txt", kRoom), "room"));
    }
};

const Database& database() {
    static const Database instance;
    return instance;
}

bool mayChangeState(std::string_view text) {
    auto contains = [&](std::string_view word) {
        return std::search(text.begin(), text.end(), word.begin(), word.end(), [](char a, char b) {
                   return std::tolower(static_cast<unsigned char>(a)) == b;
               }) != text.end();
    };
    return contains("set") || contains("use");
}

std::unique_ptr<Engine> engine;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text = fuzz::bytesOf(data, size);
    if (!engine) {
        engine = Engine::open(database().directory);
        // Closed by a handler registered after storage's own statics exist, so it runs
        // before they are destroyed at exit (the order the C API's users need, too).
        static const bool registered = std::atexit([] { engine.reset(); }) == 0;
        (void)registered;
    }
    try {
        engine->execute(text, [](ResultSet&& result) {
            // The formatters see every answer, as the shell and the C API would.
            formatTable(result);
            formatCsv(result);
            jsonText(resultJson(result));
        });
    } catch (const Error&) {
        // A user error: the expected outcome for most inputs.
    }
    if (mayChangeState(text)) engine.reset();
    return 0;
}
