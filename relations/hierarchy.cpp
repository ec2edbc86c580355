#include "relations/hierarchy.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <unordered_map>
#include <utility>
#include <vector>

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>

#include "model/geometry.hpp"
#include "relations/predicates.hpp"

namespace smql::relations {

using model::Node;

namespace {
// Metres by which a wall may be farther than a door or window and still be the parent.
constexpr double kWallPreference = 0.15;

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using Corner = bg::model::point<double, 3, bg::cs::cartesian>;
using Bounds = bg::model::box<Corner>;
using Indexed = std::pair<Bounds, std::size_t>;

Bounds toBounds(const model::Aabb& b) { return {{b.min.x, b.min.y, b.min.z}, {b.max.x, b.max.y, b.max.z}}; }

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

// The anchors and the things through their R-trees, as the predicates ask for them: walls (on and in: a picture
// a wall holds is on nothing), and what stands where a lamp's loose box stands (on: restsWithinItsBound), as a
// statement's own scene answers them, so that the tree and on() agree.
class LayoutObstacles final : public Obstacles {
public:
    LayoutObstacles(const std::vector<const Node*>& anchors, const Index& anchorIndex,
                    const std::vector<const Node*>& objects, const Index& objectIndex)
        : anchors_(anchors), anchorIndex_(anchorIndex), objects_(objects), objectIndex_(objectIndex) {}
    void within(const model::Aabb& region, std::vector<const Node*>& out) const override {
        for (const auto& [bounds, k] : meeting(anchorIndex_, region)) out.push_back(anchors_[k]);
        for (const auto& [bounds, k] : meeting(objectIndex_, region)) out.push_back(objects_[k]);
    }

private:
    const std::vector<const Node*>& anchors_;
    const Index& anchorIndex_;
    const std::vector<const Node*>& objects_;
    const Index& objectIndex_;
};

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

// Each object's parent: the wall that holds it, else one of the things it is on or in, else the
// nearest upright anchor. Of several things it is on or in, the one the others are ancestors of (a
// cushion on a tray on a sofa hangs under the tray, whose path holds the sofa), then the highest
// (a cushion sunk into a sofa beside a blanket draped over its arm is on the sofa): so `on(x)`,
// `in(x)` and the path agree (docs/relations.md, "The tree").
class ParentChooser {
public:
    ParentChooser(model::SceneData& scene, const Thresholds& thresholds) : scene_(scene), thresholds_(thresholds) {
        for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
            const Node& n = scene.nodes[i];
            position_.emplace(n.id, i);
            if (n.geometry == model::GeometryKind::None) continue;
            if (n.kind == model::NodeKind::Object) objects_.push_back(&n);
            if (n.kind != model::NodeKind::Anchor) continue;
            if (isCeiling(n)) ceilings_.push_back(&n);
            // Floors and ceilings are a last resort: every standing object touches the floor.
            bool upright = isVerticalPlane(n) || n.geometry == model::GeometryKind::Box;
            (upright ? uprightAnchors_ : otherAnchors_).push_back(&n);
        }
        anchors_ = uprightAnchors_.empty() ? &otherAnchors_ : &uprightAnchors_;
        objectIndex_ = indexOf(objects_);
        anchorIndex_ = indexOf(*anchors_);
        parents_.assign(scene.nodes.size(), model::kNoNode);
        state_.assign(scene.nodes.size(), State::Open);
    }

    void assign() {
        for (std::size_t i = 0; i < scene_.nodes.size(); ++i) choose(i);
        for (std::size_t i = 0; i < scene_.nodes.size(); ++i)
            if (parents_[i] != model::kNoNode) scene_.nodes[i].parent = parents_[i];
    }

private:
    enum class State { Open, Choosing, Chosen };

    // The parent in force: chosen here, else the one the node came with.
    model::NodeId parentOf(std::size_t i) const {
        return parents_[i] != model::kNoNode ? parents_[i] : scene_.nodes[i].parent;
    }

    bool isAncestor(model::NodeId ancestor, std::size_t of) const {
        for (std::size_t steps = 0, at = of; steps <= scene_.nodes.size(); ++steps) {
            auto it = position_.find(parentOf(at));
            if (it == position_.end()) return false;
            if (scene_.nodes[it->second].id == ancestor) return true;
            at = it->second;
        }
        return false;
    }

    void choose(std::size_t i) {
        if (state_[i] != State::Open) return;
        state_[i] = State::Choosing;
        const Node& a = scene_.nodes[i];
        if (a.kind == model::NodeKind::Object && a.parent == model::kNoNode &&
            a.geometry != model::GeometryKind::None) {
            const LayoutObstacles around(*anchors_, anchorIndex_, objects_, objectIndex_);
            if (const Node* wall = wallHolding(a, around, thresholds_)) {
                parents_[i] = wall->id;
            } else if (const Node* carrier = carrierOf(a, around)) {
                parents_[i] = carrier->id;
            } else if (const Node* ceiling = ceilingHolding(a, around)) {
                parents_[i] = ceiling->id;
            } else if (const Node* anchor = relations::nearestAnchor(a, *anchors_, anchorIndex_)) {
                parents_[i] = anchor->id;
            }
        }
        state_[i] = State::Chosen;
    }

    // The ceiling a thing hangs from (attached: a light, a vent), of the scene's ceilings; null for none.
    const Node* ceilingHolding(const Node& a, const Obstacles& around) const {
        static const Frame frame{};
        for (const Node* ceiling : ceilings_)
            if (evaluate(Predicate::Attached, a, *ceiling, thresholds_, frame, around) > 0) return ceiling;
        return nullptr;
    }

    const Node* carrierOf(const Node& a, const Obstacles& around) {
        static const Frame frame{};
        struct Carrier {
            const Node* node;
            std::size_t at;
            double score;  // how much of it carries a: on's overlap, in's share inside
        };
        std::vector<Carrier> carriers;
        const auto within = spec(Predicate::On).referenceRegion(model::worldAabb(a.box), 0, thresholds_);
        for (const auto& [bounds, k] : meeting(objectIndex_, within)) {
            const Node* b = objects_[k];
            if (b == &a || (b->hidden && !a.hidden)) continue;  // nothing visible hangs below a hidden part
            const double score = std::max(evaluate(Predicate::On, a, *b, thresholds_, frame, around),
                                          evaluate(Predicate::In, a, *b, thresholds_, frame, around));
            if (score <= 0) continue;
            const std::size_t at = position_.at(b->id);
            choose(at);  // its own parent first; one still being chosen (a cycle of containment) is passed over
            // Nor a carrier that hangs below a already (a parent the scene came with): no cycle.
            if (state_[at] == State::Choosing || isAncestor(a.id, at)) continue;
            carriers.push_back({b, at, score});
        }
        const Carrier* best = nullptr;
        std::size_t bestAncestors = 0;
        // How far b's top is from where a rests: a lamp on a nightstand inside a bed's loose box rests
        // on the nightstand's top, a cushion on a sofa's seat nearer its top than an arc lamp's over it.
        auto contact = [&](const Carrier& c) { return std::abs(model::top(c.node->box) - model::bottom(a.box)); };
        for (const Carrier& c : carriers) {
            std::size_t ancestors = 0;
            for (const Carrier& other : carriers)
                if (other.node != c.node && isAncestor(other.node->id, c.at)) ++ancestors;
            const bool better = !best || ancestors > bestAncestors ||
                                (ancestors == bestAncestors &&
                                 (c.score > best->score || (c.score == best->score && contact(c) < contact(*best))));
            if (better) best = &c, bestAncestors = ancestors;
        }
        return best ? best->node : nullptr;
    }

    model::SceneData& scene_;
    const Thresholds& thresholds_;
    std::unordered_map<model::NodeId, std::size_t> position_;
    std::vector<const Node*> objects_, uprightAnchors_, otherAnchors_, ceilings_;
    const std::vector<const Node*>* anchors_ = nullptr;
    Index objectIndex_, anchorIndex_;
    std::vector<model::NodeId> parents_;
    std::vector<State> state_;
};

}  // namespace

void assignParents(model::SceneData& scene, const Thresholds& thresholds) { ParentChooser(scene, thresholds).assign(); }

}  // namespace smql::relations
