#include "ingest/pipeline/relations_stage.hpp"

#include <algorithm>
#include <cstdlib>
#include <map>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "ingest/pipeline/descriptions.hpp"
#include "ingest/pipeline/scene_nodes.hpp"
#include "model/category.hpp"
#include "relations/hierarchy.hpp"
#include "relations/predicates.hpp"

namespace smql::ingest {

using model::Node;
using model::NodeId;
using model::NodeKind;

namespace {

// "left of", "in front of"
std::string words(relations::Predicate p) {
    std::string w(relations::toString(p));
    std::replace(w.begin(), w.end(), '_', ' ');
    return w;
}

// Vertical relations hold in the aligned frame: evaluated once, allocentric.
void addSupportRelations(model::SceneData& scene, const relations::Thresholds& thresholds) {
    std::vector<const Node*> things;
    for (const auto& n : scene.nodes)
        if (n.kind == NodeKind::Object) things.push_back(&n);
    relations::Frame none;
    const relations::NodeObstacles obstacles(scene.nodes);
    for (const Node* a : things)
        for (const Node* b : things) {
            if (a == b) continue;
            for (auto p : {relations::Predicate::On, relations::Predicate::In}) {
                double score = relations::evaluate(p, *a, *b, thresholds, none, obstacles);
                if (score > 0) scene.relations.push_back({a->id, b->id, p, static_cast<float>(score), 1, 0});
            }
        }
}

}  // namespace

void RelationsStage::run(StageProgress&) {
    relations::Thresholds thresholds;
    relations::assignParents(scene, thresholds);
    addSupportRelations(scene, thresholds);

    // Lateral relations are view-local: left/right in each frame's image where both
    // instances are seen; promoted to allocentric when enough views agree.
    std::map<std::pair<NodeId, NodeId>, std::pair<int, int>> votes;  // (a, b) -> (left votes, views together)
    std::map<std::uint32_t, std::vector<std::pair<NodeId, double>>> byFrame;
    for (const auto& t : tracked)
        for (const auto& v : t.views) byFrame[v.frame].push_back({t.node, v.centreX});
    // Each frame that saw objects is a frame node (its camera centre as a small box): the
    // view-local relations point at it.
    std::map<std::uint32_t, NodeId> frameNode;
    for (std::size_t c = 0; c < frames.cameras.size(); ++c) {
        std::uint32_t position = frames.cameras[c].frame;
        if (!byFrame.contains(position)) continue;
        Node& f = addNode(scene, NodeKind::Frame, "frame", model::GeometryKind::Box,
                          {aligned.cameraCentres[c], {0.05, 0.05, 0.05}, 0});
        f.text = capture.frames[position].colorPath;
        f.attributes = {{"frame", std::to_string(capture.frames[position].index)}};
        frameNode.emplace(position, f.id);
    }
    for (const auto& [frame, seen] : byFrame)
        for (const auto& [a, ax] : seen)
            for (const auto& [b, bx] : seen) {
                if (a >= b) continue;
                auto& vote = votes[{a, b}];
                ++vote.second;
                // As seen in this frame: left of / right of in the image, by at least 5% of its width.
                std::optional<relations::Predicate> local;
                if (ax < bx - 0.05)
                    ++vote.first, local = relations::Predicate::LeftOf;
                else if (ax > bx + 0.05)
                    --vote.first, local = relations::Predicate::RightOf;
                if (local) scene.relations.push_back({a, b, *local, 1.0f, 1, frameNode.at(frame)});
            }
    LateralPhrases lateral;
    for (const auto& [pair, vote] : votes) {
        auto [a, b] = pair;
        int agree = std::abs(vote.first);
        if (vote.second < options.descriptionAgreement || agree < options.agreementShare * vote.second) continue;
        auto p = vote.first > 0 ? relations::Predicate::LeftOf : relations::Predicate::RightOf;
        scene.relations.push_back(
            {a, b, p, static_cast<float>(double(agree) / vote.second), static_cast<std::uint32_t>(agree), 0});
        // "left of the other mug" where both are mugs; the category in words ("the wall plug").
        const bool alike = nodeById(scene, a).category == nodeById(scene, b).category;
        lateral[a].push_back(fmt::format("{} the {}{}", words(p), alike ? "other " : "",
                                         model::categoryWords(nodeById(scene, b).category)));
    }

    describeObjects(scene, tracked, lateral, capture, options);
}

std::string RelationsStage::summary() const { return fmt::format("{} relations", scene.relations.size()); }

}  // namespace smql::ingest
