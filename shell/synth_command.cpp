// `smql synth --out DIR [--seed N] [--frames K] [--objects N] [--force]`:
// a synthetic RGB-D capture of a generated room (docs/ingest.md, "Synthetic captures").
#include <iostream>

#include <fmt/format.h>

#include "model/geometry.hpp"
#include "ingest/synth/synth.hpp"
#include "shell/ingest_command.hpp"

namespace smql::shell {

int synthCommand(const std::string& outDir, std::uint64_t seed, int frames, int objects, bool force) {
    synth::SynthResult result =
        synth::writeSynth(outDir, {.seed = seed, .frames = frames, .objects = objects, .force = force});
    const model::SceneData& truth = result.scene.truth;
    int objectCount = 0, seen = 0;
    model::Vec3 size;
    for (const model::Node& n : truth.nodes) {
        if (n.kind == model::NodeKind::Object) {
            ++objectCount;
            if (result.framesSeen[n.id] > 0) ++seen;
        }
        if (n.kind == model::NodeKind::Anchor && n.category == "floor") size = n.box.size;
    }
    std::cout << fmt::format(
        "wrote {} frames of '{}' to {}: a {:.1f} x {:.1f} m room, {} objects ({} seen in at least one frame), "
        "{} anchors, {} relation labels\n",
        result.scene.poses.size(), truth.info.name, outDir, size.x, size.y, objectCount, seen,
        truth.nodes.size() - objectCount, result.scene.relations.size());
    std::cout << fmt::format("frames rendered and written in {:.2f} s, {:.2f} s in all\n", result.frameSeconds,
                             result.totalSeconds);
    return 0;
}

}  // namespace smql::shell
