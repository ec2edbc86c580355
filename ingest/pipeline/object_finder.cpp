#include "ingest/pipeline/object_finder.hpp"

#include <cassert>

namespace smql::ingest {

namespace {

struct ObjectSourceEntry {
    ObjectSource source;
    bool (*usable)(const Capture&, const IngestOptions&);
    std::unique_ptr<ObjectFinder> (*make)(const Capture&, const IngestOptions&);
};

// In the order `auto` tries them: the most specific evidence first.
constexpr ObjectSourceEntry kObjectSources[] = {
    {ObjectSource::Masks, masksUsable, makeMaskFinder},
    {ObjectSource::Detections, detectionsUsable, makeDetectionFinder},
    {ObjectSource::Detect, detectorUsable, makeDetectorFinder},
    {ObjectSource::Cluster, clustersUsable, makeClusterFinder},
};

}  // namespace

std::unique_ptr<ObjectFinder> makeObjectFinder(const Capture& capture, const IngestOptions& options) {
    for (const auto& entry : kObjectSources) {
        bool chosen =
            options.objects == ObjectSource::Auto ? entry.usable(capture, options) : options.objects == entry.source;
        if (chosen) return entry.make(capture, options);
    }
    assert(!"every ObjectSource has an entry, and clusters are always usable");
    return nullptr;
}

}  // namespace smql::ingest
