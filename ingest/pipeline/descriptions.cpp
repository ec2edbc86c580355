#include "ingest/pipeline/descriptions.hpp"

#include <algorithm>
#include <optional>
#include <utility>

#include <fmt/format.h>
#include <opencv2/core/utility.hpp>

#include "ingest/pipeline/colors.hpp"
#include "ingest/pipeline/scene_nodes.hpp"
#include "model/category.hpp"

namespace smql::ingest {

using model::Node;
using model::NodeId;
using model::NodeKind;

namespace {

using ViewColors = std::map<NodeId, std::vector<std::pair<std::uint32_t, std::string>>>;  // object -> (frame, colour)

// The colour most views name, when at least `descriptionAgreement` views (or
// all, if fewer) and `agreementShare` of them name it.
std::optional<std::string> agreedColor(const std::vector<std::pair<std::uint32_t, std::string>>& views,
                                       const IngestOptions& options) {
    std::map<std::string, int> counts;
    for (const auto& [frame, name] : views) ++counts[name];
    if (counts.empty()) return std::nullopt;
    auto best = std::max_element(counts.begin(), counts.end(),
                                 [](const auto& a, const auto& b) { return a.second < b.second; });
    int seen = static_cast<int>(views.size());
    if (best->second < std::min(options.descriptionAgreement, seen) || best->second < options.agreementShare * seen)
        return std::nullopt;
    return best->first;
}

}  // namespace

void describeObjects(model::SceneData& scene, const std::vector<TrackedNode>& tracked, const LateralPhrases& lateral,
                     const Capture& capture, const IngestOptions& options) {
    // Each view names the colour it sees; the scene-level phrase uses a colour only when
    // enough views agree on it.
    // The views' colours are named on OpenCV's threads (a k-means each: a tenth of a second for TUM fr1/rpy's
    // 60 views on one thread), then gathered in the views' order.
    struct ViewColor {
        NodeId node;
        std::uint32_t frame;
        const cv::Mat* pixels;
        std::string name;
    };
    std::vector<ViewColor> named;
    for (const auto& t : tracked) {
        if (nodeById(scene, t.node).kind != NodeKind::Object) continue;
        for (const auto& v : t.views) named.push_back({t.node, v.frame, &v.colors, {}});
    }
    cv::parallel_for_(cv::Range(0, static_cast<int>(named.size())), [&](const cv::Range& range) {
        for (int i = range.start; i < range.end; ++i) named[i].name = nameColor(*named[i].pixels).name;
    });
    ViewColors viewColors;
    for (auto& view : named)
        if (!view.name.empty()) viewColors[view.node].push_back({view.frame, std::move(view.name)});

    // Layer 2: the scene-level phrase, from what holds allocentrically (support) and what enough
    // views agree on (colour, lateral order). It is the object's text, the default answer.
    for (Node& n : scene.nodes) {
        if (n.kind != NodeKind::Object) continue;
        std::string support;
        for (const auto& r : scene.relations)
            if (r.subject == n.id && (r.type == model::RelationType::On || r.type == model::RelationType::In)) {
                support = fmt::format(" {} the {}", model::toString(r.type), nodeById(scene, r.object).category);
                break;
            }
        // The colour the object keeps (named from its fused points), said where its views agree on it: the text
        // and the colour a question reads never name two colours (TUM fr1/rpy's scissors were "gray" and "white
        // scissors"); without views (clusters), as the points name it.
        std::optional<std::string> color;
        if (auto attribute = n.attribute("color")) {
            if (viewColors.empty() || agreedColor(viewColors[n.id], options) == *attribute)
                color = std::string(*attribute);
        }
        // The category in words: "sports ball", not the name's "sports_ball".
        std::string head = (color ? *color + " " : std::string()) + model::categoryWords(n.category);
        std::string scenePhrase = head + support;
        if (auto it = lateral.find(n.id); it != lateral.end()) scenePhrase += ", " + it->second.front();
        n.text = scenePhrase;
    }
    // Layer 1: a phrase per object per view, as description nodes below each object.
    for (const auto& [id, views] : viewColors) {
        const std::string category = model::categoryWords(nodeById(scene, id).category);
        for (const auto& [frame, colorName] : views) {
            Node& d = addNode(scene, NodeKind::Description, "description", model::GeometryKind::None, {});
            d.parent = id;
            d.text = fmt::format("{} {}, seen in frame {}", colorName, category, capture.frames[frame].index);
            d.attributes = {{"frame", std::to_string(capture.frames[frame].index)}, {"layer", "image"}};
        }
    }
}

}  // namespace smql::ingest
