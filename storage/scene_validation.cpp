#include "storage/scene_validation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "model/embedding.hpp"
#include "model/error.hpp"
#include "storage/codec.hpp"
#include "storage/database_internal.hpp"

namespace smql::storage {

using model::Node;
using model::NodeId;

// Names key the name index and, followed by a zero byte and a version number, the history table.
void checkSceneName(const Environment& env, std::string_view name) {
    if (name.empty())
        throw Error(ErrorKind::Input, "a scene needs a name", std::nullopt, "give the scene a name when importing it");
    const std::size_t longest = env.maxKeySize() - codec::historyKey("", 0).size();
    if (name.size() > longest)
        throw Error(ErrorKind::Input,
                    fmt::format("scene name '{}...' is too long ({} bytes; at most {})", name.substr(0, 40),
                                name.size(), longest),
                    std::nullopt, "choose a shorter name");
    if (name.find('\0') != std::string_view::npos)
        throw Error(ErrorKind::Input, "a scene name cannot hold a NUL character", std::nullopt, "choose another name");
}

bool finiteBox(const model::Box& b) {
    const std::array values{b.center.x, b.center.y, b.center.z, b.size.x, b.size.y, b.size.z, b.yaw};
    return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

void refuseBox(const model::Box& b, std::string_view where) {
    importError(
        fmt::format("{}: its box holds a number that is not finite (centre ({}, {}, {}), size {} x {} x {}, "
                    "yaw {}); a box's numbers must be finite",
                    where, b.center.x, b.center.y, b.center.z, b.size.x, b.size.y, b.size.z, b.yaw));
}

std::unordered_map<NodeId, std::size_t> validateScene(const Environment& env, const model::SceneData& data) {
    const std::string& name = data.info.name;
    checkSceneName(env, name);

    std::unordered_map<NodeId, std::size_t> position;
    position.reserve(data.nodes.size());
    for (std::size_t i = 0; i < data.nodes.size(); ++i) {
        const Node& node = data.nodes[i];
        if (node.id == model::kNoNode)
            importError(fmt::format("scene '{}': node #{} has local id 0; local ids start at 1", name, i + 1));
        auto [it, inserted] = position.emplace(node.id, i);
        if (!inserted)
            importError(fmt::format("scene '{}': local id {} is used by node #{} and node #{}", name, node.id,
                                    it->second + 1, i + 1));
        if (node.kind == model::NodeKind::Scene)
            importError(fmt::format("scene '{}': node {} has kind scene; the import creates the scene node itself",
                                    name, node.id));
        checkBox(node, [&] { return fmt::format("scene '{}': node {}", name, node.id); });
        if (node.category.find('\0') != std::string::npos)
            importError(fmt::format("scene '{}': the category of node {} contains a NUL character", name, node.id));
        if (node.category.size() > env.maxKeySize())
            importError(fmt::format("scene '{}': the category of node {} is {} bytes long; at most {}", name, node.id,
                                    node.category.size(), env.maxKeySize()));
    }

    std::unordered_map<std::int64_t, NodeId> bySourceId;
    for (const Node& node : data.nodes) {
        if (node.parent != model::kNoNode && !position.contains(node.parent))
            importError(fmt::format("scene '{}': node {} has parent {}, which is not a node of the scene", name,
                                    node.id, node.parent));
        if (node.sourceId) {
            auto [it, inserted] = bySourceId.emplace(*node.sourceId, node.id);
            if (!inserted)
                importError(fmt::format("scene '{}': source id {} is used by node {} and node {}", name, *node.sourceId,
                                        it->second, node.id));
        }
    }

    // The parents must form a tree under the scene node: walk up from every
    // node once, marking nodes on the current walk to catch cycles.
    enum class Mark : std::uint8_t { Unseen, OnWalk, Done };
    std::vector<Mark> marks(data.nodes.size(), Mark::Unseen);
    std::vector<std::size_t> walk;
    for (std::size_t start = 0; start < data.nodes.size(); ++start) {
        walk.clear();
        std::size_t at = start;
        while (marks[at] == Mark::Unseen) {
            marks[at] = Mark::OnWalk;
            walk.push_back(at);
            NodeId parent = data.nodes[at].parent;
            if (parent == model::kNoNode) break;
            at = position.at(parent);
            if (marks[at] == Mark::OnWalk)
                importError(fmt::format("scene '{}': the parents of node {} form a cycle", name, data.nodes[at].id));
        }
        for (std::size_t i : walk) marks[i] = Mark::Done;
    }

    std::set<std::pair<NodeId, std::string_view>> blobNames;
    std::optional<std::pair<NodeId, std::size_t>> embeddings;  // the first node with one, and its length
    for (const model::Blob& blob : data.blobs) {
        if (blob.node != model::kNoNode && !position.contains(blob.node))  // kNoNode: the scene's own
            importError(fmt::format("scene '{}': blob '{}' belongs to node {}, which is not a node of the scene", name,
                                    blob.name, blob.node));
        if (blob.name.empty() || blob.name.size() + sizeof(NodeId) > env.maxKeySize() || blob.mediaType.size() > 255)
            importError(
                fmt::format("scene '{}': blob '{}' of node {} needs a name of 1 to {} bytes and a media type "
                            "of at most 255",
                            name, blob.name.substr(0, 40), blob.node, env.maxKeySize() - sizeof(NodeId)));
        if (!blobNames.emplace(blob.node, blob.name).second)
            importError(fmt::format("scene '{}': node {} has two blobs named '{}'", name, blob.node, blob.name));
        if (blob.name != model::kEmbeddingBlob) continue;
        // SIMILAR TO compares a bound vector with every node's: one model's vectors, one length.
        std::size_t dimensions = 0;
        try {
            dimensions = model::readEmbedding(blob).size();
        } catch (const Error& e) {
            importError(fmt::format("scene '{}': the embedding of node {}: {}", name, blob.node, e.message()));
        }
        if (!embeddings) embeddings = {blob.node, dimensions};
        if (embeddings->second != dimensions)
            importError(
                fmt::format("scene '{}': the embedding of node {} has {} dimensions, that of node {} has {}; "
                            "a scene's embeddings come from one model",
                            name, blob.node, dimensions, embeddings->first, embeddings->second));
    }

    for (std::size_t i = 0; i < data.relations.size(); ++i) {
        const model::Relation& r = data.relations[i];
        for (NodeId end : {r.subject, r.object})
            if (!position.contains(end))
                importError(
                    fmt::format("scene '{}': relation #{} ({}) refers to node {}, which is not a node of "
                                "the scene",
                                name, i + 1, model::toString(r.type), end));
        if (r.frame != model::kNoNode && !position.contains(r.frame))
            importError(
                fmt::format("scene '{}': relation #{} ({}) was seen from frame {}, which is not a node of "
                            "the scene",
                            name, i + 1, model::toString(r.type), r.frame));
    }
    return position;
}

}  // namespace smql::storage
