// Objects from instance masks (--objects masks): each mask value is one
// instance across all frames, named by labels.json. Frames without depth
// (COLMAP) lift the capture's sparse points onto the masks and carve each
// instance's visual hull (docs/ingest.md, "Geometry from COLMAP").
#include <algorithm>
#include <fstream>
#include <map>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "ingest/pipeline/geometry_stage.hpp"
#include "ingest/pipeline/object_finder.hpp"
#include "model/error.hpp"

namespace smql::ingest {

namespace {

struct InstanceLabel {
    std::string category;
    model::NodeKind kind = model::NodeKind::Object;
    std::string material;
};

// labels.json beside instance masks: {"instances": [{"id", "category", "kind", ...}]}.
// Colour in a labels file is ground truth for checking, never read here: ingest names colours from pixels.
std::map<std::uint16_t, InstanceLabel> readLabels(const std::string& path) {
    std::ifstream in(path);
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        throw Error(ErrorKind::Input, fmt::format("{}: not valid JSON ({})", path, e.what()));
    }
    std::map<std::uint16_t, InstanceLabel> out;
    if (!j.contains("instances") || !j["instances"].is_array())
        throw Error(ErrorKind::Input, fmt::format("{}: instances: expected an array", path), std::nullopt,
                    "labels.json holds {\"instances\": [{\"id\": 1, \"category\": \"mug\", \"kind\": \"object\"}]}");
    for (std::size_t i = 0; i < j["instances"].size(); ++i) {
        const auto& e = j["instances"][i];
        if (!e.is_object() || !e.contains("id") || !e["id"].is_number_unsigned() || !e.contains("category") ||
            !e["category"].is_string())
            throw Error(ErrorKind::Input,
                        fmt::format("{}: instances[{}]: needs an id (1..65535) and a category", path, i));
        auto id = e["id"].get<std::uint64_t>();
        if (id == 0 || id > 65535)
            throw Error(ErrorKind::Input,
                        fmt::format("{}: instances[{}].id: {} is not a 16-bit mask value", path, i, id));
        InstanceLabel label;
        label.category = e["category"].get<std::string>();
        if (e.contains("kind") && e["kind"] == "anchor") label.kind = model::NodeKind::Anchor;
        if (e.contains("material") && e["material"].is_string()) label.material = e["material"].get<std::string>();
        out.emplace(static_cast<std::uint16_t>(id), std::move(label));
    }
    return out;
}

class MaskFinder : public ObjectFinder {
public:
    MaskFinder(const Capture& capture, const IngestOptions& options)
        : capture_(capture),
          options_(options),
          labels_(readLabels(capture.labelsPath)),
          hasDepth_(framesHaveDepth(capture)) {}

    void observe(const PosedFrame& frame) override {
        auto seen = observeInstances(frame.images, frame.pose, frame.position, options_.objectStride,
                                     options_.minInstancePixels);
        if (!hasDepth_) {
            liftSparsePoints(seen, frame.images, frame.pose, capture_.points, inView_, options_.sparseDepthBand);
            maskViews_.push_back(maskView(frame.position, frame.images.instances, frame.images.intrinsics, frame.pose));
        }
        for (auto& o : seen) {
            auto& track = tracks_[o.instance];
            keepLargestEvidence(track.evidence, o, frame.images.color, options_.evidenceSize);
            track.views.push_back(std::move(o));
        }
    }

    std::vector<ObjectTrack> takeTracks() override {
        if (!hasDepth_) {
            std::vector<ObjectTrack*> all;
            for (auto& [instance, track] : tracks_) all.push_back(&track);
            keepConsistentSparsePoints(all, capture_.points, inView_);
            carveVisualHulls(all, maskViews_);
        }
        std::vector<ObjectTrack> out;
        for (auto& [instance, track] : tracks_) {
            auto label = labels_.find(instance);
            if (label == labels_.end()) continue;  // an unlabelled mask value
            track.category = label->second.category;
            track.kind = label->second.kind;
            track.material = label->second.material;
            out.push_back(std::move(track));
        }
        return out;
    }

    void addStructureObjects(const AlignedCapture&, const std::vector<WallSegment>&, model::SceneData&,
                             StageProgress&) override {}

private:
    const Capture& capture_;
    const IngestOptions& options_;
    std::map<std::uint16_t, InstanceLabel> labels_;
    bool hasDepth_;
    std::map<std::uint16_t, ObjectTrack> tracks_;  // by mask value
    std::vector<std::uint32_t> inView_;            // sparse points: frames each one projects into
    std::vector<MaskView> maskViews_;              // frames without depth: masks for carving
};

}  // namespace

bool masksUsable(const Capture& capture, const IngestOptions&) {
    return !capture.labelsPath.empty() && std::all_of(capture.frames.begin(), capture.frames.end(),
                                                      [](const auto& f) { return !f.instancePath.empty(); });
}

std::unique_ptr<ObjectFinder> makeMaskFinder(const Capture& capture, const IngestOptions& options) {
    if (!masksUsable(capture, options))
        throw Error(ErrorKind::Input,
                    fmt::format("{}: --objects masks needs instance/ masks and labels.json", capture.path),
                    std::nullopt, "use --objects cluster for captures without masks");
    return std::make_unique<MaskFinder>(capture, options);
}

extern const ObjectSourceSpec kMasksSource{"masks", "the capture's instance masks", masksUsable, makeMaskFinder};

}  // namespace smql::ingest
