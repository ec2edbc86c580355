#include "relations/hierarchy.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <utility>
#include <vector>

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>

#include "model/geometry.hpp"
#include "relations/predicates.hpp"

namespace smql::relations {

using model::Node;

namespace {
// A parent's footprint is at least half its child's.
constexpr double kMinSupporterArea = 0.5;
// Metres by which a wall may be farther than a door or window and still be the parent.
constexpr double kWallPreference = 0.15;

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using Corner = bg::model::point<double, 3, bg::cs::cartesian>;
using Bounds = bg::model::box<Corner>;
using Indexed = std::pair<Bounds, std::size_t>;

Bounds toBounds(const model::Aabb& b) { return {{b.min.x, b.min.y, b.min.z}, {b.max.x, b.max.y, b.max.z}}; }

// A thin upright slab (a picture, a mirror, a board: at most this thick, and three times as tall
// as thick) that is attached to a wall hangs on that wall, whatever its lower edge touches: a picture
// over a sofa is not on the sofa.
constexpr double kHungThickness = 0.1;

using Index = bgi::rtree<Indexed, bgi::rstar<16>>;

// Boxes' bounds in an R-tree, by their place in `nodes`: a layout of 200,000 boxes (or thousands
// of walls) asks each box's few neighbours, not every other box.
Index indexOf(const std::vector<const Node*>& nodes) {
    std::vector<Indexed> bounds;
    for (std::size_t k = 0; k < nodes.size(); ++k) bounds.emplace_back(toBounds(model::worldAabb(nodes[k]->box)), k);
    return Index(bounds);
}

// The entries whose bounds meet `region`, in the nodes' order (so that of two equal candidates
// the first wins, as it would in a walk along all of them).
std::vector<Indexed> meeting(const Index& index, const model::Aabb& region) {
    std::vector<Indexed> found;
    index.query(bgi::intersects(toBounds(region)), std::back_inserter(found));
    std::sort(found.begin(), found.end(), [](const Indexed& x, const Indexed& y) { return x.second < y.second; });
    return found;
}

const Node* hangingWall(const Node& a, const std::vector<const Node*>& anchors, const Index& anchorIndex,
                        const Thresholds& t) {
    double thickness = std::min(a.box.size.x, a.box.size.y);
    if (thickness > kHungThickness || a.box.size.z < 3 * thickness) return nullptr;
    static const Frame frame{};
    static const NodeObstacles nothing{std::span<const Node>{}};
    const Node* best = nullptr;
    double bestScore = 0;
    const auto within = spec(Predicate::Attached).referenceRegion(model::worldAabb(a.box), 0, t);
    for (const auto& [bounds, k] : meeting(anchorIndex, within)) {
        const Node* anchor = anchors[k];
        if (!isVerticalPlane(*anchor)) continue;
        double score = evaluate(Predicate::Attached, a, *anchor, t, frame, nothing);
        if (score > bestScore) bestScore = score, best = anchor;
    }
    return best;
}

// The nearest anchor; but a door or window set in a wall is no nearer, for this purpose, than the
// wall itself: a wall within kWallPreference of the nearest anchor wins, so the tree does not flip
// between a wall and its window over a few centimetres. Anchors are visited in the order of their
// bounds' distance, which is never more than their own: once it passes the nearest found and the
// preference, no later anchor can win.
const Node* nearestAnchor(const Node& a, const std::vector<const Node*>& anchors, const Index& anchorIndex) {
    struct Nearest {
        const Node* node = nullptr;
        double distance = std::numeric_limits<double>::max();
        std::size_t order = 0;
        // Of two at one distance, the first in the scene's order.
        void offer(const Node* n, double d, std::size_t k) {
            if (d < distance || (d == distance && k < order)) *this = {n, d, k};
        }
    } nearest, wall;
    auto chosen = [&] {
        return wall.node && wall.distance <= nearest.distance + kWallPreference ? wall.node : nearest.node;
    };
    const Bounds query = toBounds(model::worldAabb(a.box));
    // The query keeps its k candidates in a sorted list: k grows fourfold until the bound passes
    // (offering an anchor twice changes nothing).
    for (unsigned k = 16;; k *= 4) {
        unsigned seen = 0;
        for (auto it = anchorIndex.qbegin(bgi::nearest(query, k)); it != anchorIndex.qend(); ++it, ++seen) {
            if (bg::distance(query, it->first) > nearest.distance + kWallPreference) return chosen();
            const Node* anchor = anchors[it->second];
            double d = model::distance(a.box, anchor->box);
            nearest.offer(anchor, d, it->second);
            if (anchor->category == kWall) wall.offer(anchor, d, it->second);
        }
        if (seen < k) return chosen();  // every anchor seen
    }
}
}  // namespace

void assignParents(model::SceneData& scene, const Thresholds& thresholds) {
    std::vector<const Node*> objects, uprightAnchors, otherAnchors;
    for (const Node& n : scene.nodes) {
        if (n.geometry == model::GeometryKind::None) continue;
        if (n.kind == model::NodeKind::Object) objects.push_back(&n);
        if (n.kind != model::NodeKind::Anchor) continue;
        // Floors and ceilings are a last resort: every standing object touches the floor.
        bool upright = isVerticalPlane(n) || n.geometry == model::GeometryKind::Box;
        (upright ? uprightAnchors : otherAnchors).push_back(&n);
    }
    const auto& anchors = uprightAnchors.empty() ? otherAnchors : uprightAnchors;
    const Index objectIndex = indexOf(objects), anchorIndex = indexOf(anchors);

    std::vector<model::NodeId> parents(scene.nodes.size(), model::kNoNode);
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
        const Node& a = scene.nodes[i];
        if (a.kind != model::NodeKind::Object || a.parent != model::kNoNode || a.geometry == model::GeometryKind::None)
            continue;
        // The supporter right under `a`: of all that support it and are not much smaller than it
        // (a sofa does not rest on the blanket lying on it), the one whose top is closest to a's
        // bottom (a book on a plate on a table hangs below the plate). Support requires the
        // supporter's centre to be strictly lower, so the tree has no cycles.
        if (const Node* wall = hangingWall(a, anchors, anchorIndex, thresholds)) {
            parents[i] = wall->id;
            continue;
        }
        const Node* best = nullptr;
        auto contact = [&](const Node* b) { return std::abs(model::bottom(a.box) - model::top(b->box)); };
        auto within = spec(Predicate::On).referenceRegion(model::worldAabb(a.box), 0, thresholds);
        for (const auto& [bounds, k] : meeting(objectIndex, within)) {
            const Node* b = objects[k];
            if (b == &a || (b->hidden && !a.hidden)) continue;  // nothing visible hangs below a hidden part
            if (b->box.center.z >= a.box.center.z) continue;
            if (model::footprintArea(b->box) < kMinSupporterArea * model::footprintArea(a.box)) continue;
            if (supportScore(a, *b, thresholds) <= 0) continue;
            if (!best || contact(b) < contact(best)) best = b;
        }
        if (!best) best = nearestAnchor(a, anchors, anchorIndex);
        if (best) parents[i] = best->id;
    }
    for (std::size_t i = 0; i < scene.nodes.size(); ++i)
        if (parents[i] != model::kNoNode) scene.nodes[i].parent = parents[i];
}

}  // namespace smql::relations
