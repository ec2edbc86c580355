// DESCRIBE: a node's fields, its descriptions and children, and its evidence (from the blob table).
#include "engine/catalog/description.hpp"
#include "engine/exec/executor.hpp"
#include "storage/database.hpp"

namespace smql::exec {

ResultSet Executor::run(const binder::BoundDescribe& d) {
    ResultSet rs;
    rs.columns = {{"id", ValueType::Integer}, {"field", ValueType::Text}, {"value", ValueType::Text}};
    for (catalog::Slot s : slots(d.nodes, defaultFrame())) {
        const model::Node& n = scene().node(s);
        std::vector<const model::Node*> children;
        for (catalog::Slot c : scene().children(s)) children.push_back(&scene().node(c));
        // Evidence lives in the blob table, not in the snapshot.
        std::vector<catalog::EvidenceInfo> evidence;
        for (const auto& blob : txn_.blobsOf(n.id)) evidence.push_back({blob.name, blob.mediaType, blob.size});
        catalog::describeNode(rs, n, scene().path(s), children, evidence);
        // A scene's own node sums up the place: what "describe the room" asks for.
        if (n.kind == model::NodeKind::Scene) {
            std::vector<const model::Node*> within;
            for (const model::Node& node : scene().nodes())
                if (node.kind != model::NodeKind::Scene) within.push_back(&node);
            catalog::describePlace(rs, n, within);
        }
    }
    return rs;
}

}  // namespace smql::exec
