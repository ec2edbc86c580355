// The scene importers on arbitrary file contents: Replica's info_semantic.json,
// SpatialLM layout text, and the smql JSON scene format. One source, three
// targets (SMQL_FUZZ_IMPORTER picks the reader at compile time).
//
// A scene the smql JSON reader accepts must also survive the round trip the
// format promises: what writeSceneJson writes, readSceneJson reads back.
#include <cstdio>

#include "fuzz/fuzz_support.hpp"
#include "ingest/import/importers.hpp"
#include "model/error.hpp"

using namespace smql;

namespace {

const fuzz::Scratch& scratch() {
    static const fuzz::Scratch instance;
    return instance;
}

model::SceneData read(const std::string& path) {
#if SMQL_FUZZ_IMPORTER == 1
    return import::readReplica(path, "fuzz");
#elif SMQL_FUZZ_IMPORTER == 2
    return import::readSpatialLm(path, "fuzz");
#else
    return import::readSceneJson(path);
#endif
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    model::SceneData scene;
    try {
        scene = read(scratch().write("input", fuzz::bytesOf(data, size)));
    } catch (const Error&) {
        return 0;  // rejected with a user error: the expected outcome for most inputs
    }
    // Every accepted scene, whatever its source format, must export and import back.
    const std::string again = scratch().write("again.json", import::writeSceneJson(scene));
    try {
        import::readSceneJson(again);
    } catch (const Error& e) {
        std::fprintf(stderr, "an accepted scene does not round-trip through smql JSON: %s\n", e.message().c_str());
        __builtin_trap();
    }
    return 0;
}
