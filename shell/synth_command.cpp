// `smql synth --out DIR [--seed N] [--frames K] [--objects N] [--force] [--changes] [--rgb-only]`:
// a synthetic RGB-D capture of a generated room, or its colour frames alone as photos
// (docs/ingest.md, "Synthetic captures").
#include <iostream>

#include <fmt/format.h>

#include "ingest/synth/synth.hpp"
#include "model/geometry.hpp"
#include "shell/ingest_command.hpp"

namespace smql::shell {

int synthCommand(const synth::SynthOptions& options, const std::string& outDir) {
    synth::SynthResult result = synth::writeSynth(outDir, options);
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
    if (options.changes) {
        std::size_t moved = 0, added = 0, removed = 0;
        for (const auto& c : result.scene.changes) {
            moved += c.kind == model::ChangeKind::Moved;
            added += c.kind == model::ChangeKind::Added;
            removed += c.kind == model::ChangeKind::Missing;
        }
        std::cout << fmt::format(
            "changes since the room without --changes: {} moved, {} taken away, {} new "
            "(changes.json)\n",
            moved, removed, added);
    }
    if (options.rgbOnly)
        std::cout << fmt::format(
            "RGB only: the photos, camera.json and a perfect detector's detections.json are in {0}/images (no depth, "
            "masks or poses); ingest that folder and compare with `smql check-ingest DB --truth {0}/truth.json`\n",
            outDir);
    std::cout << fmt::format("frames rendered and written in {:.2f} s, {:.2f} s in all\n", result.frameSeconds,
                             result.totalSeconds);
    return 0;
}

}  // namespace smql::shell
